// Actuators: transmission targets, inherited ranges, limits and the activation layout.
// The force law itself (gain, bias, dynamics parameters) was set by the reader.
#include <algorithm>
#include <string>
#include <utility>

#include "compiler/compiler.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::kAuto;
using mjcf::kTrue;
using mjcf::ThrowAt;

namespace {

// Names of one kind of tree object.
template <typename T>
std::vector<std::string> Names(const std::vector<T>& items) {
  std::vector<std::string> names;
  for (const T& item : items) names.push_back(item.spec->src.name);
  return names;
}

// The objects a transmission can name, indexed once for all actuators.
struct TargetNames {
  NameIndex joints, sites, tendons, bodies;
};

// actuator_trnid: the target, and the slider or reference site where used.
void ResolveTarget(const mjcf::ActuatorSpec& a, const TargetNames& names, int* trnid) {
  trnid[0] = trnid[1] = -1;
  if (a.target.empty()) ThrowAt(a.src, "missing transmission target");
  switch (a.trntype) {
    case kTrnJoint:
    case kTrnJointInParent: trnid[0] = FindNamed(a.src, names.joints, a.target, "joint"); break;
    case kTrnTendon: trnid[0] = FindNamed(a.src, names.tendons, a.target, "tendon"); break;
    case kTrnSliderCrank:
      if (a.slidersite.empty()) ThrowAt(a.src, "missing slidersite for a slider-crank");
      trnid[1] = FindNamed(a.src, names.sites, a.slidersite, "site");
      if (a.cranklength <= 0) ThrowAt(a.src, "cranklength must be positive");
      trnid[0] = FindNamed(a.src, names.sites, a.target, "site");
      break;
    case kTrnSite:
      trnid[0] = FindNamed(a.src, names.sites, a.target, "site");
      if (!a.refsite.empty()) trnid[1] = FindNamed(a.src, names.sites, a.refsite, "site");
      break;
    case kTrnBody: trnid[0] = FindNamed(a.src, names.bodies, a.target, "body"); break;
    default: ThrowAt(a.src, "missing transmission target");
  }
}

// inheritrange: a position, intvelocity or pid actuator takes its target's range,
// scaled about the middle.
void InheritRange(const mjcf::ActuatorSpec& a, const CompileState& s, const Model& m,
                  const int* trnid, std::array<double, 2>* ctrlrange,
                  std::array<double, 2>* actrange) {
  bool servo = (a.gaintype == kGainFixed && a.gainprm[0] == -a.biasprm[1]) || a.gaintype == kGainPid;
  if (!(servo && a.biastype == kBiasAffine && a.inheritrange > 0)) return;
  std::array<double, 2>* range = nullptr;
  if (a.dyntype == kDynNone || a.dyntype == kDynFilterExact || a.dyntype == kDynPid) range = ctrlrange;
  if (a.dyntype == kDynIntegrator) range = actrange;
  if (!range) ThrowAt(a.src, "inheritrange is only available for position, intvelocity and pid actuators");
  const double* target = nullptr;
  if (a.trntype == kTrnJoint) {
    int type = s.joints[trnid[0]].spec->type;
    if (type != kJointHinge && type != kJointSlide) {
      ThrowAt(a.src, "inheritrange can only be used with hinge and slide joints");
    }
    target = s.joints[trnid[0]].range;
  } else if (a.trntype == kTrnTendon) {
    target = &m.tendon_range[2 * trnid[0]];
  } else {
    ThrowAt(a.src, "inheritrange can only be used with joint and tendon transmissions");
  }
  if (target[0] == target[1]) ThrowAt(a.src, "inheritrange used but the target has no range");
  double mean = 0.5 * (target[1] + target[0]), radius = 0.5 * (target[1] - target[0]) * a.inheritrange;
  (*range)[0] = mean - radius;
  (*range)[1] = mean + radius;
}

bool Limited(const mjcf::CompilerSpec& c, const mjcf::Source& src, int limited,
             const std::array<double, 2>& range, const char* attr) {
  bool hasrange = !(range[0] == 0 && range[1] == 0);
  if (limited == kAuto && !c.autolimits && hasrange) {
    ThrowAt(src, std::string("has ") + attr + "range but not " + attr +
                     "limited; set autolimits=\"true\" in <compiler> or set " + attr + "limited");
  }
  return limited == kTrue || (limited == kAuto && range[0] < range[1]);
}

// Limits: resolve, check. Ranges of controls are per control entry (from u on, ctrlnum of
// them), force and activation ranges per actuator, length ranges per output (from o on).
void Limits(const mjcf::ModelSpec& spec, const mjcf::ActuatorSpec& a,
            const std::array<double, 2>& ctrl, const std::array<double, 2>& act, int i, Model* m) {
  int u = m->actuator_ctrladr[i], o = m->actuator_outadr[i];
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(a.compiler, spec.compiler);  // (its own model's)
  m->actuator_forcelimited[i] = Limited(c, a.src, a.forcelimited, a.forcerange, "force");
  bool ctrllimited = Limited(c, a.src, a.ctrllimited, ctrl, "ctrl");
  // (an so3 integrator limited with no range is unlimited, as MuJoCo)
  bool so3 = a.gaintype == kGainSo3;
  int actlimited = so3 && a.actlimited == kTrue && act[0] == 0 && act[1] == 0 ? mjcf::kFalse : a.actlimited;
  m->actuator_actlimited[i] = Limited(c, a.src, actlimited, act, "act");
  if (m->actuator_forcelimited[i] && a.forcerange[0] >= a.forcerange[1]) ThrowAt(a.src, "invalid forcerange");
  if (ctrllimited && ctrl[0] >= ctrl[1]) ThrowAt(a.src, "invalid ctrlrange");
  if (m->actuator_actlimited[i] && act[0] >= act[1]) ThrowAt(a.src, "invalid actrange");
  if (m->actuator_actlimited[i] && a.dyntype == kDynNone) {
    ThrowAt(a.src, "actrange specified but dyntype is 'none'");
  }
  for (int c = u; c < u + m->actuator_ctrlnum[i]; c++) {
    m->actuator_ctrllimited[c] = ctrllimited;
    for (int k = 0; k < 2; k++) m->actuator_ctrlrange[2 * c + k] = ctrl[k];
  }
  // A pid's velocity and feedforward inputs have their own ranges, limited when lo < hi.
  if (a.gaintype == kGainPid) {
    int spec = m->actuator_ctrlspec[i], c = u + ((spec & kInputPos) ? 1 : 0);
    for (auto [bit, range] : {std::pair{kInputVel, &a.velrange}, std::pair{kInputFf, &a.ffrange}}) {
      if (!(spec & bit)) continue;
      m->actuator_ctrllimited[c] = (*range)[0] < (*range)[1];
      for (int k = 0; k < 2; k++) m->actuator_ctrlrange[2 * c + k] = (*range)[k];
      c++;
    }
  }
  for (int out = o; out < o + m->actuator_outnum[i]; out++) {
    for (int k = 0; k < 2; k++) m->actuator_lengthrange[2 * out + k] = a.lengthrange[k];
  }
  for (int k = 0; k < 2; k++) {
    m->actuator_forcerange[2 * i + k] = a.forcerange[k];
    m->actuator_actrange[2 * i + k] = act[k];
  }
}

// Muscle parameters (gainprm or biasprm of a muscle gain or bias) must describe a
// valid force-length-velocity curve.
void CheckMuscle(const mjcf::ActuatorSpec& a) {
  for (int k = 0; k < 2; k++) {
    const double* prm = nullptr;
    if (k == 0 && a.gaintype == kGainMuscle) prm = a.gainprm.data();
    if (k == 1 && a.biastype == kBiasMuscle) prm = a.biasprm.data();
    if (!prm) continue;
    if (prm[0] >= prm[1]) ThrowAt(a.src, "range[0]<range[1] required in muscle");
    if (prm[4] >= 1 || prm[5] <= 1) ThrowAt(a.src, "lmin<1<lmax required in muscle");
    if (prm[3] <= 0 || prm[6] <= 0 || prm[7] <= 0 || prm[8] <= 0) {
      ThrowAt(a.src, "positive scale, vmax, fpmax, fvmax required in muscle");
    }
  }
}

// damping and armature (MuJoCo 3.7+): only a joint or tendon target can take them.
void DampingArmature(const mjcf::ActuatorSpec& a, int i, Model* m) {
  bool has_damping = a.damping[0] != 0 || a.damping[1] != 0 || a.damping[2] != 0;
  bool joint_or_tendon =
      a.trntype == kTrnJoint || a.trntype == kTrnJointInParent || a.trntype == kTrnTendon;
  if (has_damping && !joint_or_tendon) {
    ThrowAt(a.src, "damping requires a joint or tendon transmission");
  }
  if (a.armature != 0 && !joint_or_tendon) {
    ThrowAt(a.src, "armature requires a joint or tendon transmission");
  }
  m->actuator_damping[i] = a.damping[0];
  for (int k = 0; k < kNPoly; k++) m->actuator_dampingpoly[kNPoly * i + k] = a.damping[1 + k];
  m->actuator_armature[i] = a.armature;
}

// jnt_actuatorid, tendon_actuatorid: the one actuator giving the target damping or
// armature, -2 when several do (the engine then sums over all of them), else -1.
void TargetActuatorIds(Model* m) {
  std::fill(m->jnt_actuatorid.begin(), m->jnt_actuatorid.end(), -1);
  std::fill(m->tendon_actuatorid.begin(), m->tendon_actuatorid.end(), -1);
  for (int i = 0; i < m->nactuator; i++) {
    bool contributes = m->actuator_damping[i] != 0 || m->actuator_armature[i] != 0;
    for (int k = 0; k < kNPoly; k++) contributes |= m->actuator_dampingpoly[kNPoly * i + k] != 0;
    if (!contributes) continue;
    int* slot = nullptr;
    int type = m->actuator_trntype[i], target = m->actuator_trnid[2 * i];
    if (type == kTrnJoint || type == kTrnJointInParent) slot = &m->jnt_actuatorid[target];
    if (type == kTrnTendon) slot = &m->tendon_actuatorid[target];
    if (slot) *slot = *slot == -1 ? i : -2;
  }
}

}  // namespace

