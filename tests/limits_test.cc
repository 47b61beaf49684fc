// Hostile sizes: every input of issue 15 (items 1 and 2) that crashed simlab, ran out of
// stack or asked for gigabytes now gets a simlab::Error naming the file, the line, the
// element and the attribute, quickly and without allocating what it asks for; the
// deepest tree MuJoCo accepts still loads and steps. Each input is built here in code.
#include <cmath>
#include <ctime>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "mjcf/limits.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using test_util::ExpectMessageParts;
using test_util::XmlLoadError;

// Loading `xml` as "bad.xml" fails with a message containing every expected piece.
void ExpectError(const std::string& xml, const std::vector<std::string>& pieces) {
  ExpectMessageParts(XmlLoadError(xml), pieces, xml.substr(0, 400));
}

// The message of loading `xml` as "main.xml" with in-memory files ("" if it loads).
std::string AssetsLoadError(const std::string& xml, const Assets& assets) {
  try {
    LoadXmlString(xml, "main.xml", assets);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// `n` lines each opening `open`, then `inner`, then `n` times `close`: line k + 1 of the
// result (after `head`'s lines) opens the k-th level.
std::string Nest(const std::string& head, int n, const std::string& open,
                 const std::string& inner, const std::string& close, const std::string& tail) {
  std::string xml = head;
  for (int i = 0; i < n; i++) xml += open + "\n";
  xml += inner;
  for (int i = 0; i < n; i++) xml += close;
  return xml + tail;
}

// A chain of `n` bodies, each with a hinge and a geom, one body per line from line 3.
std::string HingeChain(int n, const std::string& last_geom = "<geom size=\".05\"/>") {
  std::string link = "<body pos=\"0 0 -.1\"><joint axis=\"0 1 0\"/><geom size=\".05\"/>";
  std::string xml = "<mujoco>\n<worldbody>\n";
  for (int i = 0; i < n - 1; i++) xml += link + "\n";
  xml += "<body pos=\"0 0 -.1\"><joint axis=\"0 1 0\"/>" + last_geom;
  for (int i = 0; i < n; i++) xml += "</body>";
  return xml + "\n</worldbody>\n</mujoco>\n";
}

// ---------------------------------------------------------------- item 1: nesting

// MuJoCo's parser stops at 500 levels: the content of an element on level 499 would be
// level 500. The root <mujoco> is level 1 and <worldbody> level 2, so body k (on line
// k + 2) is on level k + 2, and the element that fails is body 497, on line 499.
TEST(Limits, NestedBodiesStopAtMujocosDepth) {
  std::string xml = Nest("<mujoco>\n<worldbody>\n", 12300, "<body><geom size=\".1\"/>", "",
                         "</body>", "</worldbody>\n</mujoco>\n");
  ExpectError(xml, {"bad.xml:499: <body>: element nesting is too deep", "500 levels"});
}

TEST(Limits, NestedFramesStopAtMujocosDepth) {
  std::string xml = Nest("<mujoco>\n<worldbody>\n", 17000, "<frame>", "<geom size=\".1\"/>",
                         "</frame>", "</worldbody>\n</mujoco>\n");
  ExpectError(xml, {"bad.xml:499: <frame>: element nesting is too deep"});
}

TEST(Limits, NestedDefaultsStopAtMujocosDepth) {
  std::string xml = "<mujoco>\n<default>\n";
  for (int i = 0; i < 20000; i++) xml += "<default class=\"c" + std::to_string(i) + "\">\n";
  for (int i = 0; i < 20000; i++) xml += "</default>";
  xml += "</default>\n<worldbody><geom size=\".1\"/></worldbody>\n</mujoco>\n";
  ExpectError(xml, {"bad.xml:499: <default>: element nesting is too deep"});
}

// The deepest chain MuJoCo accepts (its last elements, on level 499, self-closed) loads
// and steps: 496 hinged bodies on levels 3 to 498.
TEST(Limits, DeepestChainMujocoAcceptsLoadsAndSteps) {
  Model m = LoadXmlString(HingeChain(496), "deep.xml");
  EXPECT_EQ(m.nbody, 497);
  EXPECT_EQ(m.nv, 496);
  Data d = MakeData(m);
  d.qvel[0] = 1;
  for (int i = 0; i < 3; i++) Step(m, d);
  for (double q : d.qpos) ASSERT_TRUE(std::isfinite(q));
  EXPECT_NE(d.qpos[0], 0);
}

// The same chain with its last geom written open (<geom ...></geom>) has content on
// level 499: MuJoCo refuses it, and so does simlab, at that geom.
TEST(Limits, OpenElementOnTheLastLevelIsRefused) {
  std::string xml = HingeChain(496, "<geom size=\".05\"></geom>");
  ExpectError(xml, {"bad.xml:498: <geom>: element nesting is too deep"});
}

// Files put together by <include> may nest deeper than one file: a 700-body chain, 400
// fixed bodies in the main file and 300 hinged ones in an included file, loads (the
// walks of the reader and the compiler stay within their stack) and steps.
TEST(Limits, IncludedChainDeeperThanOneFileLoads) {
  std::string fixed = "<body pos=\"0 0 -.1\"><geom size=\".05\"/>";
  std::string hinged = "<body pos=\"0 0 -.1\"><joint axis=\"0 1 0\"/><geom size=\".05\"/>";
  std::string part = Nest("<mujoco>\n", 300, hinged, "", "</body>", "\n</mujoco>\n");
  std::string main = Nest("<mujoco>\n<worldbody>\n", 400, fixed, "<include file=\"part.xml\"/>",
                          "</body>", "\n</worldbody>\n</mujoco>\n");
  Model m = LoadXmlString(main, "main.xml", {{"part.xml", part}});
  EXPECT_EQ(m.nbody, 701);
  EXPECT_EQ(m.nv, 300);
  Data d = MakeData(m);
  Step(m, d);
  for (double q : d.qpos) ASSERT_TRUE(std::isfinite(q));
}

// Beyond kMaxTreeDepth levels of pasted files, the element that crosses it is named.
TEST(Limits, IncludesNestedBeyondTheTreeDepthAreRefused) {
  std::string link = "<body><geom size=\".05\"/>\n";
  Assets files;
  for (int k = 0; k < 3; k++) {
    std::string next = k < 2 ? "<include file=\"part" + std::to_string(k + 1) + ".xml\"/>" : "";
    files["part" + std::to_string(k) + ".xml"] =
        Nest("<mujoco>\n", 450, link, next, "</body>", "\n</mujoco>\n");
  }
  std::string main =
      "<mujoco>\n<worldbody>\n<include file=\"part0.xml\"/>\n</worldbody>\n</mujoco>\n";
  ExpectMessageParts(AssetsLoadError(main, files),
                     {"part2.xml:", "<geom>", "element nesting is too deep",
                      "included files pasted in", "1000 levels"},
                     main);
}

// A model attached into a model attached into this one: the copies nest as deep as the
// three models together, which is refused where it would cross kMaxTreeDepth.
TEST(Limits, AttachedModelsNestedBeyondTheTreeDepthAreRefused) {
  std::string link = "<body><geom size=\".05\"/>";
  Assets files;
  files["g.xml"] = Nest("<mujoco model=\"g\">\n<worldbody>\n", 490, link, "", "</body>",
                        "\n</worldbody>\n</mujoco>\n");
  files["c.xml"] = Nest("<mujoco model=\"c\">\n<asset><model name=\"g\" file=\"g.xml\"/></asset>\n"
                        "<worldbody>\n",
                        480, link, "<attach model=\"g\" prefix=\"g\"/>", "</body>",
                        "\n</worldbody>\n</mujoco>\n");
  std::string main = Nest("<mujoco>\n<asset><model name=\"c\" file=\"c.xml\"/></asset>\n"
                          "<worldbody>\n",
                          40, link, "<attach model=\"c\" prefix=\"c\"/>", "</body>",
                          "\n</worldbody>\n</mujoco>\n");
  ExpectMessageParts(AssetsLoadError(main, files),
                     {"main.xml:44: <attach>", "with model 'c' attached here", "more than 1000"},
                     main.substr(0, 400));
}

// ---------------------------------------------------------------- item 2: files

// Only regular files are read: a device (it would never end), a folder.
TEST(Limits, IncludeOfADeviceIsRefused) {
  ExpectError("<mujoco>\n<include file=\"/dev/zero\"/>\n</mujoco>\n",
              {"bad.xml:2: <include>: cannot read included file '/dev/zero': not a regular file"});
  ExpectError("<mujoco>\n<include file=\"/tmp\"/>\n</mujoco>\n",
              {"bad.xml:2: <include>: cannot read included file '/tmp': not a regular file"});
}

TEST(Limits, ModelFileThatIsADeviceIsRefused) {
  ExpectError("<mujoco>\n<asset>\n<model name=\"m\" file=\"/dev/zero\"/>\n</asset>\n</mujoco>\n",
              {"bad.xml:3: <model name=\"m\">",
               "cannot read model file '/dev/zero': not a regular file"});
  ExpectMessageParts(test_util::FileLoadError("/dev/zero"),
                     {"/dev/zero: cannot read file: not a regular file"}, "/dev/zero");
}

// ---------------------------------------------------------------- item 2: sizes

TEST(Limits, KeyframeCountBeyondTheBudgetIsRefused) {
  ExpectError("<mujoco>\n<size nkey=\"1000000000\"/>\n</mujoco>\n",
              {"bad.xml:2: <size>: nkey=\"1000000000\" asks for", "of keyframes",
               "over the 1.0 GB budget of one array"});
}

// MuJoCo: "sensordata too large" (when its Data buffer cannot be sized).
TEST(Limits, UserSensorDimensionBeyondTheBudgetIsRefused) {
  ExpectError("<mujoco>\n<worldbody/>\n<sensor>\n<user name=\"u\" dim=\"2000000000\"/>\n"
              "</sensor>\n</mujoco>\n",
              {"bad.xml:4: <user name=\"u\">: sensordata too large: dim=\"2000000000\" asks "
               "for 14.9 GB of sensordata, over the 1.0 GB budget of one array"});
}

// Sensors whose sizes add up past the budget: the one that crosses it is named.
TEST(Limits, SensordataAddingUpBeyondTheBudgetIsRefused) {
  std::string xml = "<mujoco>\n<worldbody/>\n<sensor>\n";
  for (int i = 0; i < 3; i++) {
    xml += "<user name=\"u" + std::to_string(i) + "\" dim=\"100000000\"/>\n";
  }
  xml += "</sensor>\n</mujoco>\n";
  ExpectError(xml, {"bad.xml:5: <user name=\"u1\">: sensordata too large",
                    "the sensors up to this one ask for 1.5 GB"});
}

// History buffers: each at most 2^24 samples, together within the budget.
TEST(Limits, HistoryBuffersBeyondTheBudgetAreRefused) {
  std::string xml = "<mujoco>\n<worldbody><body><joint name=\"j\"/><geom size=\".1\"/></body>"
                    "</worldbody>\n<sensor>\n";
  for (int i = 0; i < 6; i++) {
    xml += "<jointpos name=\"p" + std::to_string(i) + "\" joint=\"j\" nsample=\"16000000\"/>\n";
  }
  xml += "</sensor>\n</mujoco>\n";
  ExpectError(xml, {"bad.xml:8: <jointpos name=\"p4\">: history buffer too large"});
}

TEST(Limits, SensorUserNumbersBeyondTheBudgetAreRefused) {
  std::string model = "<worldbody/>\n<sensor>\n<clock/>\n</sensor>\n</mujoco>\n";
  ExpectError("<mujoco>\n<size nuser_sensor=\"1000000000\"/>\n" + model,
              {"bad.xml:2: <size>: nuser_sensor=\"1000000000\" for 1 sensors asks for 7.5 GB "
               "of sensor user numbers"});
  ExpectError("<mujoco>\n<size nuser_sensor=\"1e9\"/>\n" + model,
              {"bad.xml:2: <size>: attribute 'nuser_sensor': '1e9' is not an integer"});
}

TEST(Limits, HeightFieldBeyondTheBudgetIsRefused) {
  ExpectError("<mujoco>\n<asset>\n<hfield name=\"h\" nrow=\"100000\" ncol=\"100000\" "
              "size=\"1 1 1 1\"/>\n</asset>\n</mujoco>\n",
              {"bad.xml:3: <hfield name=\"h\">: nrow=\"100000\" x ncol=\"100000\" asks for "
               "74.5 GB of height field data"});
}

// Builtin meshes: MuJoCo's own limits first, then the budget, checked before any
// vertex is made; a parameter an int cannot hold is refused (MuJoCo's cast is
// undefined behaviour).
TEST(Limits, BuiltinMeshesBeyondTheBudgetAreRefused) {
  struct Case {
    const char* shape;
    const char* params;
    const char* expected;
  };
  const Case cases[] = {
      {"sphere", "1e9", "Sphere subdivision cannot be greater than 4"},
      {"hemisphere", "1e9", "Hemisphere resolution cannot be greater than 10"},
      {"supersphere", "1e5 1 1", "params=\"100000 1 1\" asks for 447.0 GB of mesh vertices"},
      {"supertorus", "1e5 0.5 1 1", "params=\"100000 0.5 1 1\" asks for"},
      {"wedge", "1e5 1e5 60 45 0", "params=\"100000 100000 60 45 0\" asks for"},
      {"plate", "1e5 1e5", "params=\"100000 100000\" asks for"},
      {"cone", "1e9 1", "params=\"1000000000 1\" asks for 44.7 GB of mesh vertices"},
      {"cone", "1e12 1", "params=\"1000000000000 1\": parameter 1 is out of the range of an "
                         "integer"},
      {"sphere", "-1e300", "parameter 1 is out of the range of an integer"},
      {"plate", "nan 3", "params=\"nan 3\": parameter 1 is out of the range of an integer"},
  };
  for (const Case& c : cases) {
    std::string xml = std::string("<mujoco>\n<asset>\n<mesh name=\"m\" builtin=\"") + c.shape +
                      "\" params=\"" + c.params + "\"/>\n</asset>\n<worldbody>\n"
                      "<geom type=\"mesh\" mesh=\"m\"/>\n</worldbody>\n</mujoco>\n";
    ExpectError(xml, {"bad.xml:3: <mesh name=\"m\">: ", c.expected});
  }
}

// Replicates multiply what they copy: the innermost one of three nested replicates of
// 1000 is refused before the first copy.
TEST(Limits, NestedReplicatesBeyondTheBudgetAreRefused) {
  ExpectError("<mujoco>\n<worldbody>\n<replicate count=\"1000\" offset=\"1 0 0\">\n"
              "<replicate count=\"1000\" offset=\"0 1 0\">\n"
              "<replicate count=\"1000\" offset=\"0 0 1\">\n<geom size=\".1\"/>\n"
              "</replicate>\n</replicate>\n</replicate>\n</worldbody>\n</mujoco>\n",
              {"bad.xml:5: <replicate>: count=\"1000\" (inside replicates that copy it 1000000 "
               "times) asks for", "of replicated elements"});
}

// A sensor that names no object is copied with every replica, copies included, as
// MuJoCo does (3 replicas make 8 clocks, 12 make 4096); 30 would make 2^30, so the model
// is refused once the copies pass 65,536 (the fuzzer's timeouts, tests/fuzz/findings).
std::string ClockReplicated(int count) {
  return "<mujoco>\n<worldbody>\n<replicate count=\"" + std::to_string(count) +
         "\">\n<geom name=\"g\" size=\".1\"/>\n</replicate>\n</worldbody>\n"
         "<sensor>\n<clock/>\n</sensor>\n</mujoco>\n";
}

TEST(Limits, ReplicatedClocksDoubleAsInMujoco) {
  EXPECT_EQ(LoadXmlString(ClockReplicated(3)).nsensor, 8);
  EXPECT_EQ(LoadXmlString(ClockReplicated(12)).nsensor, 4096);
}

TEST(Limits, ReplicatedClocksBeyondTheLimitAreRefused) {
  ExpectError(ClockReplicated(30),
              {"bad.xml:3: <replicate>: count=\"30\" copies the sensors without objects",
               "131071 already, over simlab's limit of 65536"});
}

// A large replicate: named bodies, each with a site that a sensor reads (so the sensor
// is replicated too), 30,000 times. Replicate copies each replica's references from the
// elements before it and the copies that name nothing only, so its work is linear in
// the count (its time is measured outside the tests: 256,000 replicas load in seconds).
TEST(Limits, LargeReplicateLoads) {
  std::string xml = "<mujoco>\n<worldbody>\n<replicate count=\"30000\" offset=\"1 0 0\">\n"
                    "<body name=\"b\"><geom name=\"g\" size=\".1\"/><site name=\"s\"/></body>\n"
                    "</replicate>\n</worldbody>\n<sensor>\n<framepos objtype=\"site\" "
                    "objname=\"s\"/>\n</sensor>\n</mujoco>\n";
  Model m = LoadXmlString(xml, "big.xml");
  EXPECT_EQ(m.nbody, 30001);
  EXPECT_EQ(m.nsensor, 30000);
  EXPECT_EQ(m.sensor_objid[29999], 29999);
  EXPECT_EQ(m.body_names[30000], "b29999");
}

// Body pairs are numbered by MuJoCo's signature (body1 << 16) + body2 in an int: a model
// with more than 32768 bodies is refused (the broad phase took body 65536 for the end of
// an interval and corrupted the heap).
TEST(Limits, BodiesBeyondTheSignaturesAreRefused) {
  ExpectError("<mujoco>\n<worldbody>\n<replicate count=\"40000\" offset=\"1 0 0\">\n"
              "<body><geom size=\".1\"/></body>\n</replicate>\n</worldbody>\n</mujoco>\n",
              {"bad.xml: too many bodies: the model has 40001 (the world included), more than "
               "the 32768 that MuJoCo's body-pair signatures (body1 << 16) + body2 can number"});
}

// 4,000 hinges, which MuJoCo loads. The stages' scratch stack is sized for the model's
// integrator: with Euler the Data takes well under half a GB and the model steps; the
// implicit integrator's RNE derivative keeps 6-row blocks over each body's ancestor and
// subtree dofs only (the body-dof pattern B, as MuJoCo), so it fits too (it took 6 nv
// doubles per body, 2.3 GB, before).
std::string FourThousandHinges(const std::string& integrator, const std::string& extra = "") {
  std::string xml = "<mujoco>\n<option integrator=\"" + integrator + "\"/>\n<worldbody>\n";
  for (int i = 0; i < 4000; i++) {
    xml += "<body pos=\"" + std::to_string(i) + " 0 0\"><joint/><geom size=\".1\"/></body>\n";
  }
  return xml + "</worldbody>\n" + extra + "</mujoco>\n";
}

TEST(Limits, FourThousandHingesLoadAndStep) {
  for (const char* integrator : {"Euler", "implicit"}) {
    Model m = LoadXmlString(FourThousandHinges(integrator), "hinges.xml");
    EXPECT_LT(DataBytes(m), uint64_t{1} << 29) << integrator;
    Data d = MakeData(m);
    Step(m, d);
    EXPECT_EQ(d.warning[kWarnEngineError].number, 0) << integrator;
    EXPECT_GT(d.time, 0) << integrator;
  }
}

// A Data past the budget is refused with the reason, before anything is allocated: here
// 4,000 hinges and 80,000 actuators, whose moments are rows of nv.
TEST(Limits, DataOverTheBudgetIsRefused) {
  std::string motors = "<actuator>\n";
  for (int i = 0; i < 80000; i++) motors += "<motor joint=\"j" + std::to_string(i % 4000) + "\"/>\n";
  motors += "</actuator>\n";
  std::string xml = FourThousandHinges("Euler", motors);
  for (int i = 0, at = 0; i < 4000; i++) {
    at = static_cast<int>(xml.find("<joint/>", at));
    xml.replace(at, 8, "<joint name=\"j" + std::to_string(i) + "\"/>");
  }
  ExpectError(xml, {"bad.xml: actuator_moment too large: the model's Data would need",
                    "over the 2.0 GB budget of one Data"});
}

// A stage that needs more scratch than the stack holds (here the implicit integrator
// chosen after MakeData) takes it from the heap, and the stack grows to that peak.
TEST(Limits, StackGrowsToWhatAStepNeeded) {
  std::string chain = "<geom size='.1'/>";
  for (int i = 0; i < 10; i++) {
    chain = "<body pos='.2 0 0'><joint/><geom size='.1'/>" + chain + "</body>";
  }
  Model m = LoadXmlString("<mujoco><worldbody>" + chain + "</worldbody></mujoco>");
  Data d = MakeData(m);
  size_t euler_stack = d.stack.size();
  m.opt.integrator = kIntegratorImplicit;
  Data expected = MakeData(m);
  Step(m, d);
  Step(m, expected);
  EXPECT_GT(d.stack_peak, euler_stack);
  EXPECT_EQ(d.qpos, expected.qpos);
  Step(m, d);
  EXPECT_GE(d.stack.size(), d.stack_peak);
  EXPECT_TRUE(d.stack_blocks.empty());
}

// MakeData checks the whole Data before allocating anything, for any Model (here one
// whose sizes were changed by hand after compiling).
TEST(Limits, MakeDataRefusesADataBeyondTheBudget) {
  Model m = LoadXmlString("<mujoco><worldbody><geom size=\".1\"/></worldbody></mujoco>");
  m.nsensordata = 2000000000;
  try {
    MakeData(m);
    FAIL() << "MakeData allocated 16 GB";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Invalid data: sensordata too large"),
              std::string::npos)
        << e.what();
  }
  m.nsensordata = 0;
  EXPECT_LT(DataBytes(m), uint64_t{1} << 20);
}

}  // namespace
}  // namespace simlab
