// The setpoint helpers the pid and the DC motor's controller share (MuJoCo 3.12): a slew
// limit on the setpoint and an integral of the error that stops growing past its limit.
#ifndef SIMLAB_ENGINE_SERVO_H_
#define SIMLAB_ENGINE_SERVO_H_

#include <algorithm>

namespace simlab {

// The setpoint moved from `previous` toward `target` by at most slewmax h; its rate,
// (limited - previous) / h, is the slew state's act_dot.
inline double SlewLimit(double target, double previous, double slewmax, double h, double* rate) {
  double step = slewmax * h;
  double limited = std::clamp(target, previous - step, previous + step);
  *rate = (limited - previous) / h;
  return limited;
}

// The integral's rate: the error, except that past +-limit (when limit > 0) it may only
// bring the integral back (a stop, not a clamp: the integral may pass the limit by a step).
inline double IntegralRate(double error, double integral, double limit) {
  if (limit > 0) {
    if (integral >= limit) return std::min(error, 0.0);
    if (integral <= -limit) return std::max(error, 0.0);
  }
  return error;
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_SERVO_H_
