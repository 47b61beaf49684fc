// `simlab explain MODEL.xml`
//
// Reads each compiled actuator back as the one law of MuJoCo's actuator model,
//
//   p = a u + b0 + b1 l + b2 l'
//
// a from gaintype/gainprm, b from biastype/biasprm, u = ctrl or the activation w
// (whose dynamics come from dyntype/dynprm), l and l' the length and velocity at the
// transmission (l = gear * q for a joint), then the clamps: ctrlrange on u, actrange on
// w, forcerange on p, actuatorfrcrange on the joint or tendon force. The element that
// wrote an actuator is not stored in the model, so the shortcut it "reads as" is
// recognized from the parameters, as the lesson's table relates them.
#include "explain.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "simlab/plugin.h"
#include "simlab/simlab.h"

namespace simlab::apps {

namespace {

// ---------------------------------------------------------------- number text

// A number in the shortest readable form ("10", "-0.5", "1e-05").
std::string Num(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%g", x == 0 ? 0.0 : x);  // no "-0"
  return buffer;
}

std::string Range(const double* range) { return "[" + Num(range[0]) + ", " + Num(range[1]) + "]"; }

std::string Quoted(const std::string& name) { return name.empty() ? "(unnamed)" : "\"" + name + "\""; }

// "c x" as a term of a sum: " + 3 l", " - 10 l"; empty for a zero coefficient.
std::string Term(double c, const std::string& symbol) {
  if (c == 0) return "";
  return (c < 0 ? " - " : " + ") + Num(std::abs(c)) + (symbol.empty() ? "" : " " + symbol);
}

// One labelled line of a block.
std::string Line(const std::string& label, const std::string& text) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "  %-14s", label.c_str());
  return buffer + text + "\n";
}

const double* Gain(const Model& m, int i) { return &m.actuator_gainprm[kNGain * i]; }
const double* Bias(const Model& m, int i) { return &m.actuator_biasprm[kNBias * i]; }
const double* Dyn(const Model& m, int i) { return &m.actuator_dynprm[kNDyn * i]; }

bool HasActivation(const Model& m, int i) { return m.actuator_actadr[i] >= 0; }

// ---------------------------------------------------------------- which shortcut

// The name of a dynamics type as MJCF writes it.
std::string DynName(int dyn) {
  switch (dyn) {
    case kDynIntegrator: return "integrator";
    case kDynFilter: return "filter";
    case kDynFilterExact: return "filterexact";
    case kDynMuscle: return "muscle";
    case kDynDcmotor: return "dcmotor";
    case kDynPid: return "pid";
    default: return "user";
  }
}

// No shortcut has these parameters: a <general>, named with its dynamics.
std::string GeneralName(int dyn) {
  return dyn == kDynNone ? "general" : "general with " + DynName(dyn) + " dynamics";
}

// Shortcuts whose bias is a PD servo on the length: b = 0, -kp, -kv.
std::string ServoShortcut(const Model& m, int i) {
  const double *g = Gain(m, i), *b = Bias(m, i);
  std::string gains = "kp " + Num(g[0]) + ", kv " + Num(-b[2]);
  switch (m.actuator_dyntype[i]) {
    case kDynNone: return "position (" + gains + ")";
    case kDynFilterExact: return "position with timeconst " + Num(Dyn(m, i)[0]) + " (" + gains + ")";
    case kDynIntegrator: return "intvelocity (" + gains + ")";
    default: return "general";
  }
}

// The names of a pid's or dcmotor's inputs in ctrl order (of pos vel ff voltage).
std::vector<std::string> InputNames(const Model& m, int i) {
  std::vector<std::string> names;
  if (m.actuator_ctrlspec[i] == kInputNone) return names;
  for (auto [bit, name] : {std::pair{kInputPos, "pos"}, std::pair{kInputVel, "vel"},
                           std::pair{kInputFf, "ff"}, std::pair{kInputVoltage, "voltage"}}) {
    if (m.actuator_ctrlspec[i] & bit) names.push_back(name);
  }
  return names;
}

