// Analytic derivative of the smooth forces with respect to velocity, for the implicit
// integrators (MuJoCo mjd_smooth_vel):
//
//   qDeriv = d(qfrc_actuator + qfrc_passive - qfrc_bias) / d qvel
//
// on the entries of the dof-dof pattern D (m.D_rowadr, D_rownnz, D_colind: a dof with its
// ancestors and descendants), as MuJoCo stores it.
//
// Actuators: moment^T (d p / d l') moment where p is affine in l' (bias b2, gain a2 times
// the input) or a muscle (the force-velocity curve's slope times the input). Passive:
// -diag(dof damping) - J^T b J for tendon damping, actuator damping included (the slope
// of the polynomial damping force at the current velocity). Bias: the
// velocity derivative of RNE, propagated body by body (Dcvel, Dcdofdot, Dcacc, Dcfrc:
// 6-row blocks per body or dof over the body's row of the body-dof pattern B).
#include <algorithm>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// qDeriv += J^T b J for a row J (length nv), on the entries of the dof-dof pattern D
// (as MuJoCo, which keeps no coupling between dofs of different chains).
void AddJtBJ(const Model& m, Data& d, const double* jac, double b) {
  for (int r = 0; r < m.nv; r++) {
    if (jac[r] == 0) continue;
    double scale = jac[r] * b;
    int adr = m.D_rowadr[r], end = adr + m.D_rownnz[r];
    for (; adr < end; adr++) d.qDeriv[adr] += scale * jac[m.D_colind[adr]];
  }
}

void ActuatorDerivative(const Model& m, Data& d) {
  if (m.opt.disableflags & kDisableActuation) return;
  for (int i = 0; i < m.nactuator; i++) {
    int group = m.actuator_group[i];
    if (group >= 0 && group < 31 && (m.opt.disableactuator & (1 << group))) continue;
    int o = m.actuator_outadr[i];
    // A force held at its clamp does not change with velocity (an orientation's: its norm).
    bool so3 = m.actuator_gaintype[i] == kGainSo3;
    if (m.actuator_forcelimited[i]) {
      const double* range = &m.actuator_forcerange[2 * i];
      if (so3 && math::Norm3(&d.actuator_force[o]) >= range[1]) continue;
      double f = d.actuator_force[o];
      if (!so3 && (f <= range[0] || f >= range[1])) continue;
    }
    bool affine = m.actuator_biastype[i] == kBiasAffine || m.actuator_biastype[i] == kBiasSo3;
    double b = affine ? m.actuator_biasprm[kNBias * i + 2] : 0;
    if (m.actuator_gaintype[i] == kGainDcmotor) b = DcmotorDampingDerivative(m, i);
    double gain_vel = 0;
    if (m.actuator_gaintype[i] == kGainAffine) gain_vel = m.actuator_gainprm[kNGain * i + 2];
    if (m.actuator_gaintype[i] == kGainMuscle) {
      gain_vel = MuscleGainVelocity(d.actuator_length[o], d.actuator_velocity[o],
                                    &m.actuator_lengthrange[2 * o], m.actuator_acc0[o],
                                    &m.actuator_gainprm[kNGain * i]);
    }
    if (gain_vel != 0) {
      if (m.actuator_dyntype[i] == kDynNone) {
        b += gain_vel * d.ctrl[m.actuator_ctrladr[i]];
      } else {
        int adr = m.actuator_actadr[i] + m.actuator_actnum[i] - 1;
        double act = m.actuator_actearly[i] ? NextActivation(m, d, i, adr, d.act_dot[adr]) : d.act[adr];
        b += gain_vel * act;
      }
    }
    if (b == 0) continue;
    for (int k = 0; k < m.actuator_outnum[i]; k++) {
      AddJtBJ(m, d, RowOf(d.actuator_moment, o + k, m.nv), b);
    }
  }
}

// Flex edges' own dampers: -J' b J for each edge that can stretch (its sparse row spread
// over the dofs).
void FlexEdgeDampingDerivative(const Model& m, Data& d) {
  if (m.nflex == 0) return;
  StackFrame frame(d);
  double* row = frame.Alloc(m.nv);
  for (int f = 0; f < m.nflex; f++) {
    if (m.flex_rigid[f] || m.flex_edgedamping[f] == 0) continue;
    for (int e = m.flex_edgeadr[f]; e < m.flex_edgeadr[f] + m.flex_edgenum[f]; e++) {
      if (m.flexedge_rigid[e]) continue;
      int adr = m.flexedge_J_rowadr[e], n = m.flexedge_J_rownnz[e];
      for (int j = 0; j < n; j++) row[m.flexedge_J_colind[adr + j]] = d.flexedge_J[adr + j];
      AddJtBJ(m, d, row, -m.flex_edgedamping[f]);
      for (int j = 0; j < n; j++) row[m.flexedge_J_colind[adr + j]] = 0;
    }
  }
}

