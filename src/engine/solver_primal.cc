// The primal constraint solvers (MuJoCo mj_solPrimal, engine_solver.c): minimize
//
//   cost(a) = 0.5 (a - a0)^T M (a - a0) + s(J a - aref)
//
// over the acceleration a, starting from the warm start. Each iteration picks a search
// direction (Newton: -H^-1 grad with H = M + J^T D_active J, factored and then updated by
// rank-one changes as rows change state; CG: Polak-Ribiere on M^-1 grad), then an exact
// line search along it: the cost along a line is piecewise quadratic, so the search
// brackets the minimum with Newton steps on the one-dimensional derivative.
//
// A model that follows MuJoCo 3.12 (Model::release) gets 3.12's iteration: the line search
// measures costs as changes from the line's start (friction and cone rows in forms without
// cancellation) and accepts only points that lower it; before the first step the start is
// kept when it already certifies (half the M^-1-norm of the gradient below the tolerance,
// and for Newton the gradient itself too, then the Newton decrement); the iteration also
// stops on the Newton decrement; CG's directions are Hager and Zhang's.
#include <algorithm>
#include <cmath>
#include <initializer_list>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/sparse_cholesky.h"
#include "math/dot.h"

namespace simlab {

using math::Dot;

// ---------------------------------------------------------------- row states and forces

namespace {

// The Hessian of one cone-zone contact's cost (dim x dim, symmetric) in contact->H.
// In the scaled space U = diag(mu, friction) jar with normal N = U0 and tangent norm T,
// the cost 0.5 Dm (N - mu T)^2 has the Hessian Dm [1, -mu/T U_t^T; ., mu^2 I + mu N/T^3
// U_t U_t^T - mu N/T I] (rank one plus curvature), scaled back by diag(mu, friction).
void ConeHessian(Contact* con, const double* U, double N, double T, double Dm) {
  int dim = con->dim;
  double mu = con->mu;
  double* H = con->H;
  auto scale = [con](int k) { return k == 0 ? con->mu : con->friction[k - 1]; };

  // Upper triangle in the scaled space: first row, tangent block, its diagonal.
  H[0] = 1;
  for (int j = 1; j < dim; j++) H[j] = -mu / T * U[j];
  double outer = mu * N / (T * T * T);
  for (int k = 1; k < dim; k++) {
    for (int j = k; j < dim; j++) H[k * dim + j] = outer * U[j] * U[k];
  }
  double diag = mu * mu - mu * N / T;
  for (int j = 1; j < dim; j++) H[j * (dim + 1)] += diag;

  // Back to jar space (both sides), times Dm; then mirror into the lower triangle.
  for (int k = 0; k < dim; k++) {
    double sk = Dm * scale(k);
    for (int j = k; j < dim; j++) H[k * dim + j] *= sk * scale(j);
  }
  for (int k = 0; k < dim; k++) {
    for (int j = k + 1; j < dim; j++) H[j * dim + k] = H[k * dim + j];
  }
}

// The cone zone's mass Dm = D_0 / (mu^2 (1 + mu^2)) of a contact with first-row D_0.
double ConeMass(double D0, double mu) { return D0 / (mu * mu * (1 + mu * mu)); }

// One elliptic contact's rows i..i+dim-1: zone, forces, state; returns its cost. With the
// friction-scaled U (normal N = mu jar_0, tangents friction_j jar_j, norm T): the top zone
// (N >= mu T) is free, the bottom zone (mu N + T <= 0) quadratic in every row, and in
// between the cost is 0.5 Dm (N - mu T)^2 with Dm = D_0 / (mu^2 (1 + mu^2)).
double UpdateEllipticContact(const RowSet& rows, int i, const double* jar, int* state,
                             double* force, bool cone_hessian) {
  Contact* con = rows.contact + rows.id[i];
  int dim = con->dim;
  double mu = con->mu;
  double U[6];
  U[0] = jar[i] * mu;
  for (int j = 1; j < dim; j++) U[j] = jar[i + j] * con->friction[j - 1];
  double N = U[0];
  double T = std::sqrt(Dot(U + 1, U + 1, dim - 1));

  double cost = 0;
  int zone;
  if (N >= mu * T || (T <= 0 && N >= 0)) {
    // Top zone: separating, no force.
    std::fill(force + i, force + i + dim, 0.0);
    zone = kStateSatisfied;
  } else if (mu * N + T <= 0 || (T <= 0 && N < 0)) {
    // Bottom zone: every row quadratic (forces -D jar as set by the caller).
    for (int j = 0; j < dim; j++) cost += 0.5 * rows.D[i + j] * jar[i + j] * jar[i + j];
    zone = kStateQuadratic;
  } else {
    // Middle zone: the force is -d cost / d jar.
    double Dm = ConeMass(rows.D[i], mu);
    double gap = N - mu * T;
    cost = 0.5 * Dm * gap * gap;
    force[i] = -Dm * gap * mu;
    for (int j = 1; j < dim; j++) force[i + j] = -force[i] / T * U[j] * con->friction[j - 1];
    zone = kStateCone;
    if (cone_hessian) ConeHessian(con, U, N, T, Dm);
  }
  std::fill(state + i, state + i + dim, zone);
  return cost;
}

}  // namespace

RowSet DataRows(Data& d) {
  return RowSet{d.ne, d.nf, d.nefc, d.efc_D.data(), d.efc_R.data(), d.efc_frictionloss.data(),
                d.efc_type.data(), d.efc_id.data(), d.contact.data()};
}

void ConstraintUpdate(const RowSet& rows, const double* jar, int* state, double* force,
                      double* cost, bool cone_hessian) {
  int ne = rows.ne, nf = rows.nf, nefc = rows.nefc;
  const double *D = rows.D, *R = rows.R, *frictionloss = rows.frictionloss;
  double s = 0;
  for (int i = 0; i < nefc; i++) force[i] = -D[i] * jar[i];
  for (int i = 0; i < nefc; i++) {
    double quadratic = 0.5 * D[i] * jar[i] * jar[i];

    // Equality: always quadratic.
    if (i < ne) {
      s += quadratic;
      state[i] = kStateQuadratic;
      continue;
    }

    // Friction: quadratic near zero, linear (constant force) beyond R * frictionloss.
    if (i < ne + nf) {
      double f = frictionloss[i], bound = R[i] * f;
      if (jar[i] <= -bound) {
        s += -0.5 * bound * f - f * jar[i];
        force[i] = f;
        state[i] = kStateLinearNeg;
      } else if (jar[i] >= bound) {
        s += -0.5 * bound * f + f * jar[i];
        force[i] = -f;
        state[i] = kStateLinearPos;
      } else {
        s += quadratic;
        state[i] = kStateQuadratic;
      }
      continue;
    }

    // Elliptic contacts: a cone over the contact's rows.
    if (rows.type[i] == kCnstrContactElliptic) {
      s += UpdateEllipticContact(rows, i, jar, state, force, cone_hessian);
      i += rows.contact[rows.id[i]].dim - 1;
      continue;
    }

    // Limits, frictionless and pyramidal contacts: one-sided.
    if (jar[i] >= 0) {
      force[i] = 0;
      state[i] = kStateSatisfied;
    } else {
      s += quadratic;
      state[i] = kStateQuadratic;
    }
  }
  if (cost) *cost = s;
}

// ---------------------------------------------------------------- small dense algebra

int CholFactor(double* mat, int n, double mindiag, bool clear_deficient) {
  int rank = n;
  for (int j = 0; j < n; j++) {
    double diag = mat[j * (n + 1)] - Dot(mat + j * n, mat + j * n, j);
    bool deficient = diag < mindiag;
    if (deficient) {
      diag = mindiag;
      rank--;
    }
    mat[j * (n + 1)] = std::sqrt(diag);
    if (deficient && clear_deficient) {
      for (int i = j + 1; i < n; i++) mat[i * n + j] = 0;
      continue;
    }
    double inv = 1 / mat[j * (n + 1)];
    for (int i = j + 1; i < n; i++) {
      mat[i * n + j] = (mat[i * n + j] - Dot(mat + i * n, mat + j * n, j)) * inv;
    }
  }
  return rank;
}

void CholSolve(const double* mat, int n, const double* vec, double* res) {
  if (res != vec) std::copy(vec, vec + n, res);
  for (int i = 0; i < n; i++) res[i] = (res[i] - Dot(mat + i * n, res, i)) / mat[i * (n + 1)];
  for (int i = n - 1; i >= 0; i--) {
    for (int j = i + 1; j < n; j++) res[i] -= mat[j * n + i] * res[j];
    res[i] /= mat[i * (n + 1)];
  }
}

int CholUpdate(double* mat, double* x, int n, bool plus) {
  int rank = n;
  for (int k = 0; k < n; k++) {
    if (x[k] == 0) continue;
    double lkk = mat[k * (n + 1)];
    double t = lkk * lkk + (plus ? x[k] * x[k] : -x[k] * x[k]);
    if (t < kMinVal) {
      t = kMinVal;
      rank--;
    }
    double r = std::sqrt(t), c = r / lkk, cinv = 1 / c, s = x[k] / lkk;
    mat[k * (n + 1)] = r;
    for (int i = k + 1; i < n; i++) {
      mat[i * n + k] = (mat[i * n + k] + (plus ? s : -s) * x[i]) * cinv;
    }
    for (int i = k + 1; i < n; i++) x[i] = c * x[i] - s * mat[i * n + k];
  }
  return rank;
}

namespace {

// ---------------------------------------------------------------- products

// res = M vec with the problem's block of M.
void MulSym(const ConstraintProblem& p, const double* vec, double* res) {
  MulSymLayout(p.nv, p.M_rownnz, p.M_rowadr, p.M_colind, p.M, vec, res);
}

// res (rows) = J vec.
void MulJ(const ConstraintProblem& p, const double* vec, double* res) {
  if (!p.sparse()) {
    math::MulMatVec(res, p.J, vec, p.nefc, p.nv);
    return;
  }
  for (int r = 0; r < p.nefc; r++) {
    int adr = p.J_rowadr[r];
    res[r] = math::DotSparse(p.J + adr, vec, p.J_rownnz[r], p.J_colind + adr);
  }
}

// ---------------------------------------------------------------- sparse rows

// The nonzeros of p's dense rows (each row keeps nv slots).
SparseRows CompressDenseRows(const ConstraintProblem& p, SolverFrame& frame) {
  size_t slots = static_cast<size_t>(p.nefc) * p.nv;
  int* rownnz = frame.IntsToWrite(p.nefc);
  int* rowadr = frame.IntsToWrite(p.nefc);
  int* colind = frame.IntsToWrite(slots);
  double* values = frame.RealsToWrite(slots);
  for (int r = 0; r < p.nefc; r++) {
    size_t at = static_cast<size_t>(r) * p.nv;
    rowadr[r] = static_cast<int>(at);
    rownnz[r] = NonzeroColumns(&p.J[at], p.nv, &colind[at]);
    for (int k = 0; k < rownnz[r]; k++) values[at + k] = p.J[at + colind[at + k]];
  }
  return SparseRows{rownnz, rowadr, colind, values};
}

// res (dofs) = J^T f over J's transpose (a sparse dot per dof, as MuJoCo on sparse rows).
void MulJT(const SparseRows& jt, int nv, const double* f, double* res) {
  for (int v = 0; v < nv; v++) {
    int adr = jt.rowadr[v];
    res[v] = math::DotSparse(jt.values + adr, f, jt.rownnz[v], jt.colind + adr);
  }
}

// The pattern of H = M + J^T D J strictly above its diagonal (row r: the dofs i > r that
// share a row of J with r, or descend from r in the dof tree), columns ascending: what
// the symbolic Cholesky reads. Every row of J counts, whatever its state, so that rank-one
// updates stay within the factor's pattern.
RowPattern HessianUpperPattern(const ConstraintProblem& p, const SparseRows& rows,
                               const SparseRows& jt, SolverFrame& frame) {
  int nv = p.nv;
  RowPattern up;
  up.n = nv;
  up.rownnz = frame.Ints(nv);
  up.rowadr = frame.IntsToWrite(nv);
  int* mark = frame.IntsToWrite(nv);
  // Room per row: its descendants (entries of M below it) and the rows of J through it.
  for (int i = 0; i < nv; i++) {
    for (int k = p.M_rowadr[i]; k < p.M_rowadr[i] + p.M_rownnz[i] - 1; k++) {
      up.rownnz[p.M_colind[k]]++;
    }
  }
  // (a row with the dofs of the row before it adds nothing new: the rows of a contact)
  int* repeats = frame.IntsToWrite(p.nefc);
  for (int e = 0; e < p.nefc; e++) repeats[e] = RepeatsRowBefore(rows, e);
  int room = 0;
  for (int r = 0; r < nv; r++) {
    up.rowadr[r] = room;
    room += up.rownnz[r];
    for (int k = jt.rowadr[r]; k < jt.rowadr[r] + jt.rownnz[r]; k++) {
      int e = jt.colind[k];
      if (!repeats[e]) room += rows.rownnz[e];
    }
    up.rownnz[r] = 0;
    mark[r] = -1;
  }
  up.colind = frame.IntsToWrite(room);
  // The tree's entries (M's lower triangle read by columns), then those of J's rows.
  for (int i = 0; i < nv; i++) {
    for (int k = p.M_rowadr[i]; k < p.M_rowadr[i] + p.M_rownnz[i] - 1; k++) {
      int r = p.M_colind[k];
      up.colind[up.rowadr[r] + up.rownnz[r]++] = i;
    }
  }
  for (int r = 0; r < nv; r++) {
    int* row = up.colind + up.rowadr[r];
    for (int k = 0; k < up.rownnz[r]; k++) mark[row[k]] = r;
    for (int k = jt.rowadr[r]; k < jt.rowadr[r] + jt.rownnz[r]; k++) {
      int e = jt.colind[k];
      if (repeats[e]) continue;
      for (int q = rows.rowadr[e] + rows.rownnz[e] - 1; q >= rows.rowadr[e]; q--) {
        int i = rows.colind[q];
        if (i <= r) break;
        if (mark[i] == r) continue;
        mark[i] = r;
        row[up.rownnz[r]++] = i;
      }
    }
    std::sort(row, row + up.rownnz[r]);
  }
  return up;
}

// The symbolic reverse Cholesky of H's pattern, in arrays of `frame`.
CholeskyPattern SymbolicHessian(const RowPattern& upper, SolverFrame& frame) {
  int n = upper.n;
  CholeskyPattern c;
  c.lower.rownnz = frame.IntsToWrite(n);
  c.lower.rowadr = frame.IntsToWrite(n);
  c.transposed.rownnz = frame.IntsToWrite(n);
  c.transposed.rowadr = frame.IntsToWrite(n);
  int* parent = frame.IntsToWrite(n);
  int* flag = frame.IntsToWrite(n);
  int* cursor = frame.IntsToWrite(n);
  int* lt_write = frame.IntsToWrite(n);
  int nnz = CountCholesky(upper, c, parent, flag);
  c.lower.colind = frame.IntsToWrite(nnz);
  c.transposed.colind = frame.IntsToWrite(nnz);
  c.lt_map = frame.IntsToWrite(nnz);
  FillCholesky(upper, c, parent, flag, cursor, lt_write);
  return c;
}

// ---------------------------------------------------------------- solver state

struct Primal {
  ConstraintProblem& p;
  bool newton;
  bool elliptic;  // the model's contacts use elliptic cones
  // Rows: J a - aref, J search, the old states; quad: 3 numbers per row (an elliptic
  // contact's first row uses 9: its rows have room).
  double *jaref, *jv, *quad;
  int* oldstate;
  // Dofs: M a, M search, the gradient, its preconditioned form and the direction; CG
  // keeps the previous gradients and the change of the preconditioned one.
  double *ma, *mv, *grad, *mgrad, *search, *gradold, *mgradold, *mgrad_change, *grad_change;
  // Sparse rows (p.sparse()): J^T by dofs, for J^T f.
  SparseRows jt;
  // Newton: the rows of J by their nonzeros (`rows`: p's own compressed rows, or the
  // nonzeros of its dense ones); the Cholesky factor of M + J^T D_active J, the same plus
  // the cone-zone contacts' Hessians, and room for update vectors (one per row of a
  // contact). The factors are dense (nv x nv) or, on sparse rows, in the layout of
  // `chol` (its nnz entries each) with two nv arrays of scratch: `dense` for the
  // factorization (zero between uses) and `scattered` for the rank-one updates. (Sparse
  // rows get the sparse factor on every problem, as MuJoCo factors each island of a sparse
  // model, so that both round alike.)
  SparseRows rows;
  CholeskyPattern chol;
  double *hessian = nullptr, *hessian_cone = nullptr, *updates = nullptr;
  double *dense = nullptr, *scattered = nullptr;
  double cost = 0;
  double quad_gauss[3] = {0, 0, 0};
  int ncone = 0;  // rows in the cone state
  int ls_iter = 0;
  // MuJoCo 3.12's solver (a model that follows 3.12, Model::release): line-search costs
  // taken as differences from the line's start, a convergence certificate before the
  // first step, the Newton decrement as a stopping test, and Hager-Zhang CG directions.
  bool newer = false;