// "pos vel", or "none".
std::string InputList(const Model& m, int i) {
  std::string list;
  for (const std::string& name : InputNames(m, i)) list += (list.empty() ? "" : " ") + name;
  return list.empty() ? "none" : list;
}

// dcmotor: its constants and the features in use.
std::string DcmotorShortcut(const Model& m, int i) {
  const double *g = Gain(m, i), *p = Dyn(m, i), *b = Bias(m, i);
  std::string text = "dcmotor (K " + Num(g[1]) + ", R " + Num(g[0]);
  if (p[0] > 0) text += ", te " + Num(p[0]) + " s";
  if (g[4] != 0 || g[5] != 0 || g[6] != 0) {
    text += ", controller kp " + Num(g[4]) + " ki " + Num(g[5]) + " kd " + Num(g[6]);
  }
  if (p[2] > 0) text += ", thermal";
  if (p[5] > 0) text += ", LuGre friction";
  if (b[0] != 0) text += ", cogging";
  return text + "; inputs " + InputList(m, i) + ")";
}

// pid: its gains and what it integrates or limits.
std::string PidShortcut(const Model& m, int i) {
  const double *g = Gain(m, i), *b = Bias(m, i), *p = Dyn(m, i);
  std::string text = "pid (kp " + Num(-b[1]) + ", kv " + Num(-b[2]);
  if (g[0] > 0) text += ", ki " + Num(g[0]) + (p[0] > 0 ? ", imax " + Num(p[0]) : "");
  if (p[1] > 0) text += ", slewmax " + Num(p[1]);
  return text + "; inputs " + InputList(m, i) + ")";
}

// The shortcut element these parameters are an instance of, or "general".
std::string ReadsAs(const Model& m, int i) {
  if (m.actuator_plugin[i] >= 0) return "plugin " + Quoted(PluginAt(m.plugin[m.actuator_plugin[i]]).name);
  const double *g = Gain(m, i), *b = Bias(m, i);
  int dyn = m.actuator_dyntype[i], gain = m.actuator_gaintype[i], bias = m.actuator_biastype[i];
  if (gain == kGainMuscle) return "muscle";
  if (gain == kGainPid) return PidShortcut(m, i);
  if (gain == kGainDcmotor) return DcmotorShortcut(m, i);
  if (gain == kGainSo3) {
    std::string kind = dyn == kDynIntegrator ? "general so3 integrator" : "orientation";
    return kind + " (kp " + Num(g[0]) + ", kv " + Num(-b[2]) + "; input " +
           (m.actuator_ctrlspec[i] == kChartQuat ? "quat" : "expmap") + ")";
  }
  if (m.actuator_trntype[i] == kTrnBody) return "adhesion (gain " + Num(g[0]) + ")";
  if (gain == kGainAffine && bias == kBiasNone && dyn == kDynNone && g[0] == 0 && g[1] == 0) {
    return "damper (kv " + Num(-g[2]) + ")";
  }
  if (gain != kGainFixed) return GeneralName(dyn);
  if (bias == kBiasNone && dyn == kDynNone && g[0] == 1) return "motor";
  if (bias == kBiasAffine && b[0] == 0 && b[1] == -g[0] && g[0] != 0) return ServoShortcut(m, i);
  if (bias == kBiasAffine && dyn == kDynNone && b[0] == 0 && b[1] == 0 && b[2] == -g[0]) {
    return "velocity (kv " + Num(g[0]) + ")";
  }
  if (bias == kBiasAffine && dyn == kDynFilter) return "cylinder, or the general it stands for";
  return GeneralName(dyn);
}

// ---------------------------------------------------------------- the law's terms

