// Actuation (MuJoCo mj_fwdActuation): activation dynamics and the one force law
//
//   p = gain * (ctrl or act) + bias,   gain = a0 + a1 l + a2 l',  bias = b0 + b1 l + b2 l'
//
// with ctrl clamped to ctrlrange (in a copy: data.ctrl is never rewritten), act_dot from
// the dynamics type, p clamped to forcerange, then qfrc_actuator = moment^T p clamped
// to each joint's actuatorfrcrange. Forces on a tendon are first scaled so their total
// respects the tendon's actuatorfrcrange. Muscles: see muscle.cc. A pid (MuJoCo 3.12)
// reads several controls (its setpoints) and has its own law (PidForce); so does the DC
// motor (dcmotor.cc).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/servo.h"
#include "engine/stack.h"
#include "engine/sleep.h"

namespace simlab {

namespace {

bool ActuatorDisabled(const Model& m, int i) {
  int group = m.actuator_group[i];
  return group >= 0 && group < 31 && (m.opt.disableactuator & (1 << group));
}

// The controls as the force law sees them (delayed ones from their history): clamped
// per control entry, or all zero if any is bad.
void EffectiveControls(const Model& m, Data& d, double* ctrl) {
  std::copy(d.ctrl.begin(), d.ctrl.end(), ctrl);
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_delay[i] != 0) ctrl[m.actuator_ctrladr[i]] = ActuatorInput(m, d, i);
  }
  for (int c = 0; c < m.nu; c++) {
    if (!(m.opt.disableflags & kDisableClampctrl) && m.actuator_ctrllimited[c]) {
      ctrl[c] = std::clamp(ctrl[c], m.actuator_ctrlrange[2 * c], m.actuator_ctrlrange[2 * c + 1]);
    }
  }
  for (int c = 0; c < m.nu; c++) {
    if (std::isnan(ctrl[c]) || std::abs(ctrl[c]) > kMaxVal) {
      RaiseWarning(d, kWarnBadCtrl, c);
      std::fill(ctrl, ctrl + m.nu, 0.0);
      return;
    }
  }
}

// act_dot of actuator i from its dynamics type and its controls `u` (an integrator
// integrates each of them into its last states; the others read one).
void ActivationRate(const Model& m, Data& d, int i, const double* u) {
  int adr = m.actuator_actadr[i] + m.actuator_actnum[i] - 1;
  double ctrl = u[0];
  const double* prm = &m.actuator_dynprm[kNDyn * i];
  switch (m.actuator_dyntype[i]) {
    case kDynIntegrator: {
      int n = m.actuator_ctrlnum[i];
      for (int k = 0; k < n; k++) d.act_dot[adr - n + 1 + k] = u[k];
      break;
    }
    case kDynFilter:
    case kDynFilterExact: d.act_dot[adr] = (ctrl - d.act[adr]) / std::max(kMinVal, prm[0]); break;
    case kDynMuscle: d.act_dot[adr] = MuscleDynamics(ctrl, d.act[adr], prm); break;
    default: d.act_dot[adr] = 0;  // user dynamics are rejected by the loader
  }
}

// Gain or bias of the affine form prm[0] + prm[1] l + prm[2] l'.
double Affine(const double* prm, double length, double velocity) {
  return prm[0] + prm[1] * length + prm[2] * velocity;
}

// ---------------------------------------------------------------- pid

// The period of a pid's setpoints on a rotational transmission (a ball joint, or a site
// and refsite turning about the gear's axis): 2 pi |gear axis|, else 0 (no wrapping).
double WrapPeriod(const Model& m, int i) {
  const double* gear = &m.actuator_gear[6 * m.actuator_outadr[i]];
  int type = m.actuator_trntype[i], id = m.actuator_trnid[2 * i];
  const double* axis = nullptr;
  if (type == kTrnSite && m.actuator_trnid[2 * i + 1] >= 0 && gear[0] == 0 && gear[1] == 0 &&
      gear[2] == 0) {
    axis = gear + 3;
  } else if ((type == kTrnJoint || type == kTrnJointInParent) && m.jnt_type[id] == kJointBall) {
    axis = gear;
  }
  if (!axis) return 0;
  return 2 * std::numbers::pi * std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
}

// The representative of setpoint u nearest to ref, on a circle of the period.
double WrapSetpoint(double u, double ref, double period) {
  return u - period * std::round((u - ref) / period);
}

// A pid's setpoints [pos, vel, ff] from its packed inputs (absent ones zero).
void PidInputs(const Model& m, int i, const double* ctrl, double setpoint[3]) {
  int spec = m.actuator_ctrlspec[i];
  const double* u = ctrl + m.actuator_ctrladr[i];
  int k = 0;
  for (int bit = 0; bit < 3; bit++) setpoint[bit] = (spec & (1 << bit)) ? u[k++] : 0;
}