// Dampers of dofs, flex edges and tendons, with their actuators' damping: -d(v b(v))/dv.
void PassiveDerivative(const Model& m, Data& d) {
  FluidDerivative(m, d);
  if (m.opt.disableflags & kDisableDamper) return;
  for (int v = 0; v < m.nv; v++) {
    double poly[kNPoly] = {0, 0};
    double damping = m.dof_damping[v] + ActuatorDamping(m, false, m.dof_jntid[v], poly);
    d.qDeriv[m.D_rowadr[v] + m.D_diag[v]] -= DampingSlope(damping, poly, d.qvel[v]);
  }
  FlexEdgeDampingDerivative(m, d);
  for (int i = 0; i < m.ntendon; i++) {
    double poly[kNPoly] = {0, 0};
    double damping = m.tendon_damping[i] + ActuatorDamping(m, true, i, poly);
    double slope = DampingSlope(damping, poly, d.ten_velocity[i]);
    if (slope != 0) AddJtBJ(m, d, RowOf(d.ten_J, i, m.nv), -slope);
  }
}

// D(v x m)/Dv for motion cross product with fixed m: a 6x6 row-major matrix.
void CrossMotionVelDerivative(double* D, const double* v) {
  std::fill(D, D + 36, 0.0);
  D[2] = -v[1]; D[1] = v[2];
  D[8] = v[0]; D[6] = -v[2];
  D[13] = -v[0]; D[12] = v[1];
  D[20] = -v[4]; D[19] = v[5]; D[23] = -v[1]; D[22] = v[2];
  D[26] = v[3]; D[24] = -v[5]; D[29] = v[0]; D[27] = -v[2];
  D[31] = -v[3]; D[30] = v[4]; D[34] = -v[0]; D[33] = v[1];
}

// D(v x* f)/Dv with f fixed.
void CrossForceVelDerivative(double* D, const double* f) {
  std::fill(D, D + 36, 0.0);
  D[2] = -f[1]; D[1] = f[2]; D[5] = -f[4]; D[4] = f[5];
  D[8] = f[0]; D[6] = -f[2]; D[11] = f[3]; D[9] = -f[5];
  D[13] = -f[0]; D[12] = f[1]; D[16] = -f[3]; D[15] = f[4];
  D[20] = -f[4]; D[19] = f[5];
  D[26] = f[3]; D[24] = -f[5];
  D[31] = -f[3]; D[30] = f[4];
}

// D(v x* f)/Df with v fixed.
void CrossForceFrcDerivative(double* D, const double* v) {
  std::fill(D, D + 36, 0.0);
  D[1] = -v[2]; D[2] = v[1]; D[4] = -v[5]; D[5] = v[4];
  D[6] = v[2]; D[8] = -v[0]; D[9] = v[5]; D[11] = -v[3];
  D[12] = -v[1]; D[13] = v[0]; D[15] = -v[4]; D[16] = v[3];
  D[22] = -v[2]; D[23] = v[1];
  D[27] = v[2]; D[29] = -v[0];
  D[33] = -v[1]; D[34] = v[0];
}

// The 6x6 matrix of the cinert product I v.
void InertiaMatrix(double* D, const double* i) {
  const double rows[36] = {i[0], i[3], i[4], 0, -i[8], i[7],
                           i[3], i[1], i[5], i[8], 0, -i[6],
                           i[4], i[5], i[2], -i[7], i[6], 0,
                           0, i[8], -i[7], i[9], 0, 0,
                           -i[8], 0, i[6], 0, i[9], 0,
                           i[7], -i[6], 0, 0, 0, i[9]};
  std::copy(rows, rows + 36, D);
}

// R (6 x n) = A (6x6) B (6 x n)
void Mul6(double* R, const double* A, const double* B, int n) {
  for (int r = 0; r < 6; r++) {
    for (int c = 0; c < n; c++) {
      double s = 0;
      for (int k = 0; k < 6; k++) s += A[6 * r + k] * B[k * n + c];
      R[r * n + c] = s;
    }
  }
}

