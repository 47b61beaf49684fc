// The constraint machinery shared by the row builder (constraint_rows.cc), the stage
// (constraint.cc), the islands (island.cc) and the solvers (solver_primal.cc, solver_pgs.cc).
//
// MuJoCo's formulation (documentation, Computation chapter): the constrained acceleration
// minimizes  0.5 (a - a0)^T M (a - a0) + s(J a - aref), a0 being the unconstrained
// acceleration and s a sum of per-row costs given by each row's state.
#ifndef SIMLAB_ENGINE_CONSTRAINT_H_
#define SIMLAB_ENGINE_CONSTRAINT_H_

#include <vector>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// efc rows of the current configuration with their softness (position stage).
void MakeConstraint(const Model& m, Data& d);
// efc_vel and efc_aref (velocity stage).
void ReferenceConstraint(const Model& m, Data& d);
// efc_AR = J M^-1 J^T + diag(R), needed by the PGS solver (position stage).
void ProjectConstraint(const Model& m, Data& d);
// The body of side j (0 or 1) of a connect or weld, in its body or site form.
int EqualityBody(const Model& m, int eq, int j);
// The impedance of solimp at position `pos` with `margin`, and its derivative.
void Impedance(const double* solimp, double pos, double margin, double* imp, double* slope);

// One constraint problem: the whole model, or one island of it. Dof arrays have nv
// entries, row arrays nefc; the first ne rows are equalities, the next nf friction.
struct ConstraintProblem {
  int nv = 0, ne = 0, nf = 0, nefc = 0;

  // dofs: inertia in the tree-sparse lower-triangle layout of Model::M_*, with its
  // L^T D L factor, and the smooth force/acceleration; qacc is the solver's iterate.
  std::vector<int> M_rownnz, M_rowadr, M_colind;
  std::vector<double> M, qLD, qLDiagInv;
  std::vector<double> qfrc_smooth, qacc_smooth, qacc, qfrc_constraint;

  // rows: dense Jacobian (nefc x nv) and the per-row data the cost needs.
  std::vector<double> J, D, R, frictionloss, aref, force;
  std::vector<int> type, state;

  double scale = 1;  // 1 / (total inertia): makes tolerances unit-free
  int niter = 0;     // iterations the solver used
};

// Row states and forces for jar = J a - aref, and optionally the constraint cost s(jar)
// (MuJoCo mj_constraintUpdate). Works on any contiguous run of rows.
void ConstraintUpdate(int ne, int nf, int nefc, const double* D, const double* R,
                      const double* frictionloss, const double* jar, int* state,
                      double* force, double* cost);

// The primal solvers: Newton (flg_newton) or nonlinear conjugate gradient.
void SolvePrimal(const Model& m, ConstraintProblem& p, bool newton);
// Projected Gauss-Seidel on the dual problem (whole model; uses efc_AR).
void SolvePGS(const Model& m, Data& d);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_CONSTRAINT_H_
