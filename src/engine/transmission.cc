// Actuator transmissions (MuJoCo mj_transmission): each actuator's length l(q) and
// moment arms dl/dq (a row of actuator_moment, nout x nv dense, at actuator_outadr). The actuator's force p
// reaches the joints as qfrc_actuator = moment^T p.
//
//   joint (hinge/slide): l = gear0 q, moment = gear0 at the joint's dof
//   joint (ball):        l = gear . rotvec(q), moment = gear (3 dofs)
//   joint (free):        l = 0, moment = gear (6 dofs); jointinparent rotates the
//                        rotational gear into the parent (world) frame
//   tendon:              l = gear0 ten_length, moment = gear0 ten_J
//   site:                l = 0; moment = J^T (R gear): the site's Jacobian projected on
//                        the gear wrench expressed in the site frame R
//   site with refsite:   l = gear . (site pose relative to the refsite, in the refsite
//                        frame: position and rotation vector); moment = the Jacobian of
//                        that relative pose projected on the gear in the refsite frame
//   slider-crank:        l = a.v - sqrt((a.v)^2 + r^2 - v.v) for the slider axis a, the
//                        vector v from slider to crank site and the rod length r
//   body (adhesion):     l = 0, moment = minus the mean normal Jacobian of the contacts
//                        that involve the body (so Transmission runs after MakeConstraint)
//   so3 (orientation):   3 lengths and 3 rows, see orientation.cc
#include <algorithm>
#include <cmath>

#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/sleep.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

using namespace math;

// ---------------------------------------------------------------- shared with orientation.cc

// The last dof shared by the dof chains of two sites' bodies, or -1.
int CommonAncestorDof(const Model& m, int site0, int site1) {
  int b0 = m.body_weldid[m.site_bodyid[site0]], b1 = m.body_weldid[m.site_bodyid[site1]];
  int dof0 = m.body_dofadr[b0] + m.body_dofnum[b0] - 1;
  int dof1 = m.body_dofadr[b1] + m.body_dofnum[b1] - 1;
  if (dof0 < 0 || dof1 < 0) return -1;
  while (dof0 != dof1) {
    if (dof0 < dof1) {
      dof1 = m.dof_parentid[dof1];
    } else {
      dof0 = m.dof_parentid[dof0];
    }
    if (dof0 < 0 || dof1 < 0) return -1;
  }
  return dof0;
}

// jac -= jac_ref, then the columns of the shared chain (which move both sites alike)
// are cleared exactly.
void RelativeJacobian(const Model& m, double* jac, const double* jac_ref, int common) {
  int nv = m.nv;
  for (int k = 0; k < 3 * nv; k++) jac[k] -= jac_ref[k];
  for (int v = common; v >= 0; v = m.dof_parentid[v]) {
    jac[v] = jac[nv + v] = jac[2 * nv + v] = 0;
  }
}

