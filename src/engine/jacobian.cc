// Jacobians of points and axes attached to bodies (MuJoCo mj_jac, mj_jacPointAxis).
//
// A dof j moves a point p of a body below it with the spatial motion cdof_j
// (angular w, linear v at the subtree centre of mass c of the tree's root), so
//
//   jacp[:, j] = v + w x (p - c),   jacr[:, j] = w
//
// for the dofs on the chain from the body up to the root; every other column is zero.
// Jacobians are 3 x nv, row-major.
#include <algorithm>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

namespace {

// Column of dof i in the Jacobians at `offset` from the tree's centre of mass: rotation
// cdof[0:3] into jacr[k * stride + col], translation cdof[3:6] + w x offset into jacp.
inline void JacobianColumn(const double* cdof, const double* offset, double* jacp,
                           double* jacr, int col, int stride) {
  if (jacr) {
    for (int k = 0; k < 3; k++) jacr[k * stride + col] = cdof[k];
  }
  if (jacp) {
    double w_cross[3];
    math::Cross3(w_cross, cdof, offset);
    for (int k = 0; k < 3; k++) jacp[k * stride + col] = cdof[3 + k] + w_cross[k];
  }
}

// The last dof that moves `body` (of its welded ancestor), -1 for the world's bodies.
int LastDof(const Model& m, int body) {
  body = m.body_weldid[body];
  if (body == 0) return -1;
  return m.body_dofadr[body] + m.body_dofnum[body] - 1;
}

}  // namespace

void Jacobian(const Model& m, const Data& d, double* jacp, double* jacr, const double* point,
              int body) {
  int nv = m.nv;
  double offset[3] = {0, 0, 0};
  if (jacp) {
    std::fill(jacp, jacp + 3 * nv, 0.0);
    math::Sub3(offset, point, &d.subtree_com[3 * m.body_rootid[body]]);
  }
  if (jacr) std::fill(jacr, jacr + 3 * nv, 0.0);

  // Walk the dof chain up from the last dof that moves the body.
  for (int i = LastDof(m, body); i >= 0; i = m.dof_parentid[i]) {
    JacobianColumn(&d.cdof[6 * i], offset, jacp, jacr, i, nv);
  }
}

void JacobianOnDofs(const Model& m, const Data& d, const int* dofs, int n, double* jacp,
                    double* jacr, const double* point, int body) {
  double offset[3] = {0, 0, 0};
  if (jacp) {
    std::fill(jacp, jacp + 3 * n, 0.0);
    math::Sub3(offset, point, &d.subtree_com[3 * m.body_rootid[body]]);
  }
  if (jacr) std::fill(jacr, jacr + 3 * n, 0.0);

  // The chain runs down the dof indices and `dofs` up them: one pass from the end.
  int col = n - 1;
  for (int i = LastDof(m, body); i >= 0; i = m.dof_parentid[i]) {
    while (col >= 0 && dofs[col] > i) col--;
    if (col < 0) break;
    JacobianColumn(&d.cdof[6 * i], offset, jacp, jacr, col, n);
  }
}

namespace {

// Calls column(k, on1, on2) for k = n-1 down to 0: whether dofs[k] moves body b1 and b2
// (both bodies' dof chains walked up with the columns; a dof off a chain has a zero
// column in that body's Jacobians).
template <typename Column>
void ForChainColumns(const Model& m, const int* dofs, int n, int b1, int b2, Column column) {
  int chain1 = LastDof(m, b1), chain2 = LastDof(m, b2);
  for (int k = n - 1; k >= 0; k--) {
    int dof = dofs[k];
    while (chain1 > dof) chain1 = m.dof_parentid[chain1];
    while (chain2 > dof) chain2 = m.dof_parentid[chain2];
    column(k, chain1 == dof, chain2 == dof);
  }
}

}  // namespace

void JacobianDifferenceAlong(const Model& m, const Data& d, const int* dofs, int n,
                             const double* p1, int b1, const double* p2, int b2,
                             const double* dir, double* row) {
  double offset1[3], offset2[3];
  math::Sub3(offset1, p1, &d.subtree_com[3 * m.body_rootid[b1]]);
  math::Sub3(offset2, p2, &d.subtree_com[3 * m.body_rootid[b2]]);
  ForChainColumns(m, dofs, n, b1, b2, [&](int k, bool on1, bool on2) {
    const double* cdof = &d.cdof[6 * dofs[k]];
    double column1[3] = {0, 0, 0}, column2[3] = {0, 0, 0};
    if (on1) JacobianColumn(cdof, offset1, column1, nullptr, 0, 1);
    if (on2) JacobianColumn(cdof, offset2, column2, nullptr, 0, 1);
    double sum = 0;
    for (int r = 0; r < 3; r++) {
      if (dir[r] != 0) sum += (column2[r] - column1[r]) * dir[r];
    }
    row[k] = sum;
  });
}

