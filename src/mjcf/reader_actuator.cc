// MJCF reader: actuators. Every shortcut (motor, position, ...) writes MuJoCo's
// general actuator parameters (dyn/gain/bias type and prm) into the same spec, so a
// default class holds one actuator default whatever shortcut set it.
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "mjcf/error.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

namespace {

// Allowed attributes per actuator element, in the model (defaults drop the
// transmission and naming attributes).
std::vector<const char*> ActuatorAttributes(const std::string& tag, bool in_default) {
  if (tag == "general") {
    if (in_default) {
      return {"ctrllimited", "forcelimited", "actlimited", "ctrlrange", "forcerange",
              "actrange", "gear", "cranklength", "user", "group", "nsample", "interp",
              "delay", "actdim", "dyntype", "gaintype", "biastype", "dynprm", "gainprm",
              "biasprm", "actearly", "input", "velrange", "ffrange"};
    }
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrllimited",
            "forcelimited", "actlimited", "ctrlrange", "forcerange", "actrange",
            "lengthrange", "gear", "cranklength", "user", "joint", "jointinparent", "tendon",
            "slidersite", "cranksite", "site", "refsite", "body", "actdim", "dyntype",
            "gaintype", "biastype", "dynprm", "gainprm", "biasprm", "actearly", "input",
            "velrange", "ffrange"};
  }
  if (tag == "plugin") {  // (an <actuator><plugin>; there is no plugin default)
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrlrange", "user",
            "plugin", "instance", "ctrllimited", "forcelimited", "actlimited", "forcerange",
            "actrange", "lengthrange", "gear", "cranklength", "joint", "jointinparent", "site",
            "tendon", "cranksite", "slidersite", "actdim", "dyntype", "dynprm", "actearly"};
  }
  if (tag == "orientation") {
    std::vector<const char*> so3 = {"group", "nsample", "interp", "delay", "ctrlrange", "user",
                                    "forcelimited", "forcerange", "kp", "kv", "dampratio",
                                    "input"};
    if (!in_default) {
      for (const char* attr : {"name", "class", "joint", "site", "refsite"}) so3.push_back(attr);
    }
    return so3;
  }
  if (tag == "dcmotor") {
    std::vector<const char*> dc = {"group", "nsample", "interp", "delay", "ctrllimited",
                                   "ctrlrange", "gear", "cranklength", "user", "motorconst",
                                   "resistance", "nominal", "saturation", "inductance",
                                   "cogging", "controller", "thermal", "lugre", "input"};
    if (!in_default) {
      for (const char* attr : {"name", "class", "lengthrange", "joint", "jointinparent", "tendon",
                               "slidersite", "cranksite", "site", "refsite"}) {
        dc.push_back(attr);
      }
    }
    return dc;
  }
  if (tag == "pid") {
    std::vector<const char*> pid = {"group", "nsample", "interp", "delay", "ctrllimited",
                                    "forcelimited", "ctrlrange", "posrange", "velrange",
                                    "ffrange", "forcerange", "inheritrange", "gear",
                                    "cranklength", "user", "kp", "kv", "dampratio", "ki",
                                    "imax", "slewmax", "input"};
    if (!in_default) {
      for (const char* attr : {"name", "class", "lengthrange", "joint", "jointinparent", "tendon",
                               "slidersite", "cranksite", "site", "refsite"}) {
        pid.push_back(attr);
      }
    }
    return pid;
  }
  if (in_default) {
    if (tag == "motor") {
      return {"ctrllimited", "forcelimited", "ctrlrange", "forcerange", "gear", "cranklength",
              "user", "group", "nsample", "interp", "delay"};
    }
    if (tag == "position") {
      return {"ctrllimited", "forcelimited", "ctrlrange", "inheritrange", "forcerange",
              "gear", "cranklength", "user", "group", "nsample", "interp", "delay", "kp",
              "kv", "dampratio", "timeconst"};
    }
    if (tag == "velocity") {
      return {"ctrllimited", "forcelimited", "ctrlrange", "forcerange", "gear", "cranklength",
              "user", "group", "nsample", "interp", "delay", "kv"};
    }
    if (tag == "intvelocity") {
      return {"ctrllimited", "forcelimited", "ctrlrange", "forcerange", "actrange",
              "inheritrange", "gear", "cranklength", "user", "group", "nsample", "interp",
              "delay", "kp", "kv", "dampratio"};
    }
    if (tag == "damper") {
      return {"forcelimited", "ctrlrange", "forcerange", "gear", "cranklength", "user",
              "group", "nsample", "interp", "delay", "kv"};
    }
    if (tag == "cylinder") {
      return {"ctrllimited", "forcelimited", "ctrlrange", "forcerange", "gear", "cranklength",
              "user", "group", "nsample", "interp", "delay", "timeconst", "area", "diameter",
              "bias"};
    }
    if (tag == "muscle") {
      return {"ctrllimited", "forcelimited", "ctrlrange", "forcerange", "gear", "cranklength",
              "user", "group", "nsample", "interp", "delay", "timeconst", "range", "force",
              "scale", "lmin", "lmax", "vmax", "fpmax", "fvmax"};
    }
    return {"forcelimited", "ctrlrange", "forcerange", "gain", "user", "group", "nsample",
            "interp", "delay"};  // adhesion
  }
  if (tag == "motor") {
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrllimited",
            "forcelimited", "ctrlrange", "forcerange", "lengthrange", "gear", "cranklength",
            "user", "joint", "jointinparent", "tendon", "slidersite", "cranksite", "site",
            "refsite"};
  }
  if (tag == "position") {
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrllimited",
            "forcelimited", "ctrlrange", "inheritrange", "forcerange", "lengthrange", "gear",
            "cranklength", "user", "joint", "jointinparent", "tendon", "slidersite",
            "cranksite", "site", "refsite", "kp", "kv", "dampratio", "timeconst"};
  }
  if (tag == "velocity") {
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrllimited",
            "forcelimited", "ctrlrange", "forcerange", "lengthrange", "gear", "cranklength",
            "user", "joint", "jointinparent", "tendon", "slidersite", "cranksite", "site",
            "refsite", "kv"};
  }
  if (tag == "intvelocity") {
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrllimited",
            "forcelimited", "ctrlrange", "forcerange", "actrange", "inheritrange",
            "lengthrange", "gear", "cranklength", "user", "joint", "jointinparent", "tendon",
            "slidersite", "cranksite", "site", "refsite", "kp", "kv", "dampratio"};
  }
  if (tag == "damper") {
    return {"name", "class", "group", "nsample", "interp", "delay", "forcelimited",
            "ctrlrange", "forcerange", "lengthrange", "gear", "cranklength", "user", "joint",
            "jointinparent", "tendon", "slidersite", "cranksite", "site", "refsite", "kv"};
  }
  if (tag == "cylinder") {
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrllimited",
            "forcelimited", "ctrlrange", "forcerange", "lengthrange", "gear", "cranklength",
            "user", "joint", "jointinparent", "tendon", "slidersite", "cranksite", "site",
            "refsite", "timeconst", "area", "diameter", "bias"};
  }
  if (tag == "muscle") {
    return {"name", "class", "group", "nsample", "interp", "delay", "ctrllimited",
            "forcelimited", "ctrlrange", "forcerange", "lengthrange", "gear", "cranklength",
            "user", "joint", "jointinparent", "tendon", "slidersite", "cranksite",
            "timeconst", "tausmooth", "range", "force", "scale", "lmin", "lmax", "vmax",
            "fpmax", "fvmax"};
  }
  return {"name", "class", "group", "nsample", "interp", "delay", "forcelimited",
          "ctrlrange", "forcerange", "user", "body", "gain"};  // adhesion
}