  Primal(ConstraintProblem& problem, bool is_newton, bool is_elliptic, SolverFrame& frame)
      : p(problem), newton(is_newton), elliptic(is_elliptic) {
    int nv = p.nv, nefc = p.nefc;
    jaref = frame.Reals(nefc);
    jv = frame.Reals(nefc);
    quad = frame.Reals(3 * static_cast<size_t>(nefc));
    oldstate = frame.Ints(nefc);
    for (double** dof_array :
         {&ma, &mv, &grad, &mgrad, &search, &gradold, &mgradold, &mgrad_change, &grad_change}) {
      *dof_array = frame.Reals(nv);
    }
    if (p.sparse()) {
      rows = SparseRows{p.J_rownnz, p.J_rowadr, p.J_colind, p.J};
      jt = TransposeRows(rows, nefc, nv, frame);
    }
    if (!newton) return;
    if (!p.sparse()) rows = CompressDenseRows(p, frame);
    // (the factors are filled by FactorHessian and AddConeHessians, the update vectors by
    // their users: not cleared here)
    size_t entries = static_cast<size_t>(nv) * nv;
    if (sparse_factor()) {
      chol = SymbolicHessian(HessianUpperPattern(p, rows, jt, frame), frame);
      entries = chol.nnz;
      dense = frame.Reals(nv);
      scattered = frame.RealsToWrite(nv);
    }
    hessian = frame.RealsToWrite(entries);
    if (elliptic) hessian_cone = frame.RealsToWrite(entries);
    updates = frame.RealsToWrite(6 * static_cast<size_t>(nv));
  }

