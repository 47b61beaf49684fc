// Invariants of the dynamics, one algorithm checked against another:
// the CRBA mass matrix against RNE column by column, the sparse L^T D L solve against
// M, energy conservation, exact quaternion integration, and divergence handling.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

std::string Corpus(const std::string& p) {
  return std::string(SIMLAB_SOURCE_DIR) + "/../shared/corpus/mujoco/" + p;
}

// Dense M (nv x nv) from its sparse lower triangle.
std::vector<double> DenseM(const Model& m, const Data& d) {
  std::vector<double> dense(m.nv * m.nv, 0.0);
  for (int i = 0; i < m.nv; i++) {
    for (int adr = m.M_rowadr[i]; adr < m.M_rowadr[i] + m.M_rownnz[i]; adr++) {
      int j = m.M_colind[adr];
      dense[i * m.nv + j] = dense[j * m.nv + i] = d.M[adr];
    }
  }
  return dense;
}

// A deterministic, nontrivial state: every joint moved and moving.
void ScrambleState(const Model& m, Data& d) {
  for (int v = 0; v < m.nv; v++) d.qvel[v] = 0.3 * std::sin(1.7 * v + 0.4);
  IntegratePos(m, d.qpos.data(), d.qvel.data(), 1.0);
}

TEST(EngineInvariants, CrbaMassMatrixEqualsRneColumns) {
  Model m = LoadXml(Corpus("model/humanoid/humanoid.xml"));
  Data d = MakeData(m);
  ScrambleState(m, d);
  Forward(m, d);
  std::vector<double> dense = DenseM(m, d);

  // RNE with qacc = e_j, minus RNE with qacc = 0 and no velocity, is column j of M.
  Data z = d;
  std::fill(z.qvel.begin(), z.qvel.end(), 0.0);
  Forward(m, z);
  std::vector<double> base(m.nv), col(m.nv);
  std::fill(z.qacc.begin(), z.qacc.end(), 0.0);
  Rne(m, z, true, base.data());
  for (int j = 0; j < m.nv; j++) {
    std::fill(z.qacc.begin(), z.qacc.end(), 0.0);
    z.qacc[j] = 1;
    Rne(m, z, true, col.data());
    for (int i = 0; i < m.nv; i++) {
      double armature = (i == j) ? m.dof_armature[i] : 0;
      EXPECT_NEAR(col[i] - base[i] + armature, dense[i * m.nv + j], 1e-12) << i << "," << j;
    }
  }
}

TEST(EngineInvariants, SparseFactorizationSolvesM) {
  Model m = LoadXml(Corpus("model/humanoid/humanoid.xml"));
  Data d = MakeData(m);
  ScrambleState(m, d);
  Forward(m, d);
  std::vector<double> dense = DenseM(m, d);
  std::vector<double> x(m.nv), b(m.nv, 0.0);
  for (int i = 0; i < m.nv; i++) x[i] = std::cos(0.9 * i);
  for (int i = 0; i < m.nv; i++) {
    for (int j = 0; j < m.nv; j++) b[i] += dense[i * m.nv + j] * x[j];
  }
  SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), b.data());
  for (int i = 0; i < m.nv; i++) EXPECT_NEAR(b[i], x[i], 1e-10);
}

// Kinetic plus gravitational potential energy.
double Energy(const Model& m, const Data& d) {
  std::vector<double> dense = DenseM(m, d);
  double kinetic = 0, potential = 0;
  for (int i = 0; i < m.nv; i++) {
    for (int j = 0; j < m.nv; j++) kinetic += 0.5 * d.qvel[i] * dense[i * m.nv + j] * d.qvel[j];
  }
  for (int b = 1; b < m.nbody; b++) {
    for (int k = 0; k < 3; k++) potential -= m.body_mass[b] * m.opt.gravity[k] * d.xipos[3 * b + k];
  }
  return kinetic + potential;
}

TEST(EngineInvariants, Rk4ConservesEnergyWithoutDamping) {
  Model m = LoadXmlString(R"(
    <mujoco><option integrator="RK4" timestep="0.001"/>
      <worldbody><body pos="0 0 1">
        <joint type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.3 0 -0.3" size="0.03"/>
        <body pos="0.3 0 -0.3"><joint type="hinge" axis="1 0 1"/>
          <geom type="box" pos="0.1 0 -0.1" size="0.05 0.02 0.1"/></body>
      </body></worldbody></mujoco>)");
  Data d = MakeData(m);
  d.qvel[0] = 2;
  d.qvel[1] = -3;
  Forward(m, d);
  double e0 = Energy(m, d);
  for (int i = 0; i < 2000; i++) Step(m, d);
  Forward(m, d);
  EXPECT_NEAR(Energy(m, d), e0, 1e-6 * std::abs(e0) + 1e-9);
}

TEST(EngineInvariants, SphereSpinsAtConstantRate) {
  // A free sphere without gravity keeps its angular velocity; its orientation after
  // time t is the rotation by w t exactly (up to integration of a constant rate).
  Model m = LoadXmlString(R"(
    <mujoco><option gravity="0 0 0" timestep="0.01"/>
      <worldbody><body><freejoint/><geom type="sphere" size="0.1"/></body></worldbody>
    </mujoco>)");
  Data d = MakeData(m);
  double w[3] = {0.3, -0.4, 1.2};
  for (int k = 0; k < 3; k++) d.qvel[3 + k] = w[k];
  for (int i = 0; i < 100; i++) Step(m, d);
  double norm = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  double half = 0.5 * norm * d.time;
  EXPECT_NEAR(d.qpos[3], std::cos(half), 1e-12);
  for (int k = 0; k < 3; k++) EXPECT_NEAR(d.qpos[4 + k], w[k] / norm * std::sin(half), 1e-12);
}

TEST(EngineInvariants, DivergenceWarnsAndResets) {
  Model m = LoadXmlString(R"(
    <mujoco><worldbody><body><joint type="slide" axis="0 0 1"/>
      <geom type="sphere" size="0.1"/></body></worldbody></mujoco>)");
  Data d = MakeData(m);
  d.qvel[0] = std::nan("");
  d.time = 1;
  Step(m, d);
  EXPECT_EQ(d.warning[kWarnBadQvel].number, 1);
  EXPECT_EQ(d.nreset, 1);
  EXPECT_FALSE(std::isnan(d.qvel[0]));
  EXPECT_NEAR(d.time, m.opt.timestep, 1e-15);  // reset to 0, then one step
}

}  // namespace
}  // namespace simlab
