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

// Grows the box [lo, hi] to hold a ball of `radius` at `pos`.
void GrowBox(double lo[3], double hi[3], const double* pos, double radius) {
  for (int k = 0; k < 3; k++) {
    lo[k] = std::min(lo[k], pos[k] - radius);
    hi[k] = std::max(hi[k], pos[k] + radius);
  }
}

// How far a geom reaches for the bounding box: its bounding sphere, or a tenth of a
// plane's or height field's largest size (0.01 for an infinite plane).
double GeomReach(const Model& m, int g) {
  if (m.geom_rbound[g] > 0) return m.geom_rbound[g];
  const double* size = &m.geom_size[3 * g];
  if (m.geom_type[g] == kGeomPlane) return size[0] || size[1] ? 0.1 * std::max(size[0], size[1]) : 0.01;
  if (m.geom_type[g] == kGeomHfield) {
    const double* h = &m.hfield_size[4 * m.geom_dataid[g]];
    return 0.1 * std::max({h[0], h[1], h[2], h[3]});
  }
  return 0;
}

// The model's statistics at qpos0 (MuJoCo's setStat, without flexes): the centre and
// largest side of the box around bodies, joint anchors, sites and geoms; the mean body
// size (its farthest joint anchor or geom from its centre of mass); the mean body mass;
// the extent at least twice the mean size. <statistic> may replace them afterwards.
void ComputeStatistics(Model* m, const Data& d) {
  double lo[3] = {1e10, 1e10, 1e10}, hi[3] = {-1e10, -1e10, -1e10};
  for (int b = 1; b < m->nbody; b++) {
    GrowBox(lo, hi, &d.xpos[3 * b], 0);
    GrowBox(lo, hi, &d.xipos[3 * b], 0);
  }
  for (int j = 0; j < m->njnt; j++) GrowBox(lo, hi, &d.xanchor[3 * j], 0);
  for (int s = 0; s < m->nsite; s++) GrowBox(lo, hi, &d.site_xpos[3 * s], 0);
  for (int g = 0; g < m->ngeom; g++) GrowBox(lo, hi, &d.geom_xpos[3 * g], GeomReach(*m, g));
  for (int k = 0; k < 3; k++) m->stat.center[k] = 0.5 * (lo[k] + hi[k]);
  if (hi[0] > lo[0]) m->stat.extent = std::max(1e-5, std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}));

  // Body sizes: the farthest joint anchor (of the body and of its children) and geom.
  std::vector<double> size(m->nbody, 0.0);
  auto distance = [](const double* a, const double* b) {
    double v[3];
    math::Sub3(v, a, b);
    return math::Norm3(v);
  };
  for (int j = 0; j < m->njnt; j++) {
    for (int b : {m->jnt_bodyid[j], m->body_parentid[m->jnt_bodyid[j]]}) {
      size[b] = std::max(size[b], distance(&d.xipos[3 * b], &d.xanchor[3 * j]));
    }
  }
  size[0] = 0;
  for (int b = 1; b < m->nbody; b++) {
    for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; g++) {
      if (m->geom_rbound[g] > 0) {
        size[b] = std::max(size[b], m->geom_rbound[g] + distance(&d.xipos[3 * b], &d.geom_xpos[3 * g]));
      }
    }
  }
  FlexBodySizes(*m, d, &size);
  if (m->nbody > 1) {
    m->stat.meansize = 0;
    m->stat.meanmass = 0;
    for (int b = 1; b < m->nbody; b++) {
      m->stat.meansize += std::max(size[b], 1e-5) / (m->nbody - 1);
      m->stat.meanmass += m->body_mass[b];
    }
    m->stat.meanmass /= m->nbody - 1;
  }
  m->stat.extent = std::max(m->stat.extent, 2 * m->stat.meansize);

  // Each dof's length scale: 1 for sliding dofs, the body's size for rotating ones.
  for (int v = 0; v < m->nv; v++) {
    int j = m->dof_jntid[v];
    bool rotates = m->jnt_type[j] == kJointBall || m->jnt_type[j] == kJointHinge ||
                   (m->jnt_type[j] == kJointFree && v - m->jnt_dofadr[j] >= 3);
    m->dof_length[v] = rotates ? std::max(size[m->dof_bodyid[v]], 1e-5) : 1;
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

  // Tendon and flex edge lengths at qpos0 (spring lengths at qpos_spring come last),
  // every flex's edges measured as if it were not rigid.
  FlexJacobianSparsity(m);
  FlexAlignToPlane(m);
  std::vector<int> rigid = m->flex_rigid;
  std::fill(m->flex_rigid.begin(), m->flex_rigid.end(), 0);
  FwdPositionSmooth(*m, d);
  m->flex_rigid = rigid;
  std::copy(d.flexedge_length.begin(), d.flexedge_length.end(), m->flexedge_length0.begin());
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

  // Statistics, inverse weights and meaninertia, from the same Data; then the spring
  // lengths.
  ComputeStatistics(m, d);
  ComputeInvWeights(m, d);
  FlexEdgeInvWeights(m, d);
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
