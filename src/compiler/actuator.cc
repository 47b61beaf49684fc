// Actuators: transmission targets, inherited ranges, limits and the activation layout.
// The force law itself (gain, bias, dynamics parameters) was set by the reader.
#include <algorithm>
#include <string>

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

// inheritrange: a position (or intvelocity) actuator takes its target's range,
// scaled about the middle.
void InheritRange(const mjcf::ActuatorSpec& a, const CompileState& s, const Model& m,
                  const int* trnid, std::array<double, 2>* ctrlrange,
                  std::array<double, 2>* actrange) {
  if (!(a.gaintype == kGainFixed && a.biastype == kBiasAffine && a.gainprm[0] == -a.biasprm[1] &&
        a.inheritrange > 0)) {
    return;
  }
  std::array<double, 2>* range = nullptr;
  if (a.dyntype == kDynNone || a.dyntype == kDynFilterExact) range = ctrlrange;
  if (a.dyntype == kDynIntegrator) range = actrange;
  if (!range) ThrowAt(a.src, "inheritrange is only available for position and intvelocity actuators");
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

bool Limited(const mjcf::ModelSpec& spec, const mjcf::Source& src, int limited,
             const std::array<double, 2>& range, const char* attr) {
  bool hasrange = !(range[0] == 0 && range[1] == 0);
  if (limited == kAuto && !spec.compiler.autolimits && hasrange) {
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
  m->actuator_forcelimited[i] = Limited(spec, a.src, a.forcelimited, a.forcerange, "force");
  bool ctrllimited = Limited(spec, a.src, a.ctrllimited, ctrl, "ctrl");
  m->actuator_actlimited[i] = Limited(spec, a.src, a.actlimited, act, "act");
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

// Activation states per actuator (checked): actdim, else 1 with dynamics.
int ActuatorActDim(const mjcf::ActuatorSpec& a) {
  if (a.dyntype == kDynUser || a.gaintype == kGainUser || a.biastype == kBiasUser) {
    ThrowAt(a.src, "user-defined actuator dynamics, gain or bias are not supported yet");
  }
  if (a.actdim > 1 && a.dyntype != kDynUser) ThrowAt(a.src, "actdim > 1 is only allowed for dyntype 'user'");
  if (a.actdim == 1 && a.dyntype == kDynNone) ThrowAt(a.src, "invalid actdim 1 in a stateless actuator");
  if (a.actdim == 0 && a.dyntype != kDynNone) ThrowAt(a.src, "invalid actdim 0 in a stateful actuator");
  return a.actdim < 0 ? (a.dyntype != kDynNone ? 1 : 0) : a.actdim;
}

// Control entries an actuator reads (its slice of ctrl).
int ActuatorCtrlNum(const mjcf::ActuatorSpec&) { return 1; }

// Force outputs of an actuator (its slice of actuator_force).
int ActuatorOutNum(const mjcf::ActuatorSpec&) { return 1; }

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

    // Its slices of the controls and of the force outputs.
    m->actuator_ctrladr[i] = ctrladr;
    m->actuator_ctrlnum[i] = ActuatorCtrlNum(a);
    ctrladr += m->actuator_ctrlnum[i];
    m->actuator_outadr[i] = outadr;
    m->actuator_outnum[i] = ActuatorOutNum(a);
    outadr += m->actuator_outnum[i];

    // Transmission and ranges.
    int trnid[2];
    ResolveTarget(a, targets, trnid);
    std::array<double, 2> ctrl = a.ctrlrange, act = a.actrange;
    InheritRange(a, state, *m, trnid, &ctrl, &act);
    Limits(spec, a, ctrl, act, i, m);

    // Types, parameters, activation layout.
    m->actuator_trntype[i] = a.trntype;
    m->actuator_trnid[2 * i] = trnid[0];
    m->actuator_trnid[2 * i + 1] = trnid[1];
    m->actuator_dyntype[i] = a.dyntype;
    m->actuator_gaintype[i] = a.gaintype;
    m->actuator_biastype[i] = a.biastype;
    int actnum = ActuatorActDim(a);
    CheckMuscle(a);
    m->actuator_actnum[i] = actnum;
    m->actuator_actadr[i] = actnum ? adr : -1;
    adr += actnum;
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