// The derivatives of a body's velocity, acceleration and force (and of its dofs'
// cdof_dot) are 6 x n blocks over the body's row of the body-dof pattern B (m.B_colind:
// its ancestors' dofs and its subtree's), the only dofs they depend on, as MuJoCo's
// sparse mjd_rne_vel keeps them.
struct BodyBlocks {
  const Model& m;
  double* data;        // block of body b at 6 * B_rowadr[b]
  double* Of(int b) const { return data + 6 * static_cast<size_t>(m.B_rowadr[b]); }
  int Width(int b) const { return m.B_rownnz[b]; }
};

// where[dof] = its column in body b's row of B (entries of other dofs are left).
void ScatterColumns(const Model& m, int b, int* where) {
  const int* cols = m.B_colind.data() + m.B_rowadr[b];
  for (int c = 0; c < m.B_rownnz[b]; c++) where[cols[c]] = c;
}

// For every entry of B, the place of its column in the parent body's row (a body's
// columns are among its parent's): in_parent, nB entries.
void ParentColumns(const Model& m, int* in_parent, int* where) {
  for (int b = 1; b < m.nbody; b++) {
    ScatterColumns(m, m.body_parentid[b], where);
    const int* cols = m.B_colind.data() + m.B_rowadr[b];
    for (int c = 0; c < m.B_rownnz[b]; c++) in_parent[m.B_rowadr[b] + c] = where[cols[c]];
  }
}

// Body b's block = its parent's block on b's columns.
void CopyFromParent(const Model& m, const BodyBlocks& blocks, int b, const int* in_parent) {
  int parent = m.body_parentid[b], n = blocks.Width(b), np = blocks.Width(parent);
  const int* place = in_parent + m.B_rowadr[b];
  const double* src = blocks.Of(parent);
  double* dst = blocks.Of(b);
  for (int k = 0; k < 6; k++) {
    for (int c = 0; c < n; c++) dst[k * n + c] = src[k * np + place[c]];
  }
}

// Velocity derivatives of cvel (per body) and cdof_dot (per dof, over its body's row).
void ComVelDerivative(const Model& m, Data& d, const BodyBlocks& dcvel, double* dcdofdot,
                      const int* dofblock, const int* in_parent, int* where) {
  double mat[36];
  for (int i = 1; i < m.nbody; i++) {
    CopyFromParent(m, dcvel, i, in_parent);
    double* dv = dcvel.Of(i);
    int n = dcvel.Width(i);
    ScatterColumns(m, i, where);
    int end = m.body_dofadr[i] + m.body_dofnum[i];
    for (int j = m.body_dofadr[i]; j >= 0 && j < end;) {
      int type = m.jnt_type[m.dof_jntid[j]];
      int ntran = type == kJointFree ? 3 : 0;
      int nrot = (type == kJointFree || type == kJointBall) ? 3 : 1;
      // Translations of a free joint: cdof_dot = 0, velocity adds directly.
      for (int t = 0; t < ntran; t++) {
        for (int k = 0; k < 6; k++) dv[k * n + where[j + t]] += d.cdof[6 * (j + t) + k];
      }
      j += ntran;
      // Rotations (or a hinge/slide): D cdof_dot = Dcross * Dcvel, then velocity.
      for (int t = 0; t < nrot; t++) {
        CrossMotionVelDerivative(mat, &d.cdof[6 * (j + t)]);
        Mul6(dcdofdot + dofblock[j + t], mat, dv, n);
      }
      for (int t = 0; t < nrot; t++) {
        for (int k = 0; k < 6; k++) dv[k * n + where[j + t]] += d.cdof[6 * (j + t) + k];
      }
      j += nrot;
    }
  }
}

