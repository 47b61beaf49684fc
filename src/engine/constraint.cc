// Constraint stage (MuJoCo mj_fwdConstraint). With no active constraint rows the
// constraint force is zero and qacc is the unconstrained acceleration M^-1 qfrc_smooth.
// The constraint solver (limits, equalities, contacts) plugs in here and fills nefc.
#include <algorithm>

#include "engine/engine.h"

namespace simlab {

void Constraint(const Model& m, Data& d) {
  d.nefc = 0;
  d.solver_niter = 0;
  std::fill(d.qfrc_constraint.begin(), d.qfrc_constraint.end(), 0.0);
  d.qacc = d.qacc_smooth;
}

}  // namespace simlab
