// Interpolated flexes in the implicit integrators: a reduced dense system on the dofs
// that move their nodes (flex_implicit.cc; MuJoCo's mj_implicitSkip).
#ifndef SIMLAB_ENGINE_FLEX_IMPLICIT_H_
#define SIMLAB_ENGINE_FLEX_IMPLICIT_H_

#include "engine/constraint.h"
#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// The step's matrix before it is factored, in compressed rows: M - h qDeriv in the layout
// D (implicit) or M (implicitfast). With `simple_diagonal`, a simple body's row keeps
// its diagonal only, as MuJoCo's M stores no other entry there.
struct StepMatrix {
  const double* values;
  const int* rownnz;
  const int* rowadr;
  const int* colind;
  bool simple_diagonal;

  // Is entry k of row `row` part of the matrix MuJoCo reads?
  bool Kept(const Model& m, int row, int k) const {
    if (!simple_diagonal || !m.body_simple[m.dof_bodyid[row]]) return true;
    return colind[rowadr[row] + k] == row;
  }
};

// The reduced system, in arrays of the caller's SolverFrame: the n dofs moving
// interpolated flex nodes (dofs, and local: a dof's place or -1), H's Cholesky factor
// (n x n, lower triangle), and the step matrix's entries coupling those dofs to others.
struct FlexImplicitSystem {
  int n = 0;
  int* dofs = nullptr;
  int* local = nullptr;
  double* H = nullptr;
  double* velocity_term = nullptr;  // the stiffness's velocity correction on the n dofs
  int ncoupling = 0;
  double* coupling_val = nullptr;
  int* coupling_row = nullptr;
  int* coupling_col = nullptr;
};

// Does the step take the interpolated flexes' stiffness (some flex is interpolated and
// no dof is asleep)?
bool UsesFlexImplicitSystem(const Model& m, const Data& d);

// Gathers the node dofs' block of the step matrix, adds (h^2 + h damping) times each
// flex's stiffness J' K J (MuJoCo's mjd_flexInterp_addH) and factors it.
FlexImplicitSystem BuildFlexImplicitSystem(const Model& m, Data& d, const StepMatrix& step,
                                           SolverFrame& frame);

// After the sparse solve: the node dofs' accelerations from the reduced system, with the
// stiffness's velocity correction (mjd_flexInterp_mulKD, computed with the system) and
// the couplings to the other dofs' accelerations in qacc, overwritten into qacc.
void SolveFlexImplicitSystem(const Model& m, Data& d, const FlexImplicitSystem& s,
                             const double* qfrc, double* qacc);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_FLEX_IMPLICIT_H_
