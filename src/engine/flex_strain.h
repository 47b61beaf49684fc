// The flexstrain equality (MuJoCo 3.12's mjEQ_FLEXSTRAIN): one element of an
// interpolated flex (a cell of its node lattice, or a face of a shell) kept near its rest
// shape by one row per stiff mode of the element.
//
// The compiler stores each element's modes in flex_stiffness (engine/flex_cells.h): their
// count, then w_i = sqrt(lambda_i) v_i for each eigenpair (lambda_i, v_i) of the element's
// stiffness above a relative threshold (3 npe numbers each, node by node). At run time
// the element's nodes x (world) are turned into its corotated frame by q, the inverse of
// the rotation nearest the deformation gradient at the element's centre, and
//
//   residual_i = w_i . (q x q* - x0)          x0: the nodes at qpos0 (flex_node0)
//   J_i        = sum_n (q* w_i,n q) . J_n      J_n: the translation Jacobian of node n
//
// so that the row's force is an elastic force along mode i (MuJoCo's engine_core_
// constraint.c; the rotation is held fixed in the Jacobian).
#ifndef SIMLAB_ENGINE_FLEX_STRAIN_H_
#define SIMLAB_ENGINE_FLEX_STRAIN_H_

#include <type_traits>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// The diagApprox of each of eq's rows: the mean translational inverse weight of its
// element's node bodies.
double FlexStrainInvWeight(const Model& m, int eq);

// What takes each row: any callable row(jac, dofs, n, pos), referred to (not copied, so
// handing a lambda to FlexStrainRows takes nothing from the heap; it must outlive the
// sink, as a lambda written in the call does).
class FlexStrainRowSink {
 public:
  template <class F, class = std::enable_if_t<!std::is_same_v<std::decay_t<F>, FlexStrainRowSink>>>
  FlexStrainRowSink(F&& row)  // NOLINT: implicit, as std::function's
      : row_(const_cast<void*>(static_cast<const void*>(&row))),
        call_(&Call<std::remove_reference_t<F>>) {}
  void operator()(const double* jac, const int* dofs, int n, double pos) const {
    call_(row_, jac, dofs, n, pos);
  }

 private:
  template <class F>
  static void Call(void* row, const double* jac, const int* dofs, int n, double pos) {
    (*static_cast<F*>(row))(jac, dofs, n, pos);
  }
  void* row_;
  void (*call_)(void*, const double*, const int*, int, double);
};

// Calls row(jac, dofs, n, pos) for each of eq's modes in turn: the Jacobian on the n
// dofs (ascending) that move the element's nodes, and the residual.
void FlexStrainRows(const Model& m, Data& d, int eq, FlexStrainRowSink row);

// The efc rows MuJoCo's cfrc_ext pass (mj_rnePostConstraint) steps over for eq: a count
// left from MuJoCo 3.5.1's strain rows (2 + 3 (order+1)^3 per cell for order 1, 6 (order+1)^3
// for order 2, times the flex's cells), not the rows eq makes.
int FlexStrainRneStep(const Model& m, int eq);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_FLEX_STRAIN_H_
