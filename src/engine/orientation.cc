// The orientation actuator (MuJoCo 3.11): a geodesic servo on SO(3) with three outputs.
//
//   transmission: the rotation of a ball joint, or of a site relative to a refsite, as a
//                 rotation vector l (the 3 lengths); the moment rows map the dofs to the
//                 angular velocity in the child frame (identity on a ball joint's dofs)
//   force:        p = kp log(q(l)^-1 q_target) + b0 + b2 l' on each of the 3 outputs, the
//                 target a rotation vector (ctrl, or act for an integrator) or a
//                 quaternion (4 controls, normalized; zero is the identity)
//   clamp:        the force's norm to forcerange[1]
//   integrator:   act' = ctrl, and after each step act is brought back to a rotation
//                 of at most pi along its own axis (the same orientation)
#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

constexpr double kPi = std::numbers::pi;

// The unit quaternion of rotation vector v.
void ExpmapToQuat(double* q, const double* v) {
  double angle = Norm3(v);
  if (angle < kTiny) {
    SetIdentityQuat(q);
    return;
  }
  double axis[3] = {v[0] / angle, v[1] / angle, v[2] / angle};
  AxisAngleToQuat(q, axis, angle);
}

// A ball joint's rotation vector; the rows are the identity on its 3 dofs.
void BallRows(const Model& m, Data& d, int o, int joint) {
  double quat[4], axis[3];
  CopyQuat(quat, &d.qpos[m.jnt_qposadr[joint]]);
  NormalizeQuat(quat);
  QuatToVel(axis, quat, 1);
  for (int k = 0; k < 3; k++) {
    int dof = m.jnt_dofadr[joint] + k;
    d.actuator_length[o + k] = axis[k];
    RowOf(d.actuator_moment, o + k, m.nv)[dof] = 1;
    RowOf(d.moment_colind, o + k, m.nv)[0] = dof;
    d.moment_rownnz[o + k] = 1;
  }
}

// A site's rotation relative to a refsite (orientations composed from the bodies'
// quaternions as MuJoCo does); row k is the relative angular Jacobian projected on the
// site's axis k.
void SiteRows(const Model& m, Data& d, int o, int site, int ref) {
  int nv = m.nv;
  double quat[4], ref_quat[4], vec[3];
  MulQuat(quat, &m.site_quat[4 * site], &d.xquat[4 * m.site_bodyid[site]]);
  MulQuat(ref_quat, &m.site_quat[4 * ref], &d.xquat[4 * m.site_bodyid[ref]]);
  SubQuat(vec, quat, ref_quat);
  StackFrame frame(d);
  double* jac = frame.Alloc(3 * nv);
  double* jac_ref = frame.Alloc(3 * nv);
  JacobianSite(m, d, nullptr, jac, site);
  JacobianSite(m, d, nullptr, jac_ref, ref);
  RelativeJacobian(m, jac, jac_ref, CommonAncestorDof(m, site, ref));
  const double* mat = &d.site_xmat[9 * site];
  for (int k = 0; k < 3; k++) {
    double axis[3] = {mat[k], mat[k + 3], mat[k + 6]};
    double* row = RowOf(d.actuator_moment, o + k, nv);
    MulJacTVec(m, jac, axis, row);
    d.actuator_length[o + k] = vec[k];
    d.moment_rownnz[o + k] = NonzeroColumns(row, nv, RowOf(d.moment_colind, o + k, nv));
  }
}

}  // namespace

void So3Transmission(const Model& m, Data& d, int i) {
  int o = m.actuator_outadr[i];
  for (int k = 0; k < 3; k++) {
    ClearPattern(RowOf(d.actuator_moment, o + k, m.nv), RowOf(d.moment_colind, o + k, m.nv),
                 d.moment_rownnz[o + k]);
  }
  int id = m.actuator_trnid[2 * i], ref = m.actuator_trnid[2 * i + 1];
  if (ref < 0) {
    BallRows(m, d, o, id);
  } else {
    SiteRows(m, d, o, id, ref);
  }
}

void So3Force(const Model& m, const Data& d, int i, const double* ctrl, double* force) {
  int u = m.actuator_ctrladr[i], o = m.actuator_outadr[i];
  double target[4];
  if (m.actuator_ctrlspec[i] == kChartQuat) {
    CopyQuat(target, ctrl + u);
    NormalizeQuat(target);
  } else {
    double v[3];
    int a = m.actuator_actadr[i];
    for (int k = 0; k < 3; k++) {
      if (m.actuator_dyntype[i] == kDynNone) v[k] = ctrl[u + k];
      else if (m.actuator_actearly[i]) v[k] = NextActivation(m, d, i, a + k, d.act_dot[a + k]);
      else v[k] = d.act[a + k];
    }
    ExpmapToQuat(target, v);
  }
  // The error rotation from the current orientation to the target, in the child frame.
  double current[4], error[3];
  ExpmapToQuat(current, &d.actuator_length[o]);
  SubQuat(error, target, current);
  double kp = m.actuator_gainprm[kNGain * i];
  const double* prm = &m.actuator_biasprm[kNBias * i];
  for (int k = 0; k < 3; k++) {
    force[o + k] = kp * error[k] + prm[0] + prm[2] * d.actuator_velocity[o + k];
  }
}

void So3ClampForce(const Model& m, Data& d, int i) {
  double* f = &d.actuator_force[m.actuator_outadr[i]];
  double limit = m.actuator_forcerange[2 * i + 1], norm = Norm3(f);
  if (norm > limit) Scale3(f, f, limit / norm);
}

void So3Rewind(const Model& m, Data& d) {
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_dyntype[i] != kDynIntegrator || m.actuator_gaintype[i] != kGainSo3) continue;
    double* act = &d.act[m.actuator_actadr[i]];
    double angle = Norm3(act);
    if (angle <= kPi) continue;
    double scale = (angle - 2 * kPi * std::round(angle / (2 * kPi))) / angle;
    for (int k = 0; k < 3; k++) act[k] *= scale;
  }
}

}  // namespace simlab
