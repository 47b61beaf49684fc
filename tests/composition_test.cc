// Model composition: <include> pastes files in (errors point into the included file),
// <attach> copies a subtree of another model with prefixed names, and the attached
// model's keyframes come along padded with the scene's defaults. Names and keyframes
// are compared with goldens written by MuJoCo 3.5.1 (tests/models/compose/dump_names.mjs,
// tools/dump_model.mjs, the oracle's rollout.mjs).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "rollout.h"
#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

std::string Source(const std::string& relative) {
  return std::string(SIMLAB_SOURCE_DIR) + "/" + relative;
}

json ReadJson(const std::string& relative) {
  std::ifstream in(Source(relative));
  EXPECT_TRUE(in.good()) << "missing " << relative;
  json j;
  if (in) in >> j;
  return j;
}

// A folder of small model files written by a test.
class Files {
 public:
  explicit Files(const std::string& name) : dir_(fs::path(testing::TempDir()) / name) {
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string Write(const std::string& relative, const std::string& text) const {
    fs::path path = dir_ / relative;
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
    return path.string();
  }

 private:
  fs::path dir_;
};

// Loading `path` fails with a message that contains each of `parts`.
void ExpectError(const std::string& path, const std::vector<std::string>& parts) {
  test_util::ExpectMessageParts(test_util::FileLoadError(path), parts, path);
}

// ---------------------------------------------------------------- <include>

TEST(Include, PastesFilesWhereverAnElementCanBe) {
  // compose_include.xml includes defaults, a body (which includes its hand from its
  // own folder) and the actuator and keyframe sections.
  Model m = LoadXml(Source("tests/compiler_models/compose_include.xml"));
  EXPECT_EQ(m.nbody, 4);
  EXPECT_GE(NameToId(m, kObjJoint, "wrist"), 0);
  EXPECT_EQ(m.nu, 1);
  EXPECT_EQ(m.key_names[0], "bent");
  // The included default (damping 0.3) applies to the included joints.
  EXPECT_EQ(m.dof_damping[NameToId(m, kObjJoint, "shoulder")], 0.3);
}

TEST(Include, ErrorsNameTheIncludedFileAndLine) {
  Files files("include_errors");
  files.Write("parts/arm.xml",
              "<mujoco>\n"
              "  <body name=\"arm\">\n"
              "    <joint name=\"j\"/>\n"
              "    <geom size=\"0.1\" colour=\"red\"/>\n"
              "  </body>\n"
              "</mujoco>\n");
  std::string main = files.Write("main.xml",
                                 "<mujoco>\n  <worldbody>\n    <include file=\"parts/arm.xml\"/>\n"
                                 "  </worldbody>\n</mujoco>\n");
  ExpectError(main, {"parts/arm.xml:4:", "<geom>", "unknown attribute 'colour'"});
}

// An asset written in an included file of another folder is found in the model's
// folder first, else beside the included file (as MuJoCo 3.5 finds it).
TEST(Include, AssetFilesAreFoundBesideTheIncludedFile) {
  Files files("include_assets");
  auto hfield = [](int nrow, int ncol) {
    std::string bytes(8 + 4 * nrow * ncol, '\0');
    const int32_t size[2] = {nrow, ncol};
    std::memcpy(bytes.data(), size, sizeof(size));
    return bytes;
  };
  files.Write("parts/only_here.bin", hfield(2, 3));
  files.Write("parts/both.bin", hfield(2, 3));
  files.Write("both.bin", hfield(4, 5));
  files.Write("parts/assets.xml",
              "<mujoco>\n  <asset>\n"
              "    <hfield name=\"here\" file=\"only_here.bin\" size=\"1 1 .1 .1\"/>\n"
              "    <hfield name=\"both\" file=\"both.bin\" size=\"1 1 .1 .1\"/>\n"
              "  </asset>\n</mujoco>\n");
  Model m = LoadXml(files.Write("main.xml", "<mujoco>\n  <include file=\"parts/assets.xml\"/>\n</mujoco>\n"));
  ASSERT_EQ(m.nhfield, 2);
  EXPECT_EQ(m.hfield_nrow[0], 2);  // (only beside the included file)
  EXPECT_EQ(m.hfield_nrow[1], 4);  // (the model's folder first)
}

TEST(Include, MalformedIncludedFileNamesItsLine) {
  Files files("include_malformed");
  files.Write("broken.xml", "<mujoco>\n  <default>\n    <joint damping=\"1\">\n</mujoco>\n");
  std::string main = files.Write("main.xml", "<mujoco>\n  <include file=\"broken.xml\"/>\n</mujoco>\n");
  ExpectError(main, {"broken.xml:", "malformed XML"});
}

TEST(Include, RecursionAndBadIncludesAreRefused) {
  Files files("include_refused");
  files.Write("a.xml", "<mujoco>\n  <include file=\"b.xml\"/>\n</mujoco>\n");
  files.Write("b.xml", "<mujoco>\n  <size nkey=\"1\"/>\n  <include file=\"a.xml\"/>\n</mujoco>\n");
  files.Write("empty.xml", "<mujoco/>\n");
  struct Case {
    std::string body, expect;
  };
  const std::vector<Case> cases = {
      {"<include file=\"a.xml\"/>", "already included"},
      {"<include file=\"missing.xml\"/>", "cannot open included file 'missing.xml'"},
      {"<include file=\"empty.xml\"/>", "is empty"},
      {"<include file=\"a.xml\"><size/></include>", "cannot have child elements"},
      {"<include/>", "file"},
  };
  for (const Case& c : cases) {
    ExpectError(files.Write("main.xml", "<mujoco>\n" + c.body + "\n</mujoco>\n"), {c.expect});
  }
  // The recursion is caught where b.xml includes a.xml again, line 3 of b.xml.
  std::string main = files.Write("main.xml", "<mujoco>\n<include file=\"a.xml\"/>\n</mujoco>\n");
  ExpectError(main, {"b.xml:3:", "already included"});
}

// ---------------------------------------------------------------- <attach>

// Every named kind of object, in id order, against MuJoCo's names.
void ExpectNames(const Model& m, const std::string& golden) {
  json names = ReadJson(golden);
  const std::pair<const char*, const std::vector<std::string>*> kinds[] = {
      {"body", &m.body_names},         {"joint", &m.jnt_names},
      {"geom", &m.geom_names},         {"site", &m.site_names},
      {"equality", &m.eq_names},       {"tendon", &m.tendon_names},
      {"actuator", &m.actuator_names}, {"key", &m.key_names}};
  for (const auto& [kind, ours] : kinds) {
    EXPECT_EQ(names[kind].get<std::vector<std::string>>(), *ours) << golden << ": " << kind;
  }
}

TEST(Attach, PrefixesNamesAsMuJoCo) {
  // Two copies of the arm's "upper" subtree, and its whole world; elements outside the
  // tree follow only when what they reference came along.
  ExpectNames(LoadXml(Source("tests/compiler_models/compose_attach.xml")),
              "tests/models/compose/compose_attach.names.json");
  ExpectNames(LoadXml(Source("models/gantry_gripper.xml")),
              "tests/models/compose/gantry_gripper.names.json");
  // A model that attaches a model: prefixes compose ("a/leaf-twist").
  ExpectNames(LoadXml(Source("tests/compiler_models/compose_nested.xml")),
              "tests/models/compose/compose_nested.names.json");
}

TEST(Attach, ChildDefaultsApplyToItsOwnElements) {
  Model m = LoadXml(Source("tests/compiler_models/compose_attach.xml"));
  // The arm's damping 0.5 on its joints, the scene's 0.1 on the scene's.
  EXPECT_EQ(m.dof_damping[m.jnt_dofadr[NameToId(m, kObjJoint, "left/elbow")]], 0.5);
  EXPECT_EQ(m.dof_damping[m.jnt_dofadr[NameToId(m, kObjJoint, "turn")]], 0.1);
  // The arm's class "finger", prefixed, is usable in the scene after the attach.
  int finger_geom = 0;
  for (int g = 0; g < m.ngeom; g++) finger_geom += m.geom_size[3 * g] == 0.01;
  EXPECT_GE(finger_geom, 4);
}

TEST(Attach, BadAttachmentsAreRefused) {
  Files files("attach_refused");
  files.Write("child.xml",
              "<mujoco>\n  <worldbody>\n    <body name=\"b\"><joint/><geom size=\"1\"/></body>\n"
              "  </worldbody>\n</mujoco>\n");
  struct Case {
    std::string xml, expect;
  };
  const std::vector<Case> cases = {
      {"<worldbody><attach model=\"nope\" body=\"b\" prefix=\"p/\"/></worldbody>",
       "unknown model 'nope'"},
      {"<asset><model name=\"c\" file=\"child.xml\"/></asset>"
       "<worldbody><attach model=\"c\" body=\"x\" prefix=\"p/\"/></worldbody>",
       "has no body 'x'"},
      {"<asset><model name=\"c\" file=\"child.xml\"/></asset>"
       "<worldbody><attach model=\"c\" body=\"b\"/></worldbody>",
       "prefix"},
      {"<asset><model name=\"c\" file=\"missing.xml\"/></asset>", "cannot open model file"},
  };
  for (const Case& c : cases) {
    ExpectError(files.Write("main.xml", "<mujoco>\n" + c.xml + "\n</mujoco>\n"),
                {"main.xml:", c.expect});
  }
  // An error inside the attached model names its own file and line.
  files.Write("bad_child.xml", "<mujoco>\n  <worldbody>\n    <body name=\"b\" size=\"1\"/>\n"
                               "  </worldbody>\n</mujoco>\n");
  ExpectError(files.Write("main.xml", "<mujoco>\n<asset><model name=\"c\" file=\"bad_child.xml\"/>"
                                      "</asset>\n</mujoco>\n"),
              {"bad_child.xml:3:", "unknown attribute 'size'"});
}

// ---------------------------------------------------------------- keyframes

// Row k of a dumped keyframe field.
std::vector<double> GoldenRow(const json& golden, const char* field, int k, int width) {
  std::vector<double> row;
  for (int i = 0; i < width; i++) row.push_back(golden["arrays"][field][k * width + i].get<double>());
  return row;
}

TEST(AttachedKeyframes, PaddedWithTheScenesDefaults) {
  // Key 1 of the gantry is the gripper's "open" (qpos 0.04 0.04, ctrl 0.04): the
  // carriage and the cube take the scene's qpos0, the carriage servos ctrl 0.
  Model m = LoadXml(Source("models/gantry_gripper.xml"));
  json golden = ReadJson("tests/compiler_goldens/gantry_gripper.json");
  int k = NameToId(m, kObjKey, "gripper/open");
  ASSERT_EQ(k, 1);
  std::vector<double> qpos(m.key_qpos.begin() + k * m.nq, m.key_qpos.begin() + (k + 1) * m.nq);
  std::vector<double> ctrl(m.key_ctrl.begin() + k * m.nu, m.key_ctrl.begin() + (k + 1) * m.nu);
  EXPECT_EQ(qpos, GoldenRow(golden, "key_qpos", k, m.nq));
  EXPECT_EQ(ctrl, GoldenRow(golden, "key_ctrl", k, m.nu));
  for (int i = 0; i < m.nq; i++) {
    if (i != 3 && i != 4) EXPECT_EQ(qpos[i], m.qpos0[i]) << "qpos[" << i << "]";
  }
  EXPECT_EQ(qpos[3], 0.04);
  EXPECT_EQ(qpos[4], 0.04);

  // After a reset to it, the state is that row.
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, k);
  for (int i = 0; i < m.nq; i++) EXPECT_EQ(d.qpos[i], qpos[i]);
}

