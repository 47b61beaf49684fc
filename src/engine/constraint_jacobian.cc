// Products with the constraint Jacobian efc_J in its compressed-row layout (Data::efc_J):
// a dense row (all nv dofs) is summed as the dense products sum it, a sparse row over
// its own dofs (MuJoCo mju_dotSparse, mju_mulMatTVecSparse).
#include <algorithm>

#include "engine/constraint.h"
#include "math/dot.h"

namespace simlab {

bool SparseJacobian(const Model& m) {
  return m.opt.jacobian == kJacobianSparse || (m.opt.jacobian == kJacobianAuto && m.nv >= 60);
}

double EfcRowDot(const Model& m, const Data& d, int r, const double* vec) {
  const int n = d.efc_J_rownnz[r], adr = d.efc_J_rowadr[r];
  if (n == m.nv) return math::Dot(d.efc_J.data() + adr, vec, n);
  return math::DotSparse(d.efc_J.data() + adr, vec, n, d.efc_J_colind.data() + adr);
}

void EfcMulVec(const Model& m, const Data& d, const double* vec, double* res) {
  for (int r = 0; r < d.nefc; r++) res[r] = EfcRowDot(m, d, r, vec);
}

void EfcMulTVec(const Model& m, const Data& d, const double* f, double* res) {
  std::fill(res, res + m.nv, 0.0);
  for (int r = 0; r < d.nefc; r++) {
    if (f[r] == 0) continue;
    const int n = d.efc_J_rownnz[r], adr = d.efc_J_rowadr[r];
    const double* values = d.efc_J.data() + adr;
    const int* cols = d.efc_J_colind.data() + adr;
    for (int k = 0; k < n; k++) res[cols[k]] += values[k] * f[r];
  }
}

void EfcRowDense(const Model& m, const Data& d, int r, double* dense) {
  std::fill(dense, dense + m.nv, 0.0);
  const int n = d.efc_J_rownnz[r], adr = d.efc_J_rowadr[r];
  for (int k = 0; k < n; k++) dense[d.efc_J_colind[adr + k]] = d.efc_J[adr + k];
}

}  // namespace simlab