namespace {

// Transmission through joint `id` for actuator i.
void JointTransmission(const Model& m, Data& d, int i, int id, double* moment) {
  const double* gear = &m.actuator_gear[6 * m.actuator_outadr[i]];
  bool in_parent = m.actuator_trntype[i] == kTrnJointInParent;
  int qadr = m.jnt_qposadr[id], dadr = m.jnt_dofadr[id];
  switch (m.jnt_type[id]) {
    case kJointSlide:
    case kJointHinge:
      d.actuator_length[m.actuator_outadr[i]] = d.qpos[qadr] * gear[0];
      moment[dadr] = gear[0];
      break;
    case kJointBall: {
      double quat[4], axis[3], gear_axis[3];
      CopyQuat(quat, &d.qpos[qadr]);
      math::NormalizeQuat(quat);
      QuatToVel(axis, quat, 1);
      if (in_parent) {
        NegQuat(quat, quat);
        RotVecQuat(gear_axis, gear, quat);
      } else {
        Copy3(gear_axis, gear);
      }
      d.actuator_length[m.actuator_outadr[i]] = Dot3(axis, gear_axis);
      Copy3(moment + dadr, gear_axis);
      break;
    }
    case kJointFree: {
      double gear_axis[3];
      if (in_parent) {
        double quat[4];
        CopyQuat(quat, &d.qpos[qadr + 3]);
        math::NormalizeQuat(quat);
        NegQuat(quat, quat);
        RotVecQuat(gear_axis, gear + 3, quat);
      } else {
        Copy3(gear_axis, gear + 3);
      }
      d.actuator_length[m.actuator_outadr[i]] = 0;
      Copy3(moment + dadr, gear);
      Copy3(moment + dadr + 3, gear_axis);
      break;
    }
  }
}

// Site transmission without a reference site: the gear is a wrench in the site frame.
void SiteTransmission(const Model& m, Data& d, int i, int id, double* moment) {
  const double* gear = &m.actuator_gear[6 * m.actuator_outadr[i]];
  StackFrame frame(d);
  double* jacp = frame.Alloc(3 * m.nv);
  double* jacr = frame.Alloc(3 * m.nv);
  double* tmp = frame.Alloc(m.nv);
  JacobianSite(m, d, jacp, jacr, id);
  double force[3], torque[3];
  MulMatVec3(force, &d.site_xmat[9 * id], gear);
  MulMatVec3(torque, &d.site_xmat[9 * id], gear + 3);
  MulJacTVec(m, jacp, force, moment);
  MulJacTVec(m, jacr, torque, tmp);
  for (int v = 0; v < m.nv; v++) moment[v] += tmp[v];
  d.actuator_length[m.actuator_outadr[i]] = 0;
}

// Site transmission relative to reference site `ref`: translation and rotation of the
// site in the refsite frame, each projected on its half of the gear.
void RefSiteTransmission(const Model& m, Data& d, int i, int id, int ref, double* moment) {
  const double* gear = &m.actuator_gear[6 * m.actuator_outadr[i]];
  const double* ref_mat = &d.site_xmat[9 * ref];
  int nv = m.nv;
  StackFrame frame(d);
  double* jacp = frame.Alloc(3 * nv);
  double* jacr = frame.Alloc(3 * nv);
  double* jac_ref = frame.Alloc(3 * nv);
  double* tmp = frame.Alloc(nv);
  JacobianSite(m, d, jacp, jacr, id);
  int common = CommonAncestorDof(m, id, ref);
  d.actuator_length[m.actuator_outadr[i]] = 0;

  // Translation: the site's position relative to the refsite, in the refsite frame.
  if (gear[0] != 0 || gear[1] != 0 || gear[2] != 0) {
    double dif[3], local[3], force[3];
    Sub3(dif, &d.site_xpos[3 * id], &d.site_xpos[3 * ref]);
    MulMatTVec3(local, ref_mat, dif);
    d.actuator_length[m.actuator_outadr[i]] += Dot3(local, gear);
    JacobianSite(m, d, jac_ref, nullptr, ref);
    RelativeJacobian(m, jacp, jac_ref, common);
    MulMatVec3(force, ref_mat, gear);
    MulJacTVec(m, jacp, force, moment);
  }

  // Rotation: the rotation vector of the site's orientation relative to the refsite's,
  // with the orientations composed from the bodies' quaternions as MuJoCo does.
  if (gear[3] != 0 || gear[4] != 0 || gear[5] != 0) {
    double quat[4], ref_quat[4], vec[3], torque[3];
    MulQuat(quat, &m.site_quat[4 * id], &d.xquat[4 * m.site_bodyid[id]]);
    MulQuat(ref_quat, &m.site_quat[4 * ref], &d.xquat[4 * m.site_bodyid[ref]]);
    SubQuat(vec, quat, ref_quat);
    d.actuator_length[m.actuator_outadr[i]] += Dot3(vec, gear + 3);
    JacobianSite(m, d, nullptr, jac_ref, ref);
    RelativeJacobian(m, jacr, jac_ref, common);
    MulMatVec3(torque, ref_mat, gear + 3);
    MulJacTVec(m, jacr, torque, tmp);
    for (int v = 0; v < nv; v++) moment[v] += tmp[v];
  }
}

// Slider-crank: the crank site `id` is pushed by a rod of length r from the slider
// site, which moves along its own z axis a. With v = crank - slider,
//   l = a.v - sqrt(det),  det = (a.v)^2 + r^2 - v.v
// (l = a.v when the rod cannot reach, det <= 0), and dl/dq by the chain rule through
// v and a.
void SliderCrankTransmission(const Model& m, Data& d, int i, int id, double* moment) {
  int slider = m.actuator_trnid[2 * i + 1], nv = m.nv;
  double rod = m.actuator_cranklength[i];
  const double* smat = &d.site_xmat[9 * slider];
  double axis[3] = {smat[2], smat[5], smat[8]}, vec[3];
  Sub3(vec, &d.site_xpos[3 * id], &d.site_xpos[3 * slider]);
  double av = Dot3(vec, axis), det = av * av + rod * rod - Dot3(vec, vec);

  // Length and its gradients with respect to the axis (dlda) and the vector (dldv).
  double dlda[3], dldv[3];
  if (det <= 0) {
    d.actuator_length[m.actuator_outadr[i]] = av;
    Copy3(dlda, vec);
    Copy3(dldv, axis);
  } else {
    double sdet = std::sqrt(det), tmp[3];
    d.actuator_length[m.actuator_outadr[i]] = av - sdet;
    Scale3(dldv, axis, 1 - av / sdet);
    Scale3(tmp, vec, 1 / sdet);
    Add3(dldv, dldv, tmp);
    Scale3(dlda, vec, 1 - av / sdet);
  }

  // Chain rule through the Jacobians of the axis and of v.
  StackFrame frame(d);
  double* jac_slider = frame.Alloc(3 * nv);
  double* jac_axis = frame.Alloc(3 * nv);
  double* jac = frame.Alloc(3 * nv);
  JacobianPointAxis(m, d, jac_slider, jac_axis, &d.site_xpos[3 * slider], axis,
                    m.site_bodyid[slider]);
  JacobianSite(m, d, jac, nullptr, id);
  for (int k = 0; k < 3 * nv; k++) jac[k] -= jac_slider[k];
  for (int v = 0; v < nv; v++) {
    for (int k = 0; k < 3; k++) moment[v] += dlda[k] * jac_axis[k * nv + v] + dldv[k] * jac[k * nv + v];
  }

  // Gear scales length and moment.
  double gear = m.actuator_gear[6 * m.actuator_outadr[i]];
  d.actuator_length[m.actuator_outadr[i]] *= gear;
  for (int v = 0; v < nv; v++) moment[v] *= gear;
}

// Weights on the constraint rows of a contact that make the rows' weighted sum its
// normal Jacobian: the first row (frictionless or elliptic), else the mean of the
// pyramid's 2 (dim - 1) edges, whose frictional parts cancel.
void MarkNormalRows(const Model& m, const Contact& con, double* weights) {
  if (con.efc_address < 0) return;
  if (con.dim == 1 || m.opt.cone == kConeElliptic) {
    weights[con.efc_address] = 1;
    return;
  }
  int edges = 2 * (con.dim - 1);
  for (int k = 0; k < edges; k++) weights[con.efc_address + k] = 0.5 / (con.dim - 1);
}

// exclude += the normal Jacobian of a contact in the gap (which has no rows): the
// difference of the two bodies' point Jacobians at the contact, projected on the normal.
void AddGapNormalJacobian(const Model& m, Data& d, const Contact& con, int b1, int b2,
                          double* exclude) {
  int nv = m.nv;
  StackFrame frame(d);
  double* jac1 = frame.Alloc(3 * nv);
  double* jac2 = frame.Alloc(3 * nv);
  double* normal = frame.Alloc(nv);
  Jacobian(m, d, jac1, nullptr, con.pos, b1);
  Jacobian(m, d, jac2, nullptr, con.pos, b2);
  for (int k = 0; k < 3 * nv; k++) jac2[k] -= jac1[k];
  MulJacTVec(m, jac2, con.frame, normal);
  for (int v = 0; v < nv; v++) exclude[v] += normal[v];
}

// Body transmission of an adhesion actuator on `body`: contacts with rows contribute
// their normal rows of efc_J, contacts in the gap their normal Jacobian; the moment is
// minus the mean over all of them (pulling the body toward what it touches).
void BodyMoment(const Model& m, Data& d, int body, double* moment) {
  int nv = m.nv;
  StackFrame frame(d);
  double* weights = frame.Alloc(d.nefc);
  double* exclude = frame.Alloc(nv);
  int count = 0;
  for (int c = 0; c < d.ncon; c++) {
    const Contact& con = d.contact[c];
    if (con.geom[0] < 0 || con.geom[1] < 0) continue;
    int b1 = m.geom_bodyid[con.geom[0]], b2 = m.geom_bodyid[con.geom[1]];
    if (b1 != body && b2 != body) continue;
    if (con.exclude == 0) {
      MarkNormalRows(m, con, weights);
      count++;
    } else if (con.exclude == 1) {
      AddGapNormalJacobian(m, d, con, b1, b2, exclude);
      count++;
    }
  }
  if (count == 0) return;

  // moment = -(J^T weights + exclude) / count, summed row by row as MuJoCo does.
  for (int r = 0; r < d.nefc; r++) {
    if (weights[r] == 0) continue;
    for (int k = d.efc_J_rowadr[r]; k < d.efc_J_rowadr[r] + d.efc_J_rownnz[r]; k++) {
      moment[d.efc_J_colind[k]] += d.efc_J[k] * weights[r];
    }
  }
  for (int v = 0; v < nv; v++) moment[v] = (moment[v] + exclude[v]) * (-1.0 / count);
}

// Records where actuator i's row may be nonzero: a joint's dofs, a tendon's pattern,
// else the row's nonzeros.
void SetMomentPattern(const Model& m, Data& d, int i) {
  int o = m.actuator_outadr[i];
  const double* moment = RowOf(d.actuator_moment, o, m.nv);
  int* cols = RowOf(d.moment_colind, o, m.nv);
  int n = 0, id = m.actuator_trnid[2 * i];
  int trntype = m.actuator_trntype[i];
  if (trntype == kTrnJoint || trntype == kTrnJointInParent) {
    int type = m.jnt_type[id];
    int dofs = type == kJointFree ? 6 : type == kJointBall ? 3 : 1;
    for (; n < dofs; n++) cols[n] = m.jnt_dofadr[id] + n;
  } else if (trntype == kTrnTendon) {
    n = d.ten_J_rownnz[id];
    std::copy_n(RowOf(d.ten_J_colind, id, m.nv), n, cols);
  } else {
    n = NonzeroColumns(moment, m.nv, cols);
  }
  d.moment_rownnz[o] = n;
}

}  // namespace