void FrameJacobianDifference(const Model& m, const Data& d, const int* dofs, int n,
                             const double* point, int b1, int b2, const double* frame, int dim,
                             double* rows) {
  double offset1[3], offset2[3];
  math::Sub3(offset1, point, &d.subtree_com[3 * m.body_rootid[b1]]);
  math::Sub3(offset2, point, &d.subtree_com[3 * m.body_rootid[b2]]);
  bool rotation = dim > 3;
  ForChainColumns(m, dofs, n, b1, b2, [&](int k, bool on1, bool on2) {
    const double* cdof = &d.cdof[6 * dofs[k]];
    double p1[3] = {0, 0, 0}, p2[3] = {0, 0, 0}, r1[3] = {0, 0, 0}, r2[3] = {0, 0, 0};
    if (on1) JacobianColumn(cdof, offset1, p1, rotation ? r1 : nullptr, 0, 1);
    if (on2) JacobianColumn(cdof, offset2, p2, rotation ? r2 : nullptr, 0, 1);
    double dif_p[3], dif_r[3];
    for (int r = 0; r < 3; r++) {
      dif_p[r] = p2[r] - p1[r];
      dif_r[r] = r2[r] - r1[r];
    }
    for (int i = 0; i < dim; i++) {
      bool rotation_row;
      const double* axis = ContactRowAxis(frame, dim, i, &rotation_row);
      const double* dif = rotation_row ? dif_r : dif_p;
      double sum = 0;
      for (int r = 0; r < 3; r++) sum += axis[r] * dif[r];
      rows[i * n + k] = sum;
    }
  });
}

int MergedDofChains(const Model& m, const int* bodies, int nbodies, int* dofs) {
  if (nbodies == 2) return MergedDofChain(m, bodies[0], bodies[1], dofs);
  // Every chain walked up together (descending dof indices): the highest cursor's dof is
  // taken once and every cursor on it moves to its parent, so shared ancestors come once;
  // then the list is turned ascending.
  int cursor[kMaxMergedChains];
  for (int i = 0; i < nbodies; i++) cursor[i] = LastDof(m, bodies[i]);
  int n = 0;
  for (;;) {
    int next = -1;
    for (int i = 0; i < nbodies; i++) next = std::max(next, cursor[i]);
    if (next < 0) break;
    dofs[n++] = next;
    for (int i = 0; i < nbodies; i++) {
      if (cursor[i] == next) cursor[i] = m.dof_parentid[next];
    }
  }
  std::reverse(dofs, dofs + n);
  return n;
}

// Two bodies' chains (a contact's, most often): the same walk with two cursors.
int MergedDofChain(const Model& m, int b0, int b1, int* dofs) {
  int c0 = LastDof(m, b0), c1 = LastDof(m, b1), n = 0;
  while (c0 >= 0 || c1 >= 0) {
    int next = std::max(c0, c1);
    dofs[n++] = next;
    if (c0 == next) c0 = m.dof_parentid[next];
    if (c1 == next) c1 = m.dof_parentid[next];
  }
  std::reverse(dofs, dofs + n);
  return n;
}

void JacobianSite(const Model& m, const Data& d, double* jacp, double* jacr, int site) {
  Jacobian(m, d, jacp, jacr, &d.site_xpos[3 * site], m.site_bodyid[site]);
}

void JacobianPointAxis(const Model& m, Data& d, double* jac_point, double* jac_axis,
                       const double* point, const double* axis, int body) {
  int nv = m.nv;
  StackFrame frame(d);
  double* jacr = frame.Alloc(3 * nv);
  Jacobian(m, d, jac_point, jacr, point, body);

  // The axis turns with the body: each column is (rotation column) x axis.
  if (!jac_axis) return;
  for (int i = 0; i < nv; i++) {
    jac_axis[i] = jacr[nv + i] * axis[2] - jacr[2 * nv + i] * axis[1];
    jac_axis[nv + i] = jacr[2 * nv + i] * axis[0] - jacr[i] * axis[2];
    jac_axis[2 * nv + i] = jacr[i] * axis[1] - jacr[nv + i] * axis[0];
  }
}

void ApplyForceTorque(const Model& m, Data& d, const double* force, const double* torque,
                      const double* point, int body, double* qfrc) {
  // Only the dofs of the body's chain move it: J^T f on those columns (the others add 0).
  StackFrame frame(d);
  SolverFrame ints(d.solver_scratch);
  int* dofs = ints.IntsToWrite(m.nv);
  int n = MergedDofChain(m, body, body, dofs);
  double* jacp = frame.Alloc(3 * n);
  double* jacr = frame.Alloc(3 * n);
  JacobianOnDofs(m, d, dofs, n, jacp, jacr, point, body);
  for (int k = 0; k < n; k++) {
    double f = jacp[k] * force[0] + jacp[n + k] * force[1] + jacp[2 * n + k] * force[2];
    double t = jacr[k] * torque[0] + jacr[n + k] * torque[1] + jacr[2 * n + k] * torque[2];
    qfrc[dofs[k]] += f;
    qfrc[dofs[k]] += t;
  }
}

void MulJacTVec(const Model& m, const double* jac, const double* vec, double* res) {
  int nv = m.nv;
  std::fill(res, res + nv, 0.0);
  for (int k = 0; k < 3; k++) {
    for (int i = 0; i < nv; i++) res[i] += jac[k * nv + i] * vec[k];
  }
}

}  // namespace simlab
