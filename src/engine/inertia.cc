// Position stage, part 2: the joint-space inertia matrix M and its factorization.
//
// Composite rigid body algorithm (Featherstone; MuJoCo mj_crb): crb = the inertia of
// each body's subtree, accumulated leaves to root; then for every dof i and each
// ancestor dof j, M(i,j) = cdof_j . (crb_body(i) cdof_i). Armature adds to the diagonal
// (the joint's own and its actuators' times gear^2), tendon armature adds a J^T J.
//
// M is stored as its lower triangle in compressed rows (M_rowadr, M_rownnz,
// M_colind): row i holds i's ancestor dofs, diagonal last. Because rows of ancestors
// are prefixes of their descendants' rows, the L^T D L factorization (eliminating the
// last dof first) creates no fill-in.
#include <algorithm>

#include "engine/actuator_target.h"
#include "engine/engine.h"
#include "engine/rows.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// M += armature J^T J for each tendon with armature (its own and its actuators'),
// kept to M's sparsity (MuJoCo mj_tendonArmature).
void TendonArmature(const Model& m, Data& d) {
  for (int t = 0; t < m.ntendon; t++) {
    double armature = m.tendon_armature[t] + ActuatorArmature(m, true, t);
    if (armature == 0) continue;
    const double* jac = RowOf(d.ten_J, t, m.nv);
    for (int i = 0; i < m.nv; i++) {
      if (jac[i] == 0) continue;
      for (int adr = m.M_rowadr[i]; adr < m.M_rowadr[i] + m.M_rownnz[i]; adr++) {
        d.M[adr] += armature * jac[i] * jac[m.M_colind[adr]];
      }
    }
  }
}

}  // namespace

double ActuatorArmature(const Model& m, bool tendon, int id) {
  double armature = 0;
  ForTargetActuators(m, tendon, id, [&](int i, double gear2) {
    armature += m.actuator_armature[i] * gear2;
  });
  return armature;
}

void CompositeInertia(const Model& m, Data& d) {
  // crb = cinert, accumulated from children to parents.
  d.crb = d.cinert;
  for (int i = m.nbody - 1; i > 0; i--) {
    int parent = m.body_parentid[i];
    if (parent > 0) {
      for (int k = 0; k < 10; k++) d.crb[10 * parent + k] += d.crb[10 * i + k];
    }
  }
}

void MakeInertia(const Model& m, Data& d) {
  CompositeInertia(m, d);

  // Row i: armature on the diagonal, then cdof_j . (crb cdof_i) over ancestors j. Dofs
  // of simple bodies have the constant diagonal dof_M0 and no couplings (MuJoCo's
  // reduced M). (M cleared at once: row by row, short rows cost a call each)
  std::fill(d.M.begin(), d.M.end(), 0.0);
  for (int i = 0; i < m.nv; i++) {
    int adr = m.M_rowadr[i] + m.M_rownnz[i] - 1;
    if (m.dof_simplenum[i]) {
      d.M[adr] = m.dof_M0[i];
      continue;
    }
    d.M[adr] = m.dof_armature[i] + ActuatorArmature(m, false, m.dof_jntid[i]);
    double f[6];
    MulInertVec(f, &d.crb[10 * m.dof_bodyid[i]], &d.cdof[6 * i]);
    for (int j = i; j >= 0; j = m.dof_parentid[j]) {
      d.M[adr--] += Dot6(&d.cdof[6 * j], f);
    }
  }

  TendonArmature(m, d);

  // qM: the same numbers in MuJoCo's legacy layout (diagonal first, then ancestors).
  for (int i = 0; i < m.nv; i++) {
    int n = m.M_rownnz[i];
    double* to = &d.qM[m.dof_Madr[i]];
    const double* from = &d.M[m.M_rowadr[i] + n - 1];
    for (int k = 0; k < n; k++) to[k] = from[-k];
  }
}

void FactorSparse(const Model& m, double* mat, double* diag_inv) {
  // Eliminate rows from the last dof to the first.
  for (int k = m.nv - 1; k >= 0; k--) {
    int start = m.M_rowadr[k];
    int diag = m.M_rownnz[k] - 1;
    int end = start + diag;
    double inv_d = 1 / mat[end];
    if (diag_inv) diag_inv[k] = inv_d;

    // Update the rows of k's ancestors: row i -= row k * L(k,i) / D(k). (Row i's columns
    // are the first of row k's; the rows never overlap. Two entries at a time: short rows.)
    const double* row_k = mat + start;
    for (int adr = end - 1; adr >= start; adr--) {
      int i = m.M_colind[adr];
      double scale = -mat[adr] * inv_d;
      double* row_i = mat + m.M_rowadr[i];
      int n = m.M_rownnz[i], t = 0;
      for (; t + 1 < n; t += 2) {
        double a = row_i[t] + row_k[t] * scale, b = row_i[t + 1] + row_k[t + 1] * scale;
        row_i[t] = a;
        row_i[t + 1] = b;
      }
      if (t < n) row_i[t] += row_k[t] * scale;
    }

    // Row k becomes L(k, ancestors) = M(k, ancestors) / D(k).
    for (int t = start; t < end; t++) mat[t] *= inv_d;
  }
}

void SolveSparse(const Model& m, const double* ld, const double* diag_inv, double* x) {
  SolveSparseLayout(m.nv, m.M_rownnz.data(), m.M_rowadr.data(), m.M_colind.data(), ld, diag_inv,
                    x);
}

void MulSymLayout(int nv, const int* rownnz, const int* rowadr, const int* colind,
                  const double* mat, const double* vec, double* res) {
  // Diagonal first, then the off-diagonals from the nearest ancestor out (MuJoCo's order).
  // Row i's own sum is held in a register: the rows before it only add to their ancestors
  // (columns below theirs), so nothing else touches res[i] until row i is done, and every
  // res[c] with c < i is already started when row i adds to it.
  for (int i = 0; i < nv; i++) {
    int adr = rowadr[i], end = adr + rownnz[i] - 1;
    double vi = vec[i], sum = mat[end] * vi;
    for (int k = end - 1; k >= adr; k--) {
      sum += mat[k] * vec[colind[k]];
      res[colind[k]] += mat[k] * vi;
    }
    res[i] = sum;
  }
}

void SolveSparseLayout(int nv, const int* rownnz, const int* rowadr, const int* colind,
                       const double* ld, const double* diag_inv, double* x) {
  // x <- L^-T x
  for (int i = nv - 1; i >= 0; i--) {
    double xi = x[i];
    if (xi == 0) continue;
    int end = rowadr[i] + rownnz[i] - 1;
    for (int adr = rowadr[i]; adr < end; adr++) x[colind[adr]] -= ld[adr] * xi;
  }
  // x <- D^-1 x
  for (int i = 0; i < nv; i++) x[i] *= diag_inv[i];
  // x <- L^-1 x
  for (int i = 0; i < nv; i++) {
    int n = rownnz[i] - 1;
    if (n > 0) x[i] -= math::DotSparse(ld + rowadr[i], x, n, colind + rowadr[i]);
  }
}

void FactorInertia(const Model& m, Data& d) {
  d.qLD = d.M;
  // A non-positive pivot means a degenerate inertia: warn and keep it tiny but positive.
  for (int k = 0; k < m.nv; k++) {
    int diag = m.M_rowadr[k] + m.M_rownnz[k] - 1;
    if (d.qLD[diag] < kMinVal) {
      RaiseWarning(d, kWarnInertia, k);
      d.qLD[diag] = kMinVal;
    }
  }
  FactorSparse(m, d.qLD.data(), d.qLDiagInv.data());
}

}  // namespace simlab
