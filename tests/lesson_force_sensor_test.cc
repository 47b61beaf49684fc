// Lesson 2.3's second exercise: a force and a torque sensor at a site on the gantry
// carriage (models/gantry_gripper.xml with a site and a <sensor> section inserted), the
// gripper closed on the 0.08 kg cube and the carriage raised slowly (the lab's slow
// schedule, tests/models/compose/gantry_lab_slow.csv, from keyframe 0).
//
// What the sensor measures (MuJoCo's XML reference, sensor/force and sensor/torque):
// "the interaction force between a child and a parent body, expressed in the site frame
// defining the sensor"; the site's body is the child, so the reading is the force
// between the carriage and its parent (the world, through the three slide joints and
// their servos) on the subtree rooted at the carriage: the carriage, the palm, the two
// fingers and whatever they hold. It "takes into account all forces acting on the
// system, including contacts as well as external perturbations". In the engine this is
// cfrc_int of the site's body (mj_rnePostConstraint: the subtree's inertial forces with
// gravity, minus the external contact and applied forces on it) moved to the site and
// rotated into the site's frame. The documentation says the force "points from the child
// towards the parent" and that a sensor mounted on the parent side reads the opposite
// sign; at rest here it reads +(subtree mass) g along the site's z, which is the world's
// up axis (slide joints do not rotate the carriage): the support the carriage's parent
// gives the subtree against gravity. The torque sensor is the same wrench's torque
// about the site.
//
// So when the cube leaves the floor, the fingers' contacts carry its weight into the
// carriage's subtree and the vertical reading rises by 0.08 kg x 9.81 m/s^2 = 0.785 N
// (measured against the reading with the carriage lowered and the gripper still open).
// The sensor values also follow MuJoCo's rollout of the same model
// (tests/lesson_force/gantry_force_slow.jsonl, tests/lesson_force/make_golden.sh).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simlab/simlab.h"
#include "test_files.h"

namespace simlab {
namespace {

using test_util::ReadControlRows;
constexpr auto Path = test_util::SourcePath;

constexpr double kCubeWeight = 0.08 * 9.81;

std::string ReadText(const std::string& file) {
  std::ifstream in(Path(file));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Inserts `addition` before the first occurrence of `marker` in `text`.
void InsertBefore(std::string& text, const std::string& marker, const std::string& addition) {
  size_t at = text.find(marker);
  ASSERT_NE(at, std::string::npos) << marker;
  text.insert(at, addition);
}

// The gantry gripper with the lesson's sensors: a site on the carriage body (beside its
// geom), a force and a torque sensor there. make_golden.sh makes the same insertions.
Model GantryWithForceSensor() {
  std::string xml = ReadText("models/gantry_gripper.xml");
  InsertBefore(xml, "<attach model=\"gripper\"", "<site name=\"carriage_ft\" pos=\"0 0 0.01\"/>\n      ");
  InsertBefore(xml, "<keyframe>",
               "<sensor>\n    <force name=\"carriage_force\" site=\"carriage_ft\"/>\n"
               "    <torque name=\"carriage_torque\" site=\"carriage_ft\"/>\n  </sensor>\n  ");
  return LoadXmlString(xml, Path("models/gantry_gripper.xml"));
}

// MuJoCo's sensordata by recorded step.
std::map<int, std::vector<double>> ReferenceSensors(const std::string& golden) {
  std::map<int, std::vector<double>> out;
  std::ifstream in(Path(golden));
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    nlohmann::json row = nlohmann::json::parse(line);
    out[row["step"].get<int>()] = row["sensordata"].get<std::vector<double>>();
  }
  return out;
}

// Whether any contact touches the floor geom and the cube geom together.
bool CubeOnFloor(const Model& m, const Data& d) {
  int floor = m.NameToId(kObjGeom, "floor"), cube = m.NameToId(kObjGeom, "cube");
  for (int i = 0; i < d.ncon; i++) {
    const Contact& c = d.contact[i];
    if ((c.geom[0] == floor && c.geom[1] == cube) || (c.geom[0] == cube && c.geom[1] == floor)) {
      return true;
    }
  }
  return false;
}

struct LiftRun {
  double open_reading = 0;     // force z, carriage lowered and still, gripper open
  double gripped_reading = 0;  // force z, grip closed, cube still on the floor
  double lifted_reading = 0;   // force z at the end, cube held in the air and still
  int left_floor_at = -1;      // first step without a cube-floor contact
  double worst_vs_mujoco = 0;  // relative, over the recorded steps, all six numbers
  int recorded = 0;
};

LiftRun RunLift() {
  Model m = GantryWithForceSensor();
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, 0);
  int force_adr = m.sensor_adr[m.NameToId(kObjSensor, "carriage_force")];
  std::vector<std::vector<double>> controls =
      ReadControlRows("tests/models/compose/gantry_lab_slow.csv");
  std::map<int, std::vector<double>> reference =
      ReferenceSensors("tests/lesson_force/gantry_force_slow.jsonl");
  LiftRun out;
  Forward(m, d);
  for (int step = 1; step <= static_cast<int>(controls.size()); step++) {
    for (int u = 0; u < m.nu; u++) d.ctrl[u] = controls[step - 1][u];
    Step(m, d);
    double force_z = d.sensordata[force_adr + 2];
    if (step == 1000) out.open_reading = force_z;     // 2.0 s: lowered, grip not closed
    if (step == 1500) out.gripped_reading = force_z;  // 3.0 s: closed, raise not begun
    if (out.left_floor_at < 0 && step > 1500 && !CubeOnFloor(m, d)) out.left_floor_at = step;
    auto ref = reference.find(step);
    if (ref == reference.end()) continue;
    out.recorded++;
    for (int k = 0; k < m.nsensordata; k++) {
      double r = ref->second[k];
      out.worst_vs_mujoco = std::max(out.worst_vs_mujoco,
                                     std::abs(d.sensordata[k] - r) / std::max(1.0, std::abs(r)));
    }
  }
  out.lifted_reading = d.sensordata[force_adr + 2];
  return out;
}

TEST(LessonForceSensor, ReadingRisesByTheCubesWeight) {
  LiftRun r = RunLift();
  std::printf("force z: open %.5f N, gripped on the floor %.5f N, lifted %.5f N; cube left "
              "the floor at step %d; rise %.5f N vs weight %.5f N; worst vs MuJoCo %.2e\n",
              r.open_reading, r.gripped_reading, r.lifted_reading, r.left_floor_at,
              r.lifted_reading - r.open_reading, kCubeWeight, r.worst_vs_mujoco);
  // Before: the subtree's own 0.54 kg (carriage 0.4, palm 0.1, fingers 2 x 0.02).
  EXPECT_NEAR(r.open_reading, 0.54 * 9.81, 0.01 * 0.54 * 9.81);
  EXPECT_GT(r.left_floor_at, 1500);
  EXPECT_NEAR(r.lifted_reading - r.open_reading, kCubeWeight, 0.02 * kCubeWeight);
  EXPECT_GT(r.recorded, 60);
  EXPECT_LT(r.worst_vs_mujoco, 1e-6);
}

}  // namespace
}  // namespace simlab
