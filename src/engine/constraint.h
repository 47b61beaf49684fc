// The constraint machinery shared by the row builder (constraint_rows.cc), the stage
// (constraint.cc), the islands (island.cc) and the solvers (solver_primal.cc, solver_pgs.cc).
//
// MuJoCo's formulation (documentation, Computation chapter): the constrained acceleration
// minimizes  0.5 (a - a0)^T M (a - a0) + s(J a - aref), a0 being the unconstrained
// acceleration and s a sum of per-row costs given by each row's state.
#ifndef SIMLAB_ENGINE_CONSTRAINT_H_
#define SIMLAB_ENGINE_CONSTRAINT_H_

#include <functional>
#include <vector>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// efc rows of the current configuration with their softness (position stage).
void MakeConstraint(const Model& m, Data& d);
// efc_vel and efc_aref (velocity stage).
void ReferenceConstraint(const Model& m, Data& d);
// The springs of contacts of passive flexes (exclude 4: no rows) into qfrc_spring: a
// stiffness of 1e4 along the normal (MuJoCo mj_contactPassive; constraint_rows.cc).
void PassiveContactForces(const Model& m, Data& d);
// efc_AR = J M^-1 J^T + diag(R), needed by PGS and noslip (position stage).
void ProjectConstraint(const Model& m, Data& d);
// The body of side j (0 or 1) of a connect or weld, in its body or site form.
int EqualityBody(const Model& m, int eq, int j);
// How far `value` is inside the lower (side -1) or upper (side +1) end of `range`; a
// limit row is made (its side active) when this is below the margin.
inline double LimitDistance(const double* range, double value, int side) {
  return side * (range[(side + 1) / 2] - value);
}
// The impedance of solimp at position `pos` with `margin`, and its derivative.
void Impedance(const double* solimp, double pos, double margin, double* imp, double* slope);

// ---------------------------------------------------------------- efc_J (constraint_jacobian.cc)

// Does MuJoCo build this model's constraint Jacobian sparse (jacobian="sparse", or "auto"
// with 60 dofs or more: mj_isSparse)? Its rows then hold only the dofs they can move.
bool SparseJacobian(const Model& m);
// Row r of efc_J times vec (nv entries).
double EfcRowDot(const Model& m, const Data& d, int r, const double* vec);
// res (nefc) = efc_J vec.
void EfcMulVec(const Model& m, const Data& d, const double* vec, double* res);
// res (nv) = efc_J^T f: rows added in order, rows whose f is zero skipped.
void EfcMulTVec(const Model& m, const Data& d, const double* f, double* res);
// Row r of efc_J as nv numbers.
void EfcRowDense(const Model& m, const Data& d, int r, double* dense);

// The rows a cost update reads: their counts (the first ne rows are equalities, the next
// nf friction losses), softness, kinds, and for elliptic contact rows the contacts they
// belong to (efc_id indexes `contact`; its mu, friction and dim shape the cone, and the
// cone Hessian is written into its H).
struct RowSet {
  int ne = 0, nf = 0, nefc = 0;
  const double* D = nullptr;
  const double* R = nullptr;
  const double* frictionloss = nullptr;
  const int* type = nullptr;
  const int* id = nullptr;
  Contact* contact = nullptr;
};

// The rows of the whole model.
RowSet DataRows(Data& d);

// Arrays for a solver taken from Data::solver_scratch, returned when the frame ends (as
// StackFrame, for doubles and ints; each array keeps its capacity for the next step).
//
//   SolverFrame frame(d.solver_scratch);
//   double* x = frame.Reals(n);   // n zeros, valid until `frame` goes out of scope
//   double* h = frame.RealsToWrite(n);  // n numbers to overwrite (not cleared)
class SolverFrame {
 public:
  explicit SolverFrame(SolverScratch& s) : s_(s), nreal_(s.nreal), nint_(s.nint) {}
  ~SolverFrame() {
    s_.nreal = nreal_;
    s_.nint = nint_;
  }
  SolverFrame(const SolverFrame&) = delete;
  SolverFrame& operator=(const SolverFrame&) = delete;

