// Quantities MuJoCo computes once, at compile time, from the model at qpos0
// (mj_setConst): subtree masses, tendon and actuator lengths at qpos0, the spring
// lengths of tendons at qpos_spring, actuator_acc0 = |M^-1 moment|, and the damping of
// position actuators given by dampratio (kv = dampratio * 2 sqrt(kp * reflected mass),
// the reflected mass being sum_j M_jj / moment_j^2 over the actuated dofs).
//
// The kinematics at qpos0 is simple: every joint is at its reference, so bodies sit at
// the composition of body_pos/body_quat. M is assembled densely from body Jacobians:
// M = sum_b m_b Jp_b^T Jp_b + Jr_b^T I_b Jr_b, plus the armature on the diagonal.
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "compiler/compiler.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using Vector = Eigen::VectorXd;

// Poses and dof axes at qpos0.
struct Kinematics {
  std::vector<double> xpos, xquat, xmat;  // bodies
  std::vector<double> axis, anchor;       // dofs, world frame
  std::vector<int> rotational;            // dofs: 1 rotation, 0 translation
  std::vector<int> lastdof;               // bodies: last dof on the path to the world
};

void BodyPoses(const Model& m, Kinematics* k) {
  k->xpos.assign(3 * m.nbody, 0);
  k->xquat.assign(4 * m.nbody, 0);
  k->xmat.assign(9 * m.nbody, 0);
  k->xquat[0] = 1;
  math::QuatToMat(&k->xmat[0], &k->xquat[0]);
  for (int b = 1; b < m.nbody; b++) {
    int p = m.body_parentid[b];
    math::MulPose(&k->xpos[3 * b], &k->xquat[4 * b], &k->xpos[3 * p], &k->xquat[4 * p],
                  &m.body_pos[3 * b], &m.body_quat[4 * b]);
    math::NormalizeQuat(&k->xquat[4 * b]);
    math::QuatToMat(&k->xmat[9 * b], &k->xquat[4 * b]);
  }
}

// World axis and anchor of every dof (ball and free rotations use the body axes).
void DofAxes(const Model& m, Kinematics* k) {
  k->axis.assign(3 * m.nv, 0);
  k->anchor.assign(3 * m.nv, 0);
  k->rotational.assign(m.nv, 0);
  for (int j = 0; j < m.njnt; j++) {
    int b = m.jnt_bodyid[j], d = m.jnt_dofadr[j];
    const double* r = &k->xmat[9 * b];
    double anchor[3];
    math::MulMatVec3(anchor, r, &m.jnt_pos[3 * j]);
    math::Add3(anchor, anchor, &k->xpos[3 * b]);
    auto set = [&](int dof, const double* axis, bool rot) {
      math::Copy3(&k->axis[3 * dof], axis);
      math::Copy3(&k->anchor[3 * dof], anchor);
      k->rotational[dof] = rot;
    };
    double a[3];
    switch (m.jnt_type[j]) {
      case kJointFree:
        for (int i = 0; i < 3; i++) {
          double e[3] = {0, 0, 0};
          e[i] = 1;
          set(d + i, e, false);
          double col[3] = {r[i], r[3 + i], r[6 + i]};
          set(d + 3 + i, col, true);
        }
        break;
      case kJointBall:
        for (int i = 0; i < 3; i++) {
          double col[3] = {r[i], r[3 + i], r[6 + i]};
          set(d + i, col, true);
        }
        break;
      default:
        math::MulMatVec3(a, r, &m.jnt_axis[3 * j]);
        set(d, a, m.jnt_type[j] == kJointHinge);
    }
  }
  k->lastdof.assign(m.nbody, -1);
  for (int b = 1; b < m.nbody; b++) {
    k->lastdof[b] = m.body_dofnum[b] ? m.body_dofadr[b] + m.body_dofnum[b] - 1
                                     : k->lastdof[m.body_parentid[b]];
  }
}