// The gain a: fixed, affine in l and l', or the muscle curves.
std::string GainText(const Model& m, int i) {
  const double* g = Gain(m, i);
  switch (m.actuator_gaintype[i]) {
    case kGainFixed: return "fixed: a = gainprm[0] = " + Num(g[0]);
    case kGainAffine:
      return "affine: a = " + Num(g[0]) + Term(g[1], "l") + Term(g[2], "l'") +
             "  (gainprm[0:3])";
    case kGainMuscle:
      return "muscle: a = -force * FL(l) * FV(l'), force " + Num(g[2]) + ", scale " + Num(g[3]) +
             ", lengths " + Num(g[4]) + ".." + Num(g[5]) + ", vmax " + Num(g[6]) + ", fvmax " +
             Num(g[8]);
    case kGainSo3:
      return "so3: a u = kp log(q(l)^-1 q_target), the rotation from where it is to the "
             "target, kp = " + Num(g[0]);
    case kGainDcmotor:
      return Dyn(m, i)[0] > 0 ? "dcmotor: a = K = " + Num(g[1]) + " on the current w"
                              : "dcmotor: a = K / R = " + Num(g[1]) + " / " + Num(g[0]) +
                                    " on the voltage (R rises with temperature)";
    case kGainPid:
      return "pid: a u = kp qref + kv vref + ff" +
             (g[0] > 0 ? " + ki w (ki = gainprm[0] = " + Num(g[0]) + ")" : std::string()) +
             ", kp and kv from biasprm";
    default: return "user: computed by a callback";
  }
}

// True when any of biasprm[0:3] is nonzero.
bool BiasprmSet(const Model& m, int i) {
  const double* b = Bias(m, i);
  return b[0] != 0 || b[1] != 0 || b[2] != 0;
}

// The bias b0 + b1 l + b2 l', stating plainly when biasprm is present but unused.
std::string BiasText(const Model& m, int i) {
  const double* b = Bias(m, i);
  switch (m.actuator_biastype[i]) {
    case kBiasNone:
      if (!BiasprmSet(m, i)) return "none: b0 = b1 = b2 = 0";
      return "none: biasprm [" + Num(b[0]) + " " + Num(b[1]) + " " + Num(b[2]) +
             "] ignored (compiled into the model, never used: biastype is none,\n" +
             std::string(16, ' ') +
             "the default of <general>; write biastype=\"affine\" to apply it)";
    case kBiasAffine:
      return "affine: b0 = " + Num(b[0]) + ", b1 = " + Num(b[1]) + ", b2 = " + Num(b[2]);
    case kBiasMuscle: return "muscle: passive force of the muscle, fpmax " + Num(b[7]);
    case kBiasSo3: return "so3: b = b0 + b2 l' on each output, b2 = " + Num(b[2]);
    case kBiasDcmotor:
      return std::string(Dyn(m, i)[0] > 0 ? "dcmotor: back-EMF acts through the current"
                                          : "dcmotor: back-EMF b = -a K l'") +
             "; cogging and LuGre friction are added after forcerange";
    default: return "user: computed by a callback";
  }
}

// A pid's law with its numbers and only the setpoints it has: "p = 10 (qref - l) - 2 l'".
std::string PidLawText(const Model& m, int i) {
  const double *b = Bias(m, i), *g = Gain(m, i);
  int spec = m.actuator_ctrlspec[i];
  double kp = -b[1], kv = -b[2];
  std::string law;
  auto add = [&law](const std::string& term) { law += (law.empty() ? "" : " + ") + term; };
  if (spec & kInputPos) add(Num(kp) + " (qref - l)");
  if (spec & kInputVel) add(Num(kv) + " (vref - l')");
  if (spec & kInputFf) add("ff");
  if (!(spec & kInputPos) && kp != 0) law += Term(-kp, "l");
  if (!(spec & kInputVel) && kv != 0) law += Term(-kv, "l'");
  if (g[0] > 0) law += Term(g[0], "w");
  if (b[0] != 0) law += Term(b[0], "");
  return "p = " + law;
}