  bool sparse_factor() const { return p.sparse(); }

  // The factor Newton steps with: with the cones' curvature when any contact is in the cone.
  const double* NewtonFactor() const { return ncone ? hessian_cone : hessian; }
};

// Row states, forces, qfrc_constraint and the total cost at the current iterate.
void UpdateConstraint(Primal& s) {
  ConstraintProblem& p = s.p;
  ConstraintUpdate(p.Rows(), s.jaref, p.state, p.force, &s.cost, s.newton && s.elliptic);
  s.ncone = static_cast<int>(std::count(p.state, p.state + p.nefc, kStateCone));
  if (p.sparse()) {
    MulJT(s.jt, p.nv, p.force, p.qfrc_constraint);
  } else {
    math::MulMatTVec(p.qfrc_constraint, p.J, p.force, p.nefc, p.nv);
  }
  double gauss = 0;
  for (int v = 0; v < p.nv; v++) {
    gauss += 0.5 * (s.ma[v] - p.qfrc_smooth[v]) * (p.qacc[v] - p.qacc_smooth[v]);
  }
  s.quad_gauss[0] = gauss;
  s.cost += gauss;
}

// grad = M a - qfrc_smooth - qfrc_constraint.
void ComputeGradient(Primal& s) {
  ConstraintProblem& p = s.p;
  for (int v = 0; v < p.nv; v++) s.grad[v] = s.ma[v] - p.qfrc_smooth[v] - p.qfrc_constraint[v];
}

// The preconditioned gradient: H^-1 grad with the Newton factor, else M^-1 grad.
void PreconditionGradient(Primal& s, bool hessian) {
  ConstraintProblem& p = s.p;
  if (hessian && s.sparse_factor()) {
    SolveCholesky(s.chol, s.NewtonFactor(), s.grad, s.mgrad);
  } else if (hessian) {
    CholSolve(s.NewtonFactor(), p.nv, s.grad, s.mgrad);
  } else {
    std::copy(s.grad, s.grad + p.nv, s.mgrad);
    SolveSparseLayout(p.nv, p.M_rownnz, p.M_rowadr, p.M_colind, p.qLD, p.qLDiagInv, s.mgrad);
  }
}

// grad and the preconditioned gradient.
void UpdateGradient(Primal& s) {
  ComputeGradient(s);
  PreconditionGradient(s, s.newton);
}

// C^T J for one cone-zone contact (rows i..i+dim-1), C the Cholesky factor of its cost's
// Hessian H = C C^T: dim vectors in `ltj` (MuJoCo HessianCone), of nv entries for the
// dense factor, or over row i's nnz dofs for the sparse one (compressed rows of one
// contact share their dofs).
int ConeUpdateVectors(const Primal& s, int i, double* ltj) {
  const ConstraintProblem& p = s.p;
  const Contact& con = p.contact[p.id[i]];
  int dim = con.dim;
  int width = s.sparse_factor() ? s.rows.rownnz[i] : p.nv;
  double local[36];
  std::copy(con.H, con.H + dim * dim, local);
  CholFactor(local, dim, kMinVal, s.newer);
  // Column c of C^T J: sum over rows r >= c of C(r, c) J_r.
  std::fill(ltj, ltj + dim * width, 0.0);
  for (int r = 0; r < dim; r++) {
    int adr = s.rows.rowadr[i + r], nnz = s.rows.rownnz[i + r];
    const double* vals = s.rows.values + adr;
    const int* cols = s.rows.colind + adr;
    for (int c = 0; c <= r; c++) {
      double* column = ltj + c * width;
      double scale = local[r * dim + c];
      for (int k = 0; k < nnz; k++) column[s.sparse_factor() ? k : cols[k]] += scale * vals[k];
    }
  }
  return width;
}

// The cone factor: the plain factor updated by each cone-zone contact's Hessian H = C C^T
// (C its Cholesky factor), i.e. by the dim vectors of (J_contact^T C).
void AddConeHessians(Primal& s) {
  ConstraintProblem& p = s.p;
  size_t entries = s.sparse_factor() ? s.chol.nnz : static_cast<size_t>(p.nv) * p.nv;
  std::copy(s.hessian, s.hessian + entries, s.hessian_cone);
  double* ltj = s.updates;
  for (int i = 0; i < p.nefc; i++) {
    if (p.state[i] != kStateCone) continue;
    int dim = p.contact[p.id[i]].dim;
    int width = ConeUpdateVectors(s, i, ltj);
    for (int r = 0; r < dim; r++) {
      if (s.sparse_factor()) {
        UpdateCholesky(s.chol, s.hessian_cone, &ltj[r * width], s.rows.colind + s.rows.rowadr[i],
                       width, true, s.scattered);
      } else {
        CholUpdate(s.hessian_cone, &ltj[r * width], p.nv, true);
      }
    }
    i += dim - 1;
  }
}

// Row r of H = J^T D J + M (columns 0..r) added into `dense`: the quadratic rows of J in
// ascending order, then M. Each product is rounded as MuJoCo rounds it: 3.5.1's
// mju_sqrMatTDSparse J(e, r) (D(e) J(e, c)) left of the diagonal, (J(e, r) J(e, r)) D(e)
// on it; 3.12's numeric phase (D(e) J(e, r)) J(e, c) throughout (s.newer).
void AddHessianRow(const Primal& s, int r, double* dense) {
  const ConstraintProblem& p = s.p;
  const SparseRows& jt = s.jt;
  for (int k = jt.rowadr[r]; k < jt.rowadr[r] + jt.rownnz[r]; k++) {
    int e = jt.colind[k];
    if (p.state[e] != kStateQuadratic) continue;
    double jr = jt.values[k], d = p.D[e];
    if (s.newer) {
      double scale = d * jr;
      if (scale == 0) continue;
      for (int q = s.rows.rowadr[e]; q < s.rows.rowadr[e] + s.rows.rownnz[e]; q++) {
        int c = s.rows.colind[q];
        if (c > r) break;
        dense[c] += scale * s.rows.values[q];
      }
      continue;
    }
    for (int q = s.rows.rowadr[e]; q < s.rows.rowadr[e] + s.rows.rownnz[e]; q++) {
      int c = s.rows.colind[q];
      if (c >= r) break;
      dense[c] += jr * (d * s.rows.values[q]);
    }
    dense[r] += (jr * jr) * d;
  }
  for (int k = p.M_rowadr[r]; k < p.M_rowadr[r] + p.M_rownnz[r]; k++) {
    dense[p.M_colind[k]] += p.M[k];
  }
}

// The quadratic rows from r on that hold the same columns as r (a contact's rows), at
// most kHessianGroup of them.
constexpr int kHessianGroup = 4;
int QuadraticRowGroup(const Primal& s, int r) {
  int g = 1;
  while (g < kHessianGroup && r + g < s.p.nefc && s.p.state[r + g] == kStateQuadratic &&
         RepeatsRowBefore(s.rows, r + g)) {
    g++;
  }
  return g;
}

// Adds the G rows' J^T D J into the lower triangle h: each entry takes the rows' products
// in row order, as one row at a time would (the same sums), but is loaded once.
template <int G>
void AddHessianGroup(const Primal& s, int r, double* h) {
  const ConstraintProblem& p = s.p;
  int nv = p.nv, nnz = s.rows.rownnz[r];
  const int* cols = s.rows.colind + s.rows.rowadr[r];
  const double* vals[G];
  for (int q = 0; q < G; q++) vals[q] = s.rows.values + s.rows.rowadr[r + q];
  for (int a = 0; a < nnz; a++) {
    double scaled[G];
    for (int q = 0; q < G; q++) scaled[q] = vals[q][a] * p.D[r + q];
    double* row = h + static_cast<size_t>(cols[a]) * nv;
    for (int b = 0; b <= a; b++) {
      double sum = row[cols[b]];
      for (int q = 0; q < G; q++) sum += scaled[q] * vals[q][b];
      row[cols[b]] = sum;
    }
  }
}

void AddHessianGroup(const Primal& s, int r, int g, double* h) {
  switch (g) {
    case 4: return AddHessianGroup<4>(s, r, h);
    case 3: return AddHessianGroup<3>(s, r, h);
    case 2: return AddHessianGroup<2>(s, r, h);
    default: return AddHessianGroup<1>(s, r, h);
  }
}

// H = M + J^T D J over the rows in the quadratic state, dense (lower triangle).
void AssembleDenseHessian(Primal& s) {
  ConstraintProblem& p = s.p;
  int nv = p.nv;
  double* h = s.hessian;
  std::fill(h, h + static_cast<size_t>(nv) * nv, 0.0);
  // (only the rows' nonzeros: the zeros would add exact zeros to the same sums)
  for (int r = 0; r < p.nefc; r++) {
    if (p.state[r] != kStateQuadratic) continue;
    int g = QuadraticRowGroup(s, r);
    AddHessianGroup(s, r, g, h);
    r += g - 1;
  }
  for (int i = 0; i < nv; i++) {
    for (int k = p.M_rowadr[i]; k < p.M_rowadr[i] + p.M_rownnz[i]; k++) {
      h[i * nv + p.M_colind[k]] += p.M[k];
    }
  }
}

// H = M + J^T D J over the rows in the quadratic state, factored; then the cone factor
// when contacts are in the cone.
void FactorHessian(Primal& s) {
  if (s.sparse_factor()) {
    FactorCholesky(s.chol, s.hessian, kMinVal, s.dense,
                   [&s](int r, double* dense) { AddHessianRow(s, r, dense); });
  } else {
    AssembleDenseHessian(s);
    CholFactor(s.hessian, s.p.nv, kMinVal, s.newer);
  }
  if (s.ncone) AddConeHessians(s);
}

// Rank-one updates of the factor for rows that entered or left the quadratic state (a
// full refactorization if an update loses rank); then the cone factor anew.
void UpdateHessian(Primal& s) {
  ConstraintProblem& p = s.p;
  double* x = s.updates;
  for (int r = 0; r < p.nefc; r++) {
    bool was = s.oldstate[r] == kStateQuadratic, is = p.state[r] == kStateQuadratic;
    if (was == is) continue;
    double sqrt_d = std::sqrt(p.D[r]);
    int adr = s.rows.rowadr[r], nnz = s.rows.rownnz[r];
    const int* cols = s.rows.colind + adr;
    int rank;
    if (s.sparse_factor()) {
      for (int k = 0; k < nnz; k++) x[k] = s.rows.values[adr + k] * sqrt_d;
      rank = UpdateCholesky(s.chol, s.hessian, x, cols, nnz, is, s.scattered);
    } else {
      std::fill(x, x + p.nv, 0.0);
      for (int k = 0; k < nnz; k++) x[cols[k]] = s.rows.values[adr + k] * sqrt_d;
      rank = CholUpdate(s.hessian, x, p.nv, is);
    }
    if (rank < p.nv) {
      FactorHessian(s);
      return;
    }
  }
  if (s.ncone) AddConeHessians(s);
}

// ---------------------------------------------------------------- line search

struct LinePoint {
  double alpha = 0;
  double cost = 0;
  double deriv[2] = {0, 0};  // first and second derivative along the line
};

// An elliptic contact's numbers along the line (rows i..i+dim-1), q = &quad[3 i]: q[0..2]
// become the bottom zone's quadratic over all its rows (still unhalved), and with the
// friction-scaled U = diag(mu, friction) jaref and V = diag(mu, friction) jv:
// q[3] = U0, q[4] = V0, q[5..7] = U_t.U_t, U_t.V_t, V_t.V_t and q[8] = Dm.
void PrepareCone(const Primal& s, int i, double* q) {
  const ConstraintProblem& p = s.p;
  const Contact& con = p.contact[p.id[i]];
  int dim = con.dim;
  double mu = con.mu;
  for (int j = 1; j < dim; j++) {
    double dj = p.D[i + j] * s.jaref[i + j];
    q[0] += s.jaref[i + j] * dj;
    q[1] += s.jv[i + j] * dj;
    q[2] += s.jv[i + j] * p.D[i + j] * s.jv[i + j];
  }
  double uu = 0, uv = 0, vv = 0;
  for (int j = 1; j < dim; j++) {
    double u = s.jaref[i + j] * con.friction[j - 1], v = s.jv[i + j] * con.friction[j - 1];
    uu += u * u;
    uv += u * v;
    vv += v * v;
  }
  q[3] = s.jaref[i] * mu;
  q[4] = s.jv[i] * mu;
  q[5] = uu;
  q[6] = uv;
  q[7] = vv;
  q[8] = ConeMass(p.D[i], mu);
}

// Per-row quadratics along the search line: cost_r(alpha) = q0 + q1 alpha + q2 alpha^2.
void PrepareLine(Primal& s) {
  ConstraintProblem& p = s.p;
  int nv = p.nv;
  s.quad_gauss[1] = Dot(s.search, s.ma, nv) - Dot(p.qfrc_smooth, s.search, nv);
  s.quad_gauss[2] = 0.5 * Dot(s.search, s.mv, nv);
  for (int r = 0; r < p.nefc; r++) {
    double* q = &s.quad[3 * r];
    double dj = p.D[r] * s.jaref[r];
    q[0] = s.jaref[r] * dj;
    q[1] = s.jv[r] * dj;
    q[2] = s.jv[r] * p.D[r] * s.jv[r];
    if (p.type[r] == kCnstrContactElliptic) {
      PrepareCone(s, r, q);
      r += p.contact[p.id[r]].dim - 1;
    }
    q[0] *= 0.5;
    q[2] *= 0.5;
  }
}

// total += q (the coefficients of a quadratic along the line).
void AddQuadratic(double total[3], const double* q) {
  total[0] += q[0];
  total[1] += q[1];
  total[2] += q[2];
}

// Where a friction row's x = J a - aref lies against its bound: -1 below -bound (the cost
// linear, falling), 0 within (quadratic), 1 above (linear, rising; NaN too).
int FrictionZone(double x, double bound) {
  if (-bound < x && x < bound) return 0;
  return x <= -bound ? -1 : 1;
}

// An elliptic contact's zone for normal N and squared tangent norm Tsqr (T its root):
// free (top), quadratic in every row (bottom), or on the cone (middle).
enum ConeZoneKind { kZoneTop = 1, kZoneBottom = 2, kZoneMiddle = 3 };
ConeZoneKind ConeZone(double N, double Tsqr, double mu, double* T) {
  *T = 0;
  if (Tsqr <= 0) return N < 0 ? kZoneBottom : kZoneTop;
  *T = std::sqrt(Tsqr);
  if (N >= mu * *T) return kZoneTop;
  return mu * N + *T <= 0 ? kZoneBottom : kZoneMiddle;
}

// The derivatives along the line of a middle-zone contact's cost 0.5 Dm (N - mu T)^2
// (q prepared by PrepareCone; N, T at alpha), added to deriv.
void AddConeMiddleDerivatives(const double* q, double alpha, double mu, double N, double T,
                              double deriv[2]) {
  double Dm = q[8];
  double N1 = q[4];
  double T1 = (q[6] + alpha * q[7]) / T;
  double T2 = q[7] / T - (q[6] + alpha * q[7]) * T1 / (T * T);
  double gap = N - mu * T, gap1 = N1 - mu * T1;
  deriv[0] += Dm * gap * gap1;
  deriv[1] += Dm * (gap1 * gap1 + gap * (-mu * T2));
}

// The cost of an elliptic contact along the line (rows i.., prepared in q[0..8]): in its
// zone at alpha, added to the totals (bottom zone) or to cost/deriv (middle zone).
void EvalCone(const Primal& s, int i, double alpha, double total[3], double* cost,
              double deriv[2]) {
  const double* q = &s.quad[3 * i];
  double mu = s.p.contact[s.p.id[i]].mu;
  double N = q[3] + alpha * q[4], T;
  ConeZoneKind zone = ConeZone(N, q[5] + alpha * (2 * q[6] + alpha * q[7]), mu, &T);
  if (zone == kZoneBottom) AddQuadratic(total, q);
  if (zone != kZoneMiddle) return;
  double gap = N - mu * T;
  *cost += 0.5 * q[8] * gap * gap;
  AddConeMiddleDerivatives(q, alpha, mu, N, T, deriv);
}

// A line point's cost and derivatives: the rows' quadratic total at alpha plus what the
// rows outside it (cone-zone contacts, friction changes) summed in cost and deriv.
void FinishLinePoint(Primal& s, double alpha, const double total[3], double cost,
                     const double deriv[2], LinePoint* point) {
  point->cost = cost + (alpha * alpha * total[2] + alpha * total[1] + total[0]);
  point->deriv[0] = deriv[0] + (2 * alpha * total[2] + total[1]);
  point->deriv[1] = deriv[1] + 2 * total[2];
  // Not convex (should not occur): counted, reported by the caller as a warning.
  if (point->deriv[1] <= 0) {
    s.p.nonconvex++;
    point->deriv[1] = kMinVal;
  }
  s.ls_iter++;
}

// ------------------------------------------------ MuJoCo 3.12's line costs, from the start

// A friction row's Huber cost at x: quadratic 0.5 D x^2 inside the bound, linear outside.
double FrictionCost(double x, double f, double bound, double D) {
  int zone = FrictionZone(x, bound);
  if (zone == 0) return 0.5 * D * x * x;
  return zone < 0 ? f * (-0.5 * bound - x) : f * (-0.5 * bound + x);
}

// A friction row's cost at x less its cost at start: within one zone, in a form without
// cancellation; across zones, the two costs subtracted.
double FrictionCostChange(double start, double x, double f, double bound, double D) {
  int from = FrictionZone(start, bound), to = FrictionZone(x, bound);
  if (from == 0 && to == 0) return 0.5 * D * (x - start) * (x + start);
  if (from == -1 && to == -1) return f * (start - x);
  if (from == 1 && to == 1) return f * (x - start);
  return FrictionCost(x, f, bound, D) - FrictionCost(start, f, bound, D);
}

// An elliptic contact's cost at alpha less its cost at 0 (q prepared by PrepareCone, Dm
// its cone mass; at alpha its zone `to`, normal N and tangent norm T), per the pair of
// zones; within the cone in rationalized form.
double ConeCostChange(const double* q, double alpha, double mu, ConeZoneKind to, double N,
                      double T) {
  double U0 = q[3], V0 = q[4], UU = q[5], UV = q[6], VV = q[7], Dm = q[8];
  double T0;
  ConeZoneKind from = ConeZone(U0, UU, mu, &T0);
  double bottom = alpha * alpha * q[2] + alpha * q[1];  // the quadratic's change
  if (from == kZoneTop && to == kZoneTop) return 0;
  if (from == kZoneBottom && to == kZoneBottom) return bottom;
  if (from == kZoneMiddle && to == kZoneMiddle) {
    double T_change = alpha * (2 * UV + alpha * VV) / (T + T0);
    double r_change = alpha * V0 - mu * T_change;
    return 0.5 * Dm * r_change * (2 * (U0 - mu * T0) + r_change);
  }
  if (from == kZoneMiddle && to == kZoneBottom) {
    double edge0 = mu * U0 + T0;
    return alpha * (alpha * q[2] + q[1]) + 0.5 * Dm * edge0 * edge0;
  }
  if (from == kZoneBottom && to == kZoneMiddle) {
    double edge = mu * N + T;
    return alpha * (alpha * q[2] + q[1]) - 0.5 * Dm * edge * edge;
  }
  if (from == kZoneTop && to == kZoneBottom) return bottom + q[0];
  if (from == kZoneTop && to == kZoneMiddle) return 0.5 * Dm * (N - mu * T) * (N - mu * T);
  if (from == kZoneMiddle && to == kZoneTop) return -0.5 * Dm * (U0 - mu * T0) * (U0 - mu * T0);
  if (from == kZoneBottom && to == kZoneTop) return -q[0];
  return 0;
}

// An elliptic contact's derivatives along the line at alpha (its zone there, N and T).
void AddConeDerivatives(const double* q, double alpha, double mu, ConeZoneKind zone, double N,
                        double T, double deriv[2]) {
  if (zone == kZoneBottom) {
    deriv[0] += 2 * alpha * q[2] + q[1];
    deriv[1] += 2 * q[2];
  } else if (zone == kZoneMiddle) {
    AddConeMiddleDerivatives(q, alpha, mu, N, T, deriv);
  }
}

// Cost at alpha less the cost at the line's start, and its derivatives (MuJoCo 3.12's
// PrimalEval): the Gauss term and quadratic rows without their constant part, friction
// and cone rows by their changes, inequality rows less their cost at the start.
void EvalLineFromStart(Primal& s, LinePoint* point) {
  ConstraintProblem& p = s.p;
  double alpha = point->alpha;
  double total[3] = {0, s.quad_gauss[1], s.quad_gauss[2]};
  double cost = 0, deriv[2] = {0, 0};
  for (int r = 0; r < p.nefc; r++) {
    const double* q = &s.quad[3 * r];
    if (r < p.ne) {
      total[1] += q[1];
      total[2] += q[2];
    } else if (r < p.ne + p.nf) {
      double start = s.jaref[r], dir = s.jv[r], x = start + alpha * dir;
      double f = p.frictionloss[r], D = p.D[r], bound = p.R[r] * f;
      cost += FrictionCostChange(start, x, f, bound, D);
      int zone = FrictionZone(x, bound);
      if (zone == 0) {
        deriv[0] += D * x * dir;
        deriv[1] += D * dir * dir;
      } else {
        deriv[0] += zone < 0 ? -f * dir : f * dir;
      }
    } else if (p.type[r] == kCnstrContactElliptic) {
      const Contact& con = p.contact[p.id[r]];
      double N = q[3] + alpha * q[4], T;
      ConeZoneKind zone = ConeZone(N, q[5] + alpha * (2 * q[6] + alpha * q[7]), con.mu, &T);
      cost += ConeCostChange(q, alpha, con.mu, zone, N, T);
      AddConeDerivatives(q, alpha, con.mu, zone, N, T, deriv);
      r += con.dim - 1;
    } else {
      double start = s.jaref[r], x = start + alpha * s.jv[r];
      double cost0 = start < 0 ? q[0] : 0;
      if (x < 0) {
        total[0] += q[0] - cost0;
        total[1] += q[1];
        total[2] += q[2];
      } else {
        cost -= cost0;
      }
    }
  }
  FinishLinePoint(s, alpha, total, cost, deriv, point);
}

// Cost and its derivatives at alpha along the search direction.
void EvalLine(Primal& s, LinePoint* point) {
  if (s.newer) {
    EvalLineFromStart(s, point);
    return;
  }
  ConstraintProblem& p = s.p;
  double alpha = point->alpha;
  double total[3] = {s.quad_gauss[0], s.quad_gauss[1], s.quad_gauss[2]};
  double cost = 0, deriv[2] = {0, 0};  // the cone-zone contacts' share
  for (int r = 0; r < p.nefc; r++) {
    double x = s.jaref[r] + alpha * s.jv[r];
    if (r < p.ne) {
      AddQuadratic(total, &s.quad[3 * r]);
    } else if (r < p.ne + p.nf) {
      // Friction: quadratic inside the bound, linear outside.
      double f = p.frictionloss[r], bound = p.R[r] * f;
      int zone = FrictionZone(x, bound);
      if (zone == 0) {
        AddQuadratic(total, &s.quad[3 * r]);
      } else if (zone < 0) {
        double q[3] = {f * (-0.5 * bound - s.jaref[r]), -f * s.jv[r], 0};
        AddQuadratic(total, q);
      } else {
        double q[3] = {f * (-0.5 * bound + s.jaref[r]), f * s.jv[r], 0};
        AddQuadratic(total, q);
      }
    } else if (p.type[r] == kCnstrContactElliptic) {
      EvalCone(s, r, alpha, total, &cost, deriv);
      r += p.contact[p.id[r]].dim - 1;
    } else if (x < 0) {
      AddQuadratic(total, &s.quad[3 * r]);
    }
  }
  FinishLinePoint(s, alpha, total, cost, deriv, point);
}

// Replaces bracket end `end` by a candidate on the same side of the minimum with a
// smaller |derivative|; then the Newton point from it. Returns whether it moved.
bool UpdateBracket(Primal& s, LinePoint* end, const LinePoint candidates[3], LinePoint* next) {
  bool moved = false;
  for (int i = 0; i < 3; i++) {
    double dc = candidates[i].deriv[0], de = end->deriv[0];
    if ((de < 0 && dc < 0 && de < dc) || (de > 0 && dc > 0 && de > dc)) {
      *end = candidates[i];
      moved = true;
    }
  }
  if (moved) {
    next->alpha = end->alpha - end->deriv[0] / end->deriv[1];
    EvalLine(s, next);
  }
  return moved;
}

// The step length along `search` (0: no improvement possible). MuJoCo's PrimalSearch;
// under 3.12's rules (s.newer) a converged point must also lower the cost (its cost is
// the change from the start), and `improvement` is set to the decrease.
double LineSearch(const Model& m, Primal& s, double* improvement) {
  ConstraintProblem& p = s.p;
  *improvement = 0;
  int ls_iterations = m.opt.ls_iterations;
  s.ls_iter = 0;
  double snorm = std::sqrt(Dot(s.search, s.search, p.nv));
  if (snorm < kMinVal) return 0;
  double gtol = m.opt.tolerance * m.opt.ls_tolerance * snorm / p.scale;

  MulSym(p, s.search, s.mv);
  MulJ(p, s.search, s.jv);
  PrepareLine(s);

  // A first Newton step from alpha = 0.
  LinePoint p0, p1;
  EvalLine(s, &p0);
  p1.alpha = p0.alpha - p0.deriv[0] / p0.deriv[1];
  EvalLine(s, &p1);
  // (the step taken, with the decrease it brings under 3.12's rules)
  auto take = [improvement](const LinePoint& point) {
    *improvement = -point.cost;
    return point.alpha;
  };
  bool lowers = !s.newer || p1.alpha == 0 || p1.cost < 0;
  if (std::abs(p1.deriv[0]) < gtol && lowers) return take(p1);

  // One-sided Newton steps until the derivative changes sign.
  int dir = p1.deriv[0] < 0 ? 1 : -1;
  LinePoint p2 = p0;
  while (p1.deriv[0] * dir <= -gtol && s.ls_iter < ls_iterations) {
    p2 = p1;
    p1.alpha -= p1.deriv[0] / p1.deriv[1];
    EvalLine(s, &p1);
    if (std::abs(p1.deriv[0]) < gtol && (!s.newer || p1.cost < 0)) return take(p1);
  }
  if (s.ls_iter >= ls_iterations) return take(p1);

  // Bracketed search between p1 and p2.
  LinePoint p2next = p1, p1next;
  p1next.alpha = p1.alpha - p1.deriv[0] / p1.deriv[1];
  EvalLine(s, &p1next);
  while (s.ls_iter < ls_iterations) {
    LinePoint mid;
    mid.alpha = 0.5 * (p1.alpha + p2.alpha);
    EvalLine(s, &mid);
    LinePoint candidates[3] = {p1next, p2next, mid};

    // Converged candidate with the lowest cost wins.
    int best = -1;
    for (int i = 0; i < 3; i++) {
      if (std::abs(candidates[i].deriv[0]) < gtol &&
          (best == -1 || candidates[i].cost < candidates[best].cost)) {
        best = i;
      }
    }
    if (best >= 0) return take(candidates[best]);

    bool moved1 = UpdateBracket(s, &p1, candidates, &p1next);
    bool moved2 = UpdateBracket(s, &p2, candidates, &p2next);
    if (!moved1 && !moved2) return take(mid);
  }

  // Out of iterations: the better bracket end, if it improves on the start.
  double start = s.newer ? 0 : p0.cost;
  if (p1.cost <= p2.cost && p1.cost < start) return take(p1);
  if (p2.cost <= p1.cost && p2.cost < start) return take(p2);
  return 0;
}

// ---------------------------------------------------------------- the iteration

// Moves the iterate alpha along the search direction and updates states, forces, the
// Newton factor and the gradient there.
void Advance(Primal& s, double alpha) {
  ConstraintProblem& p = s.p;
  int nv = p.nv, nefc = p.nefc;
  for (int v = 0; v < nv; v++) {
    p.qacc[v] += alpha * s.search[v];
    s.ma[v] += alpha * s.mv[v];
  }
  for (int r = 0; r < nefc; r++) s.jaref[r] += alpha * s.jv[r];
  if (!s.newton) {
    std::copy(s.grad, s.grad + nv, s.gradold);
    std::copy(s.mgrad, s.mgrad + nv, s.mgradold);
  }
  std::copy(p.state, p.state + nefc, s.oldstate);
  UpdateConstraint(s);
  if (s.newton) UpdateHessian(s);
  UpdateGradient(s);
}

// The next CG direction -M^-1 grad + beta search, beta by Polak-Ribiere (reset when
// negative): MuJoCo 3.5.1's.
void PolakRibiereDirection(Primal& s) {
  int nv = s.p.nv;
  for (int v = 0; v < nv; v++) s.mgrad_change[v] = s.mgrad[v] - s.mgradold[v];
  double beta = Dot(s.grad, s.mgrad_change, nv) / std::max(kMinVal, Dot(s.gradold, s.mgradold, nv));
  beta = std::max(0.0, beta);
  for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v] + beta * s.search[v];
}

// The next CG direction with beta by Hager and Zhang, bounded below so that the direction
// stays away from orthogonal to the gradient, and 0 when the last step lost conjugacy:
// MuJoCo 3.12's.
void HagerZhangDirection(Primal& s) {
  int nv = s.p.nv;
  for (int v = 0; v < nv; v++) {
    s.grad_change[v] = s.grad[v] - s.gradold[v];
    s.mgrad_change[v] = s.mgrad[v] - s.mgradold[v];
  }
  double beta = 0;
  double d_y = Dot(s.search, s.grad_change, nv);
  if (d_y >= kMinVal) {
    double y_My = Dot(s.grad_change, s.mgrad_change, nv);
    double y_Mgrad = Dot(s.grad_change, s.mgrad, nv);
    double d_grad = Dot(s.search, s.grad, nv);
    double beta_hz = (y_Mgrad - 2 * (y_My / d_y) * d_grad) / d_y;
    double d_norm = std::sqrt(Dot(s.search, s.search, nv));
    double grad_norm = std::sqrt(Dot(s.grad, s.grad, nv));
    double bound = -1.0 / std::max(kMinVal, d_norm * std::min(0.01, grad_norm));
    beta = std::max(bound, beta_hz);
  }
  for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v] + beta * s.search[v];
}