// An optional number: present or not.
struct Maybe {
  bool has = false;
  double value = 0;
};

Maybe ReadMaybe(const XmlElement& e, const char* name) {
  Maybe m;
  m.has = e.Number(name, &m.value);
  return m;
}

// The input signature of an actuator (MuJoCo's ReadInputSpec): a chart keyword (expmap,
// quat), "none", or inputs among pos, vel, ff, voltage listed once each in that order.
// An empty text means the type's default; an absent attribute keeps what was inherited.
void ReadInputSpec(const XmlElement& e, int* spec) {
  std::string text;
  if (!e.Text("input", &text)) return;
  std::istringstream words(text);
  std::vector<std::string> tokens;
  for (std::string w; words >> w;) tokens.push_back(w);
  if (tokens.size() == 1 && tokens[0] == "expmap") *spec = kChartExpmap;
  if (tokens.size() == 1 && tokens[0] == "quat") *spec = kChartQuat;
  if (tokens.size() == 1 && tokens[0] == "none") *spec = kInputNone;
  if (tokens.size() == 1 && (tokens[0] == "expmap" || tokens[0] == "quat" || tokens[0] == "none")) {
    return;
  }
  static const std::pair<const char*, int> kInputs[] = {
      {"pos", kInputPos}, {"vel", kInputVel}, {"ff", kInputFf}, {"voltage", kInputVoltage}};
  int bits = 0, last = 0;
  for (const std::string& token : tokens) {
    int bit = 0;
    for (const auto& [name, value] : kInputs) {
      if (token == name) bit = value;
    }
    if (!bit) e.Fail("unknown input '" + token + "' (pos, vel, ff, voltage, none, expmap or quat)");
    if (bit <= last) e.Fail("inputs must be listed once each, in the order pos, vel, ff, voltage");
    bits |= bit;
    last = bit;
  }
  *spec = bits;
}

}  // namespace

