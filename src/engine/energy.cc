// Potential and kinetic energy (MuJoCo mj_energyPos, mj_energyVel).
//
//   energy[0] = -sum_b m_b g . xipos_b + sum over joints k/2 |q - q_spring|^2
//               + sum over tendons k/2 (length outside lengthspring)^2
//               + sum over the edges of cables (1D flexes) k/2 (length - length0)^2
//   energy[1] = qvel' M qvel / 2
//
// Forward computes them when the energy flag is enabled; the e_potential and e_kinetic
// sensors ask for them when they have not been computed this step.
#include "engine/engine.h"
#include "engine/stack.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// Potential of gravity: bodies' masses at their centres of mass.
double GravityPotential(const Model& m, const Data& d) {
  double energy = 0;
  if (m.opt.disableflags & kDisableGravity) return energy;
  for (int b = 1; b < m.nbody; b++) energy -= m.body_mass[b] * Dot3(m.opt.gravity.data(), &d.xipos[3 * b]);
  return energy;
}

// Adds one joint's spring energy: translations by distance, rotations by the angle of
// the quaternion difference (taken from qpos as stored, as MuJoCo does).
void AddJointSpringEnergy(const Model& m, const Data& d, int j, double* energy) {
  double k = m.jnt_stiffness[j];
  int adr = m.jnt_qposadr[j];
  const double* q = &d.qpos[adr];
  const double* q0 = &m.qpos_spring[adr];
  double dif[3];
  switch (m.jnt_type[j]) {
    case kJointFree:
      Sub3(dif, q, q0);
      *energy += 0.5 * k * Dot3(dif, dif);
      SubQuat(dif, q + 3, q0 + 3);
      *energy += 0.5 * k * Dot3(dif, dif);
      break;
    case kJointBall:
      SubQuat(dif, q, q0);
      *energy += 0.5 * k * Dot3(dif, dif);
      break;
    default:
      *energy += 0.5 * k * (q[0] - q0[0]) * (q[0] - q0[0]);
  }
}

// Spring energy of one tendon: only the length outside [lower, upper] stretches it.
double TendonSpringEnergy(const Model& m, const Data& d, int i) {
  double length = d.ten_length[i];
  double lower = m.tendon_lengthspring[2 * i], upper = m.tendon_lengthspring[2 * i + 1];
  double stretch = 0;
  if (length > upper) {
    stretch = upper - length;
  } else if (length < lower) {
    stretch = lower - length;
  }
  return 0.5 * m.tendon_stiffness[i] * stretch * stretch;
}

// Spring energy of a cable's (1D flex's) edges that can stretch, at its edge stiffness;
// 2D and 3D flexes' elasticity has no energy here, as in MuJoCo. Added edge by edge.
void AddCableSpringEnergy(const Model& m, const Data& d, int f, double* energy) {
  double k = m.flex_edgestiffness[f];
  if (m.flex_rigid[f] || k == 0 || m.flex_dim[f] > 1) return;
  for (int e = m.flex_edgeadr[f]; e < m.flex_edgeadr[f] + m.flex_edgenum[f]; e++) {
    if (m.flexedge_rigid[e]) continue;
    double stretch = m.flexedge_length0[e] - d.flexedge_length[e];
    *energy += 0.5 * k * stretch * stretch;
  }
}

}  // namespace

void EnergyPos(const Model& m, Data& d) {
  d.energy[0] = GravityPotential(m, d);
  if (!(m.opt.disableflags & kDisableSpring)) {
    // Joints are numbered body by body, so this is MuJoCo's order.
    for (int j = 0; j < m.njnt; j++) {
      if (m.jnt_stiffness[j] != 0) AddJointSpringEnergy(m, d, j, &d.energy[0]);
    }
    for (int i = 0; i < m.ntendon; i++) d.energy[0] += TendonSpringEnergy(m, d, i);
    for (int f = 0; f < m.nflex; f++) AddCableSpringEnergy(m, d, f, &d.energy[0]);
  }
  d.flg_energypos = true;
}

void EnergyVel(const Model& m, Data& d) {
  StackFrame frame(d);
  double* mv = frame.Alloc(m.nv);
  MulSymLayout(m.nv, m.M_rownnz.data(), m.M_rowadr.data(), m.M_colind.data(), d.M.data(),
               d.qvel.data(), mv);
  d.energy[1] = 0.5 * Dot(mv, d.qvel.data(), m.nv);
  d.flg_energyvel = true;
}

}  // namespace simlab