// The law with this actuator's numbers: "p = 10 u - 10 l - 1 l'".
std::string LawText(const Model& m, int i) {
  std::string law = "p = ";
  std::string input = HasActivation(m, i) ? "w" : "u";
  if (m.actuator_gaintype[i] == kGainPid) return PidLawText(m, i);
  if (m.actuator_gaintype[i] == kGainSo3) {
    return "p = " + Num(Gain(m, i)[0]) + " log(q(l)^-1 q_target)" + Term(Bias(m, i)[2], "l'") +
           "  (3 outputs)";
  }
  if (m.actuator_gaintype[i] == kGainDcmotor) {
    return Dyn(m, i)[0] > 0 ? "p = K i = " + Num(Gain(m, i)[1]) + " w  (w: the current)"
                            : "p = K / R (V - K l') with K " + Num(Gain(m, i)[1]) + ", R " +
                                  Num(Gain(m, i)[0]);
  }
  if (m.actuator_gaintype[i] == kGainFixed) {
    law += Num(Gain(m, i)[0]) + " " + input;
  } else {
    law += "a(l, l') " + input;
  }
  const double* b = Bias(m, i);
  switch (m.actuator_biastype[i]) {
    case kBiasNone: break;
    case kBiasAffine: law += Term(b[0], "") + Term(b[1], "l") + Term(b[2], "l'"); break;
    default: law += " + bias(l, l')";
  }
  return law;
}

// ---------------------------------------------------------------- input and dynamics

// What u is in the law: the control, or the activation state.
std::string InputText(const Model& m, int i) {
  if (m.actuator_gaintype[i] == kGainSo3) {
    int u = m.actuator_ctrladr[i];
    std::string range = "ctrl[" + std::to_string(u) + ".." + std::to_string(u + m.actuator_ctrlnum[i] - 1) + "]";
    if (m.actuator_ctrlspec[i] == kChartQuat) return "q_target = " + range + " (w x y z, normalized; 0 is the identity)";
    if (HasActivation(m, i)) return "q_target from act[" + std::to_string(m.actuator_actadr[i]) + "..], w' = " + range;
    return "q_target = exp(" + range + "), a rotation vector";
  }
  if (m.actuator_gaintype[i] == kGainPid || m.actuator_gaintype[i] == kGainDcmotor) {
    // (setpoints named as in the law; an absent one is zero)
    static const std::map<std::string, std::string> kSetpoint = {
        {"pos", "qref"}, {"vel", "vref"}, {"ff", "ff"}, {"voltage", "V"}};
    if (m.actuator_ctrlnum[i] == 0) return "no inputs (input=\"none\"): V = 0";
    std::string text;
    int c = m.actuator_ctrladr[i];
    for (const std::string& name : InputNames(m, i)) {
      text += (text.empty() ? "" : ", ") + kSetpoint.at(name) + " = ctrl[" + std::to_string(c++) + "]";
    }
    bool all = m.actuator_ctrlnum[i] == (m.actuator_gaintype[i] == kGainPid ? 3 : 4);
    return text + (all ? "" : "; the absent ones are 0");
  }
  if (!HasActivation(m, i)) return "ctrl[" + std::to_string(m.actuator_ctrladr[i]) + "] (no activation state)";
  std::string text = "act[" + std::to_string(m.actuator_actadr[i]) + "], the activation w";
  if (m.actuator_actearly[i]) text += " (actearly: the force uses next step's w)";
  return text;
}

