// Constraint stage (MuJoCo mj_fwdConstraint): from the smooth acceleration and the rows
// made in the position stage, the constrained acceleration qacc and the constraint force
// qfrc_constraint = J^T efc_force.
//
//   1. efc_b = J qacc_smooth - aref.
//   2. Warm start: the previous step's acceleration if it costs less than qacc_smooth.
//   3. Solve: Newton or CG per island (each island an independent problem), or PGS on
//      the whole dual problem.
//   4. noslip (opt.noslip_iterations > 0): friction forces re-solved without R.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <type_traits>
#include <vector>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/island.h"
#include "engine/rows.h"
#include "engine/stack.h"
#include "math/dot.h"

namespace simlab {

namespace {

// Row states and forces at jar; returns the constraint cost.
double UpdateAll(Data& d, const double* jar) {
  double cost = 0;
  ConstraintUpdate(DataRows(d), jar, d.efc_state.data(), d.efc_force.data(), &cost, false);
  return cost;
}

// Initial qacc (and efc_force for PGS): the warm start when it is better than qacc_smooth.
// (qfrc_constraint is left to the solvers, which compute it from their solution.)
void WarmStart(const Model& m, Data& d) {
  int nv = m.nv, nefc = d.nefc;
  if (m.opt.disableflags & kDisableWarmstart) {
    d.qacc = d.qacc_smooth;
    std::fill_n(d.efc_force.begin(), d.nefc, 0.0);
    return;
  }
  StackFrame frame(d);
  double* jar = frame.Alloc(nefc);
  d.qacc = d.qacc_warmstart;
  EfcMulVec(m, d, d.qacc_warmstart.data(), jar);
  for (int r = 0; r < nefc; r++) jar[r] -= d.efc_aref[r];
  double cost_warm = UpdateAll(d, jar);

  if (m.opt.solver == kSolverPGS) {
    // Dual cost of the warm-start forces: f.b + 0.5 f.AR f; zero forces if positive.
    double* arf = frame.Alloc(nefc);
    MulAR(m, d, d.efc_force.data(), arf);
    double dual = math::Dot(d.efc_force.data(), d.efc_b.data(), nefc) +
                  0.5 * math::Dot(d.efc_force.data(), arf, nefc);
    if (dual > 0) std::fill_n(d.efc_force.begin(), d.nefc, 0.0);
  } else {
    // Primal cost: Gauss term plus constraint cost, against that of qacc_smooth.
    double* ma = frame.Alloc(nv);
    MulSymLayout(nv, m.M_rownnz.data(), m.M_rowadr.data(), m.M_colind.data(), d.M.data(),
                 d.qacc_warmstart.data(), ma);
    for (int v = 0; v < nv; v++) {
      cost_warm += 0.5 * (ma[v] - d.qfrc_smooth[v]) * (d.qacc_warmstart[v] - d.qacc_smooth[v]);
    }
    double cost_smooth = UpdateAll(d, d.efc_b.data());
    if (cost_warm > cost_smooth) d.qacc = d.qacc_smooth;
  }

  // Dofs outside every island move freely.
  if (d.nisland > 0) {
    for (int v = 0; v < nv; v++) {
      if (d.dof_island[v] < 0) d.qacc[v] = d.qacc_smooth[v];
    }
  }
}

// ---------------------------------------------------------------- problems

// src[index[i]] for i < n, in an array of `frame`.
template <class T>
T* Gather(const std::vector<T>& src, const int* index, int n, SolverFrame& frame) {
  T* dst;
  if constexpr (std::is_same_v<T, int>) {
    dst = frame.Ints(n);
  } else {
    dst = frame.Reals(n);
  }
  for (int i = 0; i < n; i++) dst[i] = src[index[i]];
  return dst;
}

// The given rows of a compressed-row efc_J with their columns renumbered by `local` (the
// problem's dofs, ascending as Data's), into p.J_* in arrays of `frame`.
void GatherSparseRows(const Data& d, const int* rows, int nefc, const int* local,
                      SolverFrame& frame, ConstraintProblem& p) {
  int* rownnz = frame.IntsToWrite(nefc);
  int* rowadr = frame.IntsToWrite(nefc);
  int nnz = 0;
  for (int r = 0; r < nefc; r++) {
    rowadr[r] = nnz;
    nnz += d.efc_J_rownnz[rows[r]];
  }
  int* colind = frame.IntsToWrite(nnz);
  double* values = frame.RealsToWrite(nnz);
  for (int r = 0; r < nefc; r++) {
    int e = rows[r], count = 0;
    for (int k = d.efc_J_rowadr[e]; k < d.efc_J_rowadr[e] + d.efc_J_rownnz[e]; k++) {
      int i = local[d.efc_J_colind[k]];
      if (i < 0) continue;
      colind[rowadr[r] + count] = i;
      values[rowadr[r] + count++] = d.efc_J[k];
    }
    rownnz[r] = count;
  }
  p.J_rownnz = rownnz;
  p.J_rowadr = rowadr;
  p.J_colind = colind;
  p.J = values;
}

// The problem over the given dofs (ascending) and rows (ascending), in arrays of `frame`.
// `local` (m.nv entries, -1 outside the problem) receives each dof's index in the problem.
ConstraintProblem MakeProblem(const Model& m, Data& d, const int* dofs, int nv, const int* rows,
                              int nefc, int* local, SolverFrame& frame) {
  ConstraintProblem p;
  p.nv = nv;
  p.nefc = nefc;
  int nnz = 0;
  for (int i = 0; i < nv; i++) {
    local[dofs[i]] = i;
    nnz += m.M_rownnz[dofs[i]];
  }

  // Inertia rows of the dofs: their ancestors are in the same tree, so in the problem.
  int* rownnz = frame.Ints(nv);
  int* rowadr = frame.Ints(nv);
  int* colind = frame.Ints(nnz);
  double* mass = frame.Reals(nnz);
  double* factor = frame.Reals(nnz);
  int adr = 0;
  for (int i = 0; i < nv; i++) {
    int v = dofs[i];
    rowadr[i] = adr;
    rownnz[i] = m.M_rownnz[v];
    for (int k = m.M_rowadr[v]; k < m.M_rowadr[v] + m.M_rownnz[v]; k++, adr++) {
      colind[adr] = local[m.M_colind[k]];
      mass[adr] = d.M[k];
      factor[adr] = d.qLD[k];
    }
  }
  p.M_rownnz = rownnz;
  p.M_rowadr = rowadr;
  p.M_colind = colind;
  p.M = mass;
  p.qLD = factor;
  p.qLDiagInv = Gather(d.qLDiagInv, dofs, nv, frame);
  p.qfrc_smooth = Gather(d.qfrc_smooth, dofs, nv, frame);
  p.qacc_smooth = Gather(d.qacc_smooth, dofs, nv, frame);
  p.qacc = Gather(d.qacc, dofs, nv, frame);
  p.qfrc_constraint = frame.Reals(nv);

  // Rows, with the Jacobian restricted to the problem's dofs.
  for (int r = 0; r < nefc; r++) {
    int e = rows[r];
    if (d.efc_type[e] == kCnstrEquality) p.ne++;
    if (d.efc_type[e] == kCnstrFrictionDof || d.efc_type[e] == kCnstrFrictionTendon) p.nf++;
  }
  if (SparseJacobian(m)) {
    GatherSparseRows(d, rows, nefc, local, frame, p);
  } else {
    double* jac = frame.Reals(static_cast<size_t>(nefc) * nv);
    for (int r = 0; r < nefc; r++) {
      int e = rows[r];
      double* row = jac + static_cast<size_t>(r) * nv;
      for (int k = d.efc_J_rowadr[e]; k < d.efc_J_rowadr[e] + d.efc_J_rownnz[e]; k++) {
        int i = local[d.efc_J_colind[k]];
        if (i >= 0) row[i] = d.efc_J[k];
      }
    }
    p.J = jac;
  }
  p.D = Gather(d.efc_D, rows, nefc, frame);
  p.R = Gather(d.efc_R, rows, nefc, frame);
  p.frictionloss = Gather(d.efc_frictionloss, rows, nefc, frame);
  p.aref = Gather(d.efc_aref, rows, nefc, frame);
  p.type = Gather(d.efc_type, rows, nefc, frame);
  p.id = Gather(d.efc_id, rows, nefc, frame);
  p.force = frame.Reals(nefc);
  p.state = frame.Ints(nefc);
  p.contact = d.contact.data();
  return p;
}

// The problem over every dof and row in Data's own arrays, without copies (efc_J dense,
// or in compressed rows when SparseJacobian). The solution is written into Data directly;
// row states go to `state`.
ConstraintProblem WholeProblem(const Model& m, Data& d, int* state) {
  ConstraintProblem p;
  p.nv = m.nv;
  p.nefc = d.nefc;
  p.ne = d.ne;
  p.nf = d.nf;
  p.M_rownnz = m.M_rownnz.data();
  p.M_rowadr = m.M_rowadr.data();
  p.M_colind = m.M_colind.data();
  p.M = d.M.data();
  p.qLD = d.qLD.data();
  p.qLDiagInv = d.qLDiagInv.data();
  p.qfrc_smooth = d.qfrc_smooth.data();
  p.qacc_smooth = d.qacc_smooth.data();
  p.qacc = d.qacc.data();
  p.qfrc_constraint = d.qfrc_constraint.data();
  p.J = d.efc_J.data();
  if (SparseJacobian(m)) {
    p.J_rownnz = d.efc_J_rownnz.data();
    p.J_rowadr = d.efc_J_rowadr.data();
    p.J_colind = d.efc_J_colind.data();
  }
  p.D = d.efc_D.data();
  p.R = d.efc_R.data();
  p.frictionloss = d.efc_frictionloss.data();
  p.aref = d.efc_aref.data();
  p.type = d.efc_type.data();
  p.id = d.efc_id.data();
  p.force = d.efc_force.data();
  p.state = state;
  p.contact = d.contact.data();
  return p;
}

// Copies a solved problem's results back into Data. Row states only with `states`: MuJoCo
// copies an island's forces back but not its states, so after island solves efc_state
// keeps the warm start's evaluation (at qacc_smooth or the warm start). A non-convex
// line search becomes a warning (its info: how many points were not convex). Without
// `dofs` (a WholeProblem) the results are in Data already.
void Scatter(const ConstraintProblem& p, const int* dofs, const int* rows, bool states,
             Data& d) {
  if (p.nonconvex > 0) RaiseWarning(d, kWarnLineSearch, p.nonconvex);
  d.solver_niter += p.niter;
  if (!dofs) return;
  for (int i = 0; i < p.nv; i++) {
    d.qacc[dofs[i]] = p.qacc[i];
    d.qfrc_constraint[dofs[i]] = p.qfrc_constraint[i];
  }
  for (int r = 0; r < p.nefc; r++) {
    d.efc_force[rows[r]] = p.force[r];
    if (states) d.efc_state[rows[r]] = p.state[r];
  }
}

// The indices i < n grouped by label (0..nlabel-1; other labels left out), ascending
// within each group: group g is order[start[g]] .. order[start[g + 1] - 1].
void GroupByLabel(const int* label, int n, int nlabel, int* start, int* order) {
  std::fill(start, start + nlabel + 1, 0);
  for (int i = 0; i < n; i++) {
    if (label[i] >= 0 && label[i] < nlabel) start[label[i] + 1]++;
  }
  for (int g = 0; g < nlabel; g++) start[g + 1] += start[g];
  for (int i = 0; i < n; i++) {
    if (label[i] >= 0 && label[i] < nlabel) order[start[label[i]]++] = i;
  }
  for (int g = nlabel; g > 0; g--) start[g] = start[g - 1];
  start[0] = 0;
}

// Newton or CG on each island; the scale is the island's total dof inertia.
void SolveIslands(const Model& m, Data& d) {
  bool newton = m.opt.solver == kSolverNewton;
  SolverFrame groups(d.solver_scratch);
  int* dof_start = groups.Ints(d.nisland + 1);
  int* dof_order = groups.Ints(m.nv);
  int* row_start = groups.Ints(d.nisland + 1);
  int* row_order = groups.Ints(d.nefc);
  int* local = groups.Ints(m.nv);
  GroupByLabel(d.dof_island.data(), m.nv, d.nisland, dof_start, dof_order);
  GroupByLabel(d.efc_island.data(), d.nefc, d.nisland, row_start, row_order);
  std::fill(local, local + m.nv, -1);
  for (int island = 0; island < d.nisland; island++) {
    SolverFrame frame(d.solver_scratch);
    const int* dofs = dof_order + dof_start[island];
    const int* rows = row_order + row_start[island];
    int nv = dof_start[island + 1] - dof_start[island];
    int nefc = row_start[island + 1] - row_start[island];
    // One island holding everything is solved in Data's arrays (its states apart).
    bool whole = nv == m.nv && nefc == d.nefc;
    ConstraintProblem p = whole ? WholeProblem(m, d, frame.Ints(nefc))
                                : MakeProblem(m, d, dofs, nv, rows, nefc, local, frame);
    for (int i = 0; i < nv && !whole; i++) local[dofs[i]] = -1;
    if (whole) dofs = rows = nullptr;
    double inertia = 0;
    for (int i = 0; i < p.nv; i++) inertia += p.M[p.M_rowadr[i] + p.M_rownnz[i] - 1];
    p.scale = 1 / inertia;
    SolvePrimal(m, p, newton, d.solver_scratch);
    Scatter(p, dofs, rows, false, d);
  }
}

// Newton or CG on the whole model at once (islands disabled).
void SolveWhole(const Model& m, Data& d) {
  ConstraintProblem p = WholeProblem(m, d, d.efc_state.data());
  p.scale = 1 / (m.stat.meaninertia * std::max(1, m.nv));
  SolvePrimal(m, p, m.opt.solver == kSolverNewton, d.solver_scratch);
  Scatter(p, nullptr, nullptr, true, d);
}

}  // namespace

// ---------------------------------------------------------------- compressed rows

SparseRows TransposeRows(const SparseRows& rows, int nrow, int ncol, SolverFrame& frame) {
  int* rownnz = frame.Ints(ncol);
  int* rowadr = frame.IntsToWrite(ncol);
  int total = 0;
  for (int r = 0; r < nrow; r++) {
    for (int q = rows.rowadr[r]; q < rows.rowadr[r] + rows.rownnz[r]; q++) {
      rownnz[rows.colind[q]]++;
    }
    total += rows.rownnz[r];
  }
  int* colind = frame.IntsToWrite(total);
  double* values = rows.values ? frame.RealsToWrite(total) : nullptr;
  for (int c = 0, adr = 0; c < ncol; c++) {
    rowadr[c] = adr;
    adr += rownnz[c];
    rownnz[c] = 0;
  }
  for (int r = 0; r < nrow; r++) {
    for (int q = rows.rowadr[r]; q < rows.rowadr[r] + rows.rownnz[r]; q++) {
      int c = rows.colind[q];
      int at = rowadr[c] + rownnz[c]++;
      colind[at] = r;
      if (values) values[at] = rows.values[q];
    }
  }
  return SparseRows{rownnz, rowadr, colind, values};
}

bool RepeatsRowBefore(const SparseRows& rows, int r) {
  if (r == 0 || rows.rownnz[r] != rows.rownnz[r - 1]) return false;
  const int* cols = rows.colind + rows.rowadr[r];
  return std::equal(cols, cols + rows.rownnz[r], rows.colind + rows.rowadr[r - 1]);
}

// ---------------------------------------------------------------- efc_AR for PGS and noslip

namespace {

// 1 / sqrt(D_i) of M = L^T D L.
double InverseSqrtPivot(const Model& m, const Data& d, int i) {
  return 1 / std::sqrt(d.qLD[m.M_rowadr[i] + m.M_rownnz[i] - 1]);
}

// x <- x L^-1 (M = L^T D L) for a row x over the ascending `dofs` (closed under
// ancestors): from the last dof to the first, each nonzero entry is taken out of its
// ancestors'.
void BackSubstituteRow(const Model& m, const Data& d, const int* dofs, int n, double* x) {
  for (int q = n - 1; q >= 0; q--) {
    int i = dofs[q];
    if (x[i] == 0) continue;
    int end = m.M_rowadr[i] + m.M_rownnz[i] - 1;
    for (int k = m.M_rowadr[i]; k < end; k++) x[m.M_colind[k]] -= d.qLD[k] * x[i];
  }
}

// Dense efc_AR = J M^-1 J^T + diag(R): B = J L^-1 D^-1/2 row by row, then B B^T.
void ProjectDense(const Model& m, Data& d) {
  int nv = m.nv, nefc = d.nefc;
  SolverFrame frame(d.solver_scratch);
  double* b = frame.Reals(static_cast<size_t>(nefc) * nv);
  int* all = frame.IntsToWrite(nv);
  for (int i = 0; i < nv; i++) all[i] = i;
  for (int r = 0; r < nefc; r++) {
    double* x = &b[static_cast<size_t>(r) * nv];
    EfcRowDense(m, d, r, x);
    BackSubstituteRow(m, d, all, nv, x);
    for (int i = 0; i < nv; i++) x[i] *= InverseSqrtPivot(m, d, i);
  }
  d.nA = nefc * nefc;
  d.efc_AR.assign(static_cast<size_t>(nefc) * nefc, 0.0);
  for (int r = 0; r < nefc; r++) {
    const double* br = &b[static_cast<size_t>(r) * nv];
    for (int c = 0; c <= r; c++) {
      const double* bc = &b[static_cast<size_t>(c) * nv];
      double s = 0;
      for (int v = 0; v < nv; v++) s += br[v] * bc[v];
      d.efc_AR[static_cast<size_t>(r) * nefc + c] = d.efc_AR[static_cast<size_t>(c) * nefc + r] = s;
    }
    d.efc_AR[static_cast<size_t>(r) * nefc + r] += d.efc_R[r];
  }
}

// The dofs of efc row r and all their ancestors (where L^-1 spreads the row), in
// `cols` when given; returns how many. `mark` (nv, never equal to r before) is set to r.
int ClosedRowDofs(const Model& m, const Data& d, int r, int* mark, int* cols) {
  int n = 0;
  for (int k = d.efc_J_rowadr[r]; k < d.efc_J_rowadr[r] + d.efc_J_rownnz[r]; k++) {
    for (int v = d.efc_J_colind[k]; v >= 0 && mark[v] != r; v = m.dof_parentid[v]) {
      mark[v] = r;
      if (cols) cols[n] = v;
      n++;
    }
  }
  return n;
}

// Y = J L^-1 D^-1/2 on compressed rows (MuJoCo's efc_Y), in arrays of `frame`.
SparseRows SparseY(const Model& m, const Data& d, SolverFrame& frame) {
  int nv = m.nv, nefc = d.nefc;
  int* rownnz = frame.IntsToWrite(nefc);
  int* rowadr = frame.IntsToWrite(nefc);
  int* mark = frame.IntsToWrite(nv);
  std::fill(mark, mark + nv, -1);
  int total = 0;
  for (int r = 0; r < nefc; r++) {
    rowadr[r] = total;
    rownnz[r] = ClosedRowDofs(m, d, r, mark, nullptr);
    total += rownnz[r];
  }
  int* colind = frame.IntsToWrite(total);
  double* values = frame.RealsToWrite(total);
  std::fill(mark, mark + nv, -1);
  double* x = frame.Reals(nv);
  for (int r = 0; r < nefc; r++) {
    int* cols = colind + rowadr[r];
    int n = ClosedRowDofs(m, d, r, mark, cols);
    std::sort(cols, cols + n);
    for (int k = d.efc_J_rowadr[r]; k < d.efc_J_rowadr[r] + d.efc_J_rownnz[r]; k++) {
      x[d.efc_J_colind[k]] = d.efc_J[k];
    }
    BackSubstituteRow(m, d, cols, n, x);
    for (int q = 0; q < n; q++) {
      values[rowadr[r] + q] = x[cols[q]] * InverseSqrtPivot(m, d, cols[q]);
      x[cols[q]] = 0;
    }
  }
  return SparseRows{rownnz, rowadr, colind, values};
}

// The rows of efc that share a dof with row r (r's columns of AR), into `cols` when given;
// returns how many. `mark` (nefc, never equal to r before) is set to r.
int CoupledRows(const SparseRows& y, const SparseRows& yt, int r, int* mark, int* cols) {
  int n = 0;
  for (int q = y.rowadr[r]; q < y.rowadr[r] + y.rownnz[r]; q++) {
    int v = y.colind[q];
    for (int k = yt.rowadr[v]; k < yt.rowadr[v] + yt.rownnz[v]; k++) {
      int c = yt.colind[k];
      if (mark[c] == r) continue;
      mark[c] = r;
      if (cols) cols[n] = c;
      n++;
    }
  }
  return n;
}

// efc_AR's compressed-row pattern: row r holds the rows that share a dof with it (a row
// repeating the dofs of the one before has its columns too); counted, then written.
void SparseARPattern(const SparseRows& y, const SparseRows& yt, int nefc, int* mark, Data& d) {
  if (d.efc_AR_rownnz.size() < static_cast<size_t>(nefc)) {
    d.efc_AR_rownnz.resize(nefc);
    d.efc_AR_rowadr.resize(nefc);
  }
  std::fill(mark, mark + nefc, -1);
  int total = 0;
  for (int r = 0; r < nefc; r++) {
    d.efc_AR_rowadr[r] = total;
    d.efc_AR_rownnz[r] =
        RepeatsRowBefore(y, r) ? d.efc_AR_rownnz[r - 1] : CoupledRows(y, yt, r, mark, nullptr);
    total += d.efc_AR_rownnz[r];
  }
  d.nA = total;
  if (d.efc_AR_colind.size() < static_cast<size_t>(total)) d.efc_AR_colind.resize(total);
  if (d.efc_AR.size() < static_cast<size_t>(total)) d.efc_AR.resize(total);
  std::fill(mark, mark + nefc, -1);
  for (int r = 0; r < nefc; r++) {
    int* cols = &d.efc_AR_colind[d.efc_AR_rowadr[r]];
    if (RepeatsRowBefore(y, r)) {
      std::copy_n(&d.efc_AR_colind[d.efc_AR_rowadr[r - 1]], d.efc_AR_rownnz[r], cols);
    } else {
      CoupledRows(y, yt, r, mark, cols);
      std::sort(cols, cols + d.efc_AR_rownnz[r]);
    }
  }
}

// Y(a, :) . Y(b, :) over the dofs both rows hold, summed one term at a time from the
// lowest dof up (MuJoCo's mju_sqrMatTDSparse order for the entries off the diagonal).
double SharedDofsDot(const SparseRows& y, int a, int b) {
  int qa = y.rowadr[a], ea = qa + y.rownnz[a];
  int qb = y.rowadr[b], eb = qb + y.rownnz[b];
  double sum = 0;
  while (qa < ea && qb < eb) {
    if (y.colind[qa] < y.colind[qb]) {
      qa++;
    } else if (y.colind[qb] < y.colind[qa]) {
      qb++;
    } else {
      sum += y.values[qb++] * y.values[qa++];
    }
  }
  return sum;
}

// Sparse efc_AR = Y Y^T + diag(R) in compressed rows (efc_AR_rownnz/rowadr/colind, nA
// entries), rounded as MuJoCo's: the diagonal a mju_dot of the row with itself, the
// entries off it a sum over the shared dofs in order; each entry above the diagonal is
// the one already computed below it.
void ProjectSparse(const Model& m, Data& d) {
  int nv = m.nv, nefc = d.nefc;
  SolverFrame frame(d.solver_scratch);
  SparseRows y = SparseY(m, d, frame);
  SparseRows yt = TransposeRows(SparseRows{y.rownnz, y.rowadr, y.colind}, nefc, nv, frame);
  SparseARPattern(y, yt, nefc, frame.IntsToWrite(nefc), d);
  for (int r = 0; r < nefc; r++) {
    for (int k = d.efc_AR_rowadr[r]; k < d.efc_AR_rowadr[r] + d.efc_AR_rownnz[r]; k++) {
      int c = d.efc_AR_colind[k];
      if (c < r) {
        d.efc_AR[k] = d.efc_AR[AREntry(m, d, c, r)];
      } else if (c == r) {
        const double* row = y.values + y.rowadr[r];
        d.efc_AR[k] = math::Dot(row, row, y.rownnz[r]) + d.efc_R[r];
      } else {
        d.efc_AR[k] = SharedDofsDot(y, c, r);
      }
    }
  }
}

}  // namespace

size_t AREntry(const Model& m, const Data& d, int r, int c) {
  if (!SparseJacobian(m)) return static_cast<size_t>(r) * d.nefc + c;
  const int* begin = &d.efc_AR_colind[d.efc_AR_rowadr[r]];
  return d.efc_AR_rowadr[r] + (std::lower_bound(begin, begin + d.efc_AR_rownnz[r], c) - begin);
}

void ProjectConstraint(const Model& m, Data& d) {
  bool dual = m.opt.solver == kSolverPGS || m.opt.noslip_iterations > 0;
  if (d.nefc == 0 || !dual) return;
  if (SparseJacobian(m)) {
    ProjectSparse(m, d);
  } else {
    ProjectDense(m, d);
  }
}

// ---------------------------------------------------------------- the stage

void Constraint(const Model& m, Data& d) {
  std::fill(d.qfrc_constraint.begin(), d.qfrc_constraint.end(), 0.0);
  d.solver_niter = 0;
  d.nisland = 0;
  if (d.nefc == 0) {
    d.qacc = d.qacc_smooth;
    return;
  }

  // efc_b = J qacc_smooth - aref.
  EfcMulVec(m, d, d.qacc_smooth.data(), d.efc_b.data());
  for (int r = 0; r < d.nefc; r++) d.efc_b[r] -= d.efc_aref[r];

  if (!(m.opt.disableflags & kDisableIsland)) FindIslands(m, d);
  WarmStart(m, d);

  bool primal = m.opt.solver == kSolverNewton || m.opt.solver == kSolverCG;
  if (primal && d.nisland > 0 && m.opt.noslip_iterations == 0) {
    SolveIslands(m, d);
  } else if (primal) {
    SolveWhole(m, d);
  } else {
    SolvePGS(m, d);
  }
  if (m.opt.noslip_iterations > 0) SolveNoSlip(m, d);
}

}  // namespace simlab
