// Camera poses along a rollout against MuJoCo: cam_xpos and cam_xmat of every tracking
// mode (fixed, track, trackcom, targetbody, targetbodycom, a target-less targetbody) on a
// swinging arm with a ball joint and a free ball, from the golden made by
// tools/dump_cameras.mjs (MuJoCo 3.5.1), and the camera loading errors.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using nlohmann::json;

constexpr double kTol = 1e-9;

json ReadGolden(const std::string& name) {
  std::ifstream in(std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_goldens/" + name);
  EXPECT_TRUE(in.good()) << "missing golden " << name;
  json j;
  if (in) in >> j;
  return j;
}

// Worst |ours - MuJoCo's| over one array of one record.
double WorstDiff(const std::vector<double>& ours, const json& ref) {
  EXPECT_EQ(ours.size(), ref.size());
  double worst = 0;
  for (size_t k = 0; k < ours.size() && k < ref.size(); k++) {
    worst = std::max(worst, std::abs(ours[k] - ref[k].get<double>()));
  }
  return worst;
}

TEST(Camera, PosesFollowMuJoCoInEveryMode) {
  json golden = ReadGolden("cameras_rollout.json");
  ASSERT_FALSE(golden.is_null());
  Model m = LoadXml(std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_models/cameras.xml");
  ASSERT_EQ(m.ncam, 14);
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, golden["key"].get<int>());
  Forward(m, d);
  int step = 0;
  double worst = 0;
  for (const json& rec : golden["records"]) {
    int target = rec["step"].get<int>();
    for (; step < target; step++) Step(m, d);
    double pos = WorstDiff(d.cam_xpos, rec["cam_xpos"]);
    double mat = WorstDiff(d.cam_xmat, rec["cam_xmat"]);
    EXPECT_LT(pos, kTol) << "cam_xpos at step " << target;
    EXPECT_LT(mat, kTol) << "cam_xmat at step " << target;
    worst = std::max({worst, pos, mat});
  }
  EXPECT_GT(step, 0);
  std::cout << "[ camera ] worst |diff| of cam_xpos/cam_xmat over " << step << " steps: " << worst
            << "\n";
}

TEST(Camera, NamedLookup) {
  Model m = LoadXml(std::string(SIMLAB_SOURCE_DIR) + "/tests/compiler_models/cameras.xml");
  EXPECT_EQ(NameToId(m, kObjCamera, "arm_track"), 5);
  EXPECT_EQ(NameToId(m, kObjCamera, "missing"), -1);
}

// Bad cameras give the element's line and what is wrong.
TEST(Camera, LoadErrors) {
  auto expect = [](const std::string& element, const std::vector<std::string>& parts) {
    std::string xml = "<mujoco><worldbody>\n" + element + "\n</worldbody></mujoco>";
    test_util::ExpectMessageParts(test_util::XmlLoadError(xml), parts, xml);
  };
  expect("<camera fovy=\"30\" sensorsize=\"1 1\" resolution=\"2 2\"/>",
         {"bad.xml:2", "<camera", "either 'fovy' or 'sensorsize'"});
  expect("<camera focal=\"1 1\"/>", {"bad.xml:2", "focal/principal require sensorsize"});
  expect("<camera sensorsize=\"1 1\" resolution=\"0 5\"/>",
         {"bad.xml:2", "sensorsize requires positive resolution"});
  expect("<camera fovy=\"180\"/>", {"bad.xml:2", "fovy too large"});
  expect("<camera mode=\"targetbody\" target=\"nobody\"/>",
         {"bad.xml:2", "unknown target body 'nobody'"});
  expect("<camera mode=\"orbit\"/>", {"bad.xml:2", "<camera", "orbit"});
  expect("<camera name=\"c\"/><camera name=\"c\"/>", {"bad.xml:2", "repeated camera name 'c'"});
  expect("<camera output=\"rgb color\"/>", {"bad.xml:2", "unknown camera output 'color'"});
}

}  // namespace
}  // namespace simlab
