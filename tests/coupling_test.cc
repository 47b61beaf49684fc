// The lesson's claims about the gripper's coupling (models/gantry_gripper.xml): one
// actuator on a tendon drives the average of the fingers, a soft joint equality keeps
// them equal. Contacts are not needed: the gripper closes in the air.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "simlab/simlab.h"

namespace simlab {
namespace {

const std::string kGantry = std::string(SIMLAB_SOURCE_DIR) + "/models/gantry_gripper.xml";

struct Fingers {
  int left, right;  // qpos addresses
  int left_dof;
};

Fingers FingerAddresses(const Model& m) {
  int left = NameToId(m, kObjJoint, "gripper/finger_left");
  int right = NameToId(m, kObjJoint, "gripper/finger_right");
  return {m.jnt_qposadr[left], m.jnt_qposadr[right], m.jnt_dofadr[left]};
}

// Largest |left - right| over the last 500 of 1000 steps from key 0 with a grip command
// of 0.03 m, while `load` newtons push the left finger open.
double FingerDrift(const Model& m, double load) {
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, 0);
  Fingers f = FingerAddresses(m);
  d.ctrl[NameToId(m, kObjActuator, "gripper/grip")] = 0.03;
  d.qfrc_applied[f.left_dof] = load;
  double drift = 0;
  for (int i = 0; i < 1000; i++) {
    Step(m, d);
    if (i >= 500) drift = std::max(drift, std::abs(d.qpos[f.left] - d.qpos[f.right]));
  }
  return drift;
}

// "the output shows the fingers equal to five decimals"
TEST(Coupling, FingersStayEqualUnderAGripCommand) {
  Model m = LoadXml(kGantry);
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, 0);
  Fingers f = FingerAddresses(m);
  d.ctrl[NameToId(m, kObjActuator, "gripper/grip")] = 0.03;
  for (int i = 0; i < 1000; i++) {
    Step(m, d);
    EXPECT_LT(std::abs(d.qpos[f.left] - d.qpos[f.right]), 5e-6) << "step " << i;
  }
  EXPECT_NEAR(d.qpos[f.left], 0.03, 5e-6);
  EXPECT_NEAR(d.ten_length[0], 0.03, 5e-6);
  EXPECT_GT(d.nefc, 0);  // the equality is a constraint row, not a hard-coded symmetry
}

// "The two fingers drift apart under load ... Stiffen its solref (smaller time constant)."
TEST(Coupling, StifferSolrefReducesDriftUnderLoad) {
  Model m = LoadXml(kGantry);
  int eq = NameToId(m, kObjEquality, "gripper/mirror");
  ASSERT_GE(eq, 0);
  double soft = FingerDrift(m, 2.0);
  m.eq_solref[kNRef * eq] = 0.005;  // time constant 0.02 s -> 0.005 s
  double stiff = FingerDrift(m, 2.0);
  EXPECT_GT(soft, 1e-5);          // a visible drift under a 2 N load...
  EXPECT_LT(stiff, 0.25 * soft);  // ...much smaller with the stiffer equality
  m.eq_solref[kNRef * eq] = 0.02;
  EXPECT_LT(FingerDrift(m, 0.0), 0.1 * soft);  // and it is the load that opens the gap
}

}  // namespace
}  // namespace simlab
