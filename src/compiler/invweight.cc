// Inverse weights at qpos0 (MuJoCo mj_setConst): how much acceleration a unit force on a
// body, a dof or a tendon produces, averaged over directions. The constraint stage uses
// them to estimate diag(J M^-1 J^T) of each row (efc_diagApprox), which sets the
// regularizer and so the softness of every constraint. Also body_simple, which marks
// bodies whose inertia needs no Jacobian (MuJoCo's "simple" bodies), and meaninertia.
#include <algorithm>
#include <cmath>
#include <vector>

#include "compiler/compiler.h"
#include "engine/engine.h"
#include "math/dot.h"

namespace simlab::compiler {

namespace {

// An axis along exactly one coordinate (MuJoCo's test uses 1e-14).
bool AxisAligned(const double* axis) {
  int n = 0;
  for (int k = 0; k < 3; k++) n += std::abs(axis[k]) > 1e-14;
  return n == 1;
}

// A = rows M^-1 rows^T for `n` dense rows of length nv (n <= 6).
void InverseInertia(const Model& m, const Data& d, const double* rows, int n, double* a) {
  std::vector<double> x(m.nv);
  for (int r = 0; r < n; r++) {
    std::copy_n(rows + static_cast<size_t>(r) * m.nv, m.nv, x.begin());
    SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), x.data());
    for (int c = 0; c < n; c++) a[r * n + c] = math::Dot(rows + static_cast<size_t>(c) * m.nv, x.data(), m.nv);
  }
}

// Translation and rotation inverse weights of body b from its 6 x 6 A at the centre of mass.
void BodyWeight(const Model& m, const Data& d, int b, double* out) {
  if (m.body_weldid[b] == 0) {
    out[0] = out[1] = 0;
    return;
  }
  if (m.body_simple[b] == 2) {
    out[0] = 1 / std::max(kMinVal, m.body_mass[b]);
    out[1] = 0;
    return;
  }
  double a[36] = {0};
  if (m.nv) {
    std::vector<double> jac(6 * static_cast<size_t>(m.nv));
    Jacobian(m, d, jac.data(), jac.data() + 3 * m.nv, &d.xipos[3 * b], b);
    InverseInertia(m, d, jac.data(), 6, a);
  }
  double tran = (a[0] + a[7] + a[14]) / 3, rot = (a[21] + a[28] + a[35]) / 3;
  if (tran < kMinVal && rot > kMinVal) tran = rot;
  else if (rot < kMinVal && tran > kMinVal) rot = tran;
  out[0] = tran;
  out[1] = rot;
}

// Inverse weights of joint j's dofs: averages over its translations and rotations.
void JointWeight(const Model& m, const Data& d, int j, double* dof_weight) {
  int adr = m.jnt_dofadr[j];
  int type = m.jnt_type[j];
  if (m.body_simple[m.jnt_bodyid[j]] == 2) {
    dof_weight[adr] = 1 / std::max(kMinVal, m.body_mass[m.jnt_bodyid[j]]);
    return;
  }
  int n = type == kJointFree ? 6 : type == kJointBall ? 3 : 1;
  std::vector<double> rows(static_cast<size_t>(n) * m.nv, 0.0);
  for (int k = 0; k < n; k++) rows[static_cast<size_t>(k) * m.nv + adr + k] = 1;
  double a[36] = {0};
  InverseInertia(m, d, rows.data(), n, a);
  if (n == 6) {
    double tran = (a[0] + a[7] + a[14]) / 3, rot = (a[21] + a[28] + a[35]) / 3;
    for (int k = 0; k < 3; k++) {
      dof_weight[adr + k] = tran;
      dof_weight[adr + 3 + k] = rot;
    }
  } else if (n == 3) {
    for (int k = 0; k < 3; k++) dof_weight[adr + k] = (a[0] + a[4] + a[8]) / 3;
  } else {
    dof_weight[adr] = a[0];
  }
}

}  // namespace

// body_simple: 1 when the body's inertia frame is its frame, it hangs from the world (or
// a static child of it), has no child bodies and its joints sit at its origin on aligned
// axes with at most one rotation first; 2 when those joints are all slides.
void SimpleBodies(Model* m) {
  for (int i = 0; i < m->nbody; i++) {
    int parent = m->body_parentid[i];
    bool simple = m->body_sameframe[i] == 1 &&
                  (m->body_rootid[i] == i ||
                   (m->body_parentid[parent] == 0 && m->body_dofnum[parent] == 0));
    bool rotation = false, slides_only = true;
    for (int j = m->body_jntadr[i]; j >= 0 && j < m->body_jntadr[i] + m->body_jntnum[i]; j++) {
      int type = m->jnt_type[j];
      const double* pos = &m->jnt_pos[3 * j];
      bool scalar = type == kJointHinge || type == kJointSlide;
      if (rotation || pos[0] != 0 || pos[1] != 0 || pos[2] != 0 ||
          (scalar && !AxisAligned(&m->jnt_axis[3 * j]))) {
        simple = false;
      }
      if (type == kJointBall || type == kJointHinge) rotation = true;
      if (type != kJointSlide) slides_only = false;
    }
    m->body_simple[i] = simple ? (m->body_dofnum[i] > 0 && slides_only ? 2 : 1) : 0;
  }
  // A body with children is never simple.
  for (int i = 1; i < m->nbody; i++) {
    if (m->body_parentid[i] > 0) m->body_simple[m->body_parentid[i]] = 0;
  }
  // Nor is a body carrying a site or wrapping geom of a tendon with inertia.
  for (int t = 0; t < m->ntendon; t++) {
    if (m->tendon_armature[t] == 0) continue;
    for (int w = m->tendon_adr[t]; w < m->tendon_adr[t] + m->tendon_num[t]; w++) {
      int obj = m->wrap_objid[w];
      if (m->wrap_type[w] == kWrapSite) m->body_simple[m->site_bodyid[obj]] = 0;
      if (m->wrap_type[w] == kWrapSphere || m->wrap_type[w] == kWrapCylinder) {
        m->body_simple[m->geom_bodyid[obj]] = 0;
      }
    }
  }
  // dof_simplenum: the run of simple-body dofs starting at each dof.
  int count = 0;
  for (int i = m->nv - 1; i >= 0; i--) {
    count = m->body_simple[m->dof_bodyid[i]] ? count + 1 : 0;
    m->dof_simplenum[i] = count;
  }
}

void ComputeInvWeights(Model* m, const Data& d) {

  for (int b = 0; b < m->nbody; b++) BodyWeight(*m, d, b, &m->body_invweight0[2 * b]);
  for (int j = 0; j < m->njnt; j++) JointWeight(*m, d, j, m->dof_invweight0.data());
  for (int t = 0; t < m->ntendon; t++) {
    double a = 0;
    if (m->nv) InverseInertia(*m, d, &d.ten_J[static_cast<size_t>(t) * m->nv], 1, &a);
    m->tendon_invweight0[t] = a;
  }

  // meaninertia: the mean diagonal of M at qpos0 (<statistic> may override it later).
  if (m->nv) {
    double sum = 0;
    for (int v = 0; v < m->nv; v++) sum += d.M[m->M_rowadr[v] + m->M_rownnz[v] - 1];
    m->stat.meaninertia = sum / m->nv;
  }
}

}  // namespace simlab::compiler
