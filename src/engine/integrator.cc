// Time integration (MuJoCo engine_forward.c: mj_Euler, mj_RungeKutta, mj_implicit).
//
// All integrators end in Advance: act <- next activation, qvel += h qacc,
// qpos <- qpos (+) h qvel on the configuration manifold, time += h. Between act and qvel,
// trees slow for long enough fall asleep (sleep.cc); only awake trees then move.
//   Euler:        qacc from forward; if any dof has damping it is treated implicitly,
//                 qacc = (M + h diag(damping))^-1 (qfrc_smooth + qfrc_constraint).
//   RK4:          classic 4-stage Runge-Kutta on (qpos, qvel, act).
//   implicit:     qacc = (M - h qDeriv)^-1 (qfrc_smooth + qfrc_constraint), full
//                 derivative including the Coriolis terms (LU).
//   implicitfast: the same without the RNE term, qDeriv restricted to M's sparsity
//                 (symmetric, so L^T D L).
#include <algorithm>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/flex_implicit.h"
#include "engine/free_body_implicit.h"
#include "engine/sleep.h"
#include "engine/stack.h"
#include "engine/timer.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

namespace {

// Joint j's coordinates moved by its velocity for dt.
void IntegrateJoint(const Model& m, double* qpos, const double* qvel, double dt, int j) {
  int padr = m.jnt_qposadr[j], vadr = m.jnt_dofadr[j];
  switch (m.jnt_type[j]) {
    case kJointFree:
      for (int t = 0; t < 3; t++) qpos[padr + t] += dt * qvel[vadr + t];
      math::QuatIntegrate(qpos + padr + 3, qvel + vadr + 3, dt);
      break;
    case kJointBall: math::QuatIntegrate(qpos + padr, qvel + vadr, dt); break;
    default: qpos[padr] += dt * qvel[vadr];
  }
}

}  // namespace

void IntegratePos(const Model& m, double* qpos, const double* qvel, double dt) {
  for (int j = 0; j < m.njnt; j++) IntegrateJoint(m, qpos, qvel, dt, j);
}

void NormalizeQuat(const Model& m, double* qpos) {
  for (int j = 0; j < m.njnt; j++) {
    int padr = m.jnt_qposadr[j];
    if (m.jnt_type[j] == kJointFree) math::NormalizeQuat(qpos + padr + 3);
    if (m.jnt_type[j] == kJointBall) math::NormalizeQuat(qpos + padr);
  }
}

namespace {

// IntegratePos on the joints of awake bodies only.
void IntegrateAwakePos(const Model& m, Data& d, const double* qvel, double dt) {
  for (int j = 0; j < m.njnt; j++) {
    if (d.body_awake[m.jnt_bodyid[j]] == kAwake) IntegrateJoint(m, d.qpos.data(), qvel, dt, j);
  }
}

// Advances activations, velocities (by qacc), positions (by qvel_for_pos, or the new
// qvel if null) and time by one step.
void Advance(const Model& m, Data& d, const double* act_dot, const double* qacc,
             const double* qvel_for_pos) {
  double h = m.opt.timestep;
  // Delayed and sampled ctrl and sensors record their sample at the current time.
  RecordHistory(m, d);
  if (m.na && !(m.opt.disableflags & kDisableActuation)) {
    for (int i = 0; i < m.nactuator; i++) {
      int group = m.actuator_group[i];
      bool off = group >= 0 && group < 31 && (m.opt.disableactuator & (1 << group));
      for (int a = m.actuator_actadr[i]; a >= 0 && a < m.actuator_actadr[i] + m.actuator_actnum[i]; a++) {
        d.act[a] = NextActivation(m, d, i, a, off ? 0 : act_dot[a]);
      }
    }
    So3Rewind(m, d);
  }
  // Trees slow for long enough fall asleep; what depends on their (now zero) velocity is
  // computed again before they stop moving (the integrated qacc stays this step's).
  if (PutToSleep(m, d)) {
    ForwardSkip(m, d, kStagePos, Sensors::kCompute);
    UpdateSleep(m, d);
  }
  if (AnyAsleep(m, d)) {
    // Only the awake trees move.
    for (int k = 0; k < d.nv_awake; k++) {
      int v = d.dof_awake_ind[k];
      d.qvel[v] += qacc[v] * h;
    }
    IntegrateAwakePos(m, d, qvel_for_pos ? qvel_for_pos : d.qvel.data(), h);
  } else {
    for (int v = 0; v < m.nv; v++) d.qvel[v] += qacc[v] * h;
    IntegratePos(m, d.qpos.data(), qvel_for_pos ? qvel_for_pos : d.qvel.data(), h);
  }
  d.time += h;
  d.qacc_warmstart = d.qacc;
  PluginAdvance(m, d);
}

}  // namespace

