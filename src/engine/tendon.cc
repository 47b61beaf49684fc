// Tendon lengths and Jacobians (MuJoCo mj_tendon). A fixed tendon is a linear
// combination of joint positions, l = sum_j coef_j q_j, so its Jacobian row holds the
// coefficients at the joints' dofs.
#include "engine/engine.h"

namespace simlab {

namespace {
constexpr int kWrapJoint = 1;  // mjWRAP_JOINT: a fixed-tendon term
}  // namespace

void Tendon(const Model& m, Data& d) {
  for (int i = 0; i < m.ntendon; i++) {
    double* jac = &d.ten_J[static_cast<size_t>(i) * m.nv];
    for (int v = 0; v < m.nv; v++) jac[v] = 0;
    d.ten_length[i] = 0;
    for (int w = m.tendon_adr[i]; w < m.tendon_adr[i] + m.tendon_num[i]; w++) {
      if (m.wrap_type[w] != kWrapJoint) continue;  // the compiler admits fixed tendons only
      int joint = m.wrap_objid[w];
      double coef = m.wrap_prm[w];
      d.ten_length[i] += coef * d.qpos[m.jnt_qposadr[joint]];
      jac[m.jnt_dofadr[joint]] = coef;
    }
  }
}

}  // namespace simlab