// How w evolves: w' from the dynamics type and its time constants.
std::string DynamicsText(const Model& m, int i) {
  const double* p = Dyn(m, i);
  switch (m.actuator_dyntype[i]) {
    case kDynNone: return "none: u = ctrl, no state";
    case kDynIntegrator: return "integrator: w' = ctrl";
    case kDynFilter:
      return "filter: w' = (ctrl - w) / tau, tau = " + Num(p[0]) +
             " s; Euler steps run ahead of 1 - exp(-t/tau)";
    case kDynFilterExact:
      return "filterexact: w' = (ctrl - w) / tau, tau = " + Num(p[0]) +
             " s; exact steps follow 1 - exp(-t/tau)";
    case kDynMuscle:
      return "muscle: activation tau " + Num(p[0]) + " s, deactivation tau " + Num(p[1]) +
             " s, smoothing " + Num(p[2]);
    case kDynDcmotor: {
      std::string states;
      if (p[7] > 0) states += ", slew-limited setpoint";
      if (Gain(m, i)[5] > 0) states += ", position error integral";
      if (p[2] > 0) states += ", winding temperature";
      if (p[5] > 0) states += ", LuGre bristle";
      if (p[0] > 0) states += ", current (te " + Num(p[0]) + " s, exact steps)";
      return "dcmotor: " + (states.empty() ? std::string("no state") : "states" + states.substr(1));
    }
    case kDynPid:
      if (p[1] > 0) return "pid: qref moves at most slewmax = " + Num(p[1]) + " per s (the state w)";
      return "pid: w' = qref - l, the integral" +
             (p[0] > 0 ? ", stops growing past imax = " + Num(p[0]) : std::string(", unbounded"));
    default: return "user: computed by a callback";
  }
}

// ---------------------------------------------------------------- transmission

// The 6 gear numbers, or the first alone when the rest are zero.
std::string GearText(const Model& m, int i) {
  const double* g = &m.actuator_gear[6 * m.actuator_outadr[i]];
  bool scalar = g[1] == 0 && g[2] == 0 && g[3] == 0 && g[4] == 0 && g[5] == 0;
  if (scalar) return Num(g[0]);
  std::string text = "[";
  for (int k = 0; k < 6; k++) text += (k ? " " : "") + Num(g[k]);
  return text + "]";
}

const char* JointTypeName(int type) {
  switch (type) {
    case kJointFree: return "free";
    case kJointBall: return "ball";
    case kJointSlide: return "slide";
    default: return "hinge";
  }
}

// Where the force goes: joint, tendon, site, slider-crank or body, with the gear.
std::string TransmissionText(const Model& m, int i) {
  int id = m.actuator_trnid[2 * i], ref = m.actuator_trnid[2 * i + 1];
  std::string gear = GearText(m, i);
  switch (m.actuator_trntype[i]) {
    case kTrnJoint:
    case kTrnJointInParent: {
      bool scalar = m.jnt_type[id] == kJointHinge || m.jnt_type[id] == kJointSlide;
      std::string text = std::string(m.actuator_trntype[i] == kTrnJoint ? "joint " : "jointinparent ") +
                         Quoted(m.jnt_names[id]) + " (" + JointTypeName(m.jnt_type[id]) +
                         "), gear " + gear;
      if (scalar) text += ": l = " + gear + " q, joint force = " + gear + " p";
      return text;
    }
    case kTrnTendon:
      return "tendon " + Quoted(m.tendon_names[id]) + ", gear " + gear + ": l = " + gear +
             " ten_length, joint forces = moment arms * " + gear + " p";
    case kTrnSite:
      return "site " + Quoted(m.site_names[id]) +
             (ref >= 0 ? " relative to refsite " + Quoted(m.site_names[ref]) : "") + ", gear " + gear;
    case kTrnSliderCrank:
      return "slider-crank: crank site " + Quoted(m.site_names[id]) + ", slider site " +
             Quoted(m.site_names[ref]) + ", crank length " + Num(m.actuator_cranklength[i]) +
             ", gear " + gear;
    case kTrnBody: return "body " + Quoted(m.body_names[id]) + " (adhesion through contacts)";
    case kTrnSo3:
      return (ref >= 0 ? "the rotation of site " + Quoted(m.site_names[id]) + " relative to refsite " +
                             Quoted(m.site_names[ref])
                       : "the rotation of ball joint " + Quoted(m.jnt_names[id])) +
             ": l = its rotation vector (3 outputs, in the child frame)";
    default: return "undefined";
  }
}

// ---------------------------------------------------------------- clamps

// "on  [lo, hi]  what it clamps" or "off".
std::string ClampText(bool on, const double* range, const std::string& meaning) {
  return on ? "on  " + Range(range) + "  " + meaning : "off";
}