// act_dot of a stateful pid: the slew-limited position setpoint (written back into the
// local ctrl, which the force then reads), then the integral of the position error,
// which stops growing past imax.
void PidActivation(const Model& m, Data& d, int i, double* ctrl) {
  double h = m.opt.timestep, period = WrapPeriod(m, i);
  double imax = m.actuator_dynprm[kNDyn * i], slewmax = m.actuator_dynprm[kNDyn * i + 1];
  double ki = m.actuator_gainprm[kNGain * i];
  int a = m.actuator_actadr[i];
  double& u = ctrl[m.actuator_ctrladr[i]];
  if (slewmax > 0) {
    double previous = d.act[a];
    double target = period > 0 ? WrapSetpoint(u, previous, period) : u;
    u = SlewLimit(target, previous, slewmax, h, &d.act_dot[a]);
    a++;
  }
  if (ki > 0) {
    double error = u - d.actuator_length[m.actuator_outadr[i]];
    if (period > 0) error -= period * std::round(error / period);
    d.act_dot[a] = IntegralRate(error, d.act[a], imax);
  }
}

// A pid's force before clamping: kp qref + kv vref + ff (+ ki times the integral), then
// the servo's affine bias -kp l - kv l' (summed in MuJoCo's order).
double PidForce(const Model& m, const Data& d, int i, const double* ctrl) {
  int o = m.actuator_outadr[i];
  double l = d.actuator_length[o], ldot = d.actuator_velocity[o];
  const double* prm = &m.actuator_biasprm[kNBias * i];
  double setpoint[3];
  PidInputs(m, i, ctrl, setpoint);
  double period = WrapPeriod(m, i);
  if (period > 0) setpoint[0] = WrapSetpoint(setpoint[0], l, period);
  double force = -prm[1] * setpoint[0] - prm[2] * setpoint[1] + setpoint[2];
  double ki = m.actuator_gainprm[kNGain * i];
  if (m.actuator_actnum[i] > 0 && ki > 0) {
    int last = m.actuator_actadr[i] + m.actuator_actnum[i] - 1;
    double z = m.actuator_actearly[i] ? NextActivation(m, d, i, last, d.act_dot[last]) : d.act[last];
    force += ki * z;
  }
  return force + Affine(prm, l, ldot);
}

// ---------------------------------------------------------------- the other types

// Scalar force of actuator i (its one output, o) before clamping.
double ActuatorForce(const Model& m, const Data& d, int i, double ctrl) {
  int o = m.actuator_outadr[i];
  double l = d.actuator_length[o], ldot = d.actuator_velocity[o];
  const double* gainprm = &m.actuator_gainprm[kNGain * i];
  const double* biasprm = &m.actuator_biasprm[kNBias * i];
  const double* lengthrange = &m.actuator_lengthrange[2 * o];
  double gain = gainprm[0];
  if (m.actuator_gaintype[i] == kGainAffine) gain = Affine(gainprm, l, ldot);
  if (m.actuator_gaintype[i] == kGainMuscle) {
    gain = MuscleGain(l, ldot, lengthrange, m.actuator_acc0[o], gainprm);
  }
  double input = ctrl;
  if (m.actuator_actadr[i] >= 0) {
    int adr = m.actuator_actadr[i] + m.actuator_actnum[i] - 1;
    input = m.actuator_actearly[i] ? NextActivation(m, d, i, adr, d.act_dot[adr]) : d.act[adr];
  }
  double bias = 0;
  if (m.actuator_biastype[i] == kBiasAffine) bias = Affine(biasprm, l, ldot);
  if (m.actuator_biastype[i] == kBiasMuscle) {
    bias = MuscleBias(l, lengthrange, m.actuator_acc0[o], biasprm);
  }
  return gain * input + bias;
}

// Tendon-level clamp: when the actuators on a tendon with actuatorfrcrange together
// push beyond the range, each is scaled by range / total.
void ClampTendonForces(const Model& m, Data& d) {
  bool any = false;
  for (int i = 0; i < m.nactuator && !any; i++) {
    any = m.actuator_trntype[i] == kTrnTendon && m.tendon_actfrclimited[m.actuator_trnid[2 * i]];
  }
  if (!any) return;
  StackFrame frame(d);
  double* total = frame.Alloc(m.ntendon);
  // (a tendon transmission has one output)
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_trntype[i] != kTrnTendon) continue;
    total[m.actuator_trnid[2 * i]] += d.actuator_force[m.actuator_outadr[i]];
  }
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_trntype[i] != kTrnTendon) continue;
    int t = m.actuator_trnid[2 * i];
    if (!m.tendon_actfrclimited[t] || total[t] == 0) continue;
    const double* range = &m.tendon_actfrcrange[2 * t];
    double& force = d.actuator_force[m.actuator_outadr[i]];
    if (total[t] < range[0]) {
      force *= range[0] / total[t];
    } else if (total[t] > range[1]) {
      force *= range[1] / total[t];
    }
  }
}

}  // namespace