namespace {

int PopCount(int bits) {
  int n = 0;
  for (; bits; bits &= bits - 1) n++;
  return n;
}

// A pid's checks (MuJoCo 3.12 mjCActuator::Compile): the bias is the servo's affine one,
// the state an integral (ki > 0) and/or a slew limit (slewmax > 0), the inputs a subset
// of pos, vel, ff (pos, vel by default). Returns the resolved signature and sets actdim.
int PidInputs(const mjcf::ActuatorSpec& a, int* actdim) {
  if (a.biastype != kBiasAffine) ThrowAt(a.src, "pid requires biastype 'affine'");
  if (a.dyntype != kDynNone && a.dyntype != kDynPid) ThrowAt(a.src, "pid requires dyntype 'none' or 'pid'");
  if (a.dyntype == kDynNone && a.gainprm[0] != 0) {
    ThrowAt(a.src, "a stateless pid needs gainprm[0] (ki) = 0");
  }
  if (a.trntype == kTrnBody) ThrowAt(a.src, "pid cannot use a body transmission");
  if (a.dyntype == kDynPid) {
    if (a.dynprm[0] < 0 || a.dynprm[1] < 0) ThrowAt(a.src, "pid imax and slewmax cannot be negative");
    int slots = (a.dynprm[1] > 0) + (a.gainprm[0] > 0);
    if (a.actdim > 0 && a.actdim != slots) ThrowAt(a.src, "pid actdim must equal its number of states");
    *actdim = slots;
  }
  int spec = a.ctrlspec ? a.ctrlspec : kInputPos | kInputVel;
  if (spec & ~(kInputPos | kInputVel | kInputFf)) ThrowAt(a.src, "pid inputs are a subset of [pos, vel, ff]");
  if (a.dyntype == kDynPid && !(spec & kInputPos)) {
    ThrowAt(a.src, "a pid with an integral or a slew limit needs the pos input");
  }
  return spec;
}

// An orientation's checks (MuJoCo 3.11): gain and bias so3, kp in both, no dynamics or an
// integrator of the rotation vector (3 states), the command a rotation vector (expmap,
// default) or a quaternion (stateless only), a force limit on the norm (lower bound 0).
// Returns the chart and sets actdim. (Its target is checked with the transmission.)
int So3Inputs(const mjcf::ActuatorSpec& a, int* actdim) {
  if (a.gaintype != kGainSo3 || a.biastype != kBiasSo3) {
    ThrowAt(a.src, "so3 gaintype and biastype must both be 'so3'");
  }
  if (a.dyntype != kDynNone && a.dyntype != kDynIntegrator) {
    ThrowAt(a.src, "an so3 actuator has dyntype 'none' or 'integrator'");
  }
  if (a.gainprm[0] != -a.biasprm[1]) ThrowAt(a.src, "so3 needs gainprm[0] = -biasprm[1] (kp)");
  if (a.dyntype == kDynIntegrator) {
    if (a.actdim > 0 && a.actdim != 3) ThrowAt(a.src, "an so3 integrator has actdim 3");
    *actdim = 3;
  }
  int chart = a.ctrlspec ? a.ctrlspec : kChartExpmap;
  if (chart != kChartExpmap && chart != kChartQuat) {
    ThrowAt(a.src, "an orientation's input is expmap or quat");
  }
  if (chart == kChartQuat && a.dyntype != kDynNone) {
    ThrowAt(a.src, "a quaternion command needs dyntype 'none'");
  }
  bool forcelimited = a.forcelimited == kTrue || (a.forcelimited == kAuto && a.forcerange[0] < a.forcerange[1]);
  if (forcelimited && a.forcerange[0] != 0) {
    ThrowAt(a.src, "an orientation limits the force's norm: forcerange lower bound must be 0");
  }
  return chart;
}

// An orientation's target: a ball joint, or a site relative to a refsite.
void CheckSo3Target(const mjcf::ActuatorSpec& a, const CompileState& s, const int* trnid) {
  if (a.trntype == kTrnSite) {
    if (trnid[1] < 0) ThrowAt(a.src, "an orientation on a site needs a refsite");
    return;
  }
  if (a.trntype != kTrnJoint || s.joints[trnid[0]].spec->type != kJointBall) {
    ThrowAt(a.src, "an orientation needs a ball joint or a site with a refsite");
  }
}

// A DC motor's number of states: slew, integral, temperature, bristle, current, each when
// its parameter is set (the engine's DcmotorSlots).
int DcmotorStates(const mjcf::ActuatorSpec& a) {
  return (a.dynprm[7] > 0) + (a.gainprm[5] > 0) + (a.dynprm[2] > 0) + (a.dynprm[5] > 0) +
         (a.dynprm[0] > 0);
}

// A dcmotor's checks: gain, bias and dynamics all dcmotor, always actearly; inputs "none"
// or a subset of pos, vel, ff, voltage (voltage by default), the controller's gains only
// with a controller input (and K > 0), the integral only with pos, the slew limit only
// with a controller. Returns the resolved signature.
int DcmotorInputs(const mjcf::ActuatorSpec& a, int actdim) {
  if (a.gaintype != kGainDcmotor || a.biastype != kBiasDcmotor || a.dyntype != kDynDcmotor) {
    ThrowAt(a.src, "dcmotor gain, bias and dynamics types go together");
  }
  if (!a.actearly) ThrowAt(a.src, "a dcmotor needs actearly");
  if (actdim != DcmotorStates(a)) {
    ThrowAt(a.src, "dcmotor actdim must equal its number of states (" +
                       std::to_string(DcmotorStates(a)) + ")");
  }
  int spec = a.ctrlspec ? a.ctrlspec : kInputVoltage;
  int all = kInputPos | kInputVel | kInputFf | kInputVoltage;
  if (spec != kInputNone && (spec & ~all)) ThrowAt(a.src, "dcmotor inputs are none or a subset of [pos, vel, ff, voltage]");
  int controller = spec == kInputNone ? 0 : spec & (kInputPos | kInputVel | kInputFf);
  if (controller && a.gainprm[1] <= 0) ThrowAt(a.src, "a dcmotor controller needs a positive motor constant");
  if (!controller && (a.gainprm[4] != 0 || a.gainprm[5] != 0 || a.gainprm[6] != 0)) {
    ThrowAt(a.src, "dcmotor controller gains need a pos, vel or ff input");
  }
  if (a.gainprm[5] > 0 && !(spec & kInputPos)) ThrowAt(a.src, "a dcmotor integral (ki) needs the pos input");
  if (a.dynprm[7] > 0 && !controller) ThrowAt(a.src, "a dcmotor slew limit needs a pos, vel or ff input");
  return spec;
}

}  // namespace

