// Lesson 2.3 on simlab: actuator force laws, clamping, activation dynamics, coupling.
//
// INPUT    models/actuator_bench.xml (four hinges, one actuator each: motor, position,
//          velocity, filter); models/gantry_gripper.xml for section 4.
// PROCESS  (1) put every joint at a known angle and velocity, set the controls, run
//          Forward, and compare actuator_force with the law p = a u + b0 + b1 l + b2 l'
//          (with gear g, l = g q); (2) push a control past ctrlrange and a force past
//          forcerange; (3) step a filter actuator and compare its activation with the
//          exact exponential; (4) the gripper's tendon and equality coupling.
// OUTPUT   the lesson's tables, line for line, with the same numbers.
//
// Run: build/l2_3_actuators
//
// The text is formatted as the lesson's Python prints it (f-string widths, numpy's
// array2string, Python's float repr), so the output can be compared with the lesson.
// Tests include this file with SIMLAB_L2_3_NO_MAIN defined and call RunLesson.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <ostream>
#include <string>
#include <vector>

#include "simlab/named.h"
#include "simlab/simlab.h"

namespace l2_3 {

// ---------------------------------------------------------------- Python-style text

// printf into a std::string.
template <typename... Args>
std::string Format(const char* format, Args... args) {
  char buffer[256];
  std::snprintf(buffer, sizeof(buffer), format, args...);
  return buffer;
}

// Python's repr of a float: the shortest text that reads back to the same double,
// positional for exponents -4..15 (with ".0" when it is a whole number), else
// scientific ("1e+16").
inline std::string PythonFloat(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  // Fewest significant digits that round-trip.
  int digits = 1;
  while (digits < 17 && std::strtod(Format("%.*e", digits - 1, x).c_str(), nullptr) != x) {
    digits++;
  }
  std::string sci = Format("%.*e", digits - 1, x);
  int exponent = std::atoi(sci.c_str() + sci.find('e') + 1);
  if (exponent < -4 || exponent >= 16) return sci;
  // Positional form with exactly those digits.
  std::string fixed = Format("%.*f", std::max(digits - 1 - exponent, 0), x);
  if (fixed.find('.') == std::string::npos) fixed += ".0";
  return fixed;
}

// One number as numpy writes it with `precision` decimals at most: trailing zeros
// dropped, the decimal point kept ("0.", "-10.", "0.125").
inline std::string NumpyNumber(double x, int precision, bool scientific) {
  std::string text = Format(scientific ? "%.*e" : "%.*f", precision, x);
  size_t end = scientific ? text.find('e') : text.size();
  size_t last = text.find_last_not_of('0', end - 1);
  return text.substr(0, last + 1) + text.substr(end);
}

// numpy.array2string(values, precision=p) for a short 1-D float array: numbers
// aligned on the decimal point (integer parts padded left, fractions padded right),
// separated by one space. Scientific notation when numpy would choose it.
inline std::string NumpyArray(const double* values, int n, int precision) {
  // numpy's choice of notation, from the nonzero magnitudes.
  double max_abs = 0, min_abs = INFINITY;
  for (int i = 0; i < n; i++) {
    double a = std::abs(values[i]);
    if (a == 0) continue;
    max_abs = std::max(max_abs, a);
    min_abs = std::min(min_abs, a);
  }
  bool scientific = max_abs >= 1e8 || (max_abs > 0 && (min_abs < 1e-4 || max_abs / min_abs > 1e3));

  // Split every number at its decimal point and find the widest sides.
  std::vector<std::string> left(n), right(n);
  size_t pad_left = 0, pad_right = 0;
  for (int i = 0; i < n; i++) {
    std::string text = NumpyNumber(values[i], precision, scientific);
    size_t dot = text.find('.');
    left[i] = text.substr(0, dot);
    right[i] = text.substr(dot);
    pad_left = std::max(pad_left, left[i].size());
    pad_right = std::max(pad_right, right[i].size());
  }

  // Pad and join.
  std::string out = "[";
  for (int i = 0; i < n; i++) {
    if (i > 0) out += " ";
    out += std::string(pad_left - left[i].size(), ' ') + left[i];
    out += right[i] + std::string(pad_right - right[i].size(), ' ');
  }
  return out + "]";
}

// ---------------------------------------------------------------- the sections

// The bench, freshly loaded, with its data at the default state.
struct Bench {
  simlab::Model model;
  simlab::Data data;
  explicit Bench(const std::string& models_dir)
      : model(simlab::LoadXml(models_dir + "/actuator_bench.xml")), data(simlab::MakeData(model)) {}
};

// Section 1: the measured force of each actuator beside the documented law.
inline void ForceLaws(const std::string& models_dir, std::ostream& out) {
  Bench bench(models_dir);
  const simlab::Model& m = bench.model;
  simlab::Data& d = bench.data;

  // Every joint at q = 0.3 rad, qdot = -0.5 rad/s; one control per actuator.
  const double q = 0.3, qd = -0.5;
  const double ctrl[] = {0.4, 0.5, 1.0, 0.8};
  for (int i = 0; i < m.nq; i++) d.qpos[i] = q;
  for (int i = 0; i < m.nv; i++) d.qvel[i] = qd;
  for (int i = 0; i < m.nu; i++) d.ctrl[i] = ctrl[i];
  simlab::Forward(m, d);

  // The law for each actuator, written from its documented parameters.
  const double expected[] = {
      0.4,                          // motor, gain 1: force = ctrl (joint torque gear * force)
      10 * (0.5 - q) - 1 * qd,      // position: kp (ctrl - q) - kv qdot
      3 * (1.0 - qd),               // velocity: kv (ctrl - qdot)
      5 * d.act[0],                 // filter: gain * activation (which starts at 0)
  };

  // The table.
  out << Format(" %-9s%11s%22s%16s%10s%15s\n", "actuator", "gainprm[0]", "biasprm[0:3]",
                "actuator_force", "formula", "qfrc_actuator");
  for (int i = 0; i < m.nu; i++) {
    std::string bias = NumpyArray(&m.actuator_biasprm[simlab::kNBias * i], 3, 3);
    out << Format(" %-9s%11.3g%22s%16.4f%10.4f%15.4f\n", m.actuator_names[i].c_str(),
                  m.actuator_gainprm[simlab::kNGain * i], bias.c_str(), d.actuator_force[i],
                  expected[i], d.qfrc_actuator[i]);
  }
  out << " (the motor's actuator_force is in actuator space, 0.4; "
         "the joint torque is gear * 0.4 = 0.8)\n";
}

// Section 2: a control beyond ctrlrange and a force beyond forcerange.
inline void Clamping(const std::string& models_dir, std::ostream& out) {
  Bench bench(models_dir);
  const simlab::Model& m = bench.model;
  simlab::Data& d = bench.data;

  // Motor asked for 5 (range [-1, 1]); position target 2 rad from q = 0: kp * 2 = 20 > 3.
  d.ctrl[0] = 5.0;
  d.ctrl[1] = 2.0;
  simlab::Forward(m, d);
  out << Format(" motor ctrl 5.0 with ctrlrange [-1, 1] -> actuator_force %.3f ",
                d.actuator_force[0])
      << "(data.ctrl still reads " << PythonFloat(d.ctrl[0]) << ")\n";
  out << Format(" position target 2 rad, kp 10, forcerange [-3, 3] -> actuator_force %.3f\n",
                d.actuator_force[1]);
}

// Section 3: the filter's Euler activation against 1 - exp(-t/tau).
inline void Activation(const std::string& models_dir, std::ostream& out) {
  Bench bench(models_dir);
  const simlab::Model& m = bench.model;
  simlab::Data& d = bench.data;

  // Control stepped to 1 at t = 0; report at four times.
  d.ctrl[3] = 1.0;
  double tau = m.actuator_dynprm[simlab::kNDyn * 3];
  for (double t_mark : {0.05, 0.1, 0.2, 0.5}) {
    while (d.time < t_mark - 1e-9) simlab::Step(m, d);
    out << Format(" t = %.2f s: act = %.4f, 1 - exp(-t/tau) = %.4f\n", d.time, d.act[0],
                  1 - std::exp(-d.time / tau));
  }
}

// Section 4: from the gantry gripper's home keyframe, command a grip half-opening of
// 0.03 m and step 1000 times. The tendon drives the average of the fingers, the joint
// equality keeps them equal: both settle at 0.03 m, equal to five decimals.
inline void Coupling(const std::string& models_dir, std::ostream& out) {
  simlab::Model m = simlab::LoadXml(models_dir + "/gantry_gripper.xml");
  simlab::Data d = simlab::MakeData(m);
  simlab::ResetDataKeyframe(m, d, 0);
  simlab::DataObject(m, d, simlab::kObjActuator, "gripper/grip")["ctrl"][0] = 0.03;
  for (int i = 0; i < 1000; i++) simlab::Step(m, d);
  // Named access, as MuJoCo's data.joint("gripper/finger_left").qpos[0].
  auto joint_qpos = [&](const char* name) {
    return simlab::DataObject(m, d, simlab::kObjJoint, name)["qpos"][0];
  };
  out << Format(" grip command 0.03 m: finger_left %.5f m, finger_right %.5f m, "
                "tendon length %.5f m\n",
                joint_qpos("gripper/finger_left"), joint_qpos("gripper/finger_right"),
                d.ten_length[0]);
}

// The whole program, section by section.
inline void RunLesson(const std::string& models_dir, std::ostream& out) {
  out << "force laws at q = 0.3 rad, qdot = -0.5 rad/s:\n";
  ForceLaws(models_dir, out);
  out << "clamping:\n";
  Clamping(models_dir, out);
  out << "filter activation, time constant 0.1 s, control stepped to 1 at t = 0:\n";
  Activation(models_dir, out);
  out << "gripper coupling (tendon + joint equality):\n";
  Coupling(models_dir, out);
}

}  // namespace l2_3

#ifndef SIMLAB_L2_3_NO_MAIN
int main() {
  try {
    l2_3::RunLesson(SIMLAB_MODELS_DIR, std::cout);
  } catch (const simlab::Error& e) {
    std::cerr << "l2_3_actuators: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
#endif