void Euler(const Model& m, Data& d) {
  StageTimer timer(d, kTimerAdvance);
  StackFrame frame(d);
  double* qacc = frame.Alloc(m.nv);
  bool damping = false;
  if (!(m.opt.disableflags & (kDisableEulerdamp | kDisableDamper))) {
    // (of the awake dofs, when trees sleep) Actuator damping on a joint counts too (MuJoCo 3.7+).
    bool any_asleep = AnyAsleep(m, d);
    for (int v = 0; v < m.nv; v++) {
      if (any_asleep && d.body_awake[m.dof_bodyid[v]] != kAwake) continue;
      damping = damping || m.dof_damping[v] > 0 || m.jnt_actuatorid[m.dof_jntid[v]] != -1;
    }
  }

  if (!damping) {
    std::copy(d.qacc.begin(), d.qacc.end(), qacc);
  } else {
    // qH = M + h diag(damping), factor, solve with the total force.
    d.qH = d.M;
    for (int v = 0; v < m.nv; v++) {
      double poly[kNPoly] = {0, 0};
      double b = m.dof_damping[v] + ActuatorDamping(m, false, m.dof_jntid[v], poly);
      d.qH[m.M_rowadr[v] + m.M_rownnz[v] - 1] += m.opt.timestep * DampingSlope(b, poly, d.qvel[v]);
    }
    FactorSparse(m, d.qH.data(), d.qHDiagInv.data());
    for (int v = 0; v < m.nv; v++) qacc[v] = d.qfrc_smooth[v] + d.qfrc_constraint[v];
    SolveSparse(m, d.qH.data(), d.qHDiagInv.data(), qacc);
  }
  Advance(m, d, d.act_dot.data(), qacc, nullptr);
}

void RungeKutta4(const Model& m, Data& d) {
  constexpr int kStages = 4;
  const double a[kStages - 1] = {0.5, 0.5, 1.0};  // diagonal Butcher tableau (= c)
  const double b[kStages] = {1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0};
  int nq = m.nq, nv = m.nv, na = m.na;
  double h = m.opt.timestep, time0 = d.time;

  // X[i] = (qpos, qvel, act) at stage i; F[i] = (qacc, act_dot) there.
  StackFrame frame(d);
  double* X[kStages];
  double* F[kStages];
  for (int i = 0; i < kStages; i++) {
    X[i] = frame.Alloc(nq + nv + na);
    F[i] = frame.Alloc(nv + na);
  }
  double* dx = frame.Alloc(2 * nv + na);  // (velocity, acceleration, act_dot)
  std::copy(d.qpos.begin(), d.qpos.end(), X[0]);
  std::copy(d.qvel.begin(), d.qvel.end(), X[0] + nq);
  std::copy(d.act.begin(), d.act.end(), X[0] + nq + nv);
  std::copy(d.qacc.begin(), d.qacc.end(), F[0]);
  std::copy(d.act_dot.begin(), d.act_dot.end(), F[0] + nv);

  // Stages 1..3: X[i] = X[0] + h a_i (X[i-1] velocity, F[i-1]); evaluate F[i] there.
  for (int i = 1; i < kStages; i++) {
    for (int k = 0; k < nv; k++) dx[k] = a[i - 1] * X[i - 1][nq + k];
    for (int k = 0; k < nv + na; k++) dx[nv + k] = a[i - 1] * F[i - 1][k];
    std::copy(X[0], X[0] + nq + nv + na, X[i]);
    IntegratePos(m, X[i], dx, h);
    for (int k = 0; k < nv + na; k++) X[i][nq + k] += h * dx[nv + k];
    std::copy(X[i], X[i] + nq, d.qpos.begin());
    std::copy(X[i] + nq, X[i] + nq + nv, d.qvel.begin());
    std::copy(X[i] + nq + nv, X[i] + nq + nv + na, d.act.begin());
    d.time = time0 + a[i - 1] * h;
    ForwardSkip(m, d, kStageNone, Sensors::kSkip);
    std::copy(d.qacc.begin(), d.qacc.end(), F[i]);
    std::copy(d.act_dot.begin(), d.act_dot.end(), F[i] + nv);
  }

  // Weighted average of the stage derivatives, applied from the initial state.
  StageTimer timer(d, kTimerAdvance);
  std::fill(dx, dx + 2 * nv + na, 0.0);
  for (int j = 0; j < kStages; j++) {
    for (int k = 0; k < nv; k++) dx[k] += b[j] * X[j][nq + k];
    for (int k = 0; k < nv + na; k++) dx[nv + k] += b[j] * F[j][k];
  }
  d.time = time0;
  std::copy(X[0], X[0] + nq, d.qpos.begin());
  std::copy(X[0] + nq, X[0] + nq + nv, d.qvel.begin());
  std::copy(X[0] + nq + nv, X[0] + nq + nv + na, d.act.begin());
  Advance(m, d, dx + 2 * nv, dx + nv, dx);
}