  double* Reals(size_t n) { return Take(s_.reals, s_.nreal, n, true); }
  int* Ints(size_t n) { return Take(s_.ints, s_.nint, n, true); }
  int* IntsToWrite(size_t n) { return Take(s_.ints, s_.nint, n, false); }
  // n numbers left as they are, for arrays their user writes in full before reading.
  double* RealsToWrite(size_t n) { return Take(s_.reals, s_.nreal, n, false); }

 private:
  // The next array of the pool, zeroed when asked; a new one when the pool is used up
  // (moving the pool's vectors keeps their buffers, so arrays handed out before stay valid).
  template <class T>
  static T* Take(std::vector<std::vector<T>>& pool, size_t& used, size_t n, bool zero) {
    if (used == pool.size()) pool.emplace_back();
    std::vector<T>& array = pool[used++];
    if (zero) {
      array.assign(n, T{});
    } else if (array.size() < n) {
      array.resize(n);
    }
    return array.data();
  }

  SolverScratch& s_;
  size_t nreal_, nint_;
};

// Rows in compressed form: row r has rownnz[r] entries from rowadr[r] on, at the columns
// colind[..] (ascending), with their numbers in `values` when the rows carry them.
struct SparseRows {
  const int *rownnz = nullptr, *rowadr = nullptr, *colind = nullptr;
  const double* values = nullptr;
};
// The transpose of `rows` (nrow rows over ncol columns): a row per column listing the rows
// that hold it, ascending, with the values when `rows` has them; in arrays of `frame`.
SparseRows TransposeRows(const SparseRows& rows, int nrow, int ncol, SolverFrame& frame);
// Does row r hold the same columns as row r - 1 (as the rows of one contact do)?
bool RepeatsRowBefore(const SparseRows& rows, int r);

// One constraint problem: the whole model, or one island of it, in arrays of a
// SolverFrame. Dof arrays have nv entries, row arrays nefc; the first ne rows are
// equalities, the next nf friction.
struct ConstraintProblem {
  int nv = 0, ne = 0, nf = 0, nefc = 0;

  // dofs: inertia in the tree-sparse lower-triangle layout of Model::M_*, with its
  // L^T D L factor, and the smooth force/acceleration; qacc is the solver's iterate.
  const int *M_rownnz = nullptr, *M_rowadr = nullptr, *M_colind = nullptr;
  const double *M = nullptr, *qLD = nullptr, *qLDiagInv = nullptr;
  const double *qfrc_smooth = nullptr, *qacc_smooth = nullptr;
  double* qacc = nullptr;
  double* qfrc_constraint = nullptr;

  // rows: the Jacobian and the per-row data the cost needs; id is efc_id (the contact of
  // a contact row), contact is Data's contact list. J is dense (nefc x nv) unless
  // J_rownnz is set: then, for a model MuJoCo treats as sparse (SparseJacobian), its rows
  // are compressed (row r: J_rownnz[r] values from J_rowadr[r], at the problem's dofs
  // J_colind[..], ascending), and the solvers work on the nonzeros.
  const int *J_rownnz = nullptr, *J_rowadr = nullptr, *J_colind = nullptr;
  const double *J = nullptr, *D = nullptr, *R = nullptr, *frictionloss = nullptr;
  const double* aref = nullptr;
  double* force = nullptr;
  const int *type = nullptr, *id = nullptr;
  int* state = nullptr;
  Contact* contact = nullptr;

  double scale = 1;  // 1 / (total inertia): makes tolerances unit-free
  int niter = 0;     // iterations the solver used
  int nonconvex = 0;  // line-search points where the objective was not convex

  RowSet Rows() const { return RowSet{ne, nf, nefc, D, R, frictionloss, type, id, contact}; }
  bool sparse() const { return J_rownnz != nullptr; }
};

// Row states and forces for jar = J a - aref, and optionally the constraint cost s(jar)
// (MuJoCo mj_constraintUpdate). Elliptic contacts between the cone's top and bottom zones
// get state kStateCone; with cone_hessian their cost's Hessian goes to contact[id].H.
void ConstraintUpdate(const RowSet& rows, const double* jar, int* state, double* force,
                      double* cost, bool cone_hessian);