ActuatorShape ActuatorShapeOf(const mjcf::ActuatorSpec& a) {
  // A plugin's actuator: one control and one output, its states as actdim says (the
  // built-in dynamics' one by default), none of the built-in types' checks.
  if (a.plugin.active) {
    ActuatorShape shape;
    shape.actnum = a.actdim > 0 ? a.actdim : (a.dyntype != kDynNone ? 1 : 0);
    return shape;
  }
  if (a.dyntype == kDynUser || a.gaintype == kGainUser || a.biastype == kBiasUser) {
    ThrowAt(a.src, "user-defined actuator dynamics, gain or bias are not supported yet");
  }
  ActuatorShape shape;
  int actdim = a.actdim;
  bool so3 = a.gaintype == kGainSo3 || a.biastype == kBiasSo3;
  bool dcmotor = a.gaintype == kGainDcmotor || a.biastype == kBiasDcmotor || a.dyntype == kDynDcmotor;
  if (so3) {
    shape.ctrlspec = So3Inputs(a, &actdim);
    shape.ctrlnum = shape.ctrlspec == kChartQuat ? 4 : 3;
    shape.outnum = 3;
  } else if (a.gaintype == kGainPid) {
    shape.ctrlspec = PidInputs(a, &actdim);
    shape.ctrlnum = PopCount(shape.ctrlspec & (kInputPos | kInputVel | kInputFf));
  } else if (dcmotor) {
    if (actdim < 0) actdim = 0;
    shape.ctrlspec = DcmotorInputs(a, actdim);
    shape.ctrlnum = shape.ctrlspec == kInputNone ? 0 : PopCount(shape.ctrlspec);
  } else if (a.ctrlspec != 0) {
    ThrowAt(a.src, "input is only available for pid, dcmotor and orientation actuators");
  }
  if (a.dyntype == kDynPid && a.gaintype != kGainPid) ThrowAt(a.src, "dyntype 'pid' requires gaintype 'pid'");
  if (actdim > 1 && a.dyntype != kDynUser && !dcmotor && !so3) {
    ThrowAt(a.src, a.dyntype == kDynPid
                       ? "a pid can have an integral (ki) or a slew limit (slewmax), not both"
                       : "actdim > 1 is only allowed for dyntype 'user'");
  }
  if (actdim == 1 && a.dyntype == kDynNone) ThrowAt(a.src, "invalid actdim 1 in a stateless actuator");
  if (actdim == 0 && a.dyntype != kDynNone && !dcmotor) {
    ThrowAt(a.src, "invalid actdim 0 in a stateful actuator");
  }
  shape.actnum = actdim < 0 ? (a.dyntype != kDynNone ? 1 : 0) : actdim;
  if ((a.delay > 0 || a.nsample > 0) && shape.ctrlnum == 0) {
    ThrowAt(a.src, "an actuator without inputs has no control history");
  }
  if (a.delay > 0 && shape.ctrlnum != 1) {
    ThrowAt(a.src, "delay needs an actuator with one control (its history holds one number)");
  }
  return shape;
}

