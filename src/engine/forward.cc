// The pipeline (MuJoCo engine_forward.c): the list of stages. Forward computes
// everything that follows from the current state; Step checks the state, runs Forward,
// then integrates.
//
//   position:     Kinematics, ComPos, CamLight, FlexKinematics, Tendon, MakeInertia, FactorInertia,
//                 Collision, MakeConstraint, Transmission (adhesion's body transmission
//                 uses the contact rows), ProjectConstraint; with sleep enabled, sleeping
//                 trees wake after Kinematics (a changed state), Tendon (a tendon limit),
//                 Collision (a contact: collide again) and for an equality (sleep.cc)
//   velocity:     FlexEdgeVelocity, TendonVelocity, ActuatorVelocity, ComVel, Passive,
//                 ReferenceConstraint, Rne and TendonBias (bias forces)
//   acceleration: Actuation, SmoothAcceleration, Constraint
//
// Each stage ends with its sensors (SensorPos/Vel/Acc, sensor.cc) and, with the energy
// flag, the energies; quantities only some sensors need (cacc/cfrc, subtree velocities)
// are computed on demand by those sensors, once per step.
#include <exception>
#include <string>

#include "engine/collision.h"
#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/sensor.h"
#include "engine/sleep.h"
#include "engine/stack.h"
#include "engine/timer.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

// ------------------------------------------------------------ errors and options

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

// ------------------------------------------------------------ energies

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

// ------------------------------------------------------------ stages

// Poses, tendons and the factored inertia: the position stage before collisions.
void KinematicsAndInertia(const Model& m, Data& d) {
  {
    StageTimer timer(d, kTimerPosKinematics);
    Kinematics(m, d);
    if (WakeChanged(m, d)) UpdateSleep(m, d);
    ComPos(m, d);
    CamLight(m, d);
    FlexKinematics(m, d);
    Tendon(m, d);
    if (WakeOnTendonLimit(m, d)) UpdateSleep(m, d);
  }
  StageTimer timer(d, kTimerPosInertia);
  MakeInertia(m, d);
  FactorInertia(m, d);
}

void FwdVelocity(const Model& m, Data& d) {
  StageTimer timer(d, kTimerVelocity);
  // What the sensors compute on demand is stale from here on.
  d.flg_subtreevel = false;
  d.flg_energyvel = false;
  FlexEdgeVelocity(m, d);
  TendonVelocity(m, d);
  ActuatorVelocity(m, d);
  ComVel(m, d);
  Passive(m, d);
  ReferenceConstraint(m, d);
  Rne(m, d, false, d.qfrc_bias.data());
  TendonBias(m, d, d.qfrc_bias.data());
}

// The position stage, its sensors and energy.
void PositionStage(const Model& m, Data& d, Sensors sensors) {
  FwdPosition(m, d);
  if (sensors == Sensors::kCompute) SensorPos(m, d);
  EnergyAfterPosition(m, d);
}

// The velocity stage, its sensors and energy.
void VelocityStage(const Model& m, Data& d, Sensors sensors) {
  FwdVelocity(m, d);
  if (sensors == Sensors::kCompute) SensorVel(m, d);
  EnergyAfterVelocity(m, d);
}

// The acceleration stage and its sensors.
void AccelerationStage(const Model& m, Data& d, Sensors sensors) {
  {
    StageTimer timer(d, kTimerActuation);
    Actuation(m, d);
  }
  SmoothAcceleration(m, d);
  {
    StageTimer timer(d, kTimerConstraint);
    Constraint(m, d);
  }
  if (sensors == Sensors::kCompute) {
    d.flg_rnepost = false;
    SensorAcc(m, d);
  }
}

// ------------------------------------------------------------ steps

// After the acceleration: a bad qacc resets the data, which is then computed again.
void RedoIfBadAcceleration(const Model& m, Data& d) {
  if (WarnAndResetIfBad(m, d, d.qacc, kWarnBadQacc) &&
      !(m.opt.disableflags & kDisableAutoreset)) {
    ForwardSkip(m, d, kStageNone, Sensors::kCompute);
  }
}

void StepPipeline(const Model& m, Data& d) {
  StageTimer timer(d, kTimerStep);
  WarnAndResetIfBad(m, d, d.qpos, kWarnBadQpos);
  WarnAndResetIfBad(m, d, d.qvel, kWarnBadQvel);
  ForwardSkip(m, d, kStageNone, Sensors::kCompute);
  RedoIfBadAcceleration(m, d);
  switch (m.opt.integrator) {
    case kIntegratorRK4: RungeKutta4(m, d); break;
    case kIntegratorImplicit:
    case kIntegratorImplicitFast: ImplicitIntegrate(m, d); break;
    default: Euler(m, d);
  }
}

void Step1Pipeline(const Model& m, Data& d) {
  CheckOptions(m.opt);
  WarnAndResetIfBad(m, d, d.qpos, kWarnBadQpos);
  WarnAndResetIfBad(m, d, d.qvel, kWarnBadQvel);
  PositionStage(m, d, Sensors::kCompute);
  VelocityStage(m, d, Sensors::kCompute);
}

void Step2Pipeline(const Model& m, Data& d) {
  CheckOptions(m.opt);
  AccelerationStage(m, d, Sensors::kCompute);
  RedoIfBadAcceleration(m, d);
  // RK4 needs the whole step; split stepping integrates it with Euler, as MuJoCo does.
  if (m.opt.integrator == kIntegratorImplicit || m.opt.integrator == kIntegratorImplicitFast) {
    ImplicitIntegrate(m, d);
  } else {
    Euler(m, d);
  }
}

}  // namespace

// ------------------------------------------------------------ the pipeline

void FwdPositionSmooth(const Model& m, Data& d) {
  KinematicsAndInertia(m, d);
  Transmission(m, d);
}

void FwdPosition(const Model& m, Data& d) {
  StageTimer timer(d, kTimerPosition);
  d.flg_energypos = false;
  KinematicsAndInertia(m, d);
  {
    StageTimer part(d, kTimerPosCollision);
    Collision(m, d);
    // Sleeping trees touched by awake ones wake, and meet each other: collide again.
    if (WakeOnContact(m, d)) {
      UpdateSleep(m, d);
      Collision(m, d);
    }
  }
  if (WakeOnEquality(m, d)) UpdateSleep(m, d);
  {
    StageTimer part(d, kTimerPosMake);
    MakeConstraint(m, d);
  }
  Transmission(m, d);
  StageTimer part(d, kTimerPosProject);
  ProjectConstraint(m, d);
}

void ForwardSkip(const Model& m, Data& d, Stage skip, Sensors sensors) {
  StageTimer timer(d, kTimerForward);
  CheckOptions(m.opt);
  if (skip < kStagePos) PositionStage(m, d, sensors);
  if (skip < kStageVel) VelocityStage(m, d, sensors);
  AccelerationStage(m, d, sensors);
}

// ------------------------------------------------------------ public entry points

void Forward(const Model& m, Data& d) {
  WithoutThrowing(m, d, [&] { ForwardSkip(m, d, kStageNone, Sensors::kCompute); });
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

}  // namespace simlab
