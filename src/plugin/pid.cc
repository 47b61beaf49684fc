// mujoco.pid, MuJoCo's first-party actuator plugin (plugin/actuator/pid.cc there): a PID
// controller on each of its actuators' length,
//
//   p = kp e + kd e' + ki I,   e = setpoint - l,   e' = setpoint' - l',   I = integral of e
//
// configured by kp, ki, kd, imax (a limit on the force ki I, so |I| <= imax / ki) and
// slewmax (the setpoint moves at most slewmax per second, from the second step on). Its
// states are the actuator's activations, in this order: I (when ki != 0), the previous
// setpoint (with slewmax), then the built-in dynamics' state (filter, filterexact or
// integrator, whose output is the setpoint). Each state moves as (target - act) / h, so
// that the engine's step lands on it. The setpoint without dynamics is ctrl clamped to
// ctrlrange. (MuJoCo's plugin reads ctrl, length and force at the actuator's index and
// finds its actuators among the first nu; it reads them here at the actuator's own
// ctrladr/outadr, which is the same for actuators of one control and one output.)
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "simlab/plugin.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

// The instance's gains and its actuators.
struct PidData : PluginInstanceData {
  double kp = 0, ki = 0, kd = 0;
  std::optional<double> integral_max;  // on I (imax / ki), with ki
  std::optional<double> slewmax;
  std::vector<int> actuators;
  std::unique_ptr<PluginInstanceData> Clone() const override {
    return std::make_unique<PidData>(*this);
  }
};

// A config number, or nothing when the key is not given; not a number is an error.
std::optional<double> Number(const Model& m, int instance, const char* key) {
  std::string text = PluginConfig(m, instance, key);
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  double value = std::strtod(text.c_str(), &end);
  while (end && (*end == ' ' || *end == '\t')) end++;
  if (end == text.c_str() || (end && *end) || errno == ERANGE) {
    throw Error("mujoco.pid instance " + std::to_string(instance) + ": config " + key + " = '" +
                text + "' is not a number");
  }
  return value;
}

// States the actuator must have for this configuration and its dynamics.
int ExpectedStates(const Model& m, const PidData& pid, int actuator) {
  int dyn = m.actuator_dyntype[actuator];
  bool filtered = dyn == kDynFilter || dyn == kDynFilterExact || dyn == kDynIntegrator;
  return (pid.ki != 0) + (pid.slewmax.has_value()) + filtered;
}

std::unique_ptr<PluginInstanceData> Init(const Model& m, Data&, int instance) {
  auto pid = std::make_unique<PidData>();
  pid->kp = Number(m, instance, "kp").value_or(0);
  pid->ki = Number(m, instance, "ki").value_or(0);
  pid->kd = Number(m, instance, "kd").value_or(0);
  std::optional<double> imax = Number(m, instance, "imax");
  if (imax && pid->ki != 0) pid->integral_max = *imax / pid->ki;
  pid->slewmax = Number(m, instance, "slewmax");
  std::string what = "mujoco.pid instance " + std::to_string(instance) + ": ";
  if (pid->integral_max && *pid->integral_max < 0) throw Error(what + "negative imax");
  if (pid->slewmax.value_or(0) < 0) throw Error(what + "slewmax must be non-negative");
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_plugin[i] == instance) pid->actuators.push_back(i);
  }
  if (pid->actuators.empty()) throw Error(what + "no actuator uses it");
  for (int i : pid->actuators) {
    int expected = ExpectedStates(m, *pid, i);
    if (m.actuator_actnum[i] != expected) {
      throw Error(what + "actuator " + std::to_string(i) + " has actdim " +
                  std::to_string(m.actuator_actnum[i]) + ", expected " + std::to_string(expected) +
                  ". Add actdim=\"" + std::to_string(expected) + "\" to the actuator plugin element");
    }
  }
  return pid;
}

// The integral and the previous setpoint held in the actuator's states.
struct PidState {
  double integral = 0, previous = 0;
  bool has_previous = false;
};

PidState StateOf(const Data& d, const PidData& pid, int adr) {
  PidState s;
  if (pid.ki != 0) s.integral = d.act[adr++];
  if (pid.slewmax) {
    s.previous = d.act[adr];
    s.has_previous = d.time > 0;
  }
  return s;
}

// The setpoint: ctrl (clamped to ctrlrange) or the dynamics' output, slew-limited.
double Setpoint(const Model& m, const Data& d, const PidData& pid, int i, const PidState& s,
                bool early) {
  double setpoint;
  if (m.actuator_dyntype[i] == kDynNone) {
    int u = m.actuator_ctrladr[i];
    setpoint = d.ctrl[u];
    if (m.actuator_ctrllimited[u]) {
      setpoint = std::clamp(setpoint, m.actuator_ctrlrange[2 * u], m.actuator_ctrlrange[2 * u + 1]);
    }
  } else {
    int last = m.actuator_actadr[i] + m.actuator_actnum[i] - 1;
    setpoint = early ? NextActivation(m, d, i, last, d.act_dot[last]) : d.act[last];
  }
  if (pid.slewmax && s.has_previous) {
    double step = *pid.slewmax * m.opt.timestep;
    setpoint = std::clamp(setpoint, s.previous - step, s.previous + step);
  }
  return setpoint;
}

// This step's integral of the error, within its limit.
double NextIntegral(const PidData& pid, const PidState& s, double error, double h) {
  double integral = s.integral + error * h;
  if (pid.integral_max) integral = std::clamp(integral, -*pid.integral_max, *pid.integral_max);
  return integral;
}

void ActDot(const Model& m, Data& d, int instance) {
  const auto& pid = static_cast<const PidData&>(*d.plugin_data[instance].data);
  double h = m.opt.timestep;
  for (int i : pid.actuators) {
    int k = m.actuator_actadr[i];
    PidState s = StateOf(d, pid, k);
    double setpoint = Setpoint(m, d, pid, i, s, false);
    double error = setpoint - d.actuator_length[m.actuator_outadr[i]];
    if (pid.ki != 0) {
      d.act_dot[k] = (NextIntegral(pid, s, error, h) - d.act[k]) / h;
      k++;
    }
    if (pid.slewmax) d.act_dot[k] = (setpoint - d.act[k]) / h;
  }
}

void Compute(const Model& m, Data& d, int instance, int) {
  const auto& pid = static_cast<const PidData&>(*d.plugin_data[instance].data);
  for (int i : pid.actuators) {
    int o = m.actuator_outadr[i], adr = m.actuator_actadr[i];
    PidState s = StateOf(d, pid, adr);
    double setpoint = Setpoint(m, d, pid, i, s, m.actuator_actearly[i]);
    double error = setpoint - d.actuator_length[o];
    double setpoint_rate = m.actuator_dyntype[i] == kDynNone
                               ? 0
                               : d.act_dot[adr + m.actuator_actnum[i] - 1];
    double error_rate = setpoint_rate - d.actuator_velocity[o];
    double integral = pid.ki != 0 ? NextIntegral(pid, s, error, m.opt.timestep) : 0;
    d.actuator_force[o] = pid.kp * error + pid.kd * error_rate + pid.ki * integral;
  }
}

}  // namespace

Plugin PidPlugin() {
  Plugin p;
  p.name = "mujoco.pid";
  p.capabilities = kPluginActuator;
  p.attributes = {"kp", "ki", "kd", "imax", "slewmax"};
  p.nstate = [](const Model&, int) { return 0; };
  p.init = Init;
  p.actuator_act_dot = ActDot;
  p.compute = Compute;
  return p;
}

}  // namespace simlab
