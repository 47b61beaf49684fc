// Projected Gauss-Seidel on the dual problem (MuJoCo mj_solPGS, engine_solver.c):
//
//   minimize over f   0.5 f^T AR f + f^T b   with f in the feasible set of each row
//
// (friction rows within +-frictionloss, limits and contacts non-negative). One sweep
// minimizes over each row in turn and projects; a step that would raise the cost is
// undone. Then qacc = qacc_smooth + M^-1 J^T f.
#include <algorithm>
#include <vector>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "math/dot.h"

namespace simlab {

namespace {

// Row states of a dual solution (MuJoCo dualState): friction signs are the primal's
// opposite; limit rows with a positive force are active.
void DualState(Data& d) {
  for (int r = 0; r < d.nefc; r++) {
    int& state = d.efc_state[r];
    double f = d.efc_force[r];
    if (r < d.ne) {
      state = kStateQuadratic;
    } else if (r < d.ne + d.nf) {
      double loss = d.efc_frictionloss[r];
      state = f <= -loss ? kStateLinearPos : f >= loss ? kStateLinearNeg : kStateQuadratic;
    } else {
      state = f <= 0 ? kStateSatisfied : kStateQuadratic;
    }
  }
}

// One Gauss-Seidel sweep over the rows; returns the (positive) cost decrease.
double Sweep(Data& d, const std::vector<double>& ar_inv) {
  int nefc = d.nefc;
  std::vector<double>& force = d.efc_force;
  double improvement = 0;
  for (int r = 0; r < nefc; r++) {
    // Residual of row r: b + AR f.
    const double* ar = &d.efc_AR[static_cast<size_t>(r) * nefc];
    double res = d.efc_b[r];
    for (int c = 0; c < nefc; c++) res += ar[c] * force[c];

    // Unconstrained minimum along the row, projected on its feasible set.
    double old = force[r];
    force[r] -= res * ar_inv[r];
    if (r >= d.ne && r < d.ne + d.nf) {
      force[r] = std::clamp(force[r], -d.efc_frictionloss[r], d.efc_frictionloss[r]);
    } else if (r >= d.ne + d.nf) {
      force[r] = std::max(0.0, force[r]);
    }

    // Cost change of the step; undo a step that does not decrease the cost.
    double delta = force[r] - old;
    double change = 0.5 * delta * delta / ar_inv[r] + delta * res;
    if (change > 1e-10) {
      force[r] = old;
      change = 0;
    }
    improvement -= change;
  }
  return improvement;
}

}  // namespace

void SolvePGS(const Model& m, Data& d) {
  int nefc = d.nefc;
  std::vector<double> ar_inv(nefc);
  for (int r = 0; r < nefc; r++) ar_inv[r] = 1 / d.efc_AR[static_cast<size_t>(r) * nefc + r];
  double scale = 1 / (m.stat.meaninertia * std::max(1, m.nv));

  DualState(d);
  int iter = 0;
  while (iter < m.opt.iterations) {
    double improvement = Sweep(d, ar_inv) * scale;
    DualState(d);
    iter++;
    if (improvement < m.opt.tolerance) break;
  }
  d.solver_niter += iter;

  // Back to joint space: qfrc_constraint = J^T f, qacc = qacc_smooth + M^-1 qfrc_constraint.
  math::MulMatTVec(d.qfrc_constraint.data(), d.efc_J.data(), d.efc_force.data(), nefc, m.nv);
  d.qacc = d.qfrc_constraint;
  SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), d.qacc.data());
  for (int v = 0; v < m.nv; v++) d.qacc[v] += d.qacc_smooth[v];
}

}  // namespace simlab
