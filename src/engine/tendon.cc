// Tendon lengths and Jacobians (MuJoCo mj_tendon, mj_tendonDot).
//
// A fixed tendon is a linear combination of joint positions, l = sum_j coef_j q_j, so
// its Jacobian row holds the coefficients at the joints' dofs.
//
// A spatial tendon is a path of straight segments between sites, possibly wrapping
// around a sphere or cylinder placed between two sites, and split into branches by
// pulleys: every segment after a pulley counts 1/divisor. For a segment from point a
// (on body A) to point b (on body B) with unit direction u = (b - a)/|b - a|,
//
//   dl = u . (J_b - J_a) dq        (J_a, J_b: the point Jacobians),
//
// and segments whose ends move with the same body add length but no Jacobian. The path
// points are kept in wrap_xpos/wrap_obj (-1 site or tangent point, geom id on a geom,
// -2 pulley), ten_wrapadr/ten_wrapnum per tendon.
#include <algorithm>
#include <cmath>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/sleep.h"
#include "engine/stack.h"
#include "engine/tendon_wrap.h"
#include "math/math.h"

namespace simlab {

namespace {

// Appends path point `p` with object code `obj` to the wrap arrays of tendon i.
void AddPathPoint(Data& d, int tendon, int* count, const double* p, int obj) {
  math::Copy3(&d.wrap_xpos[3 * static_cast<size_t>(*count)], p);
  d.wrap_obj[*count] = obj;
  d.ten_wrapnum[tendon]++;
  (*count)++;
}

// jac (nv) += scale * (J_b - J_a)^T dir for points a on body_a and b on body_b, on the
// dofs that move either body only (every other column of J_b - J_a is zero); each
// column sums its three rows in order, zero components of dir left out, as MuJoCo's
// mju_mulMatTVec does.
void AddSegmentJacobian(const Model& m, Data& d, const double* a, int body_a, const double* b,
                        int body_b, const double* dir, double scale, double* jac) {
  SolverFrame frame(d.solver_scratch);
  int* dofs = frame.IntsToWrite(m.nv);
  int n = MergedDofChain(m, body_a, body_b, dofs);
  if (n == 0) return;
  double* row = frame.RealsToWrite(n);
  JacobianDifferenceAlong(m, d, dofs, n, a, body_a, b, body_b, dir, row);
  for (int k = 0; k < n; k++) jac[dofs[k]] += row[k] * scale;
}

void FixedTendon(const Model& m, Data& d, int i, double* jac) {
  for (int w = m.tendon_adr[i]; w < m.tendon_adr[i] + m.tendon_num[i]; w++) {
    int joint = m.wrap_objid[w];
    double coef = m.wrap_prm[w];
    d.ten_length[i] += coef * d.qpos[m.jnt_qposadr[joint]];
    jac[m.jnt_dofadr[joint]] = coef;
  }
}

// One straight or wrapped stretch from site `from` to the site after it, starting at
// path element j; returns the index of the element the stretch ends at.
int SpatialStretch(const Model& m, Data& d, int i, int j, double divisor, int* count,
                   double* jac) {
  int adr = m.tendon_adr[i];
  int from = m.wrap_objid[adr + j], to = m.wrap_objid[adr + j + 1];
  int next_type = m.wrap_type[adr + j + 1];

  // Up to four points: the first site, two tangent points on a geom, the last site.
  double pts[12];
  int bodies[4];
  math::Copy3(pts, &d.site_xpos[3 * from]);
  bodies[0] = m.site_bodyid[from];
  double arc = -1;
  int geom = -1;
  if (next_type == kWrapSphere || next_type == kWrapCylinder) {
    geom = to;
    to = m.wrap_objid[adr + j + 2];
    int side = static_cast<int>(std::lround(m.wrap_prm[adr + j + 1]));
    arc = WrapAroundGeom(pts + 3, &d.site_xpos[3 * from], &d.site_xpos[3 * to],
                         &d.geom_xpos[3 * geom], &d.geom_xmat[9 * geom], m.geom_size[3 * geom],
                         next_type, side >= 0 ? &d.site_xpos[3 * side] : nullptr);
  }

  // Length of the stretch, then the Jacobian of each segment between different bodies.
  int nseg = arc < 0 ? 1 : 3;
  double dif[3];
  if (arc < 0) {
    math::Copy3(pts + 3, &d.site_xpos[3 * to]);
    bodies[1] = m.site_bodyid[to];
    math::Sub3(dif, pts, pts + 3);
    d.ten_length[i] += math::Norm3(dif) / divisor;
  } else {
    math::Copy3(pts + 9, &d.site_xpos[3 * to]);
    bodies[1] = bodies[2] = m.geom_bodyid[geom];
    bodies[3] = m.site_bodyid[to];
    double first[3], last[3];
    math::Sub3(first, pts, pts + 3);
    math::Sub3(last, pts + 6, pts + 9);
    d.ten_length[i] += (math::Norm3(first) + arc + math::Norm3(last)) / divisor;
  }
  for (int k = 0; k < nseg; k++) {
    if (bodies[k] == bodies[k + 1]) continue;
    math::Sub3(dif, pts + 3 * k + 3, pts + 3 * k);
    math::Normalize3(dif);
    AddSegmentJacobian(m, d, pts + 3 * k, bodies[k], pts + 3 * k + 3, bodies[k + 1], dif,
                       1 / divisor, jac);
  }

  // Record the points: the first site and any tangent points (on the geom).
  for (int k = 0; k < nseg; k++) AddPathPoint(d, i, count, pts + 3 * k, k == 0 ? -1 : geom);
  return j + (geom >= 0 ? 2 : 1);
}

void SpatialTendon(const Model& m, Data& d, int i, int* count, double* jac) {
  int adr = m.tendon_adr[i], num = m.tendon_num[i];
  double divisor = 1;
  const double zero[3] = {0, 0, 0};
  int j = 0;
  while (j < num - 1) {
    // A pulley starts a new branch with its divisor.
    if (m.wrap_type[adr + j] == kWrapPulley || m.wrap_type[adr + j + 1] == kWrapPulley) {
      if (m.wrap_type[adr + j] == kWrapPulley) {
        divisor = m.wrap_prm[adr + j];
        AddPathPoint(d, i, count, zero, -2);
      }
      j++;
      continue;
    }
    j = SpatialStretch(m, d, i, j, divisor, count, jac);

    // The last site of a branch closes it.
    if (j == num - 1 || m.wrap_type[adr + j + 1] == kWrapPulley) {
      AddPathPoint(d, i, count, &d.site_xpos[3 * m.wrap_objid[adr + j]], -1);
    }
  }
}

// Time derivative of the Jacobian of a point moving with `body` (MuJoCo mj_jacDot):
// columns cdof_dot(lin) + cdof_dot(ang) x (p - c) + cdof(ang) x p_dot, where ball and
// free rotations take cdof_dot from the velocity of their own body.
void JacobianDot(const Model& m, const Data& d, double* jdot, const double* point, int body) {
  int nv = m.nv;
  std::fill(jdot, jdot + 3 * nv, 0.0);
  const double* com = &d.subtree_com[3 * m.body_rootid[body]];
  double offset[3], pvel[6];
  math::Sub3(offset, point, com);
  math::TransformSpatial(pvel, &d.cvel[6 * body], false, point, com, nullptr);
  int weld = m.body_weldid[body];
  if (weld == 0) return;
  for (int i = m.body_dofadr[weld] + m.body_dofnum[weld] - 1; i >= 0; i = m.dof_parentid[i]) {
    double cdof_dot[6] = {};
    const double* cdof = &d.cdof[6 * i];
    int jnt = m.dof_jntid[i];
    bool rotation = m.jnt_type[jnt] == kJointBall ||
                    (m.jnt_type[jnt] == kJointFree && i >= m.jnt_dofadr[jnt] + 3);
    if (rotation) {
      math::CrossMotion(cdof_dot, &d.cvel[6 * m.dof_bodyid[i]], cdof);
    } else {
      std::copy(&d.cdof_dot[6 * i], &d.cdof_dot[6 * i] + 6, cdof_dot);
    }
    double turn[3], carry[3];
    math::Cross3(turn, cdof_dot, offset);
    math::Cross3(carry, cdof, pvel + 3);
    for (int k = 0; k < 3; k++) jdot[k * nv + i] += cdof_dot[3 + k] + turn[k] + carry[k];
  }
}

// Linear velocity of a site (zero on a body welded to the world).
void SiteVelocity(const Model& m, const Data& d, int site, double* vel) {
  int body = m.site_bodyid[site];
  if (m.body_weldid[body] == 0) {
    math::Zero3(vel);
    return;
  }
  double v6[6];
  math::TransformSpatial(v6, &d.cvel[6 * body], false, &d.site_xpos[3 * site],
                         &d.subtree_com[3 * m.body_rootid[body]], nullptr);
  math::Copy3(vel, v6 + 3);
}

// Jdot += scale * [(Jdot_b - Jdot_a)^T u + (J_b - J_a)^T u_dot] for the segment between
// sites a and b, u its unit direction.
void AddSegmentJacobianDot(const Model& m, Data& d, int site_a, int site_b, double scale,
                           double* jdot) {
  const double* a = &d.site_xpos[3 * site_a];
  const double* b = &d.site_xpos[3 * site_b];
  int body_a = m.site_bodyid[site_a], body_b = m.site_bodyid[site_b];
  double u[3], va[3], vb[3], udot[3];
  math::Sub3(u, b, a);
  double len = math::Normalize3(u);
  SiteVelocity(m, d, site_a, va);
  SiteVelocity(m, d, site_b, vb);
  // u_dot = (I - u u^T)(v_b - v_a) / len
  math::Sub3(udot, vb, va);
  double along = math::Dot3(u, udot);
  math::AddScaled3(udot, u, -along);
  math::Scale3(udot, udot, len > kMinVal ? 1 / len : 0);

  StackFrame frame(d);
  double* ja = frame.Alloc(3 * m.nv);
  double* jb = frame.Alloc(3 * m.nv);
  double* proj = frame.Alloc(m.nv);
  JacobianDot(m, d, ja, a, body_a);
  JacobianDot(m, d, jb, b, body_b);
  for (int k = 0; k < 3 * m.nv; k++) jb[k] -= ja[k];
  MulJacTVec(m, jb, u, proj);
  for (int v = 0; v < m.nv; v++) jdot[v] += proj[v] * scale;
  AddSegmentJacobian(m, d, a, body_a, b, body_b, udot, scale, jdot);
}

// Records where tendon i's row of ten_J may be nonzero: a fixed tendon's joint dofs
// (ascending, once each), else the row's nonzeros.
void SetTendonPattern(const Model& m, Data& d, int i) {
  const double* jac = RowOf(d.ten_J, i, m.nv);
  int* cols = RowOf(d.ten_J_colind, i, m.nv);
  int n = 0;
  int adr = m.tendon_adr[i], num = m.tendon_num[i];
  if (num > 0 && m.wrap_type[adr] == kWrapJoint) {
    for (int w = adr; w < adr + num; w++) {
      int dof = m.jnt_dofadr[m.wrap_objid[w]];
      int at = n;
      while (at > 0 && cols[at - 1] > dof) at--;
      if (at > 0 && cols[at - 1] == dof) continue;
      std::copy_backward(cols + at, cols + n, cols + n + 1);
      cols[at] = dof;
      n++;
    }
  } else {
    n = NonzeroColumns(jac, m.nv, cols);
  }
  d.ten_J_rownnz[i] = n;
}

}  // namespace

void Tendon(const Model& m, Data& d) {
  int count = 0;
  bool any_asleep = AnyAsleep(m, d);
  for (int i = 0; i < m.ntendon; i++) {
    // (zero where the last pattern said it may not be)
    double* jac = RowOf(d.ten_J, i, m.nv);
    ClearPattern(jac, RowOf(d.ten_J_colind, i, m.nv), d.ten_J_rownnz[i]);
    d.ten_J_rownnz[i] = 0;
    d.ten_length[i] = 0;
    // (a sleeping tendon keeps zero length and Jacobian, and its old wrap points)
    if (any_asleep && ElementSleepState(m, d, kObjTendon, i) == kAsleep) continue;
    d.ten_wrapadr[i] = count;
    d.ten_wrapnum[i] = 0;
    if (m.tendon_num[i] == 0) continue;
    if (m.wrap_type[m.tendon_adr[i]] == kWrapJoint) {
      FixedTendon(m, d, i, jac);
    } else {
      SpatialTendon(m, d, i, &count, jac);
    }
    SetTendonPattern(m, d, i);
  }
}

void TendonJacobianDot(const Model& m, Data& d, int i, double* jdot) {
  std::fill(jdot, jdot + m.nv, 0.0);
  int adr = m.tendon_adr[i], num = m.tendon_num[i];
  if (num == 0 || m.wrap_type[adr] == kWrapJoint) return;  // fixed: constant Jacobian
  // Site-to-site segments only: the compiler refuses armature on wrapping tendons.
  double divisor = 1;
  for (int j = 0; j < num - 1; j++) {
    int type0 = m.wrap_type[adr + j], type1 = m.wrap_type[adr + j + 1];
    if (type0 == kWrapPulley) divisor = m.wrap_prm[adr + j];
    if (type0 != kWrapSite || type1 != kWrapSite) continue;
    int a = m.wrap_objid[adr + j], b = m.wrap_objid[adr + j + 1];
    if (m.site_bodyid[a] == m.site_bodyid[b]) continue;
    AddSegmentJacobianDot(m, d, a, b, 1 / divisor, jdot);
  }
}

void TendonVelocity(const Model& m, Data& d) {
  for (int i = 0; i < m.ntendon; i++) {
    d.ten_velocity[i] = PatternDot(RowOf(d.ten_J, i, m.nv), RowOf(d.ten_J_colind, i, m.nv),
                                   d.ten_J_rownnz[i], d.qvel.data());
  }
}

}  // namespace simlab
