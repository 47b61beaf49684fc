// Passive forces (MuJoCo mj_passive): joint springs toward qpos_spring, dof dampers,
// tendon springs (with a dead band [lower, upper]) and dampers.
#include "engine/engine.h"
#include <algorithm>

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

// Spring and damper of tendon i, mapped to joint space by its Jacobian.
void TendonSpringDamper(const Model& m, Data& d, int i, bool spring, bool damper) {
  double stiffness = spring ? m.tendon_stiffness[i] : 0;
  double damping = damper ? m.tendon_damping[i] : 0;
  if (stiffness == 0 && damping == 0) return;
  double length = d.ten_length[i];
  double lower = m.tendon_lengthspring[2 * i], upper = m.tendon_lengthspring[2 * i + 1];
  double f_spring = 0;
  if (length > upper) {
    f_spring = stiffness * (upper - length);
  } else if (length < lower) {
    f_spring = stiffness * (lower - length);
  }
  double f_damper = -damping * d.ten_velocity[i];
  const double* jac = &d.ten_J[static_cast<size_t>(i) * m.nv];
  for (int v = 0; v < m.nv; v++) {
    if (f_spring != 0) d.qfrc_spring[v] += jac[v] * f_spring;
    if (f_damper != 0) d.qfrc_damper[v] += jac[v] * f_damper;
  }
}

}  // namespace

void Passive(const Model& m, Data& d) {
  std::fill(d.qfrc_spring.begin(), d.qfrc_spring.end(), 0.0);
  std::fill(d.qfrc_damper.begin(), d.qfrc_damper.end(), 0.0);
  std::fill(d.qfrc_passive.begin(), d.qfrc_passive.end(), 0.0);
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
      if (m.dof_damping[v] != 0) d.qfrc_damper[v] = -m.dof_damping[v] * d.qvel[v];
    }
  }

  // Tendon springs and dampers.
  for (int i = 0; i < m.ntendon; i++) TendonSpringDamper(m, d, i, spring, damper);

  for (int v = 0; v < m.nv; v++) d.qfrc_passive[v] = d.qfrc_spring[v] + d.qfrc_damper[v];
}

}  // namespace simlab