// Dcfrc of body i from its Dcacc and Dcvel: I Dcacc + (Dcross_v(I v) + Dcross_f(v) I) Dcvel.
void BodyForceDerivative(const Data& d, int i, const double* da, const double* dv, int n,
                         double* df, double* tmp) {
  double dmul[36], mat[36], mat1[36], momentum[6];
  InertiaMatrix(dmul, &d.cinert[10 * i]);
  Mul6(df, dmul, da, n);
  MulInertVec(momentum, &d.cinert[10 * i], &d.cvel[6 * i]);
  CrossForceVelDerivative(mat, momentum);
  CrossForceFrcDerivative(mat1, &d.cvel[6 * i]);
  for (int r = 0; r < 6; r++) {
    for (int c = 0; c < 6; c++) {
      double s = 0;
      for (int k = 0; k < 6; k++) s += mat1[6 * r + k] * dmul[6 * k + c];
      mat[6 * r + c] += s;
    }
  }
  Mul6(tmp, mat, dv, n);
  for (int t = 0; t < 6 * n; t++) df[t] += tmp[t];
}

// qDeriv -= d qfrc_bias / d qvel.
void RneDerivative(const Model& m, Data& d) {
  StackFrame frame(d);
  size_t nb = 6 * static_cast<size_t>(m.nB);
  BodyBlocks dcvel{m, frame.Alloc(nb)}, dcacc{m, frame.Alloc(nb)}, dcfrc{m, frame.Alloc(nb)};
  // (each dof's cdof_dot derivative over its body's row)
  SolverFrame ints(d.solver_scratch);
  int* where = ints.Ints(m.nv);
  int* dofblock = ints.Ints(m.nv);
  int* in_parent = ints.Ints(m.nB);
  ParentColumns(m, in_parent, where);
  double* dcdofdot = frame.Alloc(DofBlockOffsets(m, dofblock));
  double* tmp = frame.Alloc(6 * static_cast<size_t>(m.nv));
  ComVelDerivative(m, d, dcvel, dcdofdot, dofblock, in_parent, where);

  // Forward pass: Dcacc from the parent's, the dofs' cdof_dot and its derivative; Dcfrc.
  for (int i = 1; i < m.nbody; i++) {
    CopyFromParent(m, dcacc, i, in_parent);
    double* da = dcacc.Of(i);
    int n = dcacc.Width(i);
    ScatterColumns(m, i, where);
    for (int j = m.body_dofadr[i]; j >= 0 && j < m.body_dofadr[i] + m.body_dofnum[i]; j++) {
      for (int k = 0; k < 6; k++) da[k * n + where[j]] += d.cdof_dot[6 * j + k];
      const double* dd = dcdofdot + dofblock[j];
      for (int t = 0; t < 6 * n; t++) da[t] += dd[t] * d.qvel[j];
    }
    BodyForceDerivative(d, i, da, dcvel.Of(i), n, dcfrc.Of(i), tmp);
  }

  // Backward pass (a body's columns are among its parent's), then onto the dofs: the
  // entries of dof v's row of D are all in its body's row of B.
  for (int i = m.nbody - 1; i > 0; i--) {
    int parent = m.body_parentid[i];
    if (parent == 0) continue;
    const int* place = in_parent + m.B_rowadr[i];
    int n = dcfrc.Width(i), np = dcfrc.Width(parent);
    const double* src = dcfrc.Of(i);
    double* dst = dcfrc.Of(parent);
    for (int k = 0; k < 6; k++) {
      for (int c = 0; c < n; c++) dst[k * np + place[c]] += src[k * n + c];
    }
  }
  for (int v = 0; v < m.nv; v++) {
    int b = m.dof_bodyid[v], n = dcfrc.Width(b);
    if (v == 0 || m.dof_bodyid[v - 1] != b) ScatterColumns(m, b, where);  // (once per body)
    const double* df = dcfrc.Of(b);
    for (int k = 0; k < 6; k++) {
      double c = d.cdof[6 * v + k];
      int adr = m.D_rowadr[v], end = adr + m.D_rownnz[v];
      for (; adr < end; adr++) d.qDeriv[adr] -= c * df[k * n + where[m.D_colind[adr]]];
    }
  }
}

}  // namespace

size_t DofBlockOffsets(const Model& m, int* offset) {
  size_t total = 0;
  for (int j = 0; j < m.nv; j++) {
    if (offset) offset[j] = static_cast<int>(total);
    total += 6 * static_cast<size_t>(m.B_rownnz[m.dof_bodyid[j]]);
  }
  return total;
}

void SmoothVelocityDerivative(const Model& m, Data& d, bool with_bias) {
  std::fill(d.qDeriv.begin(), d.qDeriv.end(), 0.0);
  ActuatorDerivative(m, d);
  PassiveDerivative(m, d);
  if (with_bias) RneDerivative(m, d);
}

}  // namespace simlab
