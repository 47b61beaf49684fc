// Sleeping trees: what a user does to a sleeping tree wakes it (a force, a new pose, a
// velocity, turning sleep off), as MuJoCo 3.5's mj_wake and its kinematic check do; the
// rollouts themselves are checked against MuJoCo by the corpus goldens (sleep_*).
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "simlab/simlab.h"

namespace simlab {
namespace {

// A box resting on the floor and a pendulum marked sleep="init".
const char* kModel = R"(
<mujoco>
  <option><flag sleep="enable"/></option>
  <worldbody>
    <geom type="plane" size="1 1 .1"/>
    <body name="box" pos="0 0 .1">
      <freejoint/>
      <geom type="box" size=".1 .1 .1"/>
    </body>
    <body name="pendulum" pos="1 0 1" sleep="init">
      <joint type="hinge" axis="0 1 0" damping=".1"/>
      <geom type="capsule" fromto="0 0 0 .3 0 0" size=".02"/>
    </body>
  </worldbody>
</mujoco>)";

bool Asleep(const Data& d, int tree) { return d.tree_asleep[tree] >= 0; }

// Steps until the box (tree 0) sleeps; false if it does not within 5 s.
bool StepUntilBoxSleeps(const Model& m, Data& d) {
  for (int i = 0; i < 2500 && !Asleep(d, 0); i++) Step(m, d);
  return Asleep(d, 0);
}

TEST(Sleep, InitTreeStartsAsleepAndStaysStill) {
  Model m = LoadXmlString(kModel, "sleep.xml");
  Data d = MakeData(m);
  ASSERT_EQ(m.ntree, 2);
  EXPECT_FALSE(Asleep(d, 0));
  EXPECT_TRUE(Asleep(d, 1));
  EXPECT_EQ(d.nv_awake, 6);
  double angle = d.qpos[7];
  for (int i = 0; i < 100; i++) Step(m, d);
  EXPECT_EQ(d.qpos[7], angle);  // a horizontal pendulum that would swing down
  EXPECT_EQ(d.qvel[6], 0.0);
}

TEST(Sleep, RestingBoxFallsAsleepWithZeroVelocity) {
  Model m = LoadXmlString(kModel, "sleep.xml");
  Data d = MakeData(m);
  ASSERT_TRUE(StepUntilBoxSleeps(m, d));
  std::vector<double> pose(d.qpos.begin(), d.qpos.begin() + 7);
  for (int i = 0; i < 6; i++) EXPECT_EQ(d.qvel[i], 0.0);
  for (int i = 0; i < 50; i++) Step(m, d);
  EXPECT_TRUE(std::equal(pose.begin(), pose.end(), d.qpos.begin()));
  EXPECT_EQ(d.ncon, 0);  // asleep against the world: no contacts
}

TEST(Sleep, ForceOrVelocityWakes) {
  Model m = LoadXmlString(kModel, "sleep.xml");
  Data d = MakeData(m);
  ASSERT_TRUE(StepUntilBoxSleeps(m, d));
  d.xfrc_applied[6 * 1 + 2] = 1;  // box
  Step(m, d);
  EXPECT_FALSE(Asleep(d, 0));
  d.qvel[6] = 0.5;  // pendulum
  Step(m, d);
  EXPECT_FALSE(Asleep(d, 1));
  EXPECT_NE(d.qvel[6], 0.0);
}

TEST(Sleep, NewPoseWakes) {
  Model m = LoadXmlString(kModel, "sleep.xml");
  Data d = MakeData(m);
  d.qpos[7] += 0.1;  // move the sleeping pendulum
  Forward(m, d);
  EXPECT_FALSE(Asleep(d, 1));
}

TEST(Sleep, DisablingSleepWakesEverything) {
  Model m = LoadXmlString(kModel, "sleep.xml");
  Data d = MakeData(m);
  m.opt.enableflags &= ~kEnableSleep;
  Step(m, d);
  EXPECT_FALSE(Asleep(d, 1));
  EXPECT_EQ(d.nv_awake, m.nv);
  EXPECT_NE(d.qvel[6], 0.0);
}

TEST(Sleep, NeverPolicyStaysAwake) {
  std::string xml = kModel;
  xml.replace(xml.find("<body name=\"box\" pos=\"0 0 .1\">"), 30, "<body name=\"box\" pos=\"0 0 .1\" sleep=\"never\">");
  Model m = LoadXmlString(xml, "sleep.xml");
  Data d = MakeData(m);
  for (int i = 0; i < 1000; i++) Step(m, d);
  EXPECT_FALSE(Asleep(d, 0));
}

}  // namespace
}  // namespace simlab
