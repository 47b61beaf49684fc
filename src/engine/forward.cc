// The pipeline (MuJoCo engine_forward.c). Forward computes everything that follows
// from the current state; Step checks the state, runs Forward, then integrates.
//
//   position:     Kinematics, ComPos, CamLight, Tendon, MakeInertia, FactorInertia, Collision,
//                 MakeConstraint, Transmission (adhesion's body transmission uses the
//                 contact rows), ProjectConstraint
//   velocity:     tendon/actuator velocities, ComVel, Passive, constraint reference
//                 accelerations, Rne (bias forces)
//   acceleration: Actuation, SmoothAcceleration, Constraint
//
// Each stage ends with its sensors (SensorPos/Vel/Acc, sensor.cc) and, with the energy
// flag, the energies; quantities only some sensors need (cacc/cfrc, subtree velocities)
// are computed on demand by those sensors, once per step.
#include <cmath>
#include <exception>
#include <string>

#include "engine/collision.h"
#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/sensor.h"
#include "engine/stack.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

bool IsBad(double x) { return std::isnan(x) || x > kMaxVal || x < -kMaxVal; }

// The steps' pipelines, which the public functions run without letting errors escape
// (inside them the pipeline is ForwardSkip, which may throw, not Forward).
void StepPipeline(const Model& m, Data& d);
void Step1Pipeline(const Model& m, Data& d);
void Step2Pipeline(const Model& m, Data& d);

// Runs a pipeline; an engine error inside it becomes the warning kWarnEngineError (its
// message kept in d.error and given to the callback) and a reset of the data that keeps
// that warning's count, as a state that diverged does. Nothing escapes.
template <typename Run>
void WithoutThrowing(const Model& m, Data& d, Run run) {
  std::string message;
  GrowStack(d);
  try {
    run();
    return;
  } catch (const std::exception& e) {
    message = e.what();
  } catch (...) {
    message = "unknown error";
  }
  RaiseWarning(d, kWarnEngineError, 0, "engine error: " + message);
  WarningStat kept = d.warning[kWarnEngineError];
  try {
    ResetData(m, d);
  } catch (const std::exception&) {
    // A model the reset itself fails on (history buffers with a timestep <= 0): the
    // data stays as the error left it; the warning says so.
  }
  d.warning[kWarnEngineError] = kept;
  d.error = message;
  d.nreset++;
}

// One option outside its values: a clear error rather than undefined behaviour (the
// options can be changed after compilation, from C++ or Python).
void CheckOption(int value, int count, const char* what, const char* values) {
  if (value < 0 || value >= count) {
    throw Error("unknown " + std::string(what) + " " + std::to_string(value) + " (" + values + ")");
  }
}

// The options the stages switch on, before a pipeline runs.
void CheckOptions(const Option& o) {
  CheckOption(o.integrator, 4, "integrator",
              "opt.integrator: 0 Euler, 1 RK4, 2 implicit, 3 implicitfast");
  CheckOption(o.cone, 2, "cone type", "opt.cone: 0 pyramidal, 1 elliptic");
  CheckOption(o.jacobian, 3, "jacobian type", "opt.jacobian: 0 dense, 1 sparse, 2 auto");
  CheckOption(o.solver, 3, "solver type", "opt.solver: 0 PGS, 1 CG, 2 Newton");
}


void FwdVelocity(const Model& m, Data& d) {
  // What the sensors compute on demand is stale from here on.
  d.flg_subtreevel = false;
  d.flg_energyvel = false;
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
  ReferenceConstraint(m, d);
  Rne(m, d, false, d.qfrc_bias.data());
  TendonBias(m, d, d.qfrc_bias.data());
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
// applied at the body's centre of mass (MuJoCo mj_xfrcAccumulate, mj_applyFT).
void XfrcAccumulate(const Model& m, Data& d, double* qfrc) {
  for (int b = 1; b < m.nbody; b++) {
    const double* f = &d.xfrc_applied[6 * b];
    if (f[0] == 0 && f[1] == 0 && f[2] == 0 && f[3] == 0 && f[4] == 0 && f[5] == 0) continue;
    ApplyForceTorque(m, d, f, f + 3, &d.xipos[3 * b], b, qfrc);
  }
}

// Energies after the position and velocity stages, unless a sensor has computed them:
// with the energy flag, else both zero (MuJoCo's forward).
void EnergyAfterPosition(const Model& m, Data& d) {
  if (d.flg_energypos) return;
  if (m.opt.enableflags & kEnableEnergy) {
    EnergyPos(m, d);
  } else {
    d.energy[0] = d.energy[1] = 0;
  }
}
void EnergyAfterVelocity(const Model& m, Data& d) {
  if ((m.opt.enableflags & kEnableEnergy) && !d.flg_energyvel) EnergyVel(m, d);
}

// Poses, tendons and the factored inertia: the position stage before collisions.
void KinematicsAndInertia(const Model& m, Data& d) {
  Kinematics(m, d);
  ComPos(m, d);
  CamLight(m, d);
  Tendon(m, d);
  MakeInertia(m, d);
  FactorInertia(m, d);
}

}  // namespace