double NextActivation(const Model& m, const Data& d, int i, int act_adr, double act_dot) {
  if (m.actuator_dyntype[i] == kDynDcmotor) return DcmotorNextActivation(m, d, i, act_adr, act_dot);
  double act = d.act[act_adr];
  // Exact filter: act moves toward ctrl by 1 - exp(-h/tau) of the gap; else Euler.
  if (m.actuator_dyntype[i] == kDynFilterExact) {
    double tau = std::max(kMinVal, m.actuator_dynprm[kNDyn * i]);
    act += act_dot * tau * (1 - std::exp(-m.opt.timestep / tau));
  } else {
    act += act_dot * m.opt.timestep;
  }
  if (m.actuator_actlimited[i]) {
    act = std::clamp(act, m.actuator_actrange[2 * i], m.actuator_actrange[2 * i + 1]);
  }
  return act;
}

void Actuation(const Model& m, Data& d) {
  std::fill(d.actuator_force.begin(), d.actuator_force.end(), 0.0);
  std::fill(d.qfrc_actuator.begin(), d.qfrc_actuator.end(), 0.0);
  if (m.nactuator == 0 || (m.opt.disableflags & kDisableActuation)) return;

  StackFrame frame(d);
  double* ctrl = frame.Alloc(m.nu);
  EffectiveControls(m, d, ctrl);

  // Activation dynamics, then forces (disabled actuators stay at zero; sleeping ones
  // too, and keep their act_dot).
  bool any_asleep = AnyAsleep(m, d);
  auto asleep = [&](int i) { return any_asleep && ElementSleepState(m, d, kObjActuator, i) == kAsleep; };
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_actadr[i] < 0 || asleep(i)) continue;
    // (a plugin's own states wait for its act_dot; the built-in dynamics has the last)
    if (m.actuator_plugin[i] >= 0) {
      std::fill_n(&d.act_dot[m.actuator_actadr[i]], m.actuator_actnum[i], 0.0);
      if (m.actuator_dyntype[i] == kDynNone) continue;
    }
    if (m.actuator_dyntype[i] == kDynPid) {
      PidActivation(m, d, i, ctrl);
    } else if (m.actuator_dyntype[i] == kDynDcmotor) {
      DcmotorActivation(m, d, i, ctrl);
    } else {
      ActivationRate(m, d, i, ctrl + m.actuator_ctrladr[i]);
    }
  }
  PluginActDot(m, d);
  for (int i = 0; i < m.nactuator; i++) {
    if (ActuatorDisabled(m, i) || m.actuator_plugin[i] >= 0 || asleep(i)) continue;
    if (m.actuator_gaintype[i] == kGainSo3) {
      So3Force(m, d, i, ctrl, d.actuator_force.data());
      continue;
    }
    double& force = d.actuator_force[m.actuator_outadr[i]];
    switch (m.actuator_gaintype[i]) {
      case kGainPid: force = PidForce(m, d, i, ctrl); break;
      case kGainDcmotor: force = DcmotorForce(m, d, i, ctrl); break;
      default: force = ActuatorForce(m, d, i, ctrl[m.actuator_ctrladr[i]]);
    }
  }

  PluginActuatorForces(m, d);

  // Clamps: tendon totals, then each output (of disabled actuators too) to its
  // actuator's forcerange.
  ClampTendonForces(m, d);
  for (int i = 0; i < m.nactuator; i++) {
    if (!m.actuator_forcelimited[i]) continue;
    if (m.actuator_gaintype[i] == kGainSo3) {
      So3ClampForce(m, d, i);
      continue;
    }
    for (int o = m.actuator_outadr[i]; o < m.actuator_outadr[i] + m.actuator_outnum[i]; o++) {
      d.actuator_force[o] = std::clamp(d.actuator_force[o], m.actuator_forcerange[2 * i],
                                       m.actuator_forcerange[2 * i + 1]);
    }
  }
  // A DC motor's cogging and friction are mechanical: past the electrical clamp.
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_biastype[i] != kBiasDcmotor || ActuatorDisabled(m, i) || m.actuator_plugin[i] >= 0 ||
        asleep(i)) {
      continue;
    }
    DcmotorMechanics(m, d, i);
  }

  // Joint space, clamped per joint to actuatorfrcrange.
  for (int o = 0; o < m.nout; o++) {
    const double* moment = RowOf(d.actuator_moment, o, m.nv);
    const int* cols = RowOf(d.moment_colind, o, m.nv);
    for (int k = 0; k < d.moment_rownnz[o]; k++) {
      d.qfrc_actuator[cols[k]] += moment[cols[k]] * d.actuator_force[o];
    }
  }
  AddActuatorGravcomp(m, d);
  for (int j = 0; j < m.njnt; j++) {
    if (!m.jnt_actfrclimited[j]) continue;
    int n = m.jnt_type[j] == kJointFree ? 6 : m.jnt_type[j] == kJointBall ? 3 : 1;
    for (int t = 0; t < n; t++) {
      double& q = d.qfrc_actuator[m.jnt_dofadr[j] + t];
      q = std::clamp(q, m.jnt_actfrcrange[2 * j], m.jnt_actfrcrange[2 * j + 1]);
    }
  }
}

}  // namespace simlab
