// Velocity stage and inverse dynamics: com-based velocities and the recursive
// Newton-Euler algorithm (Featherstone; MuJoCo mj_comVel, mj_rne).
//
// cvel(body) = cvel(parent) + sum cdof * qvel;  cdof_dot = cvel x cdof (the rate of
// change of a motion axis carried by its body). RNE: body accelerations
// cacc = cacc(parent) + cdof_dot*qvel [+ cdof*qacc], with the world accelerating at
// -gravity so that gravity appears as an inertial force; body forces
// f = I cacc + cvel x* (I cvel), accumulated leaves to root; qfrc = cdof . f.
#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/stack.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// cvel += sum over n dofs of cdof * qvel (summed first, then added, as MuJoCo does).
void AddDofVelocity(double* cvel, const double* cdof, const double* qvel, int n) {
  double sum[6] = {0, 0, 0, 0, 0, 0};
  for (int t = 0; t < n; t++) {
    for (int r = 0; r < 6; r++) sum[r] += cdof[6 * t + r] * qvel[t];
  }
  for (int r = 0; r < 6; r++) cvel[r] += sum[r];
}

// cdof_dot = cvel x cdof for n consecutive dofs.
void DofDerivatives(double* cdof_dot, const double* cvel, const double* cdof, int n) {
  for (int t = 0; t < n; t++) CrossMotion(cdof_dot + 6 * t, cvel, cdof + 6 * t);
}

}  // namespace

void ComVel(const Model& m, Data& d) {
  for (int k = 0; k < 6; k++) d.cvel[k] = 0;
  for (int i = 1; i < m.nbody; i++) {
    double cvel[6];
    for (int k = 0; k < 6; k++) cvel[k] = d.cvel[6 * m.body_parentid[i] + k];

    // Each joint: its axes' rates of change from the velocity so far, then its motion.
    int end = m.body_dofadr[i] + m.body_dofnum[i];
    for (int j = m.body_dofadr[i]; j < end;) {
      const double* cdof = &d.cdof[6 * j];
      double* cdof_dot = &d.cdof_dot[6 * j];
      switch (m.jnt_type[m.dof_jntid[j]]) {
        case kJointFree:
          // World-fixed translation axes do not change; then three rotations.
          for (int k = 0; k < 18; k++) cdof_dot[k] = 0;
          AddDofVelocity(cvel, cdof, &d.qvel[j], 3);
          DofDerivatives(cdof_dot + 18, cvel, cdof + 18, 3);
          AddDofVelocity(cvel, cdof + 18, &d.qvel[j + 3], 3);
          j += 6;
          break;
        case kJointBall:
          DofDerivatives(cdof_dot, cvel, cdof, 3);
          AddDofVelocity(cvel, cdof, &d.qvel[j], 3);
          j += 3;
          break;
        default:
          DofDerivatives(cdof_dot, cvel, cdof, 1);
          AddDofVelocity(cvel, cdof, &d.qvel[j], 1);
          j += 1;
      }
    }
    for (int k = 0; k < 6; k++) d.cvel[6 * i + k] = cvel[k];
  }
}

void RneBodyStep(const Model& m, const Data& d, int body, bool flg_acc, double* cacc,
                 double* cfrc_body) {
  double* a = cacc + 6 * body;
  for (int k = 0; k < 6; k++) a[k] = cacc[6 * m.body_parentid[body] + k];
  // The body's dofs add their terms (a zero sum for a body without dofs).
  int adr = m.body_dofadr[body], num = m.body_dofnum[body];
  AddDofVelocity(a, DofRows(d.cdof_dot, adr, 6, num), DofRows(d.qvel, adr, 1, num), num);
  if (flg_acc) AddDofVelocity(a, DofRows(d.cdof, adr, 6, num), DofRows(d.qacc, adr, 1, num), num);
  double momentum[6], gyro[6];
  MulInertVec(cfrc_body, &d.cinert[10 * body], a);
  MulInertVec(momentum, &d.cinert[10 * body], &d.cvel[6 * body]);
  CrossForce(gyro, &d.cvel[6 * body], momentum);
  for (int k = 0; k < 6; k++) cfrc_body[k] += gyro[k];
}

void Rne(const Model& m, Data& d, bool flg_acc, double* result) {
  StackFrame frame(d);
  double* cacc = frame.Alloc(6 * m.nbody);
  double* cfrc = frame.Alloc(6 * m.nbody);

  // The world accelerates upward at g: gravity as an inertial force.
  if (!(m.opt.disableflags & kDisableGravity)) Scale3(cacc + 3, m.opt.gravity.data(), -1);

  // Forward pass: body accelerations and the forces they need.
  for (int i = 1; i < m.nbody; i++) RneBodyStep(m, d, i, flg_acc, cacc, cfrc + 6 * i);

  // Backward pass: children's forces act on their parents.
  for (int i = m.nbody - 1; i > 0; i--) {
    int parent = m.body_parentid[i];
    if (parent > 0) {
      for (int k = 0; k < 6; k++) cfrc[6 * parent + k] += cfrc[6 * i + k];
    }
  }

  // Project onto the dofs (summed in mju_dot's order).
  for (int v = 0; v < m.nv; v++) {
    result[v] = Dot6(&d.cdof[6 * v], cfrc + 6 * m.dof_bodyid[v]);
  }
}

// Tendon armature a turns the tendon's acceleration J qacc + Jdot qvel into a force
// along J; the Jdot qvel part is a bias (MuJoCo mj_tendonBias).
void TendonBias(const Model& m, Data& d, double* qfrc) {
  StackFrame frame(d);
  double* jdot = nullptr;
  for (int i = 0; i < m.ntendon; i++) {
    double armature = m.tendon_armature[i] + ActuatorArmature(m, true, i);
    if (armature == 0) continue;
    if (!jdot) jdot = frame.Alloc(m.nv);
    TendonJacobianDot(m, d, i, jdot);
    double rate = 0;
    for (int v = 0; v < m.nv; v++) rate += jdot[v] * d.qvel[v];
    double coef = armature * rate;
    if (coef == 0) continue;
    const double* jac = RowOf(d.ten_J, i, m.nv);
    for (int v = 0; v < m.nv; v++) qfrc[v] += jac[v] * coef;
  }
}

}  // namespace simlab