void CompileActuators(const mjcf::ModelSpec& spec, const CompileState& state, Model* m) {
  TargetNames targets = {NameIndex(Names(state.joints)), NameIndex(Names(state.sites)),
                         NameIndex(m->tendon_names), NameIndex(m->body_names)};
  NameIndex seen;
  int adr = 0, ctrladr = 0, outadr = 0;
  for (int i = 0; i < m->nactuator; i++) {
    const mjcf::ActuatorSpec& a = spec.actuators[i];
    if (!seen.Insert(a.src.name, i)) {
      ThrowAt(a.src, "repeated actuator name '" + a.src.name + "'");
    }
    m->actuator_names[i] = a.src.name;

    // Its slices of the controls, the force outputs and the activations.
    ActuatorShape shape = ActuatorShapeOf(a);
    m->actuator_ctrladr[i] = ctrladr;
    m->actuator_ctrlnum[i] = shape.ctrlnum;
    m->actuator_ctrlspec[i] = shape.ctrlspec;
    ctrladr += shape.ctrlnum;
    m->actuator_outadr[i] = outadr;
    m->actuator_outnum[i] = shape.outnum;
    outadr += shape.outnum;
    m->actuator_actnum[i] = shape.actnum;
    m->actuator_actadr[i] = shape.actnum ? adr : -1;
    adr += shape.actnum;

    // Transmission and ranges.
    int trnid[2];
    ResolveTarget(a, targets, trnid);
    bool so3 = a.gaintype == kGainSo3;
    if (so3) CheckSo3Target(a, state, trnid);
    std::array<double, 2> ctrl = a.ctrlrange, act = a.actrange;
    InheritRange(a, state, *m, trnid, &ctrl, &act);
    Limits(spec, a, ctrl, act, i, m);

    // Types, parameters, activation layout.
    m->actuator_trntype[i] = so3 ? kTrnSo3 : a.trntype;
    m->actuator_trnid[2 * i] = trnid[0];
    m->actuator_trnid[2 * i + 1] = trnid[1];
    m->actuator_dyntype[i] = a.dyntype;
    m->actuator_gaintype[i] = a.gaintype;
    m->actuator_biastype[i] = a.biastype;
    CheckMuscle(a);
    m->actuator_group[i] = a.group;
    m->actuator_actearly[i] = a.actearly;
    m->actuator_cranklength[i] = a.cranklength;
    for (int out = m->actuator_outadr[i]; out < outadr; out++) {
      for (int k = 0; k < 6; k++) m->actuator_gear[6 * out + k] = a.gear[k];
    }
    for (int k = 0; k < kNDyn; k++) m->actuator_dynprm[kNDyn * i + k] = a.dynprm[k];
    for (int k = 0; k < kNGain; k++) m->actuator_gainprm[kNGain * i + k] = a.gainprm[k];
    for (int k = 0; k < kNBias; k++) m->actuator_biasprm[kNBias * i + k] = a.biasprm[k];
    DampingArmature(a, i, m);
  }
  TargetActuatorIds(m);
}

}  // namespace simlab::compiler
