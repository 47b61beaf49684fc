// The mouse perturbation (simlab/perturb.h) against native MuJoCo 3.12's mjv_initPerturb
// and mjv_applyPerturbForce (numbers printed by a program linking libmujoco: the
// humanoid after 50 steps, its torso pulled at a point off its centre and turned), and
// the springs doing their job: a free box pulled to a point and turned to an orientation
// settles there.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "math/math.h"
#include "simlab/perturb.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

const std::string kHumanoid = std::string(SIMLAB_SOURCE_DIR) + "/../shared/corpus/mujoco/model/humanoid/humanoid.xml";

void ExpectNearAll(const double* ours, const std::array<double, 6>& native, const char* what) {
  for (int k = 0; k < 6; k++) {
    EXPECT_NEAR(ours[k], native[k], 1e-7 * (1 + std::abs(native[k]))) << what << " [" << k << "]";
  }
}

TEST(Perturb, ForcesAsMuJoCo) {
  Model m = LoadXml(kHumanoid);
  Data d = MakeData(m);
  for (int i = 0; i < 50; i++) Step(m, d);
  Perturb p;
  p.select = 3;
  p.localpos = {0.05, -0.02, 0.03};
  InitPerturb(m, d, &p);
  EXPECT_NEAR(p.localmass, 11.028146379389742, 1e-9);
  p.refselpos[0] += 0.3;
  p.refselpos[2] += 0.2;
  double q[4] = {0.9, 0.1, -0.2, 0.3};
  math::NormalizeQuat(q);
  p.refquat = {q[0], q[1], q[2], q[3]};
  p.active = kPerturbTranslate;
  ApplyPerturbForce(m, d, p);
  ExpectNearAll(&d.xfrc_applied[18], {327.10134039392517, 1.7196158638902469e-15, 221.80659975010647,
                                      -4.4361319950021345, -1.5812417765748332, 6.542026807878508}, "translate");
  p.active = kPerturbRotate;
  ApplyPerturbForce(m, d, p);
  ExpectNearAll(&d.xfrc_applied[18], {0, 0, 0, -148.9165886806569, -95.543650643764011, 19.614771348026174}, "rotate");
}

TEST(Perturb, FreeBoxSettlesAtTheReference) {
  Model m = LoadXmlString(R"(<mujoco><option gravity="0 0 0"/>
    <worldbody><body name="box" pos="0 0 1"><freejoint/><geom type="box" size=".1 .2 .3" mass="2"/></body></worldbody>
  </mujoco>)");
  Data d = MakeData(m);
  Forward(m, d);
  Perturb p;
  p.select = 1;
  InitPerturb(m, d, &p);
  EXPECT_NEAR(p.localmass, 2, 1e-12);  // a free body pulled at its centre moves with its mass
  p.refselpos = {0.5, -0.25, 1.5};
  double q[4] = {std::cos(0.5), 0, 0, std::sin(0.5)};  // 1 radian about z
  p.refquat = {q[0], q[1], q[2], q[3]};
  p.active = kPerturbTranslate | kPerturbRotate;
  for (int i = 0; i < 3000; i++) {
    ApplyPerturbForce(m, d, p);
    Step(m, d);
  }
  EXPECT_NEAR(d.xpos[3], 0.5, 1e-4);
  EXPECT_NEAR(d.xpos[4], -0.25, 1e-4);
  EXPECT_NEAR(d.xpos[5], 1.5, 1e-4);
  EXPECT_NEAR(std::abs(d.xquat[4] * q[0] + d.xquat[7] * q[3]), 1, 1e-6);
  // Inactive, or no body: nothing is applied.
  std::fill(d.xfrc_applied.begin(), d.xfrc_applied.end(), 0.0);
  p.active = 0;
  ApplyPerturbForce(m, d, p);
  p.active = kPerturbTranslate;
  p.select = -1;
  ApplyPerturbForce(m, d, p);
  for (double f : d.xfrc_applied) EXPECT_EQ(f, 0);
}

}  // namespace
}  // namespace simlab