// MuJoCo 3.5.1's iteration from the start's states: steps until the cost or the gradient
// (scaled) is not worth another. Returns the iterations.
int IterateAsMuJoCo351(const Model& m, Primal& s) {
  ConstraintProblem& p = s.p;
  int nv = p.nv;
  if (s.newton) FactorHessian(s);
  UpdateGradient(s);
  for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v];
  int iter = 0;
  while (iter < m.opt.iterations) {
    double unused;
    double alpha = LineSearch(m, s, &unused);
    if (alpha == 0) break;
    double oldcost = s.cost;
    Advance(s, alpha);
    double improvement = p.scale * (oldcost - s.cost);
    double gradient = p.scale * std::sqrt(Dot(s.grad, s.grad, nv));
    iter++;
    if (improvement < m.opt.tolerance || gradient < m.opt.tolerance) break;
    if (s.newton) {
      for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v];
    } else {
      PolakRibiereDirection(s);
    }
  }
  return iter;
}

// 0.5 grad' mgrad scaled, never negative: with mgrad = M^-1 grad a bound on how far the
// cost is above its minimum, with H^-1 grad the Newton decrement.
double HalfGradientNorm(const Primal& s) {
  return std::max(0.0, 0.5 * s.p.scale * Dot(s.grad, s.mgrad, s.p.nv));
}