bool IsActuatorElement(const std::string& tag) {
  static const char* const kTags[] = {"general", "motor",   "position", "velocity",
                                      "intvelocity", "damper", "cylinder", "muscle",
                                      "adhesion", "pid", "dcmotor", "orientation"};
  for (const char* t : kTags) {
    if (tag == t) return true;
  }
  return false;
}

// ---------------------------------------------------------------- common attributes

void Reader::ReadActuator(const XmlElement& e, ActuatorSpec* a, bool in_default) const {
  // Every kind but adhesion passes damping and armature to its joint or tendon.
  std::vector<const char*> allowed = ActuatorAttributes(e.tag(), in_default);
  if (e.tag() != "adhesion") {
    allowed.push_back("damping");
    allowed.push_back("armature");
  }
  e.CheckAttributes(allowed);
  e.Numbers("damping", a->damping, false);
  e.Number("armature", &a->armature);
  if (!in_default) a->src = e.src();
  e.Int("group", &a->group);
  e.Int("nsample", &a->nsample);
  e.Enum("interp", &a->interp, {{"zoh", 0}, {"linear", 1}, {"cubic", 2}});
  e.Number("delay", &a->delay);
  e.Tri("ctrllimited", &a->ctrllimited);
  e.Tri("forcelimited", &a->forcelimited);
  e.Tri("actlimited", &a->actlimited);
  e.Numbers("ctrlrange", a->ctrlrange);
  e.Numbers("forcerange", a->forcerange);
  e.Numbers("actrange", a->actrange);
  e.Numbers("lengthrange", a->lengthrange);
  e.Numbers("velrange", a->velrange);
  e.Numbers("ffrange", a->ffrange);
  e.Numbers("gear", a->gear, false);
  ReadTransmission(e, a);
  ReadShortcut(e, a);
  e.Vector("user");
}

void Reader::ReadTransmission(const XmlElement& e, ActuatorSpec* a) const {
  // At most one target attribute sets the transmission type.
  struct Target {
    const char* attr;
    int type;
  };
  static const Target kTargets[] = {{"joint", kTrnJoint},         {"jointinparent", kTrnJointInParent},
                                    {"tendon", kTrnTendon},       {"cranksite", kTrnSliderCrank},
                                    {"site", kTrnSite},           {"body", kTrnBody}};
  int count = 0;
  for (const Target& t : kTargets) {
    if (e.Text(t.attr, &a->target)) {
      a->trntype = t.type;
      count++;
    }
  }
  if (count > 1) e.Fail("an actuator can have at most one transmission target");

  // Slider-crank and reference-site parameters belong to their transmissions.
  bool crank = e.Number("cranklength", &a->cranklength);
  bool slider = e.Text("slidersite", &a->slidersite);
  if ((crank || slider) && a->trntype != kTrnSliderCrank && a->trntype != kTrnUndefined) {
    e.Fail("cranklength and slidersite can only be used in a slider-crank transmission");
  }
  bool ref = e.Text("refsite", &a->refsite);
  if (ref && a->trntype != kTrnSite && a->trntype != kTrnUndefined) {
    e.Fail("refsite can only be used with a site transmission");
  }
}