// The force clamp of the joint or tendon the actuator drives, if it has one.
std::string TargetClampLine(const Model& m, int i) {
  int id = m.actuator_trnid[2 * i];
  switch (m.actuator_trntype[i]) {
    case kTrnJoint:
    case kTrnJointInParent:
      return Line("", "actuatorfrcrange of joint " + Quoted(m.jnt_names[id]) + ": " +
                          ClampText(m.jnt_actfrclimited[id], &m.jnt_actfrcrange[2 * id],
                                    "clamps the total actuator force on the joint"));
    case kTrnTendon:
      return Line("", "actuatorfrcrange of tendon " + Quoted(m.tendon_names[id]) + ": " +
                          ClampText(m.tendon_actfrclimited[id], &m.tendon_actfrcrange[2 * id],
                                    "clamps the total actuator force on the tendon"));
    default: return "";
  }
}

// Every clamp, one per line, in the order MuJoCo applies them.
std::string ClampLines(const Model& m, int i) {
  int u = m.actuator_ctrladr[i];
  std::string ctrl = ClampText(m.actuator_ctrllimited[u], &m.actuator_ctrlrange[2 * u],
                               "clamps ctrl inside the computation (data.ctrl keeps what was written)");
  if (m.actuator_ctrllimited[u] && (m.opt.disableflags & kDisableClampctrl)) {
    ctrl = "set " + Range(&m.actuator_ctrlrange[2 * u]) + " but disabled by <flag clampctrl>";
  }
  std::string text = Line("clamps", "ctrlrange: " + ctrl);
  // (a pid's other inputs have their own ranges)
  for (int k = 1; k < m.actuator_ctrlnum[i]; k++) {
    int c = u + k;
    text += Line("", "ctrl[" + std::to_string(c) + "]: " +
                         ClampText(m.actuator_ctrllimited[c], &m.actuator_ctrlrange[2 * c],
                                   "clamps this input"));
  }
  if (HasActivation(m, i)) {
    text += Line("", "actrange: " + ClampText(m.actuator_actlimited[i], &m.actuator_actrange[2 * i],
                                               "clamps the activation w"));
  }
  text += Line("", "forcerange: " + ClampText(m.actuator_forcelimited[i],
                                               &m.actuator_forcerange[2 * i],
                                               m.actuator_gaintype[i] == kGainSo3
                                                   ? "clamps the norm of p to the upper bound"
                                                   : "clamps p"));
  return text + TargetClampLine(m, i);
}

// The name of object `id` of an MJCF object type, quoted, or its index if unnamed.
std::string ObjectName(const Model& m, int type, int id) {
  const std::vector<std::string>* names = m.Names(static_cast<ObjType>(type));
  bool named = names && id < static_cast<int>(names->size()) && !(*names)[id].empty();
  return std::string(ObjTypeName(type)) + " " + (named ? Quoted((*names)[id]) : "#" + std::to_string(id));
}

const char* StageName(int stage) {
  switch (stage) {
    case kStagePos: return "position";
    case kStageVel: return "velocity";
    case kStageAcc: return "acceleration";
    default: return "no";
  }
}

// Delay, sampling and the filters a sensor's output goes through.
std::string SensorTiming(const Model& m, int i) {
  std::string text;
  if (m.sensor_cutoff[i] > 0) text += ", cutoff " + Num(m.sensor_cutoff[i]);
  if (m.sensor_noise[i] > 0) text += ", noise " + Num(m.sensor_noise[i]) + " (stored, not applied)";
  if (m.sensor_history[2 * i] > 0) {
    text += ", history of " + std::to_string(m.sensor_history[2 * i]) + " samples";
  }
  if (m.sensor_delay[i] > 0) text += ", delay " + Num(m.sensor_delay[i]) + " s";
  if (m.sensor_interval[2 * i] > 0) text += ", every " + Num(m.sensor_interval[2 * i]) + " s";
  return text;
}

}  // namespace

