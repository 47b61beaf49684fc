// Bad input: each kind of malformed or unsupported MJCF gets a clear error that names
// the file, the line, the element and the problem; nothing crashes.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// Loading `xml` as "bad.xml" fails with a message containing every expected piece.
void ExpectError(const std::string& xml, const std::vector<std::string>& pieces) {
  test_util::ExpectMessageParts(test_util::XmlLoadError(xml), pieces, xml);
}

TEST(MjcfErrors, NotXml) { ExpectError("this is not xml", {"bad.xml:1:", "malformed XML"}); }

TEST(MjcfErrors, MalformedXml) {
  ExpectError("<mujoco>\n  <worldbody>\n    <body>\n  </worldbody>\n</mujoco>\n",
              {"bad.xml:", "malformed XML"});
}

TEST(MjcfErrors, WrongRoot) { ExpectError("<robot/>", {"bad.xml:1:", "<robot>", "<mujoco>"}); }

TEST(MjcfErrors, UnknownElement) {
  ExpectError("<mujoco>\n<worldbody>\n<bogus/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<bogus>", "unknown element"});
}

TEST(MjcfErrors, UnknownAttribute) {
  ExpectError("<mujoco>\n<worldbody>\n<geom name=\"g\" size=\".1\" colour=\"red\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<geom name=\"g\">", "unknown attribute 'colour'"});
}

TEST(MjcfErrors, WrongCount) {
  ExpectError("<mujoco>\n<worldbody>\n<body name=\"b\" pos=\"1 2\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<body name=\"b\">", "'pos'", "expects 3", "got 2"});
}

TEST(MjcfErrors, NotANumber) {
  ExpectError("<mujoco>\n<worldbody>\n<geom size=\"abc\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<geom>", "'abc' is not a number"});
}

TEST(MjcfErrors, MissingRequiredAttribute) {
  ExpectError(
      "<mujoco>\n<worldbody><body><joint name=\"j\"/><geom size=\".1\"/></body></worldbody>\n"
      "<tendon>\n<fixed name=\"t\">\n<joint coef=\"1\"/>\n</fixed>\n</tendon>\n</mujoco>",
      {"bad.xml:5:", "<joint>", "missing required attribute 'joint'"});
}

TEST(MjcfErrors, UnknownTendonJoint) {
  ExpectError(
      "<mujoco>\n<worldbody><body><joint name=\"j\"/><geom size=\".1\"/></body></worldbody>\n"
      "<tendon>\n<fixed name=\"t\">\n<joint joint=\"nope\" coef=\"1\"/>\n</fixed>\n</tendon>\n</mujoco>",
      {"bad.xml:5:", "<joint>", "unknown joint 'nope'"});
}

TEST(MjcfErrors, NegativeGeomMass) {
  ExpectError("<mujoco>\n<worldbody>\n<body>\n<joint/>\n<geom name=\"g\" size=\".1\" mass=\"-1\"/>\n"
              "</body>\n</worldbody>\n</mujoco>",
              {"bad.xml:5:", "<geom name=\"g\">", "mass", "negative"});
}

TEST(MjcfErrors, ZeroInertialMassOnMovingBody) {
  ExpectError("<mujoco>\n<worldbody>\n<body name=\"b\">\n<joint/>\n"
              "<inertial pos=\"0 0 0\" mass=\"0\" diaginertia=\"1 1 1\"/>\n</body>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<body name=\"b\">", "mass"});
}

TEST(MjcfErrors, NegativeInertialMass) {
  ExpectError("<mujoco>\n<worldbody>\n<body>\n<inertial pos=\"0 0 0\" mass=\"-2\"/>\n</body>\n"
              "</worldbody>\n</mujoco>",
              {"bad.xml:4:", "<inertial>", "mass must not be negative"});
}

TEST(MjcfErrors, UnknownDefaultClass) {
  ExpectError("<mujoco>\n<worldbody>\n<geom class=\"nope\" size=\".1\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<geom>", "unknown default class 'nope'"});
  ExpectError("<mujoco>\n<worldbody>\n<body childclass=\"nope\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<body>", "unknown default class 'nope'"});
}