// MuJoCo 3.12's iteration: done before any step when the start already certifies (the
// gap bound, and for Newton the gradient too, below the tolerance; then Newton's decrement);
// then steps until the line search's decrease, the gradient or the Newton decrement is
// below it. Returns the iterations.
int IterateAsMuJoCo312(const Model& m, Primal& s) {
  ConstraintProblem& p = s.p;
  int nv = p.nv;
  double tolerance = m.opt.tolerance;
  ComputeGradient(s);
  PreconditionGradient(s, false);
  bool small_gradient = p.scale * std::sqrt(Dot(s.grad, s.grad, nv)) < tolerance;
  bool done = HalfGradientNorm(s) < tolerance && (!s.newton || small_gradient);
  if (!done && s.newton) {
    FactorHessian(s);
    PreconditionGradient(s, true);
    done = small_gradient && HalfGradientNorm(s) < tolerance;
  }
  if (!done) {
    for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v];
  }
  int iter = 0;
  while (!done && iter < m.opt.iterations) {
    double decrease;
    double alpha = LineSearch(m, s, &decrease);
    if (alpha == 0) break;
    Advance(s, alpha);
    double improvement = p.scale * decrease;
    double gradient = p.scale * std::sqrt(Dot(s.grad, s.grad, nv));
    double decrement = s.newton ? HalfGradientNorm(s) : 0;
    iter++;
    if ((improvement > 0 && improvement < tolerance) || gradient < tolerance ||
        (s.newton && decrement < tolerance)) {
      break;
    }
    if (s.newton) {
      for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v];
    } else {
      HagerZhangDirection(s);
    }
  }
  return iter;
}

}  // namespace

void SolvePrimal(const Model& m, ConstraintProblem& p, bool newton, SolverScratch& scratch) {
  int nefc = p.nefc;
  SolverFrame frame(scratch);
  Primal s(p, newton, m.opt.cone == kConeElliptic, frame);
  s.newer = m.release == Release::k3_12;

  // Start: M a, J a - aref, states and forces; then the release's iteration.
  MulSym(p, p.qacc, s.ma);
  MulJ(p, p.qacc, s.jaref);
  for (int r = 0; r < nefc; r++) s.jaref[r] -= p.aref[r];
  UpdateConstraint(s);
  p.niter = s.newer ? IterateAsMuJoCo312(m, s) : IterateAsMuJoCo351(m, s);
}

}  // namespace simlab
