// Quantities MuJoCo computes once, at compile time, from the model at qpos0
// (mj_setConst): subtree masses, tendon and actuator lengths at qpos0, the spring
// lengths of tendons at qpos_spring, actuator_acc0 = |M^-1 moment|, and the damping of
// position actuators given by dampratio (kv = dampratio * 2 sqrt(kp * reflected mass),
// the reflected mass being sum_j M_jj / moment_j^2 over the actuated dofs).
//
// As in MuJoCo, the engine's own position stage computes them: the compiler runs
// kinematics, tendons, the mass matrix and the transmissions on a Data at qpos0.
#include <algorithm>
#include <cmath>
#include <vector>

#include "compiler/compiler.h"
#include "engine/engine.h"
#include "engine/rows.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

// Tendon spring lengths left at -1 ("use the length at qpos_spring"): on the Data of
// the constants once they are done with it (a copy of a whole Data is as large as the
// model's Data).
void TendonSpringLengths(Model* m, Data& d) {
  d.qpos = m->qpos_spring;
  Kinematics(*m, d);
  Tendon(*m, d);
  for (int t = 0; t < m->ntendon; t++) {
    if (m->tendon_lengthspring[2 * t] == -1 && m->tendon_lengthspring[2 * t + 1] == -1) {
      m->tendon_lengthspring[2 * t] = m->tendon_lengthspring[2 * t + 1] = d.ten_length[t];
    }
  }
}

// dampratio -> negative biasprm[2] for position-like actuators.
void DampRatio(Model* m, int i, const Data& d, const double* moment) {
  double* gain = &m->actuator_gainprm[kNGain * i];
  double* bias = &m->actuator_biasprm[kNBias * i];
  bool pid = m->actuator_gaintype[i] == kGainPid;
  if ((!pid && gain[0] != -bias[1]) || bias[2] <= 0) return;
  double kp = pid ? -bias[1] : gain[0];
  double reflected = 0;
  for (int v = 0; v < m->nv; v++) {
    double t2 = moment[v] * moment[v];
    double mass = d.M[m->M_rowadr[v] + m->M_rownnz[v] - 1];
    if (moment[v] != 0 && t2 > kMinVal) reflected += mass / t2;
  }
  bias[2] = -bias[2] * 2 * std::sqrt(kp * reflected);
}

}  // namespace

void SetTotalMass(double total, Model* m) {
  double current = 0;
  for (int b = 1; b < m->nbody; b++) current += m->body_mass[b];
  double scale = std::max(kMinVal, total / std::max(kMinVal, current));
  for (int b = 1; b < m->nbody; b++) {
    m->body_mass[b] *= scale;
    for (int k = 0; k < 3; k++) m->body_inertia[3 * b + k] *= scale;
  }
}

namespace {

// dof_M0: the diagonal of M at qpos0 by the composite rigid body algorithm, in MuJoCo's
// summation order; simple dofs keep it as their whole row.
void SetM0(Model* m, Data& d) {
  CompositeInertia(*m, d);
  for (int i = 0; i < m->nv; i++) {
    double buf[6];
    math::MulInertVec(buf, &d.crb[10 * m->dof_bodyid[i]], &d.cdof[6 * i]);
    m->dof_M0[i] = m->dof_armature[i] + ActuatorArmature(*m, false, m->dof_jntid[i]) +
                   math::Dot(&d.cdof[6 * i], buf, 6);
  }
}

}  // namespace

void ComputeConstants(Model* m) {
  // Subtree masses, leaves first.
  for (int b = 0; b < m->nbody; b++) m->body_subtreemass[b] = m->body_mass[b];
  for (int b = m->nbody - 1; b > 0; b--) {
    m->body_subtreemass[m->body_parentid[b]] += m->body_subtreemass[b];
  }

  // Simple bodies and the constant diagonal of their rows of M, before anything at
  // qpos0 uses M (MuJoCo mj_setM0).
  SimpleBodies(m);
  Data d = MakeData(*m);
  Kinematics(*m, d);
  ComPos(*m, d);
  SetM0(m, d);

  // Tendon lengths at qpos0 (spring lengths at qpos_spring come last).
  FwdPositionSmooth(*m, d);
  for (int t = 0; t < m->ntendon; t++) m->tendon_length0[t] = d.ten_length[t];

  // Actuators: length0, acc0 = |M^-1 moment| and the dampratio damping.
  std::vector<double> acc(m->nv);
  // (per force output; the dampratio from the first output's row, as MuJoCo)
  for (int i = 0; i < m->nactuator; i++) {
    int first = m->actuator_outadr[i], count = m->actuator_outnum[i];
    for (int o = first; o < first + count; o++) {
      const double* moment = RowOf(d.actuator_moment, o, m->nv);
      m->actuator_length0[o] = d.actuator_length[o];
      std::copy(moment, moment + m->nv, acc.begin());
      SolveSparse(*m, d.qLD.data(), d.qLDiagInv.data(), acc.data());
      m->actuator_acc0[o] = std::sqrt(math::Dot(acc.data(), acc.data(), m->nv));
    }
    DampRatio(m, i, d, RowOf(d.actuator_moment, first, m->nv));
  }

  // Inverse weights and meaninertia, from the same Data; then the spring lengths.
  ComputeInvWeights(m, d);
  TendonSpringLengths(m, d);
}

// Joints with springdamper="timeconst dampratio" get the stiffness and damping of that
// spring for the joint's mean inertia at qpos0, 1 / mean(dof_invweight0) (MuJoCo's
// AutoSpringDamper, run after the constants).
void AutoSpringDamper(const CompileState& state, Model* m) {
  for (int j = 0; j < m->njnt; j++) {
    const std::array<double, 2>& sd = state.joints[j].spec->springdamper;
    double timeconst = sd[0], dampratio = sd[1];
    if (timeconst <= 0 || dampratio <= 0) continue;
    int adr = m->jnt_dofadr[j];
    int type = m->jnt_type[j];
    int ndof = type == kJointFree ? 6 : type == kJointBall ? 3 : 1;
    double invweight = 0;
    for (int i = 0; i < ndof; i++) invweight += m->dof_invweight0[adr + i];
    double inertia = ndof / std::max(kMinVal, invweight);
    m->jnt_stiffness[j] =
        inertia / std::max(kMinVal, timeconst * timeconst * dampratio * dampratio);
    for (int i = 0; i < ndof; i++) {
      m->dof_damping[adr + i] = 2 * inertia / std::max(kMinVal, timeconst);
    }
  }
}

}  // namespace simlab::compiler