// 3 x nv translational and rotational Jacobians of a point moving with body b.
void Jacobian(const Model& m, const Kinematics& k, int b, const double* point, Matrix* jacp,
              Matrix* jacr) {
  jacp->setZero(3, m.nv);
  jacr->setZero(3, m.nv);
  for (int d = k.lastdof[b]; d >= 0; d = m.dof_parentid[d]) {
    const double* axis = &k.axis[3 * d];
    if (!k.rotational[d]) {
      for (int i = 0; i < 3; i++) (*jacp)(i, d) = axis[i];
      continue;
    }
    double arm[3], lin[3];
    math::Sub3(arm, point, &k.anchor[3 * d]);
    math::Cross3(lin, axis, arm);
    for (int i = 0; i < 3; i++) {
      (*jacp)(i, d) = lin[i];
      (*jacr)(i, d) = axis[i];
    }
  }
}

// The joint-space inertia matrix at qpos0.
Matrix MassMatrix(const Model& m, const Kinematics& k) {
  Matrix mass = Matrix::Zero(m.nv, m.nv);
  Matrix jacp, jacr;
  for (int b = 1; b < m.nbody; b++) {
    double com[3], iquat[4], rot[9];
    math::MulMatVec3(com, &k.xmat[9 * b], &m.body_ipos[3 * b]);
    math::Add3(com, com, &k.xpos[3 * b]);
    math::MulQuat(iquat, &k.xquat[4 * b], &m.body_iquat[4 * b]);
    math::QuatToMat(rot, iquat);
    Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(rot);
    Eigen::Vector3d diag(m.body_inertia[3 * b], m.body_inertia[3 * b + 1], m.body_inertia[3 * b + 2]);
    Eigen::Matrix3d inertia = r * diag.asDiagonal() * r.transpose();
    Jacobian(m, k, b, com, &jacp, &jacr);
    mass += m.body_mass[b] * jacp.transpose() * jacp + jacr.transpose() * inertia * jacr;
  }
  for (int i = 0; i < m.nv; i++) mass(i, i) += m.dof_armature[i];
  return mass;
}

// World pose of a site at qpos0.
void SitePose(const Model& m, const Kinematics& k, int s, double* pos, double* mat) {
  int b = m.site_bodyid[s];
  double quat[4];
  math::MulMatVec3(pos, &k.xmat[9 * b], &m.site_pos[3 * s]);
  math::Add3(pos, pos, &k.xpos[3 * b]);
  math::MulQuat(quat, &k.xquat[4 * b], &m.site_quat[4 * s]);
  math::QuatToMat(mat, quat);
}

// ---------------------------------------------------------------- tendons

// Fixed tendon length (at qpos) and Jacobian.
double TendonLength(const Model& m, int t, const double* qpos, Vector* jac) {
  double length = 0;
  if (jac) jac->setZero(m.nv);
  for (int w = m.tendon_adr[t]; w < m.tendon_adr[t] + m.tendon_num[t]; w++) {
    int j = m.wrap_objid[w];
    length += m.wrap_prm[w] * qpos[m.jnt_qposadr[j]];
    if (jac) (*jac)[m.jnt_dofadr[j]] += m.wrap_prm[w];
  }
  return length;
}

// ---------------------------------------------------------------- transmissions

// Joint transmission at qpos0: moment on the joint's dofs, length gear * q.
double JointTransmission(const Model& m, int i, Vector* moment) {
  int j = m.actuator_trnid[2 * i], d = m.jnt_dofadr[j], q = m.jnt_qposadr[j];
  const double* gear = &m.actuator_gear[6 * i];
  switch (m.jnt_type[j]) {
    case kJointSlide:
    case kJointHinge:
      (*moment)[d] = gear[0];
      return m.qpos0[q] * gear[0];
    case kJointBall:
      for (int k = 0; k < 3; k++) (*moment)[d + k] = gear[k];
      return 0;  // qpos0 is the identity rotation
    default: {
      // Free joint: in-parent gears rotate into the body frame.
      double axis[3], quat[4];
      math::Copy3(axis, gear + 3);
      if (m.actuator_trntype[i] == kTrnJointInParent) {
        math::CopyQuat(quat, &m.qpos0[q + 3]);
        math::NormalizeQuat(quat);
        math::NegQuat(quat, quat);
        math::RotVecQuat(axis, gear + 3, quat);
      }
      for (int k = 0; k < 3; k++) {
        (*moment)[d + k] = gear[k];
        (*moment)[d + 3 + k] = axis[k];
      }
      return 0;
    }
  }
}