TEST(MjcfErrors, DuplicateNames) {
  ExpectError("<mujoco>\n<worldbody>\n<geom name=\"a\" size=\".1\"/>\n<geom name=\"a\" size=\".2\"/>\n"
              "</worldbody>\n</mujoco>",
              {"bad.xml:4:", "<geom name=\"a\">", "repeated geom name 'a'"});
  ExpectError("<mujoco>\n<default>\n<default class=\"x\"/>\n<default class=\"x\"/>\n</default>\n</mujoco>",
              {"bad.xml:4:", "repeated default class name 'x'"});
}

TEST(MjcfErrors, MissingFile) {
  try {
    LoadXml("/nonexistent/dir/robot.xml");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/robot.xml"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
}

TEST(MjcfErrors, NotSupportedYet) {
  ExpectError("<mujoco>\n<option><flag nativeccd=\"disable\"/></option>\n<asset>\n"
              "<hfield name=\"h\" nrow=\"2\" ncol=\"2\" size=\"1 1 .1 .1\"/>\n</asset>\n<worldbody>\n"
              "<geom name=\"ground\" type=\"hfield\" hfield=\"h\"/>\n"
              "<body><freejoint/><geom name=\"ball\" size=\".1\"/></body>\n</worldbody>\n</mujoco>",
              {"bad.xml:7:", "<geom name=\"ground\">", "nativeccd flag disabled are not supported yet",
               "'ball'"});
  ExpectError("<mujoco>\n<option><flag nativeccd=\"disable\"/></option>\n<asset>\n"
              "<hfield name=\"h\" nrow=\"2\" ncol=\"2\" size=\"1 1 .1 .1\"/>\n</asset>\n<worldbody>\n"
              "<geom name=\"ground\" type=\"hfield\" hfield=\"h\"/>\n"
              "<flexcomp name=\"cloth\" type=\"grid\" count=\"2 2 1\" spacing=\".1 .1 .1\" dim=\"2\"/>\n"
              "</worldbody>\n</mujoco>",
              {"bad.xml:7:", "<geom name=\"ground\">", "nativeccd flag disabled are not supported yet",
               "flex 'cloth'"});
  ExpectError("<mujoco>\n<worldbody>\n<body>\n<composite/>\n</body>\n</worldbody>\n</mujoco>",
              {"bad.xml:4:", "<composite> is not supported yet"});
  ExpectError("<mujoco>\n<worldbody>\n<body><joint name=\"j\"/><geom size=\".1\"/></body>\n</worldbody>\n"
              "<actuator>\n<muscle joint=\"j\"/>\n</actuator>\n</mujoco>",
              {"bad.xml:6:", "<muscle>", "lengthrange simulation did not converge"});
}

// Equality constraints: lookups, the body/site forms, joint types, names (line 8 is
// the constraint).
TEST(MjcfErrors, Equality) {
  const std::string head =
      "<mujoco>\n<worldbody>\n"
      "<body name=\"a\"><joint name=\"j\"/><joint name=\"s\" type=\"slide\"/><geom size=\".1\"/>"
      "<site name=\"sa\"/></body>\n"
      "<body name=\"b\"><joint name=\"ball\" type=\"ball\"/><geom size=\".1\"/></body>\n"
      "</worldbody>\n<tendon><fixed name=\"t\"><joint joint=\"j\" coef=\"1\"/></fixed></tendon>\n"
      "<equality>\n";
  auto expect = [&](const std::string& element, const std::vector<std::string>& pieces) {
    ExpectError(head + element + "\n</equality>\n</mujoco>", pieces);
  };
  expect("<connect body1=\"nope\" anchor=\"0 0 0\"/>", {"bad.xml:8:", "<connect>", "unknown body 'nope'"});
  expect("<weld body1=\"a\" body2=\"nope\"/>", {"bad.xml:8:", "<weld>", "unknown body 'nope'"});
  expect("<connect name=\"c\" site1=\"sa\" site2=\"nope\"/>",
         {"bad.xml:8:", "<connect name=\"c\">", "unknown site 'nope'"});
  expect("<connect body1=\"a\" site2=\"sa\" anchor=\"0 0 0\"/>",
         {"bad.xml:8:", "<connect>", "body and site attributes cannot be mixed"});
  expect("<weld site1=\"sa\" relpose=\"0 0 0 1 0 0 0\"/>", {"bad.xml:8:", "<weld>", "cannot be mixed"});
  expect("<connect body1=\"a\"/>", {"bad.xml:8:", "<connect>", "a connect needs body1 and anchor"});
  expect("<connect site1=\"sa\"/>", {"bad.xml:8:", "a connect needs body1 and anchor"});
  expect("<weld site2=\"sa\"/>", {"bad.xml:8:", "<weld>", "a weld needs body1"});
  expect("<connect anchor=\"0 0\" body1=\"a\"/>", {"bad.xml:8:", "'anchor'", "expects 3"});
  expect("<joint joint2=\"j\"/>", {"bad.xml:8:", "<joint>", "missing required attribute 'joint1'"});
  expect("<joint joint1=\"j\" joint2=\"ball\"/>", {"bad.xml:8:", "joint 'ball' is not a hinge or a slide"});
  expect("<joint joint1=\"j\" joint2=\"j\"/>", {"bad.xml:8:", "joint 'j' is used twice"});
  expect("<weld body1=\"world\"/>", {"bad.xml:8:", "body 'world' is used twice"});
  expect("<tendon tendon1=\"nope\"/>", {"bad.xml:8:", "<tendon>", "unknown tendon 'nope'"});
  expect("<joint joint1=\"j\" anchor=\"0 0 0\"/>", {"bad.xml:8:", "unknown attribute 'anchor'"});
  expect("<joint joint1=\"j\" polycoef=\"1 2 3 4 5 6\"/>", {"bad.xml:8:", "'polycoef'"});
  expect("<joint joint1=\"j\" class=\"nope\"/>", {"bad.xml:8:", "unknown default class 'nope'"});
  expect("<distance/>", {"bad.xml:8:", "removed"});
  expect("<gear/>", {"bad.xml:8:", "unknown element <gear> in <equality>"});
  expect("<joint name=\"x\" joint1=\"j\"/>\n<joint name=\"x\" joint1=\"s\"/>",
         {"bad.xml:9:", "repeated equality name 'x'"});
  ExpectError("<mujoco>\n<default>\n<equality body1=\"a\"/>\n</default>\n</mujoco>",
              {"bad.xml:3:", "unknown attribute 'body1'"});
}

TEST(MjcfErrors, MuscleParameters) {
  const std::string head =
      "<mujoco>\n<worldbody>\n<body><joint name=\"j\"/><geom size=\".1\"/></body>\n</worldbody>\n"
      "<actuator>\n";
  ExpectError(head + "<muscle joint=\"j\" lengthrange=\"0 1\" range=\"1 0.5\"/>\n</actuator>\n</mujoco>",
              {"bad.xml:6:", "range[0]<range[1] required in muscle"});
  ExpectError(head + "<muscle joint=\"j\" lengthrange=\"0 1\" lmin=\"1.2\"/>\n</actuator>\n</mujoco>",
              {"bad.xml:6:", "lmin<1<lmax required in muscle"});
  ExpectError(head + "<muscle joint=\"j\" lengthrange=\"0 1\" tausmooth=\"-1\"/>\n</actuator>\n</mujoco>",
              {"bad.xml:6:", "tausmooth cannot be negative"});
}

TEST(MjcfErrors, CompileErrorsNameTheElement) {
  ExpectError("<mujoco>\n<worldbody>\n<body>\n<joint name=\"h\" limited=\"true\" range=\"10 -10\"/>\n<geom size=\".1\"/>\n"
              "</body>\n</worldbody>\n</mujoco>",
              {"bad.xml:4:", "<joint name=\"h\">", "range[0] should be smaller"});
  ExpectError("<mujoco>\n<worldbody>\n<body><joint name=\"j\"/><geom size=\".1\"/></body>\n</worldbody>\n"
              "<actuator>\n<motor name=\"m\" joint=\"nope\"/>\n</actuator>\n</mujoco>",
              {"bad.xml:6:", "<motor name=\"m\">", "unknown joint 'nope'"});
  ExpectError("<mujoco>\n<worldbody>\n<body><joint/><geom size=\".1\"/></body>\n</worldbody>\n"
              "<keyframe>\n<key name=\"k\" qpos=\"1 2 3\"/>\n</keyframe>\n</mujoco>",
              {"bad.xml:6:", "<key name=\"k\">", "invalid qpos size"});
  ExpectError("<mujoco>\n<worldbody>\n<geom type=\"box\" size=\".1 .1\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<geom>", "size[2] must be positive"});
}

