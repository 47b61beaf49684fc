// Position stage, part 1: where every body, joint, geom and site is, and the
// com-based quantities (subtree_com, cinert, cdof) that the dynamics work in.
//
// As MuJoCo (Computation chapter; engine_core_smooth.c mj_kinematics, mj_comPos):
// a body's frame is its parent's frame times its fixed offset (body_pos, body_quat),
// then each of its joints applied in order about the joint's anchor. A free joint sets
// the frame directly from qpos. Spatial quantities are expressed in the world frame at
// the centre of mass of the body's kinematic subtree root (subtree_com[rootid]).
#include "engine/engine.h"
#include "engine/sleep.h"
#include "math/math.h"

namespace simlab {

using namespace math;

// Sameframe codes (mjtSameFrame): a child frame that coincides with the body frame or
// the inertial frame is copied instead of recomputed.
enum SameFrame { kSameNone = 0, kSameBody, kSameInertia, kSameBodyRot, kSameInertiaRot };

void LocalToGlobal(const Data& d, double* xpos, double* xmat, const double* pos,
                   const double* quat, int body, int sameframe) {
  // Position.
  switch (sameframe) {
    case kSameBody: Copy3(xpos, &d.xpos[3 * body]); break;
    case kSameInertia: Copy3(xpos, &d.xipos[3 * body]); break;
    default:
      MulMatVec3(xpos, &d.xmat[9 * body], pos);
      AddScaled3(xpos, &d.xpos[3 * body], 1);
  }
  // Orientation.
  switch (sameframe) {
    case kSameBody:
    case kSameBodyRot:
      for (int k = 0; k < 9; k++) xmat[k] = d.xmat[9 * body + k];
      break;
    case kSameInertia:
    case kSameInertiaRot:
      for (int k = 0; k < 9; k++) xmat[k] = d.ximat[9 * body + k];
      break;
    default: {
      double q[4];
      MulQuat(q, &d.xquat[4 * body], quat);
      QuatToMat(xmat, q);
    }
  }
}

namespace {

// Applies the joints of body i to its frame (xpos, xquat), filling xanchor and xaxis.
void ApplyJoints(const Model& m, Data& d, int i, double* xpos, double* xquat) {
  for (int j = m.body_jntadr[i]; j < m.body_jntadr[i] + m.body_jntnum[i]; j++) {
    int qadr = m.jnt_qposadr[j];
    double xaxis[3], xanchor[3];
    RotVecQuat(xaxis, &m.jnt_axis[3 * j], xquat);
    RotVecQuat(xanchor, &m.jnt_pos[3 * j], xquat);
    AddScaled3(xanchor, xpos, 1);

    switch (m.jnt_type[j]) {
      case kJointSlide:
        AddScaled3(xpos, xaxis, d.qpos[qadr] - m.qpos0[qadr]);
        break;
      case kJointBall:
      case kJointHinge: {
        // Rotate about the anchor: the anchor stays put, the body origin moves.
        double qloc[4];
        if (m.jnt_type[j] == kJointBall) {
          CopyQuat(qloc, &d.qpos[qadr]);
          math::NormalizeQuat(qloc);
        } else {
          AxisAngleToQuat(qloc, &m.jnt_axis[3 * j], d.qpos[qadr] - m.qpos0[qadr]);
        }
        MulQuat(xquat, xquat, qloc);
        double offset[3];
        RotVecQuat(offset, &m.jnt_pos[3 * j], xquat);
        Sub3(xpos, xanchor, offset);
        break;
      }
      default: break;  // a free joint is always alone in its body (handled by caller)
    }
    Copy3(&d.xanchor[3 * j], xanchor);
    Copy3(&d.xaxis[3 * j], xaxis);
  }
}

// Frame of body i (>0) from its parent, its offset and its joints.
void BodyFrame(const Model& m, Data& d, int i) {
  double xpos[3], xquat[4];
  int jntadr = m.body_jntadr[i];

  // A free joint places the body directly.
  if (m.body_jntnum[i] == 1 && m.jnt_type[jntadr] == kJointFree) {
    int qadr = m.jnt_qposadr[jntadr];
    Copy3(xpos, &d.qpos[qadr]);
    CopyQuat(xquat, &d.qpos[qadr + 3]);
    math::NormalizeQuat(xquat);
    Copy3(&d.xanchor[3 * jntadr], xpos);
    Copy3(&d.xaxis[3 * jntadr], &m.jnt_axis[3 * jntadr]);
  } else {
    // Fixed offset from the parent (or the mocap pose), then the joints.
    int parent = m.body_parentid[i];
    const double* bpos = &m.body_pos[3 * i];
    const double* bquat = &m.body_quat[4 * i];
    double mquat[4];
    if (m.body_mocapid[i] >= 0) {
      bpos = &d.mocap_pos[3 * m.body_mocapid[i]];
      CopyQuat(mquat, &d.mocap_quat[4 * m.body_mocapid[i]]);
      math::NormalizeQuat(mquat);
      bquat = mquat;
    }
    if (parent > 0) {
      MulMatVec3(xpos, &d.xmat[9 * parent], bpos);
      AddScaled3(xpos, &d.xpos[3 * parent], 1);
      MulQuat(xquat, &d.xquat[4 * parent], bquat);
    } else {
      Copy3(xpos, bpos);
      CopyQuat(xquat, bquat);
    }
    ApplyJoints(m, d, i, xpos, xquat);
  }

  math::NormalizeQuat(xquat);
  CopyQuat(&d.xquat[4 * i], xquat);
  Copy3(&d.xpos[3 * i], xpos);
  QuatToMat(&d.xmat[9 * i], xquat);
}

}  // namespace

void Kinematics(const Model& m, Data& d) {
  // The world body sits at the origin.
  Zero3(&d.xpos[0]);
  SetIdentityQuat(&d.xquat[0]);
  Zero3(&d.xipos[0]);
  for (int k = 0; k < 9; k++) d.xmat[k] = d.ximat[k] = (k % 4 == 0) ? 1 : 0;

  // Body frames, parents before children. A sleeping body that moved (its state was
  // changed) marks its tree awake, for WakeChanged.
  bool any_asleep = AnyAsleep(m, d);
  for (int i = 1; i < m.nbody; i++) {
    if (!any_asleep || d.body_awake[i] != kAsleep || m.body_jntnum[i] == 0) {
      BodyFrame(m, d, i);
      continue;
    }
    double xpos[3], xquat[4];
    Copy3(xpos, &d.xpos[3 * i]);
    math::CopyQuat(xquat, &d.xquat[4 * i]);
    BodyFrame(m, d, i);
    bool moved = false;
    for (int k = 0; k < 3; k++) moved = moved || xpos[k] != d.xpos[3 * i + k];
    for (int k = 0; k < 4; k++) moved = moved || xquat[k] != d.xquat[4 * i + k];
    if (moved) d.tree_awake[m.body_treeid[i]] = 1;
  }

  // Inertial frames of the bodies.
  for (int i = 1; i < m.nbody; i++) {
    LocalToGlobal(d, &d.xipos[3 * i], &d.ximat[9 * i], &m.body_ipos[3 * i],
                  &m.body_iquat[4 * i], i, m.body_sameframe[i]);
  }

  // Geoms and sites.
  for (int g = 0; g < m.ngeom; g++) {
    LocalToGlobal(d, &d.geom_xpos[3 * g], &d.geom_xmat[9 * g], &m.geom_pos[3 * g],
                  &m.geom_quat[4 * g], m.geom_bodyid[g], m.geom_sameframe[g]);
  }
  for (int s = 0; s < m.nsite; s++) {
    LocalToGlobal(d, &d.site_xpos[3 * s], &d.site_xmat[9 * s], &m.site_pos[3 * s],
                  &m.site_quat[4 * s], m.site_bodyid[s], m.site_sameframe[s]);
  }
}

namespace {

// subtree_com: mass-weighted mean of xipos over each body's subtree.
void SubtreeCom(const Model& m, Data& d) {
  for (int i = 0; i < m.nbody; i++) Scale3(&d.subtree_com[3 * i], &d.xipos[3 * i], m.body_mass[i]);
  for (int i = m.nbody - 1; i > 0; i--) {
    AddScaled3(&d.subtree_com[3 * m.body_parentid[i]], &d.subtree_com[3 * i], 1);
  }
  for (int i = 0; i < m.nbody; i++) {
    if (m.body_subtreemass[i] < kMinVal) {
      Copy3(&d.subtree_com[3 * i], &d.xipos[3 * i]);
    } else {
      Scale3(&d.subtree_com[3 * i], &d.subtree_com[3 * i], 1.0 / m.body_subtreemass[i]);
    }
  }
}

// Motion axis of a rotational dof about `axis` through a point `offset` from the
// reference point: (axis, axis x offset); translational: (0, axis).
void DofCom(double* cdof, const double* axis, const double* offset) {
  if (offset) {
    Copy3(cdof, axis);
    Cross3(cdof + 3, axis, offset);
  } else {
    Zero3(cdof);
    Copy3(cdof + 3, axis);
  }
}

// cdof for the joints of body i.
void BodyDofs(const Model& m, Data& d, int i) {
  const double* com = &d.subtree_com[3 * m.body_rootid[i]];
  for (int j = m.body_jntadr[i]; j < m.body_jntadr[i] + m.body_jntnum[i]; j++) {
    double* cdof = &d.cdof[6 * m.jnt_dofadr[j]];
    double offset[3];
    Sub3(offset, com, &d.xanchor[3 * j]);
    switch (m.jnt_type[j]) {
      case kJointFree:
        // Three world-axis translations, then the three rotations of a ball.
        for (int k = 0; k < 18; k++) cdof[k] = 0;
        cdof[3] = cdof[6 + 4] = cdof[12 + 5] = 1;
        cdof += 18;
        [[fallthrough]];
      case kJointBall:
        // Rotations about the body frame's axes (columns of xmat).
        for (int k = 0; k < 3; k++) {
          double axis[3] = {d.xmat[9 * i + k], d.xmat[9 * i + k + 3], d.xmat[9 * i + k + 6]};
          DofCom(cdof + 6 * k, axis, offset);
        }
        break;
      case kJointSlide: DofCom(cdof, &d.xaxis[3 * j], nullptr); break;
      case kJointHinge: DofCom(cdof, &d.xaxis[3 * j], offset); break;
    }
  }
}

}  // namespace

void ComPos(const Model& m, Data& d) {
  SubtreeCom(m, d);

  // Body inertias about the subtree com of their tree's root.
  for (int k = 0; k < 10; k++) d.cinert[k] = 0;
  for (int i = 1; i < m.nbody; i++) {
    double offset[3];
    Sub3(offset, &d.xipos[3 * i], &d.subtree_com[3 * m.body_rootid[i]]);
    InertCom(&d.cinert[10 * i], &m.body_inertia[3 * i], &d.ximat[9 * i], offset,
             m.body_mass[i]);
  }

  // Motion axes of all dofs.
  for (int i = 1; i < m.nbody; i++) BodyDofs(m, d, i);
}

}  // namespace simlab