// The last dof shared by the dof chains of two bodies, or -1.
int CommonDof(const Kinematics& k, const Model& m, int b0, int b1) {
  int d0 = k.lastdof[b0], d1 = k.lastdof[b1];
  while (d0 >= 0 && d1 >= 0 && d0 != d1) {
    if (d0 < d1) {
      d1 = m.dof_parentid[d1];
    } else {
      d0 = m.dof_parentid[d0];
    }
  }
  return d0 >= 0 && d0 == d1 ? d0 : -1;
}

// Site transmission relative to a reference site (as the engine's, transmission.cc):
// position and rotation vector of the site in the refsite frame.
double RefSiteTransmission(const Model& m, const Kinematics& k, int i, Vector* moment) {
  int s = m.actuator_trnid[2 * i], ref = m.actuator_trnid[2 * i + 1];
  int bs = m.site_bodyid[s], br = m.site_bodyid[ref];
  const double* gear = &m.actuator_gear[6 * i];
  double pos[3], mat[9], rpos[3], rmat[9];
  SitePose(m, k, s, pos, mat);
  SitePose(m, k, ref, rpos, rmat);
  Matrix jacp, jacr, refp, refr;
  Jacobian(m, k, bs, pos, &jacp, &jacr);
  Jacobian(m, k, br, rpos, &refp, &refr);
  jacp -= refp;
  jacr -= refr;
  for (int d = CommonDof(k, m, bs, br); d >= 0; d = m.dof_parentid[d]) {
    jacp.col(d).setZero();
    jacr.col(d).setZero();
  }
  double length = 0, dif[3], local[3], force[3], torque[3], quat[4], rquat[4], vec[3];
  math::Sub3(dif, pos, rpos);
  math::MulMatTVec3(local, rmat, dif);
  math::MulMatVec3(force, rmat, gear);
  math::MulMatVec3(torque, rmat, gear + 3);
  // Orientations composed as MuJoCo does (site_quat first), then their difference.
  math::MulQuat(quat, &m.site_quat[4 * s], &k.xquat[4 * bs]);
  math::MulQuat(rquat, &m.site_quat[4 * ref], &k.xquat[4 * br]);
  math::SubQuat(vec, quat, rquat);
  moment->setZero(m.nv);
  if (gear[0] != 0 || gear[1] != 0 || gear[2] != 0) {
    length += math::Dot3(local, gear);
    *moment += jacp.transpose() * Eigen::Map<Eigen::Vector3d>(force);
  }
  if (gear[3] != 0 || gear[4] != 0 || gear[5] != 0) {
    length += math::Dot3(vec, gear + 3);
    *moment += jacr.transpose() * Eigen::Map<Eigen::Vector3d>(torque);
  }
  return length;
}

// Site transmission without a reference site: the gear is a wrench in the site frame.
void SiteTransmission(const Model& m, const Kinematics& k, int i, Vector* moment) {
  int s = m.actuator_trnid[2 * i];
  const double* gear = &m.actuator_gear[6 * i];
  double pos[3], mat[9], force[3], torque[3];
  SitePose(m, k, s, pos, mat);
  math::MulMatVec3(force, mat, gear);
  math::MulMatVec3(torque, mat, gear + 3);
  Matrix jacp, jacr;
  Jacobian(m, k, m.site_bodyid[s], pos, &jacp, &jacr);
  *moment = jacp.transpose() * Eigen::Map<Eigen::Vector3d>(force) +
            jacr.transpose() * Eigen::Map<Eigen::Vector3d>(torque);
}

