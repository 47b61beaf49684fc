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
#include <vector>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/island.h"
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
void WarmStart(const Model& m, Data& d, const Islands& islands) {
  int nv = m.nv, nefc = d.nefc;
  if (m.opt.disableflags & kDisableWarmstart) {
    d.qacc = d.qacc_smooth;
    std::fill(d.efc_force.begin(), d.efc_force.end(), 0.0);
    return;
  }
  StackFrame frame(d);
  double* jar = frame.Alloc(nefc);
  d.qacc = d.qacc_warmstart;
  math::MulMatVec(jar, d.efc_J.data(), d.qacc_warmstart.data(), nefc, nv);
  for (int r = 0; r < nefc; r++) jar[r] -= d.efc_aref[r];
  double cost_warm = UpdateAll(d, jar);

  if (m.opt.solver == kSolverPGS) {
    // Dual cost of the warm-start forces: f.b + 0.5 f.AR f; zero forces if positive.
    double* arf = frame.Alloc(nefc);
    math::MulMatVec(arf, d.efc_AR.data(), d.efc_force.data(), nefc, nefc);
    double dual = math::Dot(d.efc_force.data(), d.efc_b.data(), nefc) +
                  0.5 * math::Dot(d.efc_force.data(), arf, nefc);
    if (dual > 0) std::fill(d.efc_force.begin(), d.efc_force.end(), 0.0);
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
  if (islands.nisland > 0) {
    for (int v = 0; v < nv; v++) {
      if (islands.dof_island[v] < 0) d.qacc[v] = d.qacc_smooth[v];
    }
  }
}

// ---------------------------------------------------------------- problems

// The problem over the given dofs (ascending) and rows (ascending).
ConstraintProblem MakeProblem(const Model& m, Data& d, const std::vector<int>& dofs,
                              const std::vector<int>& rows) {
  ConstraintProblem p;
  p.nv = static_cast<int>(dofs.size());
  p.nefc = static_cast<int>(rows.size());
  std::vector<int> local(m.nv, -1);
  for (int i = 0; i < p.nv; i++) local[dofs[i]] = i;

  // Inertia rows of the dofs: their ancestors are in the same tree, so in the problem.
  for (int i = 0; i < p.nv; i++) {
    int v = dofs[i];
    p.M_rowadr.push_back(static_cast<int>(p.M_colind.size()));
    p.M_rownnz.push_back(m.M_rownnz[v]);
    for (int k = m.M_rowadr[v]; k < m.M_rowadr[v] + m.M_rownnz[v]; k++) {
      p.M_colind.push_back(local[m.M_colind[k]]);
      p.M.push_back(d.M[k]);
      p.qLD.push_back(d.qLD[k]);
    }
    p.qLDiagInv.push_back(d.qLDiagInv[v]);
    p.qfrc_smooth.push_back(d.qfrc_smooth[v]);
    p.qacc_smooth.push_back(d.qacc_smooth[v]);
    p.qacc.push_back(d.qacc[v]);
  }
  p.qfrc_constraint.assign(p.nv, 0.0);

  // Rows, with the Jacobian restricted to the problem's dofs.
  p.J.assign(static_cast<size_t>(p.nefc) * p.nv, 0.0);
  for (int r = 0; r < p.nefc; r++) {
    int e = rows[r];
    if (d.efc_type[e] == kCnstrEquality) p.ne++;
    if (d.efc_type[e] == kCnstrFrictionDof || d.efc_type[e] == kCnstrFrictionTendon) p.nf++;
    for (int i = 0; i < p.nv; i++) {
      p.J[static_cast<size_t>(r) * p.nv + i] = d.efc_J[static_cast<size_t>(e) * m.nv + dofs[i]];
    }
    p.D.push_back(d.efc_D[e]);
    p.R.push_back(d.efc_R[e]);
    p.frictionloss.push_back(d.efc_frictionloss[e]);
    p.aref.push_back(d.efc_aref[e]);
    p.type.push_back(d.efc_type[e]);
    p.id.push_back(d.efc_id[e]);
  }
  p.contact = d.contact.data();
  p.force.assign(p.nefc, 0.0);
  p.state.assign(p.nefc, 0);
  return p;
}

// Copies a solved problem's results back into Data. Row states only with `states`: MuJoCo
// copies an island's forces back but not its states, so after island solves efc_state
// keeps the warm start's evaluation (at qacc_smooth or the warm start).
void Scatter(const ConstraintProblem& p, const std::vector<int>& dofs,
             const std::vector<int>& rows, bool states, Data& d) {
  for (int i = 0; i < p.nv; i++) {
    d.qacc[dofs[i]] = p.qacc[i];
    d.qfrc_constraint[dofs[i]] = p.qfrc_constraint[i];
  }
  for (int r = 0; r < p.nefc; r++) {
    d.efc_force[rows[r]] = p.force[r];
    if (states) d.efc_state[rows[r]] = p.state[r];
  }
  d.solver_niter += p.niter;
}

// Newton or CG on each island; the scale is the island's total dof inertia.
void SolveIslands(const Model& m, Data& d, const Islands& islands) {
  bool newton = m.opt.solver == kSolverNewton;
  for (int island = 0; island < islands.nisland; island++) {
    std::vector<int> dofs, rows;
    for (int v = 0; v < m.nv; v++) {
      if (islands.dof_island[v] == island) dofs.push_back(v);
    }
    for (int r = 0; r < d.nefc; r++) {
      if (islands.efc_island[r] == island) rows.push_back(r);
    }
    ConstraintProblem p = MakeProblem(m, d, dofs, rows);
    double inertia = 0;
    for (int i = 0; i < p.nv; i++) inertia += p.M[p.M_rowadr[i] + p.M_rownnz[i] - 1];
    p.scale = 1 / inertia;
    SolvePrimal(m, p, newton);
    Scatter(p, dofs, rows, false, d);
  }
}

// Newton or CG on the whole model at once (islands disabled).
void SolveWhole(const Model& m, Data& d) {
  std::vector<int> dofs(m.nv), rows(d.nefc);
  for (int v = 0; v < m.nv; v++) dofs[v] = v;
  for (int r = 0; r < d.nefc; r++) rows[r] = r;
  ConstraintProblem p = MakeProblem(m, d, dofs, rows);
  p.scale = 1 / (m.stat.meaninertia * std::max(1, m.nv));
  SolvePrimal(m, p, m.opt.solver == kSolverNewton);
  Scatter(p, dofs, rows, true, d);
}

}  // namespace