// ---------------------------------------------------------------- shortcuts

namespace {

// A servo's damping: kv (stored negative in biasprm[2]) or a dampratio (stored positive,
// turned into a damping at compile time), not both.
void SetDamping(const XmlElement& e, ActuatorSpec* a, Maybe kv, Maybe dampratio) {
  if (kv.has && dampratio.has) e.Fail("kv and dampratio cannot both be defined");
  if (kv.has) {
    if (kv.value < 0) e.Fail("kv cannot be negative");
    a->biasprm[2] = -kv.value;
  }
  if (dampratio.has) {
    if (dampratio.value < 0) e.Fail("dampratio cannot be negative");
    a->biasprm[2] = dampratio.value;
  }
}

// motor: unit gain, no dynamics or bias.
void SetMotor(ActuatorSpec* a) {
  a->gainprm[0] = 1;
  a->dyntype = kDynNone;
  a->gaintype = kGainFixed;
  a->biastype = kBiasNone;
}

// position servo: gain kp, bias -kp*length - kv*velocity; dampratio is stored as a
// positive biasprm[2] and turned into a damping at compile time.
void SetPosition(const XmlElement& e, ActuatorSpec* a, double kp, Maybe kv, Maybe dampratio,
                 Maybe timeconst, double inheritrange) {
  a->gainprm[0] = kp;
  a->biasprm[1] = -kp;
  SetDamping(e, a, kv, dampratio);
  if (timeconst.has) {
    if (timeconst.value < 0) e.Fail("timeconst cannot be negative");
    a->dynprm[0] = timeconst.value;
    a->dyntype = timeconst.value == 0 ? kDynNone : kDynFilterExact;
  }
  a->inheritrange = inheritrange;
  if (inheritrange > 0 && (a->ctrlrange[0] != 0 || a->ctrlrange[1] != 0)) {
    e.Fail("ctrlrange and inheritrange cannot both be defined");
  }
  a->gaintype = kGainFixed;
  a->biastype = kBiasAffine;
}

// velocity servo: gain kv, bias -kv*velocity.
void SetVelocity(ActuatorSpec* a, double kv) {
  a->biasprm.fill(0);
  a->gainprm[0] = kv;
  a->biasprm[2] = -kv;
  a->dyntype = kDynNone;
  a->gaintype = kGainFixed;
  a->biastype = kBiasAffine;
}

// damper: force -kv*velocity*ctrl, control limited to nonnegative values.
void SetDamper(const XmlElement& e, ActuatorSpec* a, double kv) {
  a->gainprm.fill(0);
  a->gainprm[2] = -kv;
  a->ctrllimited = kTrue;
  a->dyntype = kDynNone;
  a->gaintype = kGainAffine;
  a->biastype = kBiasNone;
  if (kv < 0) e.Fail("damping coefficient cannot be negative");
  if (a->ctrlrange[0] < 0 || a->ctrlrange[1] < 0) {
    e.Fail("damper control range cannot be negative");
  }
}

// cylinder: first-order filter on pressure, force area*act + bias. MuJoCo 3.5 keeps
// only the first of the three bias numbers (biasprm[0]).
void SetCylinder(ActuatorSpec* a, double timeconst, const std::array<double, 3>& bias,
                 double area, double diameter) {
  a->dynprm[0] = timeconst;
  a->biasprm[0] = bias[0];
  a->gainprm[0] = area;
  if (diameter >= 0) a->gainprm[0] = std::numbers::pi / 4 * diameter * diameter;
  a->dyntype = kDynFilter;
  a->gaintype = kGainFixed;
  a->biastype = kBiasAffine;
}

// adhesion: gain on a body transmission, control limited to nonnegative values.
void SetAdhesion(const XmlElement& e, ActuatorSpec* a, double gain) {
  a->gainprm[0] = gain;
  a->ctrllimited = kTrue;
  a->gaintype = kGainFixed;
  a->biastype = kBiasNone;
  if (gain < 0) e.Fail("adhesion gain cannot be negative");
  if (a->ctrlrange[0] < 0 || a->ctrlrange[1] < 0) {
    e.Fail("adhesion control range cannot be negative");
  }
}

// muscle: MuJoCo's muscle model. gainprm = biasprm = (range[2], force, scale, lmin,
// lmax, vmax, fpmax, fvmax), dynprm = (tau activation, tau deactivation, tausmooth).
// Parameters still at the general defaults take the muscle defaults first; each
// attribute given (>= 0) then overrides its slot.
struct MuscleAttrs {
  std::array<double, 2> timeconst = {-1, -1}, range = {-1, -1};
  double tausmooth = 0, force = -1, scale = -1, lmin = -1, lmax = -1, vmax = -1;
  double fpmax = -1, fvmax = -1;
};

void SetMuscle(const XmlElement& e, ActuatorSpec* a, const MuscleAttrs& m) {
  static const double kDefaults[9] = {0.75, 1.05, -1, 200, 0.5, 1.6, 1.5, 1.3, 1.2};
  static const double kGeneral[9] = {1, 0, 0, 0, 0, 0, 0, 0, 0};
  if (a->dynprm[0] == 1) a->dynprm[0] = 0.01;
  if (a->dynprm[1] == 0) a->dynprm[1] = 0.04;
  for (int k = 0; k < 9; k++) {
    if (a->gainprm[k] == kGeneral[k]) a->gainprm[k] = kDefaults[k];
  }
  if (m.tausmooth < 0) e.Fail("muscle tausmooth cannot be negative");
  a->dynprm[2] = m.tausmooth;
  const double given[11] = {m.timeconst[0], m.timeconst[1], m.range[0], m.range[1], m.force,
                            m.scale, m.lmin, m.lmax, m.vmax, m.fpmax, m.fvmax};
  for (int k = 0; k < 2; k++) {
    if (given[k] >= 0) a->dynprm[k] = given[k];
  }
  for (int k = 0; k < 9; k++) {
    if (given[2 + k] >= 0) a->gainprm[k] = given[2 + k];
  }
  for (int k = 0; k < 9; k++) a->biasprm[k] = a->gainprm[k];
  a->dyntype = kDynMuscle;
  a->gaintype = kGainMuscle;
  a->biastype = kBiasMuscle;
}

// pid (MuJoCo 3.12): force kp (qref - l) + kv (vref - l') + ff + ki * integral, its
// inputs packed in ctrl as `input` lists them; an integral (ki) or a slew limit (slewmax)
// is its activation state. kp and kv sit in biasprm as a position servo's (so that a pid
// with a zero velocity setpoint is that servo), ki in gainprm[0], imax and slewmax in
// dynprm[0] and [1]; dampratio is stored as a positive biasprm[2] and turned into a
// damping at compile time.
struct PidAttrs {
  double kp = 0, ki = 0, imax = 0, slewmax = 0, inheritrange = 0;
  Maybe kv, dampratio;
};

void SetPid(const XmlElement& e, ActuatorSpec* a, const PidAttrs& p) {
  a->biasprm[1] = -p.kp;
  SetDamping(e, a, p.kv, p.dampratio);
  if (p.slewmax < 0) e.Fail("slewmax cannot be negative");
  a->gainprm[0] = p.ki;
  a->dynprm[1] = p.slewmax;
  a->dyntype = p.ki != 0 || p.slewmax != 0 ? kDynPid : kDynNone;
  if (p.ki != 0) a->dynprm[0] = p.imax;
  a->inheritrange = p.inheritrange;
  if (p.inheritrange > 0 && (a->ctrlrange[0] != 0 || a->ctrlrange[1] != 0)) {
    e.Fail("posrange and inheritrange cannot both be defined");
  }
  a->gaintype = kGainPid;
  a->biastype = kBiasAffine;
}

// orientation (MuJoCo 3.11): a geodesic servo on SO(3), force kp log(q^-1 q_target) -
// kv w on 3 outputs, commanded by a rotation vector (3 controls) or a quaternion (4).
// kp also sits in biasprm[1] (as a position servo's, for dampratio), kv in biasprm[2].
void SetOrientation(const XmlElement& e, ActuatorSpec* a, double kp, Maybe kv, Maybe dampratio) {
  a->gainprm[0] = kp;
  a->biasprm[1] = -kp;
  SetDamping(e, a, kv, dampratio);
  a->gaintype = kGainSo3;
  a->biastype = kBiasSo3;
  a->dyntype = kDynNone;
}

// dcmotor (MuJoCo 3.7, controller redesigned in 3.12): a DC motor's electrical law with
// optional states. Each attribute is a vector of which a prefix may be given:
//   motorconst (Kt Ke), resistance R, nominal (volts, stall torque, no-load speed),
//   saturation (torque, current, current rate), inductance (L, or 0 then te),
//   cogging (amplitude, poles, phase), controller (kp ki kd slewmax imax vmax),
//   thermal (RT C tau alpha T0 Tambient), lugre (sigma0 sigma1 Fcoulomb Fstatic vstribeck).
// Stored as gainprm = [R K alpha T0 kp ki kd vmax 0 0], dynprm = [te di/dt RT C Ta sigma0
// sigma1 slewmax imax 0], biasprm = [A Np phase Fc Fs vs ...]; one state per feature in
// use (slew, integral, temperature, bristle, current).
struct DcmotorAttrs {
  std::array<double, 2> motorconst = {0, 0}, inductance = {0, 0};
  double resistance = 0;
  std::array<double, 3> nominal = {0, 0, 0}, saturation = {0, 0, 0}, cogging = {0, 0, 0};
  std::array<double, 6> controller = {0, 0, 0, 0, 0, 0}, thermal = {0, 0, 0, 0, 0, 0};
  std::array<double, 5> lugre = {0, 0, 0, 0, 0};
};

// The back-EMF constant from nominal ratings (volts vn, stall torque tau0, no-load speed
// omega0), given the viscous damping b of the actuator.
double BackEmfFromNominal(double vn, double tau0, double omega0, double b, double r) {
  if (b > 0 && r > 0) {
    double disc = vn * vn - 4 * r * b * omega0 * omega0;
    return disc > 0 ? (vn + std::sqrt(disc)) / (2 * omega0) : vn / omega0;
  }
  if (b > 0 && tau0 > 0) {
    double ke = vn / omega0 - vn * b / tau0;
    return ke <= 0 ? vn / omega0 : ke;
  }
  return vn / omega0;
}

// The winding's thermal resistance and capacitance, the one missing found from the time
// constant tau = RT C.
void ThermalConstants(const XmlElement& e, const std::array<double, 6>& t, double* rt, double* c) {
  *rt = t[0], *c = t[1];
  double tau = t[2];
  if (tau > 0 && *rt > 0 && *c == 0) *c = tau / *rt;
  else if (tau > 0 && *c > 0 && *rt == 0) *rt = tau / *c;
  if (*rt <= 0 || *c <= 0) e.Fail("dcmotor thermal needs a positive resistance and capacitance");
}

void SetDcmotor(const XmlElement& e, ActuatorSpec* a, const DcmotorAttrs& p) {
  double r = p.resistance, kt = p.motorconst[0], ke = p.motorconst[1];
  double vn = p.nominal[0], tau0 = p.nominal[1], omega0 = p.nominal[2];
  if (vn > 0 && ke <= 0 && omega0 > 0) ke = BackEmfFromNominal(vn, tau0, omega0, a->damping[0], r);
  double k = kt > 0 && ke > 0 ? std::sqrt(kt * ke) : (kt > 0 ? kt : ke);
  if (r == 0 && vn > 0 && tau0 > 0 && k > 0) r = k * vn / tau0;
  if (k <= 0) e.Fail("DC motor: motor constant K must be positive");
  if (r <= 0) e.Fail("DC motor: resistance R must be positive");
  a->dyntype = kDynDcmotor;
  a->gaintype = kGainDcmotor;
  a->biastype = kBiasDcmotor;
  a->gainprm[0] = r;
  a->gainprm[1] = k;
  for (int j = 0; j < 3; j++) a->gainprm[4 + j] = p.controller[j];
  a->dynprm[7] = p.controller[3];
  a->dynprm[8] = p.controller[4];
  if (p.controller[5] > 0) a->gainprm[7] = p.controller[5];
  // Saturation: a torque limit (or a current limit times K), and a current rate limit.
  if (p.saturation[0] > 0 || p.saturation[1] > 0) {
    double limit = p.saturation[0] == 0 ? k * p.saturation[1] : p.saturation[0];
    a->forcerange = {-limit, limit};
    a->forcelimited = kTrue;
  }
  if (p.saturation[2] > 0) a->dynprm[1] = p.saturation[2];
  for (int j = 0; j < 3; j++) a->biasprm[j] = p.cogging[j];
  // The states: current (te = L / R), slew, integral, temperature, bristle.
  if (p.inductance[0] < 0 || p.inductance[1] < 0) e.Fail("dcmotor inductance cannot be negative");
  double te = p.inductance[0] > 0 ? p.inductance[0] / r : p.inductance[1];
  a->dynprm[0] = te;
  int states = (te > 0) + (p.controller[3] > 0) + (p.controller[1] > 0);
  if (p.thermal[0] > 0 || p.thermal[1] > 0 || p.thermal[2] > 0) {
    ThermalConstants(e, p.thermal, &a->dynprm[2], &a->dynprm[3]);
    a->dynprm[4] = p.thermal[5];
    a->gainprm[2] = p.thermal[3];
    a->gainprm[3] = p.thermal[4];
    states++;
  }
  if (p.lugre[0] > 0) {
    a->dynprm[5] = p.lugre[0];
    a->dynprm[6] = p.lugre[1];
    for (int j = 0; j < 3; j++) a->biasprm[3 + j] = p.lugre[2 + j];
    states++;
  }
  a->gainprm[8] = 0;
  a->actdim = states;
  a->actlimited = kFalse;
  a->actearly = true;
}

}  // namespace