// Slider-crank: length a.v - sqrt((a.v)^2 + r^2 - v.v), v from slider to crank site.
double SliderCrank(const Model& m, const Kinematics& k, int i, Vector* moment) {
  int crank = m.actuator_trnid[2 * i], slider = m.actuator_trnid[2 * i + 1];
  double rod = m.actuator_cranklength[i], gear = m.actuator_gear[6 * i];
  double cpos[3], cmat[9], spos[3], smat[9], vec[3];
  SitePose(m, k, crank, cpos, cmat);
  SitePose(m, k, slider, spos, smat);
  double axis[3] = {smat[2], smat[5], smat[8]};
  math::Sub3(vec, cpos, spos);
  double av = math::Dot3(vec, axis), det = av * av + rod * rod - math::Dot3(vec, vec);
  bool ok = det > 0;
  double sdet = ok ? std::sqrt(det) : 0, length = ok ? av - sdet : av;

  // Derivatives of the length with respect to vec and axis, then the chain rule.
  Eigen::Vector3d dlda, dldv, v(vec[0], vec[1], vec[2]), a(axis[0], axis[1], axis[2]);
  if (ok) {
    dldv = a * (1 - av / sdet) + v / sdet;
    dlda = v * (1 - av / sdet);
  } else {
    dlda = v;
    dldv = a;
  }
  Matrix jacs, jacsr, jacc, jaccr;
  Jacobian(m, k, m.site_bodyid[slider], spos, &jacs, &jacsr);
  Jacobian(m, k, m.site_bodyid[crank], cpos, &jacc, &jaccr);
  Matrix jaca = Matrix::Zero(3, m.nv);
  for (int d = 0; d < m.nv; d++) {
    Eigen::Vector3d w = jacsr.col(d);
    jaca.col(d) = w.cross(a);
  }
  *moment = gear * (jaca.transpose() * dlda + (jacc - jacs).transpose() * dldv);
  return length * gear;
}

// Moment arm (nv) and length of actuator i at qpos0.
double Transmission(const Model& m, const Kinematics& k, int i, Vector* moment) {
  moment->setZero(m.nv);
  int id = m.actuator_trnid[2 * i];
  switch (m.actuator_trntype[i]) {
    case kTrnJoint:
    case kTrnJointInParent: return JointTransmission(m, i, moment);
    case kTrnTendon: {
      Vector jac;
      double length = TendonLength(m, id, m.qpos0.data(), &jac);
      *moment = m.actuator_gear[6 * i] * jac;
      return length * m.actuator_gear[6 * i];
    }
    case kTrnSite:
      if (m.actuator_trnid[2 * i + 1] >= 0) return RefSiteTransmission(m, k, i, moment);
      SiteTransmission(m, k, i, moment);
      return 0;
    case kTrnSliderCrank: return SliderCrank(m, k, i, moment);
    default: return 0;  // body transmission: no contacts at compile time
  }
}

// dampratio -> negative biasprm[2] for position-like actuators.
void DampRatio(Model* m, int i, const Matrix& mass, const Vector& moment) {
  double* gain = &m->actuator_gainprm[kNGain * i];
  double* bias = &m->actuator_biasprm[kNBias * i];
  if (gain[0] != -bias[1] || bias[2] <= 0) return;
  double reflected = 0;
  for (int d = 0; d < m->nv; d++) {
    double t2 = moment[d] * moment[d];
    if (moment[d] != 0 && t2 > kMinVal) reflected += mass(d, d) / t2;
  }
  bias[2] = -bias[2] * 2 * std::sqrt(gain[0] * reflected);
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

void ComputeConstants(Model* m) {
  // Subtree masses, leaves first.
  for (int b = 0; b < m->nbody; b++) m->body_subtreemass[b] = m->body_mass[b];
  for (int b = m->nbody - 1; b > 0; b--) {
    m->body_subtreemass[m->body_parentid[b]] += m->body_subtreemass[b];
  }

  // Tendon lengths at qpos0 and spring lengths at qpos_spring.
  for (int t = 0; t < m->ntendon; t++) {
    m->tendon_length0[t] = TendonLength(*m, t, m->qpos0.data(), nullptr);
    if (m->tendon_lengthspring[2 * t] == -1 && m->tendon_lengthspring[2 * t + 1] == -1) {
      double spring = TendonLength(*m, t, m->qpos_spring.data(), nullptr);
      m->tendon_lengthspring[2 * t] = m->tendon_lengthspring[2 * t + 1] = spring;
    }
  }

  // Actuators: length0, acc0 and dampratio need M at qpos0.
  if (m->nu == 0) return;
  Kinematics k;
  BodyPoses(*m, &k);
  DofAxes(*m, &k);
  Matrix mass = MassMatrix(*m, k);
  Eigen::LLT<Matrix> llt(mass);
  for (int i = 0; i < m->nu; i++) {
    Vector moment;
    m->actuator_length0[i] = Transmission(*m, k, i, &moment);
    m->actuator_acc0[i] = m->nv ? llt.solve(moment).norm() : 0;
    DampRatio(m, i, mass, moment);
  }
}

}  // namespace simlab::compiler
