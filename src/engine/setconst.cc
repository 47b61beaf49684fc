// Model constants derived from the kinematic tree.
#include "engine/engine.h"

namespace simlab {

// Sparsity of the joint-space inertia matrix: dof i couples only with its ancestors.
// Row i of the lower triangle lists i's ancestor dofs in increasing order, then i.
static void InertiaSparsity(Model& m) {
  int adr = 0;
  for (int i = 0; i < m.nv; i++) {
    // Count the ancestors, then write them from the root down.
    int depth = 0;
    for (int j = i; j >= 0; j = m.dof_parentid[j]) depth++;
    m.M_rownnz[i] = depth;
    m.M_rowadr[i] = adr;
    int k = adr + depth - 1;
    for (int j = i; j >= 0; j = m.dof_parentid[j]) m.M_colind[k--] = j;
    adr += depth;
  }
}

void SetConst(Model& m) {
  // M_colind has nM entries: the sum of the ancestor-chain depths.
  int nM = 0;
  for (int i = 0; i < m.nv; i++) {
    for (int j = i; j >= 0; j = m.dof_parentid[j]) nM++;
  }
  m.nM = nM;
  m.M_rownnz.assign(m.nv, 0);
  m.M_rowadr.assign(m.nv, 0);
  m.M_colind.assign(nM, 0);
  InertiaSparsity(m);
}

}  // namespace simlab
