// Passive forces (MuJoCo mj_passive): joint springs toward qpos_spring, dof dampers,
// tendon springs (with a dead band [lower, upper]) and dampers.
//
// Gravity compensation (MuJoCo mj_gravcomp): each body with gravcomp g feels the force
// -g * mass * gravity at its centre of mass, into qfrc_gravcomp. A dof of a joint with
// actuatorgravcomp takes that force as actuator force (actuation.cc) instead of passive.
//
// Actuator damping (MuJoCo 3.7+) joins the damping of its joint or tendon, scaled by
// gear^2, with higher-order terms: force = -v (b + p0 |v| + p1 v^2).
#include <algorithm>
#include <cmath>

#include "engine/actuator_target.h"
#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/flex_elasticity.h"
#include "engine/rows.h"
#include "engine/sleep.h"

#include "math/math.h"

namespace simlab {

namespace {

// Spring force of joint j toward its spring reference, into qfrc_spring.
void JointSpring(const Model& m, Data& d, int j) {
  double k = m.jnt_stiffness[j];
  int padr = m.jnt_qposadr[j], dadr = m.jnt_dofadr[j];
  switch (m.jnt_type[j]) {
    case kJointFree:
      for (int t = 0; t < 3; t++) {
        d.qfrc_spring[dadr + t] = -k * (d.qpos[padr + t] - m.qpos_spring[padr + t]);
      }
      padr += 3;
      dadr += 3;
      [[fallthrough]];
    case kJointBall: {
      // The rotation from the reference to the current orientation, as a vector.
      double quat[4], dif[3];
      math::CopyQuat(quat, &d.qpos[padr]);
      math::NormalizeQuat(quat);
      math::SubQuat(dif, quat, &m.qpos_spring[padr]);
      for (int t = 0; t < 3; t++) d.qfrc_spring[dadr + t] = -k * dif[t];
      break;
    }
    default:
      d.qfrc_spring[dadr] = -k * (d.qpos[padr] - m.qpos_spring[padr]);
  }
}

// Spring and damper of tendon i (its own and its actuators' damping), mapped to joint
// space by its Jacobian.
void TendonSpringDamper(const Model& m, Data& d, int i, bool spring, bool damper) {
  double stiffness = spring ? m.tendon_stiffness[i] : 0;
  double poly[kNPoly] = {0, 0};
  double damping = damper ? m.tendon_damping[i] + ActuatorDamping(m, true, i, poly) : 0;
  if (stiffness == 0 && damping == 0 && poly[0] == 0 && poly[1] == 0) return;
  double length = d.ten_length[i];
  double lower = m.tendon_lengthspring[2 * i], upper = m.tendon_lengthspring[2 * i + 1];
  double f_spring = 0;
  if (length > upper) {
    f_spring = stiffness * (upper - length);
  } else if (length < lower) {
    f_spring = stiffness * (lower - length);
  }
  double vel = d.ten_velocity[i];
  double f_damper = -vel * DampingCoefficient(damping, poly, vel);
  const double* jac = RowOf(d.ten_J, i, m.nv);
  const int* cols = RowOf(d.ten_J_colind, i, m.nv);
  for (int k = 0; k < d.ten_J_rownnz[i]; k++) {
    int v = cols[k];
    if (f_spring != 0) d.qfrc_spring[v] += jac[v] * f_spring;
    if (f_damper != 0) d.qfrc_damper[v] += jac[v] * f_damper;
  }
}

// qfrc_gravcomp from every body with gravcomp (the caller checks GravcompActive).
void GravityCompensation(const Model& m, Data& d) {
  const double torque[3] = {0, 0, 0};
  for (int b = 1; b < m.nbody; b++) {
    if (m.body_gravcomp[b] == 0) continue;
    double scale = -m.body_mass[b] * m.body_gravcomp[b], force[3];
    for (int k = 0; k < 3; k++) force[k] = scale * m.opt.gravity[k];
    ApplyForceTorque(m, d, force, torque, &d.xipos[3 * b], b, d.qfrc_gravcomp.data());
  }
}

}  // namespace

bool GravcompActive(const Model& m) {
  // A gravity whose norm underflows to zero counts as none, as in MuJoCo.
  if ((m.opt.disableflags & kDisableGravity) || math::Norm3(m.opt.gravity.data()) == 0) {
    return false;
  }
  // Only positive gravcomp values switch the feature on (MuJoCo's ngravcomp).
  return m.ngravcomp > 0;
}

void AddActuatorGravcomp(const Model& m, Data& d) {
  if (!GravcompActive(m)) return;
  for (int v = 0; v < m.nv; v++) {
    if (m.jnt_actgravcomp[m.dof_jntid[v]]) d.qfrc_actuator[v] += d.qfrc_gravcomp[v];
  }
}

double ActuatorDamping(const Model& m, bool tendon, int id, double poly[kNPoly]) {
  double damping = 0;
  ForTargetActuators(m, tendon, id, [&](int i, double gear2) {
    damping += m.actuator_damping[i] * gear2;
    for (int k = 0; k < kNPoly; k++) poly[k] += m.actuator_dampingpoly[kNPoly * i + k] * gear2;
  });
  return damping;
}

double DampingCoefficient(double linear, const double poly[kNPoly], double v) {
  double speed = std::abs(v), power = 1, coef = linear;
  for (int k = 0; k < kNPoly; k++) {
    power *= speed;
    coef += poly[k] * power;
  }
  return coef;
}

double DampingSlope(double linear, const double poly[kNPoly], double v) {
  double speed = std::abs(v), power = 1, slope = linear;
  for (int k = 0; k < kNPoly; k++) {
    power *= speed;
    slope += (k + 2) * poly[k] * power;
  }
  return slope;
}

namespace {

// Springs, dampers, fluid forces and gravity compensation of every dof.
void PassiveForces(const Model& m, Data& d) {
  std::fill(d.qfrc_spring.begin(), d.qfrc_spring.end(), 0.0);
  std::fill(d.qfrc_damper.begin(), d.qfrc_damper.end(), 0.0);
  std::fill(d.qfrc_passive.begin(), d.qfrc_passive.end(), 0.0);
  std::fill(d.qfrc_gravcomp.begin(), d.qfrc_gravcomp.end(), 0.0);
  bool spring = !(m.opt.disableflags & kDisableSpring);
  bool damper = !(m.opt.disableflags & kDisableDamper);
  if (!spring && !damper) return;

  // Joint springs and dof dampers.
  if (spring) {
    for (int j = 0; j < m.njnt; j++) {
      if (m.jnt_stiffness[j] != 0) JointSpring(m, d, j);
    }
  }
  if (damper) {
    for (int v = 0; v < m.nv; v++) {
      double poly[kNPoly] = {0, 0};
      double damping = m.dof_damping[v] + ActuatorDamping(m, false, m.dof_jntid[v], poly);
      if (damping == 0 && poly[0] == 0 && poly[1] == 0) continue;
      d.qfrc_damper[v] = -d.qvel[v] * DampingCoefficient(damping, poly, d.qvel[v]);
    }
  }

  // Flexes: their elasticity, then their edges' own springs and dampers.
  if (m.nflex) {
    FlexElasticForces(m, d, spring, damper);
    FlexEdgeSpringDamper(m, d, spring, damper);
  }

  // Tendon springs and dampers.
  for (int i = 0; i < m.ntendon; i++) TendonSpringDamper(m, d, i, spring, damper);

  // Contacts of passive flexes push as springs.
  if (m.nflex) PassiveContactForces(m, d);

  for (int v = 0; v < m.nv; v++) d.qfrc_passive[v] = d.qfrc_spring[v] + d.qfrc_damper[v];
  FluidForces(m, d);

  // Gravity compensation: passive, except on joints that route it through actuation.
  if (GravcompActive(m)) {
    GravityCompensation(m, d);
    for (int v = 0; v < m.nv; v++) {
      if (!m.jnt_actgravcomp[m.dof_jntid[v]]) d.qfrc_passive[v] += d.qfrc_gravcomp[v];
    }
  }
}

}  // namespace

void Passive(const Model& m, Data& d) {
  // (a sleeping tree's passive forces stay as they were when it fell asleep)
  StackFrame frame(d);
  SleepingDofValues kept(m, d, frame, {d.qfrc_spring.data(), d.qfrc_damper.data(), d.qfrc_passive.data(),
                                       d.qfrc_gravcomp.data(), d.qfrc_fluid.data()});
  PassiveForces(m, d);
  kept.Restore();
  // Passive-force plugins add theirs last.
  PluginPassiveForces(m, d);
}

}  // namespace simlab