// ---------------------------------------------------------------- efc_AR for PGS and noslip

void ProjectConstraint(const Model& m, Data& d) {
  int nv = m.nv, nefc = d.nefc;
  bool dual = m.opt.solver == kSolverPGS || m.opt.noslip_iterations > 0;
  if (nefc == 0 || !dual) return;

  // B = J L^-1 D^-1/2 row by row (M = L^T D L), so that J M^-1 J^T = B B^T.
  std::vector<double> b(static_cast<size_t>(nefc) * nv);
  for (int r = 0; r < nefc; r++) {
    double* x = &b[static_cast<size_t>(r) * nv];
    std::copy_n(&d.efc_J[static_cast<size_t>(r) * nv], nv, x);
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
  math::MulMatVec(d.efc_b.data(), d.efc_J.data(), d.qacc_smooth.data(), d.nefc, m.nv);
  for (int r = 0; r < d.nefc; r++) d.efc_b[r] -= d.efc_aref[r];

  Islands islands;
  if (!(m.opt.disableflags & kDisableIsland)) FindIslands(m, d, &islands);
  d.nisland = islands.nisland;
  WarmStart(m, d, islands);

  bool primal = m.opt.solver == kSolverNewton || m.opt.solver == kSolverCG;
  if (primal && islands.nisland > 0 && m.opt.noslip_iterations == 0) {
    SolveIslands(m, d, islands);
  } else if (primal) {
    SolveWhole(m, d);
  } else {
    SolvePGS(m, d);
  }
  if (m.opt.noslip_iterations > 0) SolveNoSlip(m, d);
}

}  // namespace simlab
