// Sensors: what the loader refuses (with file, line and element), and the behaviour
// around the values that conformance goldens cannot show: the user sensor callback,
// cutoffs, noise kept but never applied, the disable flag, and sensor names.
#include <cmath>
#include <fstream>
#include <sstream>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// A hinge arm with a site, wrapped around a <sensor> section.
std::string ArmWith(const std::string& sensors) {
  return "<mujoco>\n<worldbody>\n<body name=\"arm\">\n"
         "<joint name=\"hinge\" axis=\"0 1 0\" range=\"-1 1\"/>\n"
         "<body name=\"hand\" pos=\".3 0 0\"><joint name=\"ball\" type=\"ball\"/>"
         "<geom size=\".05\"/></body>\n"
         "<geom size=\".1\" pos=\".2 0 0\"/>\n<site name=\"s\" pos=\".3 0 0\"/>\n"
         "</body>\n</worldbody>\n<sensor>\n" + sensors + "\n</sensor>\n</mujoco>\n";
}

void ExpectError(const std::string& xml, const std::vector<std::string>& pieces) {
  test_util::ExpectMessageParts(test_util::XmlLoadError(xml), pieces, xml);
}

TEST(SensorErrors, NameTheLineAndTheProblem) {
  ExpectError(ArmWith("<jointpos joint=\"nope\"/>"),
              {"bad.xml:11:", "<jointpos>", "unrecognized name 'nope'"});
  ExpectError(ArmWith("<jointpos joint=\"ball\"/>"),
              {"bad.xml:11:", "joint must be slide or hinge"});
  ExpectError(ArmWith("<ballquat joint=\"hinge\"/>"), {"bad.xml:11:", "joint must be ball"});
  ExpectError(ArmWith("<jointlimitpos joint=\"ball\"/>"), {"bad.xml:11:", "must be limited"});
  ExpectError(ArmWith("<framepos objtype=\"site\"/>"), {"bad.xml:11:", "'objname'"});
  ExpectError(ArmWith("<framepos objtype=\"joint\" objname=\"hinge\"/>"),
              {"bad.xml:11:", "(x)body, geom, site or camera"});
  ExpectError(ArmWith("<framepos objtype=\"site\" objname=\"s\" refname=\"s\"/>"),
              {"bad.xml:11:", "reftype is missing"});
  ExpectError(ArmWith("<rangefinder site=\"s\" data=\"point dist\"/>"),
              {"bad.xml:11:", "data attributes must be in order"});
  ExpectError(ArmWith("<jointpos joint=\"hinge\" delay=\"0.1\"/>"),
              {"bad.xml:11:", "delay > 0 without a history buffer"});
  ExpectError(ArmWith("<jointpos joint=\"hinge\" cutoff=\"-1\"/>"),
              {"bad.xml:11:", "negative cutoff"});
  ExpectError(ArmWith("<framequat objtype=\"site\" objname=\"s\" cutoff=\"1\"/>"),
              {"bad.xml:11:", "cutoff applied to axis or quaternion"});
  ExpectError(ArmWith("<jointpos name=\"a\" joint=\"hinge\"/><jointvel name=\"a\" joint=\"hinge\"/>"),
              {"bad.xml:11:", "repeated sensor name 'a'"});
  ExpectError(ArmWith("<user dim=\"3\" datatype=\"quaternion\"/>"),
              {"bad.xml:11:", "QUATERNION requires dim=4"});
  ExpectError(ArmWith("<jointpos joint=\"hinge\" interval=\"0.1 0.1\"/>"),
              {"bad.xml:11:", "positive phase"});
}

TEST(Sensors, LayoutAndNames) {
  Model m = LoadXmlString(ArmWith("<jointpos name=\"angle\" joint=\"hinge\"/>"
                                  "<framequat name=\"q\" objtype=\"site\" objname=\"s\"/>"
                                  "<clock/>"));
  ASSERT_EQ(m.nsensor, 3);
  EXPECT_EQ(m.nsensordata, 6);
  EXPECT_EQ(m.sensor_adr[1], 1);
  EXPECT_EQ(m.sensor_dim[1], 4);
  EXPECT_EQ(m.sensor_datatype[1], kDataQuaternion);
  EXPECT_EQ(m.sensor_needstage[2], kStagePos);
  EXPECT_EQ(NameToId(m, kObjSensor, "q"), 1);
  EXPECT_EQ(m.sensor_names[0], "angle");
  EXPECT_STREQ(SensorTypeName(m.sensor_type[1]), "framequat");
  EXPECT_STREQ(ObjTypeName(m.sensor_objtype[1]), "site");

  // Named access to the output, as data.sensor("angle").data in MuJoCo's bindings.
  Data d = MakeData(m);
  d.qpos[0] = 0.25;
  Forward(m, d);
  EXPECT_EQ(SensorId(m, "q"), 1);
  std::span<double> q = SensorData(m, d, "q");
  ASSERT_EQ(q.size(), 4u);
  EXPECT_EQ(q.data(), &d.sensordata[1]);
  EXPECT_EQ(SensorData(m, d, "angle")[0], 0.25);
  EXPECT_THROW(SensorData(m, d, "nope"), Error);
}