namespace {

// qLU = M - h qDeriv in the dof-dof pattern D (M's lower triangle mirrored).
void BuildImplicitMatrix(const Model& m, Data& d) {
  double h = m.opt.timestep;
  for (int i = 0; i < m.nv; i++) {
    int adr = m.D_rowadr[i];
    for (int s = 0; s < m.D_rownnz[i]; s++) {
      int j = m.D_colind[adr + s];
      // Row i of M is the beginning of row i of D; M(j, i) for a descendant j sits in row
      // j after i's ancestors.
      double mass = j <= i ? d.M[m.M_rowadr[i] + s] : d.M[m.M_rowadr[j] + m.D_diag[i]];
      d.qLU[adr + s] = mass + d.qDeriv[adr + s] * -h;
    }
  }
}

// Factors qLU in place, eliminating from the last dof up (MuJoCo's reverse-order sparse
// LU): afterwards A = (U + I) L with L the lower triangle and diagonal of qLU and U its
// strictly upper triangle. The pattern D keeps every dof's chain, so elimination fills in
// nothing: the rows holding column r are r's ancestors', whose remaining columns include
// every column of row r's.
void FactorImplicitMatrix(const Model& m, Data& d) {
  SolverFrame ints(d.solver_scratch);
  int* remaining = ints.IntsToWrite(m.nv);
  std::copy(m.D_rownnz.begin(), m.D_rownnz.end(), remaining);
  double* lu = d.qLU.data();
  for (int r = m.nv - 1; r >= 0; r--) {
    // Row r's descendants are eliminated already: its last remaining entry is the pivot.
    int pivot = m.D_rowadr[r] + --remaining[r];
    for (int c = m.dof_parentid[r]; c >= 0; c = m.dof_parentid[c]) {
      // Row c's last remaining entry is (c, r): scale it, then subtract it times row r.
      int cr = m.D_rowadr[c] + --remaining[c];
      lu[cr] /= lu[pivot];
      int rk = m.D_rowadr[r], ck = m.D_rowadr[c];
      int rend = rk + remaining[r], cend = ck + remaining[c];
      for (; ck < cend && rk < rend; ck++) {
        if (m.D_colind[ck] == m.D_colind[rk]) lu[ck] -= lu[rk++] * lu[cr];
      }
    }
  }
}

// qacc = A^-1 qfrc for A = (U + I) L factored by FactorImplicitMatrix.
void SolveImplicitMatrix(const Model& m, const Data& d, const double* qfrc, double* qacc) {
  const double* lu = d.qLU.data();
  // (U + I) y = qfrc, from the last dof up.
  for (int i = m.nv - 1; i >= 0; i--) {
    int after = m.D_diag[i] + 1, adr = m.D_rowadr[i] + after;
    qacc[i] = qfrc[i];
    int n = m.D_rownnz[i] - after;
    if (n > 0) qacc[i] -= math::DotSparse(lu + adr, qacc, n, &m.D_colind[adr]);
  }
  // L qacc = y, from the first dof down.
  for (int i = 0; i < m.nv; i++) {
    int adr = m.D_rowadr[i], before = m.D_diag[i];
    if (before > 0) qacc[i] -= math::DotSparse(lu + adr, qacc, before, &m.D_colind[adr]);
    qacc[i] /= lu[adr + before];
  }
}

// qH = M - h qDeriv restricted to M's sparsity. MuJoCo's M stores no off-diagonal
// entries in the rows of simple bodies' dofs, so their qDeriv couplings (fluid drag on a
// free body, say) are dropped there. A free body that MuJoCo 3.12 solves on its own keeps
// M's rows (SolveFreeBodies).
void BuildFastMatrix(const Model& m, Data& d) {
  double h = m.opt.timestep;
  bool apart = SolvesFreeBodiesApart(m);
  for (int i = 0; i < m.nv; i++) {
    if (apart && IsStandaloneFreeBody(m, m.dof_bodyid[i])) {
      std::copy_n(&d.M[m.M_rowadr[i]], m.M_rownnz[i], &d.qH[m.M_rowadr[i]]);
      continue;
    }
    bool simple = m.body_simple[m.dof_bodyid[i]] != 0;
    // Row i of M is the beginning of row i of D.
    const double* deriv = &d.qDeriv[m.D_rowadr[i]];
    for (int s = 0; s < m.M_rownnz[i]; s++) {
      int adr = m.M_rowadr[i] + s;
      d.qH[adr] = simple && m.M_colind[adr] != i ? d.M[adr] : d.M[adr] - h * deriv[s];
    }
  }
}

// The step matrix as built, before it is factored: M - h qDeriv in D's layout (qLU,
// implicit) or M's (qH, implicitfast).
StepMatrix StepMatrixOf(const Model& m, const Data& d) {
  if (m.opt.integrator == kIntegratorImplicit) {
    return StepMatrix{d.qLU.data(), m.D_rownnz.data(), m.D_rowadr.data(), m.D_colind.data(),
                      false};
  }
  return StepMatrix{d.qH.data(), m.M_rownnz.data(), m.M_rowadr.data(), m.M_colind.data(), true};
}

}  // namespace