void Transmission(const Model& m, Data& d) {
  bool any_asleep = AnyAsleep(m, d);
  for (int i = 0; i < m.nactuator; i++) {
    // A sleeping actuator has no moment (so no velocity) and keeps its length.
    if (any_asleep && ElementSleepState(m, d, kObjActuator, i) == kAsleep) {
      for (int o = m.actuator_outadr[i]; o < m.actuator_outadr[i] + m.actuator_outnum[i]; o++) {
        ClearPattern(RowOf(d.actuator_moment, o, m.nv), RowOf(d.moment_colind, o, m.nv), d.moment_rownnz[o]);
        d.moment_rownnz[o] = 0;
      }
      continue;
    }
    if (m.actuator_trntype[i] == kTrnSo3) {
      So3Transmission(m, d, i);  // (3 rows: orientation.cc)
      continue;
    }
    // (zero where the last pattern said it may not be)
    int o = m.actuator_outadr[i];
    double* moment = RowOf(d.actuator_moment, o, m.nv);
    ClearPattern(moment, RowOf(d.moment_colind, o, m.nv), d.moment_rownnz[o]);
    int id = m.actuator_trnid[2 * i];
    switch (m.actuator_trntype[i]) {
      case kTrnJoint:
      case kTrnJointInParent:
        JointTransmission(m, d, i, id, moment);
        break;
      case kTrnTendon: {
        double gear = m.actuator_gear[6 * m.actuator_outadr[i]];
        d.actuator_length[m.actuator_outadr[i]] = d.ten_length[id] * gear;
        const double* jac = RowOf(d.ten_J, id, m.nv);
        const int* cols = RowOf(d.ten_J_colind, id, m.nv);
        for (int k = 0; k < d.ten_J_rownnz[id]; k++) moment[cols[k]] = jac[cols[k]] * gear;
        break;
      }
      case kTrnSite:
        if (m.actuator_trnid[2 * i + 1] < 0) {
          SiteTransmission(m, d, i, id, moment);
        } else {
          RefSiteTransmission(m, d, i, id, m.actuator_trnid[2 * i + 1], moment);
        }
        break;
      case kTrnSliderCrank:
        SliderCrankTransmission(m, d, i, id, moment);
        break;
      default:
        // Body transmission (adhesion), from this step's contacts and their rows.
        d.actuator_length[m.actuator_outadr[i]] = 0;
        BodyMoment(m, d, id, moment);
    }
    SetMomentPattern(m, d, i);
  }
}

void ActuatorVelocity(const Model& m, Data& d) {
  bool actuation = !(m.opt.disableflags & kDisableActuation);
  for (int o = 0; o < m.nout; o++) {
    d.actuator_velocity[o] = actuation ? PatternDot(RowOf(d.actuator_moment, o, m.nv),
                                                    RowOf(d.moment_colind, o, m.nv),
                                                    d.moment_rownnz[o], d.qvel.data())
                                       : 0;
  }
}

}  // namespace simlab
