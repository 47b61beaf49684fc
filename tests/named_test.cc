// Named access (simlab/named.h) and the support functions (simlab/support.h): views
// slice the right rows and write through; names are found by hash exactly as by a scan;
// state vectors round-trip; M from FullM agrees with MulM; Jacobians map qvel to the
// velocity of the frame.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "simlab/named.h"
#include "simlab/simlab.h"
#include "simlab/support.h"
#include "test_files.h"

namespace simlab {
namespace {

constexpr auto Path = test_util::SourcePath;

Model Gantry() { return LoadXml(Path("models/gantry_gripper.xml")); }

// A chain with a free, a ball, a slide and a hinge joint, and a site at its tip.
Model Chain() {
  return LoadXmlString(R"(
    <mujoco>
      <worldbody>
        <body name="base" pos="0 0 1">
          <freejoint name="free"/>
          <geom size="0.1"/>
          <body name="arm" pos="0.2 0 0">
            <joint name="ball" type="ball"/>
            <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
            <body name="slider" pos="0.3 0 0">
              <joint name="slide" type="slide" axis="1 0 0"/>
              <geom size="0.05"/>
              <body name="tip" pos="0.1 0 0">
                <joint name="hinge" axis="0 1 0"/>
                <geom type="box" size="0.05 0.02 0.02"/>
                <site name="tip" pos="0.1 0.02 0"/>
              </body>
            </body>
          </body>
        </body>
      </worldbody>
    </mujoco>)");
}

TEST(Named, JointViewsSliceQposAndDofsByType) {
  Model m = Chain();
  Data d = MakeData(m);
  const int nq[] = {7, 4, 1, 1}, nv[] = {6, 3, 1, 1};
  for (int j = 0; j < m.njnt; j++) {
    Named joint = DataObject(m, d, kObjJoint, j);
    EXPECT_EQ(joint["qpos"].size(), static_cast<size_t>(nq[j]));
    EXPECT_EQ(joint["qpos"].Doubles().data(), &d.qpos[m.jnt_qposadr[j]]);
    EXPECT_EQ(joint["qvel"].size(), static_cast<size_t>(nv[j]));
    EXPECT_EQ(joint["cdof"].ndim, 2);
    EXPECT_EQ(joint["cdof"].shape[0], nv[j]);
    EXPECT_EQ(joint["cdof"].shape[1], 6);
  }
  // Writes go through.
  DataObject(m, d, kObjJoint, "hinge")["qpos"][0] = 0.5;
  EXPECT_EQ(d.qpos[m.nq - 1], 0.5);
}

TEST(Named, ViewsHaveTheTablesAttributesUnderMujocosNames) {
  Model m = Gantry();
  Data d = MakeData(m);
  Named grip = ModelObject(m, kObjActuator, "gripper/grip");
  EXPECT_EQ(grip.id(), 3);
  EXPECT_EQ(grip["gainprm"][0], 500);
  EXPECT_STREQ(grip["gainprm"].field, "actuator_gainprm");
  EXPECT_EQ(grip["trntype"].Ints()[0], kTrnTendon);
  EXPECT_NE(ModelObject(m, kObjTendon, 0).Find("_range"), nullptr);  // MuJoCo's tendon names
  EXPECT_EQ(ModelObject(m, kObjKey, "home")["qpos"].size(), static_cast<size_t>(m.nq));
  Named force = DataObject(m, d, kObjActuator, 3);
  std::vector<std::string> attrs;
  for (const Slice& s : force.attributes()) attrs.push_back(s.attr);
  EXPECT_EQ(attrs, (std::vector<std::string>{"ctrl", "length", "moment", "velocity", "force"}));
  EXPECT_EQ(DataObject(m, d, kObjGeom, "cube")["xpos"].size(), 3u);
  EXPECT_EQ(DataObject(m, d, kObjTendon, 0)["J"].size(), static_cast<size_t>(m.nv));
}

TEST(Named, UnknownNamesAndIndicesAreClearErrors) {
  Model m = Gantry();
  Data d = MakeData(m);
  try {
    ModelObject(m, kObjActuator, "grip");
    FAIL() << "no error";
  } catch (const UnknownName& e) {
    EXPECT_STREQ(e.what(), "Invalid name 'grip'. Valid names: ['gripper/grip', 'x', 'y', 'z']");
  }
  EXPECT_THROW(DataObject(m, d, kObjJoint, m.njnt), BadIndex);
  EXPECT_THROW(DataObject(m, d, kObjJoint, -1), BadIndex);
  EXPECT_THROW(DataObject(m, d, kObjEquality, 0), BadIndex);  // no data view for equalities
  EXPECT_THROW(ModelObject(m, kObjActuator, 0)["nonsense"], BadIndex);
  EXPECT_THROW(ModelObject(m, kObjActuator, 0)["trntype"].Doubles(), BadIndex);
}

TEST(Named, HashedNamesAgreeWithAScan) {
  Model m = LoadXml(std::string(SIMLAB_SOURCE_DIR) +
                    "/../shared/corpus/mujoco/model/humanoid/humanoid.xml");
  for (ObjType kind : {kObjBody, kObjJoint, kObjGeom, kObjActuator, kObjSite, kObjKey}) {
    const std::vector<std::string>& names = *m.Names(kind);
    for (size_t i = 0; i < names.size(); i++) {
      if (names[i].empty()) continue;
      size_t first = 0;
      while (names[first] != names[i]) first++;
      EXPECT_EQ(m.NameToId(kind, names[i]), static_cast<int>(first)) << names[i];
    }
    EXPECT_EQ(m.NameToId(kind, "no such name"), -1);
  }
  Model by_hand = m;
  by_hand.name_index.clear();  // a model without the tables falls back to a scan
  EXPECT_EQ(by_hand.NameToId(kObjBody, "torso"), m.NameToId(kObjBody, "torso"));
}

TEST(Support, StateVectorsRoundTrip) {
  Model m = Gantry();
  Data d = MakeData(m);
  ResetDataKeyframe(m, d, 0);
  for (int i = 0; i < 50; i++) Step(m, d);
  ASSERT_EQ(StateSize(m, kStateFullPhysics), 1 + m.nq + m.nv + m.na + m.nhistory);
  ASSERT_EQ(StateSize(m, kStateIntegration),
            1 + m.nq + m.nv + m.na + m.nhistory + m.nv + m.nu + m.nv + 6 * m.nbody + m.neq +
                7 * m.nmocap);
  std::vector<double> state(StateSize(m, kStateIntegration));
  GetState(m, d, state.data(), kStateIntegration);
  Data other = MakeData(m);
  SetState(m, other, state.data(), kStateIntegration);
  // Stepping both gives the same numbers.
  for (int i = 0; i < 50; i++) Step(m, d), Step(m, other);
  EXPECT_EQ(d.qpos, other.qpos);
  EXPECT_EQ(d.qvel, other.qvel);
  EXPECT_THROW(StateSize(m, 1 << kNStateBits), Error);
  EXPECT_THROW(StateSize(m, -1), Error);
}

TEST(Support, FullMAgreesWithMulM) {
  Model m = Chain();
  Data d = MakeData(m);
  for (int i = 0; i < m.nq; i++) d.qpos[i] += 0.1 * (i + 1);
  Forward(m, d);
  std::vector<double> full(m.nv * m.nv), column(m.nv), unit(m.nv);
  FullM(m, full.data(), d.qM.data());
  for (int j = 0; j < m.nv; j++) {
    std::fill(unit.begin(), unit.end(), 0.0);
    unit[j] = 1;
    MulM(m, d, column.data(), unit.data());
    for (int i = 0; i < m.nv; i++) {
      EXPECT_NEAR(full[i * m.nv + j], column[i], 1e-12);
      EXPECT_EQ(full[i * m.nv + j], full[j * m.nv + i]);
    }
  }
}

TEST(Support, SiteJacobianMapsQvelToTheSitesVelocity) {
  Model m = Chain();
  Data d = MakeData(m);
  for (int i = 0; i < m.nv; i++) d.qvel[i] = 0.3 - 0.1 * i;
  Forward(m, d);
  int site = m.NameToId(kObjSite, "tip");
  std::vector<double> jacp(3 * m.nv), jacr(3 * m.nv);
  JacSite(m, d, jacp.data(), jacr.data(), site);
  // Finite difference of the site's position along qvel.
  const double h = 1e-7;
  std::vector<double> before(&d.site_xpos[3 * site], &d.site_xpos[3 * site] + 3);
  Data moved = d;
  IntegratePos(m, moved.qpos.data(), d.qvel.data(), h);
  Forward(m, moved);
  for (int k = 0; k < 3; k++) {
    double v = 0;
    for (int i = 0; i < m.nv; i++) v += jacp[k * m.nv + i] * d.qvel[i];
    EXPECT_NEAR(v, (moved.site_xpos[3 * site + k] - before[k]) / h, 1e-5);
  }
}

}  // namespace
}  // namespace simlab
