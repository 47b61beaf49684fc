// The pipeline (MuJoCo engine_forward.c). Forward computes everything that follows
// from the current state; Step checks the state, runs Forward, then integrates.
//
//   position:     Kinematics, ComPos, Tendon, MakeInertia, FactorInertia, Transmission
//   velocity:     tendon/actuator velocities, ComVel, Passive, Rne (bias forces)
//   acceleration: Actuation, SmoothAcceleration, Constraint
#include <cmath>
#include <cstdio>

#include "engine/engine.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

const char* const kWarningText[kNumWarnings] = {
    "inertia matrix is too close to singular",
    "contact buffer is full",
    "constraint buffer is full",
    "visual geom buffer is full",
    "bad qpos (NaN or too large): simulation reset",
    "bad qvel (NaN or too large): simulation reset",
    "bad qacc (NaN or too large): simulation reset",
    "bad ctrl (NaN or too large): controls zeroed",
};

bool IsBad(double x) { return std::isnan(x) || x > kMaxVal || x < -kMaxVal; }

void FwdPosition(const Model& m, Data& d) {
  Kinematics(m, d);
  ComPos(m, d);
  Tendon(m, d);
  MakeInertia(m, d);
  FactorInertia(m, d);
  Transmission(m, d);
}

void FwdVelocity(const Model& m, Data& d) {
  // Tendon and actuator velocities: their Jacobians times qvel.
  for (int i = 0; i < m.ntendon; i++) {
    double s = 0;
    for (int v = 0; v < m.nv; v++) s += d.ten_J[static_cast<size_t>(i) * m.nv + v] * d.qvel[v];
    d.ten_velocity[i] = s;
  }
  bool actuation = !(m.opt.disableflags & kDisableActuation);
  for (int i = 0; i < m.nu; i++) {
    double s = 0;
    for (int v = 0; v < m.nv && actuation; v++) {
      s += d.actuator_moment[static_cast<size_t>(i) * m.nv + v] * d.qvel[v];
    }
    d.actuator_velocity[i] = s;
  }
  ComVel(m, d);
  Passive(m, d);
  Rne(m, d, false, d.qfrc_bias.data());
}

// Resets when the state holds a NaN or a huge value; returns true if it did.
bool CheckState(const Model& m, Data& d, const std::vector<double>& values, Warning w) {
  for (size_t i = 0; i < values.size(); i++) {
    if (!IsBad(values[i])) continue;
    RaiseWarning(d, w, static_cast<int>(i));
    WarningStat kept = d.warning[w];
    if (!(m.opt.disableflags & kDisableAutoreset)) {
      ResetData(m, d);
      d.nreset++;
    }
    d.warning[w] = kept;
    return true;
  }
  return false;
}

// qfrc += J^T (force, torque) for every body with a Cartesian force in xfrc_applied,
// applied at the body's centre of mass (MuJoCo mj_xfrcAccumulate).
void XfrcAccumulate(const Model& m, const Data& d, double* qfrc) {
  for (int b = 1; b < m.nbody; b++) {
    const double* f = &d.xfrc_applied[6 * b];
    if (f[0] == 0 && f[1] == 0 && f[2] == 0 && f[3] == 0 && f[4] == 0 && f[5] == 0) continue;
    // The last dof that moves the body, then up the dof tree.
    int body = b;
    while (body > 0 && m.body_dofnum[body] == 0) body = m.body_parentid[body];
    if (body == 0) continue;
    double offset[3];
    for (int k = 0; k < 3; k++) offset[k] = d.xipos[3 * b + k] - d.subtree_com[3 * m.body_rootid[b] + k];
    for (int j = m.body_dofadr[body] + m.body_dofnum[body] - 1; j >= 0; j = m.dof_parentid[j]) {
      const double* c = &d.cdof[6 * j];
      // Linear Jacobian column: v + w x offset; angular: w.
      double jp[3] = {c[3] + c[1] * offset[2] - c[2] * offset[1],
                      c[4] + c[2] * offset[0] - c[0] * offset[2],
                      c[5] + c[0] * offset[1] - c[1] * offset[0]};
      qfrc[j] += jp[0] * f[0] + jp[1] * f[1] + jp[2] * f[2] + c[0] * f[3] + c[1] * f[4] + c[2] * f[5];
    }
  }
}

}  // namespace

void RaiseWarning(Data& d, Warning w, int info) {
  if (d.warning[w].number == 0) {
    std::fprintf(stderr, "simlab warning: %s (index %d, time %g)\n", kWarningText[w], info, d.time);
  }
  d.warning[w].number++;
  d.warning[w].lastinfo = info;
}

void SmoothAcceleration(const Model& m, Data& d) {
  for (int v = 0; v < m.nv; v++) {
    d.qfrc_smooth[v] = d.qfrc_passive[v] - d.qfrc_bias[v] + d.qfrc_applied[v] + d.qfrc_actuator[v];
  }
  XfrcAccumulate(m, d, d.qfrc_smooth.data());
  d.qacc_smooth = d.qfrc_smooth;
  SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), d.qacc_smooth.data());
}

void ForwardSkip(const Model& m, Data& d, bool skip_position, bool skip_sensor) {
  if (!skip_position) FwdPosition(m, d);
  FwdVelocity(m, d);
  Actuation(m, d);
  SmoothAcceleration(m, d);
  Constraint(m, d);
}

void Forward(const Model& m, Data& d) { ForwardSkip(m, d, false, false); }

void Step(const Model& m, Data& d) {
  CheckState(m, d, d.qpos, kWarnBadQpos);
  CheckState(m, d, d.qvel, kWarnBadQvel);
  Forward(m, d);
  if (CheckState(m, d, d.qacc, kWarnBadQacc) && !(m.opt.disableflags & kDisableAutoreset)) {
    Forward(m, d);
  }
  switch (m.opt.integrator) {
    case kIntegratorRK4: RungeKutta4(m, d); break;
    case kIntegratorImplicit:
    case kIntegratorImplicitFast: ImplicitIntegrate(m, d); break;
    default: Euler(m, d);
  }
}

}  // namespace simlab
