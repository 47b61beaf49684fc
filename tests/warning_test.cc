// The one warning channel: every warning is counted in d.warning and passed with its
// text to d.warning_callback; the engine prints nothing; an engine error inside Forward
// or a Step (a tactile sensor on a height field, an option set to a value that does not
// exist) becomes a warning and a reset instead of an exception.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "simlab/simlab.h"

namespace simlab {
namespace {

// What a callback saw.
struct Seen {
  Warning kind;
  int info;
  std::string text;
};

std::vector<Seen>* Listen(Data& d) {
  auto* seen = new std::vector<Seen>;
  d.warning_callback = [seen](const Data&, Warning w, int info, const std::string& text) {
    seen->push_back({w, info, text});
  };
  return seen;
}

Model Pendulum() {
  return LoadXmlString(R"(
    <mujoco>
      <worldbody>
        <body><joint name="hinge" axis="0 1 0"/><geom type="capsule" fromto="0 0 0 0 0 -1" size="0.05"/></body>
      </worldbody>
    </mujoco>)");
}

TEST(Warnings, ABadStateIsCountedPassedToTheCallbackAndNotPrinted) {
  Model m = Pendulum();
  Data d = MakeData(m);
  std::unique_ptr<std::vector<Seen>> seen(Listen(d));
  d.qvel[0] = 1e300;
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  Step(m, d);
  Step(m, d);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(d.warning[kWarnBadQvel].number, 1);
  EXPECT_EQ(d.warning[kWarnBadQvel].lastinfo, 0);
  ASSERT_EQ(seen->size(), 1u);
  EXPECT_EQ((*seen)[0].kind, kWarnBadQvel);
  EXPECT_EQ((*seen)[0].text, "bad qvel (NaN or too large): simulation reset (info 0, time 0.0000)");
}

// A pad with a tactile sensor resting on a height field: MuJoCo's tactile sensor has no
// signed distance for height fields and stops with an error.
const char* kPadOnHeightField = R"(
<mujoco>
  <asset>
    <mesh name="plate" builtin="plate" params="3 2" scale="0.04 0.03 0.012"/>
    <hfield name="bumps" nrow="2" ncol="2" size="0.2 0.2 0.01 0.01"/>
  </asset>
  <worldbody>
    <geom name="bumps" type="hfield" hfield="bumps"/>
    <body name="pad" pos="0 0 0.009">
      <joint type="slide" axis="0 0 1"/>
      <geom name="pad_box" type="box" size="0.05 0.05 0.01" mass="0.2"/>
      <geom name="taxels" type="mesh" mesh="plate" contype="0" conaffinity="0" mass="0.01"/>
    </body>
  </worldbody>
  <sensor>
    <tactile name="pad" mesh="plate" geom="taxels"/>
  </sensor>
</mujoco>)";

TEST(Warnings, AnEngineErrorInsideAStepBecomesAWarningAndAReset) {
  Model m = LoadXmlString(kPadOnHeightField, "pad.xml");
  Data d = MakeData(m);
  std::unique_ptr<std::vector<Seen>> seen(Listen(d));
  d.time = 1.5;
  d.qpos[0] = -0.001;
  EXPECT_NO_THROW(Step(m, d));
  EXPECT_EQ(d.warning[kWarnEngineError].number, 1);
  EXPECT_NE(d.error.find("tactile sensor 'pad'"), std::string::npos) << d.error;
  EXPECT_EQ(d.time, 0);          // reset
  EXPECT_EQ(d.qpos[0], m.qpos0[0]);
  ASSERT_EQ(seen->size(), 1u);
  EXPECT_EQ((*seen)[0].kind, kWarnEngineError);
  EXPECT_NE((*seen)[0].text.find("engine error: tactile sensor 'pad'"), std::string::npos);
  EXPECT_NO_THROW(Forward(m, d));
  EXPECT_EQ(d.warning[kWarnEngineError].number, 2);
}

TEST(Warnings, AnOptionThatDoesNotExistIsAnEngineErrorNotACrash) {
  Model m = Pendulum();
  Data d = MakeData(m);
  d.qvel[0] = 1;
  for (int* option : {&m.opt.solver, &m.opt.integrator, &m.opt.cone, &m.opt.jacobian}) {
    int kept = *option;
    *option = 10;
    EXPECT_NO_THROW(Step(m, d));
    EXPECT_NO_THROW(Step1(m, d));
    EXPECT_NO_THROW(Step2(m, d));
    EXPECT_NE(d.error.find("unknown"), std::string::npos) << d.error;
    *option = kept;
  }
  EXPECT_EQ(d.warning[kWarnEngineError].number, 12);
  // Usable again with the options restored.
  d.qvel[0] = 1;
  Step(m, d);
  EXPECT_EQ(d.warning[kWarnEngineError].number, 12);
  EXPECT_GT(d.time, 0);
}

TEST(Warnings, EveryKindHasAName) {
  for (int w = 0; w < kNumWarnings; w++) EXPECT_STRNE(WarningName(w), "unknown warning") << w;
  EXPECT_STREQ(WarningName(kNumWarnings), "unknown warning");
  EXPECT_EQ(kNumMujocoWarnings, 8);
}

}  // namespace
}  // namespace simlab