void Reader::ReadShortcut(const XmlElement& e, ActuatorSpec* a) const {
  const std::string& tag = e.tag();
  static const std::initializer_list<Keyword> kDyn = {
      {"none", kDynNone},           {"integrator", kDynIntegrator}, {"filter", kDynFilter},
      {"filterexact", kDynFilterExact}, {"muscle", kDynMuscle},     {"dcmotor", kDynDcmotor},
      {"pid", kDynPid},             {"user", kDynUser}};
  if (tag == "plugin") {
    e.Int("actdim", &a->actdim);
    e.Enum("dyntype", &a->dyntype, kDyn);
    e.Numbers("dynprm", a->dynprm, false);
    e.Bool("actearly", &a->actearly);
  } else if (tag == "general") {
    e.Enum("dyntype", &a->dyntype, kDyn);
    e.Enum("gaintype", &a->gaintype,
           {{"fixed", kGainFixed}, {"affine", kGainAffine}, {"muscle", kGainMuscle},
            {"dcmotor", kGainDcmotor}, {"so3", kGainSo3}, {"pid", kGainPid}, {"user", kGainUser}});
    e.Enum("biastype", &a->biastype,
           {{"none", kBiasNone}, {"affine", kBiasAffine}, {"muscle", kBiasMuscle},
            {"dcmotor", kBiasDcmotor}, {"so3", kBiasSo3}, {"user", kBiasUser}});
    ReadInputSpec(e, &a->ctrlspec);
    e.Bool("actearly", &a->actearly);
    e.Numbers("dynprm", a->dynprm, false);
    e.Numbers("gainprm", a->gainprm, false);
    e.Numbers("biasprm", a->biasprm, false);
    e.Int("actdim", &a->actdim);
  } else if (tag == "motor") {
    SetMotor(a);
  } else if (tag == "position" || tag == "intvelocity") {
    double kp = a->gainprm[0];
    e.Number("kp", &kp);
    Maybe kv = ReadMaybe(e, "kv");
    Maybe dampratio = ReadMaybe(e, "dampratio");
    Maybe timeconst = ReadMaybe(e, "timeconst");
    double inheritrange = a->inheritrange;
    e.Number("inheritrange", &inheritrange);
    SetPosition(e, a, kp, kv, dampratio, timeconst, inheritrange);
    if (tag == "intvelocity") {
      a->dyntype = kDynIntegrator;
      a->actlimited = kTrue;
      if (inheritrange > 0 && (a->actrange[0] != 0 || a->actrange[1] != 0)) {
        e.Fail("actrange and inheritrange cannot both be defined");
      }
    }
  } else if (tag == "velocity") {
    double kv = a->gainprm[0];
    e.Number("kv", &kv);
    SetVelocity(a, kv);
  } else if (tag == "damper") {
    double kv = 0;
    e.Number("kv", &kv);
    SetDamper(e, a, kv);
  } else if (tag == "cylinder") {
    double timeconst = a->dynprm[0], area = a->gainprm[0], diameter = -1;
    std::array<double, 3> bias = {a->biasprm[0], a->biasprm[1], a->biasprm[2]};
    e.Number("timeconst", &timeconst);
    e.Numbers("bias", bias);
    e.Number("area", &area);
    e.Number("diameter", &diameter);
    SetCylinder(a, timeconst, bias, area, diameter);
  } else if (tag == "muscle") {
    MuscleAttrs attrs;
    attrs.tausmooth = a->dynprm[2];
    e.Numbers("timeconst", attrs.timeconst);
    e.Number("tausmooth", &attrs.tausmooth);
    e.Numbers("range", attrs.range);
    e.Number("force", &attrs.force);
    e.Number("scale", &attrs.scale);
    e.Number("lmin", &attrs.lmin);
    e.Number("lmax", &attrs.lmax);
    e.Number("vmax", &attrs.vmax);
    e.Number("fpmax", &attrs.fpmax);
    e.Number("fvmax", &attrs.fvmax);
    SetMuscle(e, a, attrs);
  } else if (tag == "adhesion") {
    double gain = a->gainprm[0];
    e.Number("gain", &gain);
    SetAdhesion(e, a, gain);
  } else if (tag == "orientation") {
    double kp = a->gainprm[0];
    e.Number("kp", &kp);
    Maybe kv = ReadMaybe(e, "kv");
    Maybe dampratio = ReadMaybe(e, "dampratio");
    ReadInputSpec(e, &a->ctrlspec);
    SetOrientation(e, a, kp, kv, dampratio);
  } else if (tag == "dcmotor") {
    // (a dcmotor class passes its parameters; nominal ratings are never inherited)
    DcmotorAttrs p;
    if (a->gaintype == kGainDcmotor) {
      const auto &g = a->gainprm, &dyn = a->dynprm, &b = a->biasprm;
      p.motorconst = {g[1], 0};
      p.resistance = g[0];
      p.saturation = {0, 0, dyn[1]};
      p.controller = {g[4], g[5], g[6], dyn[7], dyn[8], g[7]};
      p.inductance = {0, dyn[0]};
      p.cogging = {b[0], b[1], b[2]};
      p.thermal = {dyn[2], dyn[3], 0, g[2], g[3], dyn[4]};
      p.lugre = {dyn[5], dyn[6], b[3], b[4], b[5]};
    } else {
      a->ctrlspec = 0;
    }
    e.Numbers("motorconst", p.motorconst, false);
    e.Number("resistance", &p.resistance);
    e.Numbers("nominal", p.nominal, false);
    e.Numbers("saturation", p.saturation, false);
    e.Numbers("inductance", p.inductance, false);
    e.Numbers("cogging", p.cogging, false);
    e.Numbers("controller", p.controller, false);
    e.Numbers("thermal", p.thermal, false);
    e.Numbers("lugre", p.lugre, false);
    ReadInputSpec(e, &a->ctrlspec);
    SetDcmotor(e, a, p);
  } else if (tag == "pid") {
    // (a class of any kind passes its kp; ki, imax and slewmax only from a stateful pid)
    PidAttrs p;
    bool stateful_pid = a->dyntype == kDynPid;
    p.kp = -a->biasprm[1];
    p.ki = stateful_pid ? a->gainprm[0] : 0;
    p.imax = stateful_pid ? a->dynprm[0] : 0;
    p.slewmax = stateful_pid ? a->dynprm[1] : 0;
    p.inheritrange = a->inheritrange;
    e.Number("kp", &p.kp);
    p.kv = ReadMaybe(e, "kv");
    p.dampratio = ReadMaybe(e, "dampratio");
    e.Number("ki", &p.ki);
    e.Number("imax", &p.imax);
    e.Number("slewmax", &p.slewmax);
    e.Number("inheritrange", &p.inheritrange);
    ReadInputSpec(e, &a->ctrlspec);
    e.Numbers("posrange", a->ctrlrange);  // the position input's range: ctrlrange
    SetPid(e, a, p);
  }
}

}  // namespace simlab::mjcf
