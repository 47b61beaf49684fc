// Mouse perturbation (simlab/perturb.h), as MuJoCo's mjv_initPerturb and
// mjv_applyPerturbForce: springs with critical damping from a point of the selected body
// to a reference point, and from its orientation to a reference one.
#include "simlab/perturb.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/engine.h"
#include "engine/sensor.h"
#include "math/math.h"
#include "simlab/support.h"

namespace simlab {

namespace {

// 3 / trace(J M^-1 J^T): the mass the selection point moves with (1 when it cannot move).
double LocalMass(const Model& m, Data& d, const double point[3], int body) {
  std::vector<double> jac(3 * m.nv), x(m.nv);
  Jac(m, d, jac.data(), nullptr, point, body);
  double invmass = 0;
  for (int k = 0; k < 3; k++) {
    const double* row = &jac[k * m.nv];
    std::copy(row, row + m.nv, x.begin());
    SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), x.data());
    for (int i = 0; i < m.nv; i++) invmass += row[i] * x[i];
  }
  return invmass == 0 ? 1 : 3 / std::max(invmass, kMinVal);
}

}  // namespace

void PerturbSelectionPoint(const Data& d, const Perturb& p, double out[3]) {
  math::MulMatVec3(out, &d.xmat[9 * p.select], p.localpos.data());
  math::Add3(out, out, &d.xpos[3 * p.select]);
}

void InitPerturb(const Model& m, Data& d, Perturb* p) {
  if (p->select <= 0 || p->select >= m.nbody) return;
  double selpos[3];
  PerturbSelectionPoint(d, *p, selpos);
  p->localmass = LocalMass(m, d, selpos, p->select);
  ObjectQuat(m, d, kObjBody, p->select, p->refquat.data());  // (its inertia frame)
  math::Copy3(p->refselpos.data(), selpos);
}

void ApplyPerturbForce(const Model& m, Data& d, const Perturb& p) {
  if (p.select <= 0 || p.select >= m.nbody || !p.active) return;
  double* force = &d.xfrc_applied[6 * p.select];
  double* torque = force + 3;
  std::fill(force, force + 6, 0.0);
  double vel[6];  // (angular, linear) at the body's frame, world orientation
  ObjectVelocity(m, d, kObjBody, p.select, vel, false);
  double invweight = m.body_invweight0[2 * p.select + 1];
  double inertia = invweight ? 1 / std::max(kMinVal, invweight) : 1;

  // Translation: spring and damper at the selection point, and the torque they make
  // about the centre of mass, with the spin about the pull damped.
  if (p.active & kPerturbTranslate) {
    double selpos[3], diff[3], arm[3], pointvel[3];
    PerturbSelectionPoint(d, p, selpos);
    math::Sub3(diff, selpos, p.refselpos.data());
    double k = m.vis.map.stiffness;
    for (int i = 0; i < 3; i++) force[i] = -k * p.localmass * diff[i];
    math::Sub3(arm, selpos, &d.xipos[3 * p.select]);
    math::Cross3(pointvel, vel, arm);
    math::Add3(pointvel, pointvel, vel + 3);
    for (int i = 0; i < 3; i++) force[i] -= std::sqrt(k) * p.localmass * pointvel[i];
    math::Cross3(torque, arm, force);
    math::Normalize3(diff);
    double spin = math::Dot3(diff, vel);
    for (int i = 0; i < 3; i++) torque[i] -= std::sqrt(m.vis.map.stiffnessrot) * inertia * spin * diff[i];
  }

  // Rotation: a spring towards refquat, with critical damping.
  if (p.active & kPerturbRotate) {
    double k = m.vis.map.stiffnessrot;
    double current[4], difference[4];
    ObjectQuat(m, d, kObjBody, p.select, current);
    math::NegQuat(current, current);
    math::MulQuat(difference, p.refquat.data(), current);
    math::QuatToVel(torque, difference, 1 / (k * inertia));
    for (int i = 0; i < 3; i++) torque[i] -= std::sqrt(k) * inertia * vel[i];
  }
}

}  // namespace simlab