TEST(AttachedKeyframes, MuJoCosStoredValuesTravelWithLaterCopies) {
  // MuJoCo keeps an attached model's keyframe values on the child's elements. The
  // arm's "spin" joint is not in the "upper" subtree, so it keeps the value of
  // "left/reach" (0.7) and hands it to the whole-world copy, "whole/spin".
  Model m = LoadXml(Source("tests/compiler_models/compose_attach.xml"));
  json golden = ReadJson("tests/compiler_goldens/compose_attach.json");
  int k = NameToId(m, kObjKey, "left/reach");
  int spin = m.jnt_qposadr[NameToId(m, kObjJoint, "whole/spin")];
  EXPECT_EQ(m.key_qpos[k * m.nq + spin], 0.7);
  EXPECT_EQ(golden["arrays"]["key_qpos"][k * m.nq + spin].get<double>(), 0.7);
}

// Our rollout from keyframe `key` against the oracle's golden.
void ExpectRolloutMatches(int key) {
  std::string golden_path =
      "tests/models/compose/goldens/compose_rollout_key" + std::to_string(key) + ".jsonl";
  std::ifstream golden_file(Source(golden_path));
  ASSERT_TRUE(golden_file) << golden_path;
  apps::RolloutOptions options;
  options.model = Source("tests/compiler_models/compose_rollout.xml");
  options.ctrl = Source("tests/models/compose/compose_rollout.csv");
  options.key = key;
  options.steps = 300;
  options.every = 10;
  std::stringstream ours_text;
  ASSERT_EQ(apps::RunRollout(options, ours_text), 0);
  std::string ref_line, our_line;
  int rows = 0;
  double worst = 0;
  while (std::getline(golden_file, ref_line)) {
    ASSERT_TRUE(static_cast<bool>(std::getline(ours_text, our_line)));
    json ref = json::parse(ref_line), ours = json::parse(our_line);
    for (auto& [name, values] : ref.items()) {
      if (!values.is_array()) continue;
      ASSERT_EQ(values.size(), ours[name].size()) << name;
      for (size_t i = 0; i < values.size(); i++) {
        double a = values[i].get<double>(), b = ours[name][i].get<double>();
        double err = std::abs(a - b) / std::max(1.0, std::abs(a));
        EXPECT_LE(err, 1e-9) << "key " << key << " row " << rows << " " << name << "[" << i << "]";
        worst = std::max(worst, err);
      }
    }
    rows++;
  }
  EXPECT_EQ(rows, 32);
  std::cout << "[ compose ] rollout from key " << key << ": worst relative error " << worst << "\n";
}

TEST(AttachedKeyframes, RolloutsFromThemMatchMuJoCo) {
  ExpectRolloutMatches(0);  // "left/reach": qpos, ctrl, act, mocap pose
  ExpectRolloutMatches(3);  // "whole/": qvel and time
}

}  // namespace
}  // namespace simlab