void ImplicitIntegrate(const Model& m, Data& d) {
  StageTimer timer(d, kTimerAdvance);
  StackFrame frame(d);
  double* qfrc = frame.Alloc(m.nv);
  double* qacc = frame.Alloc(m.nv);
  for (int v = 0; v < m.nv; v++) qfrc[v] = d.qfrc_smooth[v] + d.qfrc_constraint[v];
  bool implicit = m.opt.integrator == kIntegratorImplicit;

  // The step matrix M - h qDeriv: with qDeriv's RNE part (implicit) or without it.
  SmoothVelocityDerivative(m, d, implicit);
  if (implicit) {
    BuildImplicitMatrix(m, d);
  } else {
    BuildFastMatrix(m, d);
  }

  // Interpolated flexes: their nodes' block, with their stiffness, set apart first.
  SolverFrame flex_frame(d.solver_scratch);
  FlexImplicitSystem flex;
  if (UsesFlexImplicitSystem(m, d)) flex = BuildFlexImplicitSystem(m, d, StepMatrixOf(m, d), flex_frame);

  // qacc = (M - h qDeriv)^-1 qfrc: by sparse LU (no pivoting: the matrix is dominated by
  // the positive definite M for any sensible step) or by L^T D L.
  if (implicit) {
    FactorImplicitMatrix(m, d);
    SolveImplicitMatrix(m, d, qfrc, qacc);
  } else {
    FactorSparse(m, d.qH.data(), d.qHDiagInv.data());
    std::copy(qfrc, qfrc + m.nv, qacc);
    SolveSparse(m, d.qH.data(), d.qHDiagInv.data(), qacc);
    if (SolvesFreeBodiesApart(m)) SolveFreeBodies(m, d, qfrc, qacc);
  }
  SolveFlexImplicitSystem(m, d, flex, qfrc, qacc);
  Advance(m, d, d.act_dot.data(), qacc, nullptr);
}

}  // namespace simlab