void FwdPositionSmooth(const Model& m, Data& d) {
  KinematicsAndInertia(m, d);
  Transmission(m, d);
}

void FwdPosition(const Model& m, Data& d) {
  d.flg_energypos = false;
  KinematicsAndInertia(m, d);
  Collision(m, d);
  MakeConstraint(m, d);
  Transmission(m, d);
  ProjectConstraint(m, d);
}

void RaiseWarning(Data& d, Warning w, int info, const std::string& text) {
  d.warning[w].number++;
  d.warning[w].lastinfo = info;
  if (d.warning_callback) {
    d.warning_callback(d, w, info, text.empty() ? WarningText(w, info, d.time) : text);
  }
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
  CheckOptions(m.opt);
  // Each stage, then the sensors that need it.
  if (!skip_position) {
    FwdPosition(m, d);
    if (!skip_sensor) SensorPos(m, d);
    EnergyAfterPosition(m, d);
  }
  FwdVelocity(m, d);
  if (!skip_sensor) SensorVel(m, d);
  EnergyAfterVelocity(m, d);
  Actuation(m, d);
  SmoothAcceleration(m, d);
  Constraint(m, d);
  if (!skip_sensor) {
    d.flg_rnepost = false;
    SensorAcc(m, d);
  }
}

void Forward(const Model& m, Data& d) {
  WithoutThrowing(m, d, [&] { ForwardSkip(m, d, false, false); });
}

void Step(const Model& m, Data& d) {
  WithoutThrowing(m, d, [&] { StepPipeline(m, d); });
}

void Step1(const Model& m, Data& d) {
  WithoutThrowing(m, d, [&] { Step1Pipeline(m, d); });
}

void Step2(const Model& m, Data& d) {
  WithoutThrowing(m, d, [&] { Step2Pipeline(m, d); });
}

namespace {

void StepPipeline(const Model& m, Data& d) {
  CheckState(m, d, d.qpos, kWarnBadQpos);
  CheckState(m, d, d.qvel, kWarnBadQvel);
  ForwardSkip(m, d, false, false);
  if (CheckState(m, d, d.qacc, kWarnBadQacc) && !(m.opt.disableflags & kDisableAutoreset)) {
    ForwardSkip(m, d, false, false);
  }
  switch (m.opt.integrator) {
    case kIntegratorRK4: RungeKutta4(m, d); break;
    case kIntegratorImplicit:
    case kIntegratorImplicitFast: ImplicitIntegrate(m, d); break;
    default: Euler(m, d);
  }
}

void Step1Pipeline(const Model& m, Data& d) {
  CheckOptions(m.opt);
  CheckState(m, d, d.qpos, kWarnBadQpos);
  CheckState(m, d, d.qvel, kWarnBadQvel);
  FwdPosition(m, d);
  SensorPos(m, d);
  EnergyAfterPosition(m, d);
  FwdVelocity(m, d);
  SensorVel(m, d);
  EnergyAfterVelocity(m, d);
}

void Step2Pipeline(const Model& m, Data& d) {
  CheckOptions(m.opt);
  Actuation(m, d);
  SmoothAcceleration(m, d);
  Constraint(m, d);
  d.flg_rnepost = false;
  SensorAcc(m, d);
  if (CheckState(m, d, d.qacc, kWarnBadQacc) && !(m.opt.disableflags & kDisableAutoreset)) {
    ForwardSkip(m, d, false, false);
  }
  // RK4 needs the whole step; split stepping integrates it with Euler, as MuJoCo does.
  if (m.opt.integrator == kIntegratorImplicit || m.opt.integrator == kIntegratorImplicitFast) {
    ImplicitIntegrate(m, d);
  } else {
    Euler(m, d);
  }
}

}  // namespace

}  // namespace simlab
