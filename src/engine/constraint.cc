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
    math::MulMatVec(arf, d.efc_AR.data(), d.efc_force.data(), nefc, nefc);
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
  double* jac = frame.Reals(static_cast<size_t>(nefc) * nv);
  for (int r = 0; r < nefc; r++) {
    int e = rows[r];
    if (d.efc_type[e] == kCnstrEquality) p.ne++;
    if (d.efc_type[e] == kCnstrFrictionDof || d.efc_type[e] == kCnstrFrictionTendon) p.nf++;
    double* row = jac + static_cast<size_t>(r) * nv;
    for (int k = d.efc_J_rowadr[e]; k < d.efc_J_rowadr[e] + d.efc_J_rownnz[e]; k++) {
      int i = local[d.efc_J_colind[k]];
      if (i >= 0) row[i] = d.efc_J[k];
    }
  }
  p.J = jac;
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

// The problem over every dof and row in Data's own arrays, without copies: possible when
// efc_J is dense (nv columns per row: !SparseJacobian). The solution is written into Data directly; row
// states go to `state`.
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
    bool whole = nv == m.nv && nefc == d.nefc && !SparseJacobian(m);
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
  SolverFrame frame(d.solver_scratch);
  // With a dense Jacobian in Data's own arrays; else gathered into dense rows.
  int *dofs = nullptr, *rows = nullptr;
  ConstraintProblem p;
  if (!SparseJacobian(m)) {
    p = WholeProblem(m, d, d.efc_state.data());
  } else {
    dofs = frame.Ints(m.nv);
    rows = frame.Ints(d.nefc);
    for (int v = 0; v < m.nv; v++) dofs[v] = v;
    for (int r = 0; r < d.nefc; r++) rows[r] = r;
    p = MakeProblem(m, d, dofs, m.nv, rows, d.nefc, frame.Ints(m.nv), frame);
  }
  p.scale = 1 / (m.stat.meaninertia * std::max(1, m.nv));
  SolvePrimal(m, p, m.opt.solver == kSolverNewton, d.solver_scratch);
  Scatter(p, dofs, rows, true, d);
}

}  // namespace

// ---------------------------------------------------------------- efc_AR for PGS and noslip

void ProjectConstraint(const Model& m, Data& d) {
  int nv = m.nv, nefc = d.nefc;
  bool dual = m.opt.solver == kSolverPGS || m.opt.noslip_iterations > 0;
  if (nefc == 0 || !dual) return;

  // B = J L^-1 D^-1/2 row by row (M = L^T D L), so that J M^-1 J^T = B B^T.
  SolverFrame frame(d.solver_scratch);
  double* b = frame.Reals(static_cast<size_t>(nefc) * nv);
  for (int r = 0; r < nefc; r++) {
    double* x = &b[static_cast<size_t>(r) * nv];
    EfcRowDense(m, d, r, x);
    for (int i = nv - 1; i >= 0; i--) {
      if (x[i] == 0) continue;
      int end = m.M_rowadr[i] + m.M_rownnz[i] - 1;
      for (int k = m.M_rowadr[i]; k < end; k++) x[m.M_colind[k]] -= d.qLD[k] * x[i];
    }
    for (int i = 0; i < nv; i++) x[i] *= 1 / std::sqrt(d.qLD[m.M_rowadr[i] + m.M_rownnz[i] - 1]);
  }
  d.efc_AR.assign(static_cast<size_t>(nefc) * nefc, 0.0);
  for (int r = 0; r < nefc; r++) {
    for (int c = 0; c <= r; c++) {
      double s = 0;
      for (int v = 0; v < nv; v++) s += b[static_cast<size_t>(r) * nv + v] * b[static_cast<size_t>(c) * nv + v];
      d.efc_AR[static_cast<size_t>(r) * nefc + c] = d.efc_AR[static_cast<size_t>(c) * nefc + r] = s;
    }
    d.efc_AR[static_cast<size_t>(r) * nefc + r] += d.efc_R[r];
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