// Every prefix of a real model either loads or throws simlab::Error: never a crash.
TEST(MjcfErrors, TruncatedFilesNeverCrash) {
  std::ifstream in(std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_models/actuators.xml");
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  ASSERT_FALSE(xml.empty());
  int errors = 0;
  for (size_t n = 0; n < xml.size(); n += 7) {
    try {
      LoadXmlString(xml.substr(0, n), "cut.xml");
    } catch (const Error& e) {
      errors++;
      EXPECT_EQ(std::string(e.what()).rfind("cut.xml:", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(errors, 0);
}

// Textures, materials and lights: files that are missing or are no PNG, references to
// nothing, impossible sizes.
std::string TextureModel(const std::string& asset) {
  return "<mujoco>\n<asset>\n" + asset + "\n</asset>\n</mujoco>";
}

std::string LoadWithAssets(const std::string& xml, const Assets& assets) {
  try {
    LoadXmlString(xml, "bad.xml", assets);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(MjcfErrors, TextureFiles) {
  ExpectError(TextureModel("<texture name=\"t\" type=\"2d\" file=\"missing.png\"/>"),
              {"bad.xml:3:", "<texture name=\"t\">", "cannot open texture file", "missing.png"});
  ExpectError(TextureModel("<texture type=\"2d\" file=\"image.jpg\"/>"),
              {"bad.xml:3:", "unsupported texture file", "PNG"});
  std::ifstream in(std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_models/textures/rgba8.png",
                   std::ios::binary);
  std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(png.size(), 60u);
  std::string xml = TextureModel("<texture type=\"2d\" file=\"a.png\"/>");
  test_util::ExpectMessageParts(LoadWithAssets(xml, {{"a.png", "not a png at all"}}),
                                {"bad.xml:3:", "cannot read PNG file", "a.png"}, xml);
  test_util::ExpectMessageParts(LoadWithAssets(xml, {{"a.png", png.substr(0, 60)}}),
                                {"bad.xml:3:", "cannot read PNG file"}, xml);
  std::string grid = TextureModel("<texture type=\"cube\" file=\"a.png\" gridsize=\"3 3\"/>");
  test_util::ExpectMessageParts(LoadWithAssets(grid, {{"a.png", png}}),
                                {"bad.xml:3:", "integer multiple of gridsize"}, grid);
}

// Height-field files: missing, not PNG, a binary file of the wrong size, an unknown
// content type, a size given beside the file.
TEST(MjcfErrors, HFieldFiles) {
  const std::string png = TextureModel("<hfield name=\"h\" file=\"h.png\" size=\"1 1 .1 .1\"/>");
  test_util::ExpectMessageParts(LoadWithAssets(png, {{"other.png", "x"}}),
                                {"bad.xml:3:", "<hfield name=\"h\">", "could not read hfield file", "h.png"}, png);
  test_util::ExpectMessageParts(LoadWithAssets(png, {{"h.png", "not a png"}}),
                                {"bad.xml:3:", "cannot read PNG file", "h.png"}, png);
  const std::string bin = TextureModel("<hfield name=\"h\" file=\"h.bin\" size=\"1 1 .1 .1\"/>");
  std::string header(8, '\0');
  const int32_t size[2] = {2, 3};
  std::memcpy(header.data(), size, sizeof(size));
  test_util::ExpectMessageParts(LoadWithAssets(bin, {{"h.bin", header + std::string(20, '\0')}}),
                                {"bad.xml:3:", "unexpected file size", "h.bin"}, bin);
  test_util::ExpectMessageParts(LoadWithAssets(bin, {{"h.bin", "abc"}}), {"bad.xml:3:", "hfield missing header"}, bin);
  const int32_t huge[2] = {1 << 20, 1 << 20};
  std::memcpy(header.data(), huge, sizeof(huge));
  test_util::ExpectMessageParts(LoadWithAssets(bin, {{"h.bin", header}}), {"bad.xml:3:", "over simlab's limit"}, bin);
  ExpectError(TextureModel("<hfield name=\"h\" file=\"h.bin\" content_type=\"image/jpeg\" size=\"1 1 .1 .1\"/>"),
              {"bad.xml:3:", "unsupported content type: 'image/jpeg'"});
  ExpectError(TextureModel("<hfield name=\"h\" file=\"h.png\" nrow=\"2\" ncol=\"2\" size=\"1 1 .1 .1\"/>"),
              {"bad.xml:3:", "hfield specified from file and manually"});
}

TEST(MjcfErrors, TextureSizesAndReferences) {
  ExpectError(TextureModel("<texture type=\"2d\" builtin=\"checker\" width=\"0\" height=\"4\"/>"),
              {"bad.xml:3:", "invalid width of builtin texture"});
  ExpectError(TextureModel("<texture type=\"2d\" builtin=\"checker\" width=\"100000\" height=\"100000\"/>"),
              {"bad.xml:3:", "too large"});
  ExpectError(TextureModel("<texture type=\"2d\"/>"), {"bad.xml:3:", "needs a file or a builtin"});
  ExpectError(TextureModel("<material name=\"m\" texture=\"nothing\"/>"),
              {"bad.xml:3:", "<material name=\"m\">", "unknown texture 'nothing'"});
  ExpectError("<mujoco>\n<worldbody>\n<geom size=\".1\" material=\"none\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<geom>", "unknown material 'none'"});
  ExpectError("<mujoco>\n<worldbody>\n<light dir=\"0 0 0\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "<light>", "zero direction in light"});
  ExpectError("<mujoco>\n<worldbody>\n<light mode=\"targetbody\" target=\"nobody\"/>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "unknown body 'nobody'"});
}

// Sleep policies: only on a moving root body; not on trees a springy or 3-tree tendon
// couples; and trees marked init must be able to start asleep (MuJoCo's own test model,
// where the init trees are welded to one that may not sleep).
TEST(MjcfErrors, SleepPolicies) {
  ExpectError("<mujoco>\n<worldbody>\n<body sleep=\"never\"><geom size=\".1\"/></body>\n</worldbody>\n</mujoco>",
              {"bad.xml:3:", "sleep policy only allowed for movable root bodies"});
  ExpectError(
      "<mujoco>\n<worldbody>\n<body><freejoint/><geom size=\".1\"/>\n"
      "<body sleep=\"allowed\"><joint/><geom size=\".1\"/></body></body>\n</worldbody>\n</mujoco>",
      {"bad.xml:4:", "sleep policy only allowed for movable root bodies"});
  const std::string springy =
      "<mujoco>\n<worldbody>\n"
      "<body sleep=\"allowed\"><freejoint/><geom size=\".1\"/><site name=\"a\"/></body>\n"
      "<body pos=\"1 0 0\"><freejoint/><geom size=\".1\"/><site name=\"b\"/></body>\n"
      "</worldbody>\n<tendon>\n<spatial stiffness=\"1\"><site site=\"a\"/><site site=\"b\"/></spatial>\n"
      "</tendon>\n</mujoco>";
  ExpectError(springy, {"bad.xml:7:", "tree 0 connected to tendon 0 with non-zero stiffness or damping"});
  test_util::ExpectMessageParts(
      test_util::FileLoadError(std::string(SIMLAB_SOURCE_DIR) +
                               "/tests/conformance/corpus/mujoco/sleep/sleep_init_island_fail.xml"),
      {"sleep_init_island_fail.xml:16:", "<body name=\"asleep_init0\">",
       "3 trees were marked as sleep='init' but only 0 could be slept"},
      "sleep_init_island_fail.xml");
}

// Skins: bad data, bones and files are refused with the skin's line; so is a flex without
// its bodies.
TEST(MjcfErrors, Skins) {
  auto skin = [](const std::string& attrs, const std::string& bone) {
    return "<mujoco>\n<worldbody><body name=\"b\"><geom size=\".1\"/></body></worldbody>\n"
           "<deformable>\n<skin " + attrs + ">\n" + bone + "\n</skin>\n</deformable>\n</mujoco>";
  };
  const std::string bone =
      "<bone body=\"b\" bindpos=\"0 0 0\" bindquat=\"1 0 0 0\" vertid=\"0 1 2\" vertweight=\"1 1 1\"/>";
  ExpectError(skin("vertex=\"0 0 0 1 0 0 0 1 0\" face=\"0 1 2\" group=\"7\"", bone),
              {"bad.xml:4:", "skin group must be between 0 and 5"});
  ExpectError(skin("vertex=\"0 0 0 1 0 0 0 1\" face=\"0 1 2\"", bone),
              {"bad.xml:4:", "vertex data must be a multiple of 3"});
  ExpectError(skin("vertex=\"0 0 0 1 0 0 0 1 0\"", bone), {"bad.xml:4:", "missing data in skin"});
  ExpectError(skin("vertex=\"0 0 0 1 0 0 0 1 0\" face=\"0 1 2\"",
                   "<bone body=\"nobody\" bindpos=\"0 0 0\" bindquat=\"1 0 0 0\" vertid=\"0\" vertweight=\"1\"/>"),
              {"bad.xml:5:", "unknown body 'nobody' in skin"});
  ExpectError(skin("vertex=\"0 0 0 1 0 0 0 1 0\" face=\"0 1 2\"",
                   "<bone body=\"b\" bindpos=\"0 0 0\" bindquat=\"1 0 0 0\" vertid=\"0 5\" vertweight=\"1 1\"/>"),
              {"bad.xml:5:", "vertid 5 out of range in skin"});
  ExpectError(skin("vertex=\"0 0 0 1 0 0 0 1 0\" face=\"0 1 2\"",
                   "<bone body=\"b\" bindpos=\"0 0 0\" bindquat=\"1 0 0 0\" vertid=\"0 1\" vertweight=\"1 1\"/>"),
              {"bad.xml:4:", "vertex 2 must have positive total weight in skin"});
  ExpectError(skin("vertex=\"0 0 0 1 0 0 0 1 0\" face=\"0 1 2\" material=\"cloth\"", bone),
              {"bad.xml:4:", "unknown material 'cloth' in skin"});
  ExpectError(skin("file=\"a.skn\" vertex=\"0 0 0 1 0 0 0 1 0\"", ""),
              {"bad.xml:4:", "both skin data and file were specified"});
  ExpectError(skin("file=\"a.obj\"", ""), {"bad.xml:4:", "unknown skin file type"});
  ExpectError(skin("file=\"missing.skn\"", ""), {"bad.xml:4:", "could not read SKN file"});
  ExpectError("<mujoco>\n<deformable>\n<flex name=\"f\"/>\n</deformable>\n</mujoco>",
              {"bad.xml:3:", "<flex name=\"f\">", "missing required attribute 'body'"});
}

// A truncated .skn file is refused, not read past its end.
TEST(MjcfErrors, TruncatedSkinFile) {
  std::string skn = std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_models/tetra.skn";
  std::ifstream in(skn, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 100u);
  const std::string xml =
      "<mujoco>\n<worldbody><body name=\"arm\"/><body name=\"hand\"/></worldbody>\n"
      "<deformable>\n<skin file=\"t.skn\"/>\n</deformable>\n</mujoco>";
  for (size_t cut : {size_t{0}, size_t{10}, size_t{60}, bytes.size() - 200, bytes.size() - 3}) {
    Assets assets{{"t.skn", bytes.substr(0, cut)}};
    std::string message;
    try {
      LoadXmlString(xml, "bad.xml", assets);
    } catch (const Error& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("bad.xml:4:"), std::string::npos) << cut << ": " << message;
    EXPECT_NE(message.find("SKN file"), std::string::npos) << cut << ": " << message;
  }
  Assets whole{{"t.skn", bytes}};
  EXPECT_EQ(LoadXmlString(xml, "bad.xml", whole).nskin, 1);
}

}  // namespace
}  // namespace simlab