// ---------------------------------------------------------------- public

std::string ExplainSensor(const Model& m, int i) {
  std::string text = "sensor " + std::to_string(i) + " " + Quoted(m.sensor_names[i]) + ": " +
                     SensorTypeName(m.sensor_type[i]);
  if (m.sensor_objid[i] >= 0) text += " of " + ObjectName(m, m.sensor_objtype[i], m.sensor_objid[i]);
  if (m.sensor_refid[i] >= 0) {
    text += " relative to " + ObjectName(m, m.sensor_reftype[i], m.sensor_refid[i]);
  }
  int adr = m.sensor_adr[i], dim = m.sensor_dim[i];
  text += " -> sensordata[" + std::to_string(adr) +
          (dim > 1 ? ".." + std::to_string(adr + dim - 1) : "") + "], after the " +
          StageName(m.sensor_needstage[i]) + " stage" + SensorTiming(m, i) + "\n";
  return text;
}

std::string ExplainActuator(const Model& m, int i) {
  std::string head = "actuator " + std::to_string(i) + " " + Quoted(m.actuator_names[i]) +
                     ", reads as: " + ReadsAs(m, i) + "\n";
  if (m.actuator_plugin[i] >= 0) {
    // (a plugin computes p: the law's gain and bias are not used)
    const Plugin& plugin = PluginAt(m.plugin[m.actuator_plugin[i]]);
    std::string config;
    for (const std::string& key : plugin.attributes) {
      std::string value = PluginConfig(m, m.actuator_plugin[i], key);
      if (!value.empty()) config += (config.empty() ? "" : ", ") + key + " " + value;
    }
    return head + Line("law", "p computed by plugin " + Quoted(plugin.name) + " (instance " +
                                  std::to_string(m.actuator_plugin[i]) + ": " +
                                  (config.empty() ? "no config" : config) + ")") +
           Line("u", "ctrl[" + std::to_string(m.actuator_ctrladr[i]) + "], read by the plugin") +
           Line("dynamics", DynamicsText(m, i) +
                                (m.actuator_actnum[i] ? "; the plugin's states first" : "")) +
           Line("transmission", TransmissionText(m, i)) + ClampLines(m, i);
  }
  return head + Line("law", LawText(m, i)) + Line("a (gain)", GainText(m, i)) +
         Line("b (bias)", BiasText(m, i)) + Line("u", InputText(m, i)) +
         Line("dynamics", DynamicsText(m, i)) + Line("transmission", TransmissionText(m, i)) +
         ClampLines(m, i);
}

std::string ExplainModel(const Model& m) {
  std::string name = m.model_name.empty() ? "model" : m.model_name;
  std::string text = name + ": " + std::to_string(m.nactuator) +
                     " actuator(s), each an instance of p = a u + b0 + b1 l + b2 l'\n" +
                     "(u: ctrl or activation w; l, l': length and velocity at the transmission)\n";
  if (m.opt.disableflags & kDisableActuation) {
    text += "note: <flag actuation=\"disable\"/>: every actuator force is zero\n";
  }
  for (int i = 0; i < m.nactuator; i++) text += "\n" + ExplainActuator(m, i);
  if (m.nsensor > 0) {
    text += "\n" + std::to_string(m.nsensor) + " sensor(s), " + std::to_string(m.nsensordata) +
            " number(s) in sensordata\n";
    for (int i = 0; i < m.nsensor; i++) text += ExplainSensor(m, i);
  }
  return text;
}

int RunExplain(const std::string& path, std::ostream& out) {
  Model m = LoadXml(path);
  out << ExplainModel(m);
  return 0;
}

void AddExplainCommand(CLI::App& app, CommandIo& io) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "explain", "read every actuator as an instance of p = a u + b0 + b1 l + b2 l'");
  cmd->add_option("model", *path, "MJCF file")->required();
  cmd->callback([path, &io] { io.status = RunExplain(*path, *io.out); });
}

}  // namespace simlab::apps