// ---------------------------------------------------------------- small dense algebra
// (MuJoCo's mju_cholFactor, mju_cholSolve, mju_cholUpdate and the QCQP helpers.)

// In-place dense Cholesky L L^T of the lower triangle (row-major n x n); pivots below
// `mindiag` are raised to it, and (MuJoCo 3.12, clear_deficient) their columns below
// cleared. Returns the rank.
int CholFactor(double* mat, int n, double mindiag, bool clear_deficient = false);
// res = (L L^T)^-1 vec.
void CholSolve(const double* mat, int n, const double* vec, double* res);
// L L^T +/- x x^T, in place (x is overwritten); returns the rank.
int CholUpdate(double* mat, double* x, int n, bool plus);

// The friction QCQP of an elliptic contact:
//   minimize 0.5 x^T A x + x^T b  subject to  sum (x_i / d_i)^2 <= r^2
// over n (2..5) entries; returns whether the constraint is active. QCQP2 and QCQP3 are
// MuJoCo's closed-form 2x2 and 3x3 variants, QCQP the Cholesky-based general one: all
// three run the same Newton iteration on the multiplier, and the solvers call the one
// MuJoCo calls for each size so that results agree to the last bit.
bool QCQP2(double* res, const double* A, const double* b, const double* d, double r);
bool QCQP3(double* res, const double* A, const double* b, const double* d, double r);
bool QCQP(double* res, const double* A, const double* b, const double* d, double r, int n);

// The primal solvers: Newton (flg_newton) or nonlinear conjugate gradient; their work
// arrays come from `scratch`.
void SolvePrimal(const Model& m, ConstraintProblem& p, bool newton, SolverScratch& scratch);
// Projected Gauss-Seidel on the dual problem (whole model; uses efc_AR).
void SolvePGS(const Model& m, Data& d);
// MuJoCo's noslip post-pass (opt.noslip_iterations > 0): Gauss-Seidel on the friction
// forces alone, without the regularizer R, keeping normal forces fixed (uses efc_AR).
void SolveNoSlip(const Model& m, Data& d);

// ---------------------------------------------------------------- dual solver helpers
// Shared by PGS (solver_pgs.cc) and noslip (noslip.cc); `no_r` drops R from AR's diagonal.

// The dual solvers' loop: sweep(iter) returns its cost decrease; sweeps run until that
// decrease (scaled by the total inertia) is below `tolerance` or `maxiter` ran, updating
// the row states after each; then joint space: qfrc_constraint = J^T f and
// qacc = qacc_smooth + M^-1 qfrc_constraint.
void RunDualSweeps(const Model& m, Data& d, int maxiter, double tolerance,
                   const std::function<double(int)>& sweep);
// (efc_AR is dense or in compressed rows, as the model's efc_J: SparseJacobian.)
// The index in efc_AR of AR(r, c), in either layout (on compressed rows, row r holds c).
size_t AREntry(const Model& m, const Data& d, int r, int c);
// inv = 1 / diag(AR) (or of AR - R, floored at kMinVal) for every row.
void InverseDiagAR(const Model& m, const Data& d, bool no_r, double* inv);
// The dim x dim diagonal block of AR at row `start` (minus R, floored at 1e-10).
void BlockAR(const Model& m, const Data& d, int start, int dim, bool no_r, double* block);
// res = b + AR f over rows start..start+dim-1 (minus R f).
void Residual(const Model& m, const Data& d, int start, int dim, bool no_r, double* res);
// res (nefc) = AR f.
void MulAR(const Model& m, const Data& d, const double* f, double* res);
// The dual cost change of moving `force` (dim rows) from `old` given the block A and the
// residual at `old`; a step that raises the cost is undone (returns 0 then).
double CostChange(const double* A, double* force, const double* old, const double* res,
                  int dim);
// Friction forces of an elliptic contact with normal force fn, by the QCQP of the block
// (A, b) over dim-1 entries: zero when fn is too small, else put back on the cone's
// surface when the cone constraint is active.
void EllipticFriction(const double* A, const double* b, const double* mu, double fn, int dim,
                      double* friction_force);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_CONSTRAINT_H_