// Cutoff clamps; noise is stored and never applied.
TEST(Sensors, CutoffClampsAndNoiseIsNotApplied) {
  Model m = LoadXmlString(ArmWith("<jointpos joint=\"hinge\" cutoff=\"0.3\"/>"
                                  "<jointpos joint=\"hinge\" noise=\"10\"/>"));
  Data d = MakeData(m);
  d.qpos[0] = 0.7;
  Forward(m, d);
  EXPECT_EQ(d.sensordata[0], 0.3);
  EXPECT_EQ(d.sensordata[1], 0.7);
  EXPECT_EQ(m.sensor_noise[1], 10);
  d.qpos[0] = -0.5;
  Forward(m, d);
  EXPECT_EQ(d.sensordata[0], -0.3);
}

// User sensors are zeroed, then the callback fills them at their stage; the cutoff
// applies after it.
TEST(Sensors, UserCallbackRunsAtItsStage) {
  Model m = LoadXmlString(ArmWith("<user dim=\"2\" needstage=\"vel\" cutoff=\"5\"/>"
                                  "<user dim=\"1\" needstage=\"acc\"/>"));
  Data d = MakeData(m);
  std::vector<int> stages;
  d.sensor_callback = [&](const Model& mm, Data& dd, int stage) {
    stages.push_back(stage);
    if (stage == kStageVel) {
      dd.sensordata[mm.sensor_adr[0]] = 7;
      dd.sensordata[mm.sensor_adr[0] + 1] = dd.qvel[0];
    } else {
      dd.sensordata[mm.sensor_adr[1]] = dd.qacc[0];
    }
  };
  d.qvel[0] = 1.5;
  Forward(m, d);
  EXPECT_EQ(stages, (std::vector<int>{kStageVel, kStageAcc}));
  EXPECT_EQ(d.sensordata[0], 5);  // clamped by the cutoff
  EXPECT_EQ(d.sensordata[1], 1.5);
  EXPECT_EQ(d.sensordata[2], d.qacc[0]);
}

// The sensor disable flag leaves sensordata untouched.
TEST(Sensors, DisableFlagSkipsThem) {
  std::string xml = ArmWith("<jointpos joint=\"hinge\"/>");
  xml.replace(xml.find("<mujoco>"), 8, "<mujoco><option><flag sensor=\"disable\"/></option>");
  Model m = LoadXmlString(xml);
  Data d = MakeData(m);
  d.qpos[0] = 0.4;
  Forward(m, d);
  EXPECT_EQ(d.sensordata[0], 0);
}

}  // namespace
}  // namespace simlab

namespace simlab {
namespace {

std::string ReadSource(const std::string& rel) {
  std::ifstream in(std::string(SIMLAB_SOURCE_DIR) + "/" + rel);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Loads `xml`; a model that loads is stepped a few times. Returns whether it loaded;
// an error must name the file.
bool LoadAndStep(const std::string& xml) {
  try {
    Model m = LoadXmlString(xml, "mutated.xml");
    Data d = MakeData(m);
    for (int k = 0; k < 3; k++) Step(m, d);
    return true;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("mutated.xml:", 0), 0u) << e.what();
    return false;
  }
}

// Sensor sections cut short, and every attribute value of every sensor element
// replaced by bad values (negative, empty, unknown names, huge), load with a clear
// error or run: never a crash.
TEST(SensorErrors, MutatedSensorFilesNeverCrash) {
  for (const char* file : {"tests/sensors/simple_sensors.xml", "tests/sensors/touch.xml",
                           "tests/sensors/geometry_sensors.xml"}) {
    std::string xml = ReadSource(file);
    ASSERT_FALSE(xml.empty()) << file;
    size_t begin = xml.find("<sensor>"), end = xml.find("</sensor>");
    ASSERT_NE(begin, std::string::npos) << file;
    int loaded = 0, refused = 0;
    for (size_t cut = begin; cut < end; cut += 13) {
      (LoadAndStep(xml.substr(0, cut)) ? loaded : refused)++;
    }
    // Each quoted value inside the section, replaced in turn.
    for (size_t q = xml.find('"', begin); q < end; q = xml.find('"', xml.find('"', q + 1) + 1)) {
      size_t close = xml.find('"', q + 1);
      for (const char* bad : {"-1", "", "nope", "1e300", "0 0 0 0 0 0 0"}) {
        std::string mutated = xml.substr(0, q + 1) + bad + xml.substr(close);
        (LoadAndStep(mutated) ? loaded : refused)++;
      }
    }
    EXPECT_GT(refused, 0) << file;
    EXPECT_GT(loaded, 0) << file;
  }
}

}  // namespace
}  // namespace simlab
