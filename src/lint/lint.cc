// simlab lint (simlab/lint.h): each check is a function over the compiled model, the
// state at the chosen keyframe after Forward, and where each element was written.
#include "simlab/lint.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "compiler/compiler.h"
#include "engine/engine.h"
#include "mjcf/reader.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

// ---------------------------------------------------------------- text

// A number in the shortest readable form ("10", "-0.5", "1e-05"), no "-0".
std::string Num(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.4g", x == 0 ? 0.0 : x);
  return buffer;
}

// ---------------------------------------------------------------- what the checks share

// The model, its state at the keyframe, and where its elements were written.
struct Subject {
  const Model& m;
  const Data& d;  // at the keyframe (or the default state), after Forward
  const compiler::ElementSources& src;
  std::vector<LintFinding>* out;

  // "actuator \"grip\"" or "actuator 3".
  std::string Element(ObjType type, const char* kind, int id) const {
    const std::vector<std::string>* names = m.Names(type);
    const bool named = names && id < static_cast<int>(names->size()) && !(*names)[id].empty();
    std::string text = kind;
    text.append(named ? " \"" + (*names)[id] + "\"" : " " + std::to_string(id));
    return text;
  }

  void Add(const std::vector<mjcf::Source>& sources, int id, LintFinding f) const {
    f.id = id;
    if (id >= 0 && id < static_cast<int>(sources.size())) {
      f.file = sources[id].file;
      f.line = sources[id].line;
    }
    out->push_back(std::move(f));
  }

  // Adds f on element `id` of `kind`: its name, kind, file and line filled in.
  void AddOn(ObjType type, const char* kind, const std::vector<mjcf::Source>& sources, int id,
             LintFinding f) const {
    f.element = Element(type, kind, id);
    f.kind = kind;
    Add(sources, id, std::move(f));
  }

  void AddActuator(int i, LintFinding f) const {
    AddOn(kObjActuator, "actuator", src.actuator, i, std::move(f));
  }
};

// A finding of `check` (its element, file and line are filled in where it is added).
LintFinding Finding(const char* check, LintSeverity severity, std::string numbers,
                    std::string meaning, std::string advice) {
  return {check, severity, "", "", 0, std::move(numbers), std::move(meaning), std::move(advice), "", -1};
}

// A one-input, one-output actuator (the lesson's kind), whose numbers are at i.
bool IsSiso(const Model& m, int i) {
  return m.actuator_ctrlnum[i] == 1 && m.actuator_outnum[i] == 1;
}

// A position servo's law: fixed gain kp, affine bias -kp l (and -kv l'), so that
// p = kp (u - l) - kv l'.
bool IsPositionServo(const Model& m, int i) {
  const double* gain = &m.actuator_gainprm[kNGain * i];
  const double* bias = &m.actuator_biasprm[kNBias * i];
  return IsSiso(m, i) && m.actuator_gaintype[i] == kGainFixed &&
         m.actuator_biastype[i] == kBiasAffine && gain[0] > 0 && bias[0] == 0 &&
         bias[1] == -gain[0];
}

// The joint a SISO actuator drives (a hinge or slide through a joint transmission), or -1.
int DrivenScalarJoint(const Model& m, int i) {
  const int type = m.actuator_trntype[i];
  if (type != kTrnJoint && type != kTrnJointInParent) return -1;
  const int j = m.actuator_trnid[2 * i];
  return (m.jnt_type[j] == kJointHinge || m.jnt_type[j] == kJointSlide) ? j : -1;
}

// What the servo is commanded: ctrl, or the activation when the actuator has dynamics.
double ServoInput(const Model& m, const Data& d, int i) {
  if (m.actuator_dyntype[i] == kDynNone) return d.ctrl[m.actuator_ctrladr[i]];
  return d.act[m.actuator_actadr[i] + m.actuator_actnum[i] - 1];
}

// ---------------------------------------------------------------- the lesson's traps

// A general actuator with biasprm but biastype "none": the bias is never applied.
void CheckBiasIgnored(const Subject& s) {
  const Model& m = s.m;
  for (int i = 0; i < m.nactuator; i++) {
    const double* bias = &m.actuator_biasprm[kNBias * i];
    if (m.actuator_biastype[i] != kBiasNone) continue;
    std::string written;
    for (int k = 0; k < 3; k++) {
      if (bias[k] != 0) written += " b" + std::to_string(k) + " = " + Num(bias[k]);
    }
    if (written.empty()) continue;
    s.AddActuator(i, Finding("bias-ignored", LintSeverity::kWarning,
                      "biastype none, biasprm" + written,
                      "biasprm is ignored because biastype defaults to none: the actuator "
                      "applies p = a u only, with no b0 + b1 l + b2 l' term.",
                      "add biastype=\"affine\" (or use the position/velocity shortcut that "
                      "sets it)."));
  }
}

// The load a joint must hold at rest: gravity (qfrc_bias with zero velocity) less what
// its springs give (qfrc_passive), at the joint's dof.
double HoldingLoad(const Model& m, const Data& d, int j) {
  const int dof = m.jnt_dofadr[j];
  return d.qfrc_bias[dof] - d.qfrc_passive[dof];
}

// The span a servo's target covers, in joint units: ctrlrange / gear (actrange / gear
// when the target is an activation, as an intvelocity's), else the joint's range, else
// one radian or metre.
double TargetSpan(const Model& m, int i, int j, double gear) {
  const int c = m.actuator_ctrladr[i];
  if (m.actuator_dyntype[i] != kDynNone) {
    if (m.actuator_actlimited[i]) {
      return std::abs(m.actuator_actrange[2 * i + 1] - m.actuator_actrange[2 * i]) / std::abs(gear);
    }
  } else if (m.actuator_ctrllimited[c]) {
    return std::abs(m.actuator_ctrlrange[2 * c + 1] - m.actuator_ctrlrange[2 * c]) / std::abs(gear);
  }
  if (m.jnt_limited[j]) return m.jnt_range[2 * j + 1] - m.jnt_range[2 * j];
  return 1.0;
}

// A position servo too weak for the load it holds: at rest it sags by load / (kp gear^2),
// a large part of its range ("the servo does nothing"), or its forcerange cannot hold the
// load at all.
void CheckServoTooWeak(const Subject& s) {
  const Model& m = s.m;
  for (int i = 0; i < m.nactuator; i++) {
    const int j = DrivenScalarJoint(m, i);
    if (!IsPositionServo(m, i) || j < 0) continue;
    const double gear = m.actuator_gear[6 * m.actuator_outadr[i]];
    const double kp = m.actuator_gainprm[kNGain * i];
    const double load = HoldingLoad(m, s.d, j);
    if (gear == 0 || load == 0) continue;
    const double force = std::abs(load / gear);  // actuator force that holds the load
    const double sag = std::abs(load) / (kp * gear * gear);
    const double span = TargetSpan(m, i, j, gear);
    const double* range = &m.actuator_forcerange[2 * i];
    const double most = std::max(std::abs(range[0]), std::abs(range[1]));
    const char* unit = m.jnt_type[j] == kJointHinge ? "rad" : "m";
    const std::string load_text = "the joint must hold " + Num(std::abs(load)) +
                                  (m.jnt_type[j] == kJointHinge ? " N m" : " N") +
                                  " against gravity at rest";
    if (m.actuator_forcelimited[i] && force > most) {
      s.AddActuator(i, Finding("servo-cannot-hold", LintSeverity::kWarning,
                        load_text + "; with gear " + Num(gear) + " that is an actuator force of " +
                            Num(force) + ", beyond forcerange [" + Num(range[0]) + ", " +
                            Num(range[1]) + "]",
                        "the force clamp stops the servo short of the force that holds the "
                        "load: the link falls whatever ctrl says.",
                        "widen forcerange, raise gear, or add gravity compensation."));
    } else if (sag > 0.1 * span) {
      s.AddActuator(i, Finding("servo-too-weak", LintSeverity::kWarning,
                        load_text + "; kp " + Num(kp) + ", gear " + Num(gear) +
                            ": at rest it sags " + Num(sag) + " " + unit + " from its target, " +
                            Num(100 * sag / span) + "% of its range of " + Num(span) + " " + unit,
                        "the servo does nothing: kp is too small for the load, so the joint "
                        "settles far from the commanded position.",
                        "raise kp (with kv, or dampratio, to keep it damped) until the sag "
                        "kp would leave is small."));
    }
  }
}

// A position servo whose input is 0 at the start while its joint is elsewhere: ctrl = 0
// commands position 0, and the robot moves although ctrl is zero.
void CheckZeroTarget(const Subject& s) {
  const Model& m = s.m;
  for (int i = 0; i < m.nactuator; i++) {
    if (!IsPositionServo(m, i)) continue;
    const double u = ServoInput(m, s.d, i);
    const double length = s.d.actuator_length[m.actuator_outadr[i]];
    if (u != 0 || std::abs(length) < 1e-6) continue;
    const std::string input = m.actuator_dyntype[i] == kDynNone ? "ctrl" : "its activation";
    s.AddActuator(i, Finding("servo-targets-zero", LintSeverity::kWarning,
                      input + " = 0 at the start, while the actuator length is " + Num(length),
                      "a position servo's input is a target position: ctrl = 0 commands "
                      "position 0, so the robot moves although ctrl is zero.",
                      "start ctrl at the joint's position (a keyframe's ctrl), or use a "
                      "motor if 0 should mean no force."));
  }
}

// A filter integrated by Euler faster than the timestep: explicit Euler of
// act' = (u - act) / tau overshoots for tau < timestep and diverges for tau < timestep / 2.
void CheckEulerFilter(const Subject& s) {
  const Model& m = s.m;
  const double dt = m.opt.timestep;
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_dyntype[i] != kDynFilter) continue;
    const double tau = m.actuator_dynprm[kNDyn * i];
    if (tau <= 0 || tau >= dt) continue;
    const bool diverges = tau < dt / 2;
    s.AddActuator(i, Finding("filter-faster-than-timestep", LintSeverity::kWarning,
                      "dyntype filter, time constant dynprm[0] = " + Num(tau) + " s, timestep " +
                          Num(dt) + " s (ratio " + Num(dt / tau) + ")",
                      std::string("the Euler-integrated filter ") +
                          (diverges ? "diverges: each step multiplies the activation's error by "
                                    : "overshoots: each step multiplies the activation's error by ") +
                          Num(1 - dt / tau) + ".",
                      "use dyntype=\"filterexact\" (exact for any timestep), or a time constant "
                      "of several timesteps."));
  }
}

// gear != 1: actuator_force is in actuator space; the joint or tendon gets gear times it.
void CheckGear(const Subject& s) {
  const Model& m = s.m;
  for (int i = 0; i < m.nactuator; i++) {
    const int type = m.actuator_trntype[i];
    if (!IsSiso(m, i) || (type != kTrnJoint && type != kTrnJointInParent && type != kTrnTendon)) continue;
    const double gear = m.actuator_gear[6 * m.actuator_outadr[i]];
    if (gear == 1) continue;
    s.AddActuator(i, Finding("gear-scales-force", LintSeverity::kNote, "gear " + Num(gear),
                      "actuator_force is the force in actuator space; the " +
                          std::string(type == kTrnTendon ? "tendon" : "joint") + " gets gear x "
                          "actuator_force (" + Num(gear) + " x), which qfrc_actuator holds.",
                      "log the joint torque from qfrc_actuator (or gear x actuator_force), not "
                      "actuator_force."));
  }
}

// A keyframe's ctrl outside ctrlrange: the engine clamps it, and ctrl keeps what was
// written, so logging ctrl logs the wrong action.
void CheckKeyCtrlRange(const Subject& s) {
  const Model& m = s.m;
  for (int k = 0; k < m.nkey; k++) {
    for (int c = 0; c < m.nu; c++) {
      if (!m.actuator_ctrllimited[c]) continue;
      const double u = m.key_ctrl[k * m.nu + c];
      const double lo = m.actuator_ctrlrange[2 * c], hi = m.actuator_ctrlrange[2 * c + 1];
      if (u >= lo && u <= hi) continue;
      s.AddOn(kObjKey, "keyframe", s.src.key, k, Finding("key-ctrl-clamped", LintSeverity::kWarning,
                    "ctrl[" + std::to_string(c) + "] = " + Num(u) + ", ctrlrange [" + Num(lo) +
                        ", " + Num(hi) + "]",
                    "the engine clamps ctrl to ctrlrange before using it, but data.ctrl keeps "
                    "the value written: a log of ctrl shows an action that was not applied.",
                    "keep keyframe controls inside ctrlrange (and log the clamped value)."));
    }
  }
}

// The largest force actuator i can apply (in actuator space), or 0 when nothing bounds
// it: its forcerange, else a servo's kp times its ctrl span, else a fixed gain times its
// largest ctrl.
double LargestForce(const Model& m, int i) {
  if (m.actuator_forcelimited[i]) {
    return std::max(std::abs(m.actuator_forcerange[2 * i]), std::abs(m.actuator_forcerange[2 * i + 1]));
  }
  const int c = m.actuator_ctrladr[i];
  if (m.actuator_gaintype[i] != kGainFixed || !m.actuator_ctrllimited[c]) return 0;
  const double gain = std::abs(m.actuator_gainprm[kNGain * i]);
  const double lo = m.actuator_ctrlrange[2 * c], hi = m.actuator_ctrlrange[2 * c + 1];
  if (IsPositionServo(m, i)) return gain * (hi - lo);
  return m.actuator_biastype[i] == kBiasNone ? gain * std::max(std::abs(lo), std::abs(hi)) : 0;
}

// A joint equality that has to transmit an actuator's force stretches ("the fingers drift
// apart under load"). The force it carries when actuator i pushes with p: the part of
// the actuator's generalized force tau = moment p that the constraint must hold back,
// f = (J M^-1 tau) / A with A = J M^-1 J' (J: the equality's row, q1 - c q2). At rest a
// soft constraint carrying f sits r = f R / k from its target: MuJoCo's regularizer
// R = (1 - d) / d A at impedance d (solimp's dmin, or dmax past its width), stiffness
// k = 1 / (dmax^2 tc^2 dr^2) from solref (tc at least two timesteps).
void CheckEqualityStretch(const Subject& s) {
  const Model& m = s.m;
  const Data& d = s.d;
  std::vector<double> row(m.nv), solved(m.nv);
  for (int e = 0; e < m.neq; e++) {
    const int j1 = m.eq_obj1id[e], j2 = m.eq_obj2id[e];
    if (m.eq_type[e] != kEqJoint || j2 < 0) continue;
    const double* solref = &m.eq_solref[kNRef * e];
    const double* solimp = &m.eq_solimp[kNImp * e];
    if (solref[0] <= 0) continue;  // (stiffness given directly)
    // The equality's row and A = J M^-1 J'.
    std::fill(row.begin(), row.end(), 0.0);
    row[m.jnt_dofadr[j1]] = 1;
    row[m.jnt_dofadr[j2]] -= m.eq_data[kNEqData * e + 1];  // (polycoef[1])
    solved = row;
    SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), solved.data());
    double a = 0;
    for (int k = 0; k < m.nv; k++) a += row[k] * solved[k];
    if (a <= 0) continue;
    // The actuator that drives one of the coupled joints and loads the equality most
    // (actuators elsewhere reach it only through inertia).
    double load = 0;
    int by = -1;
    const int dof1 = m.jnt_dofadr[j1], dof2 = m.jnt_dofadr[j2];
    for (int i = 0; i < m.nactuator; i++) {
      if (!IsSiso(m, i)) continue;
      const double* moment = &d.actuator_moment[static_cast<size_t>(m.actuator_outadr[i]) * m.nv];
      if (moment[dof1] == 0 && moment[dof2] == 0) continue;
      double carried = 0;
      for (int k = 0; k < m.nv; k++) carried += solved[k] * moment[k];
      carried = std::abs(carried * LargestForce(m, i)) / a;
      if (carried > load) load = carried, by = i;
    }
    if (by < 0 || load < 1e-9) continue;
    const double tc = std::max(solref[0], 2 * m.opt.timestep), dr = solref[1];
    const double dmin = solimp[0], dmax = solimp[1];
    const double stiffness = 1 / (dmax * dmax * tc * tc * dr * dr);
    // (the impedance is dmin at no violation and dmax from solimp's width on)
    const auto stretch_at = [&](double d) { return load * (1 - d) / d * a / stiffness; };
    const double stretch = stretch_at(dmin) > solimp[2] ? std::max(solimp[2], stretch_at(dmax)) : stretch_at(dmin);
    const bool hinge = m.jnt_type[j1] == kJointHinge;
    const double span = m.jnt_limited[j1] ? m.jnt_range[2 * j1 + 1] - m.jnt_range[2 * j1] : 0;
    // (visible: 5% of the joint's range, else 0.01 rad or 5 mm)
    const double allowed = span > 0 ? 0.05 * span : (hinge ? 0.01 : 0.005);
    if (stretch <= allowed) continue;
    s.AddOn(kObjEquality, "equality", s.src.equality, e, Finding(
        "equality-stretches", LintSeverity::kWarning,
        s.Element(kObjActuator, "actuator", by) + " can load it with " + Num(load) +
            (hinge ? " N m" : " N") + "; solref " + Num(solref[0]) + " " + Num(dr) + ", solimp " +
            Num(dmin) + " " + Num(dmax) + ": at rest it stretches " + Num(stretch) +
            (hinge ? " rad" : " m") + (span > 0 ? " (" + Num(100 * stretch / span) + "% of the joint's range)" : ""),
        "the equality has to transmit the actuator's force, and a soft constraint "
        "transmitting large forces stretches visibly: the joints it couples drift apart "
        "under load.",
        "drive the average and constrain the difference (one actuator on a tendon over both "
        "joints), or stiffen the equality's solref (a smaller time constant)."));
  }
}

// ---------------------------------------------------------------- what users check

// A position servo stiffer than the timestep allows: on a joint of inertia I (M's
// diagonal, armature included) its spring has frequency w = sqrt(kp gear^2 / I), and the
// explicit step is unstable from w dt = 2 on (damping other than the joint's own does not
// help: kv is explicit too). Warned from w dt = 1, when the servo already rings.
void CheckServoStability(const Subject& s) {
  const Model& m = s.m;
  if (m.opt.integrator != kIntegratorEuler) return;  // (implicit integrators take kv in)
  const double dt = m.opt.timestep;
  for (int i = 0; i < m.nactuator; i++) {
    const int j = DrivenScalarJoint(m, i);
    if (!IsPositionServo(m, i) || j < 0) continue;
    const int dof = m.jnt_dofadr[j];
    const double inertia = s.d.qM[m.dof_Madr[dof]];
    const double gear = m.actuator_gear[6 * m.actuator_outadr[i]];
    const double kp = m.actuator_gainprm[kNGain * i];
    if (inertia <= 0) continue;
    const double w = std::sqrt(kp * gear * gear / inertia);
    if (w * dt < 1) continue;
    s.AddActuator(i, Finding("servo-unstable", LintSeverity::kWarning,
                             "kp " + Num(kp) + ", gear " + Num(gear) + ", joint inertia " + Num(inertia) +
                                 " (armature " + Num(m.dof_armature[dof]) + ", damping " +
                                 Num(m.dof_damping[dof]) + "): w dt = " + Num(w * dt) +
                                 " (w = " + Num(w) + " rad/s, timestep " + Num(dt) + " s)",
                             std::string(w * dt >= 2 ? "the servo is beyond the stability bound "
                                                       "w dt < 2 of the explicit step: it diverges."
                                                     : "the servo is near the stability bound w dt < 2 "
                                                       "of the explicit step: it rings and nearly diverges."),
                             "add armature (or joint damping), lower kp, shorten the timestep, or "
                             "use the implicitfast integrator."));
  }
}

// A moving body (and everything it carries) nearly massless against the model's mean
// body mass, with no armature on its dofs: a small force gives it a huge acceleration,
// so it jitters or blows up at ordinary timesteps.
void CheckNearlyMassless(const Subject& s) {
  const Model& m = s.m;
  const double light = 1e-3 * m.stat.meanmass;
  for (int b = 1; b < m.nbody; b++) {
    if (m.body_dofnum[b] == 0 || m.body_subtreemass[b] >= light) continue;
    double armature = 0;
    for (int k = 0; k < m.body_dofnum[b]; k++) armature += m.dof_armature[m.body_dofadr[b] + k];
    if (armature > 0) continue;
    s.AddOn(kObjBody, "body", s.src.body, b,
            Finding("nearly-massless", LintSeverity::kWarning,
                    "it moves, with " + Num(m.body_subtreemass[b]) + " kg in all (itself and what it "
                    "carries), against a mean body mass of " + Num(m.stat.meanmass) + " kg, and no armature",
                    "a nearly massless moving body gets huge accelerations from small forces: it "
                    "jitters, or the simulation diverges.",
                    "give it a realistic mass (inertial or geom mass), or armature on its joints."));
  }
}

// A joint whose actuatorfrcrange (limited with autolimits as soon as it is given) clamps
// the actuators' total force below what they can apply: qfrc_actuator stops at the clamp
// while actuator_force shows the unclamped force.
void CheckJointForceClamp(const Subject& s) {
  const Model& m = s.m;
  for (int i = 0; i < m.nactuator; i++) {
    const int j = DrivenScalarJoint(m, i);
    if (j < 0 || !m.jnt_actfrclimited[j]) continue;
    const double gear = m.actuator_gear[6 * m.actuator_outadr[i]];
    const double most = std::abs(gear) * LargestForce(m, i);
    const double lo = m.jnt_actfrcrange[2 * j], hi = m.jnt_actfrcrange[2 * j + 1];
    if (most <= std::max(std::abs(lo), std::abs(hi))) continue;
    s.AddActuator(i, Finding("joint-clamps-force", LintSeverity::kWarning,
                             "it can apply " + Num(most) + " at " + s.Element(kObjJoint, "joint", j) +
                                 ", whose actuatorfrcrange is [" + Num(lo) + ", " + Num(hi) + "]",
                             "the joint clamps the total actuator force (a fourth clamp, after "
                             "ctrlrange, actrange and forcerange): qfrc_actuator stops at the joint's "
                             "range while actuator_force shows the unclamped force.",
                             "read the joint's force from qfrc_actuator, or widen actuatorfrcrange "
                             "if the clamp was not meant."));
  }
}

// A geom set up to collide (nonzero contype or conaffinity), in a model whose other
// bodies have colliding geoms, whose bits match none of theirs, and that no <pair> names:
// it collides with nothing.
void CheckGeomsCollideWithNothing(const Subject& s) {
  const Model& m = s.m;
  std::vector<bool> paired(m.ngeom, false);
  for (int p = 0; p < m.npair; p++) paired[m.pair_geom1[p]] = paired[m.pair_geom2[p]] = true;
  for (int g = 0; g < m.ngeom; g++) {
    const int type = m.geom_contype[g], affinity = m.geom_conaffinity[g];
    if ((type == 0 && affinity == 0) || paired[g]) continue;
    // (only where other bodies have geoms that collide: a lone body has nothing to meet)
    bool others = false, match = false;
    for (int h = 0; h < m.ngeom && !match; h++) {
      if (h == g || m.geom_bodyid[h] == m.geom_bodyid[g]) continue;
      others = others || m.geom_contype[h] || m.geom_conaffinity[h];
      match = (type & m.geom_conaffinity[h]) || (affinity & m.geom_contype[h]);
    }
    if (match || !others) continue;
    s.AddOn(kObjGeom, "geom", s.src.geom, g, Finding("collides-with-nothing", LintSeverity::kWarning,
                            "contype " + std::to_string(type) + ", conaffinity " + std::to_string(affinity) +
                                ": no geom of another body has a matching bit",
                            "contacts need contype of one geom to share a bit with conaffinity of "
                            "the other: this geom never touches anything.",
                            "give it a contype/conaffinity bit the other geoms share, or set both "
                            "to 0 if it is only visual."));
  }
}

// A root body that asks to sleep (sleep="allowed" or "init") in a model that does not
// enable sleeping: the attribute does nothing, and the tree is simulated all the time.
void CheckSleepIgnored(const Subject& s) {
  const Model& m = s.m;
  if (m.opt.enableflags & kEnableSleep) return;
  for (int t = 0; t < m.ntree; t++) {
    const int policy = m.tree_sleep_policy[t];
    if (policy != kSleepAllowed && policy != kSleepInit) continue;
    const char* asked = policy == kSleepInit ? "init" : "allowed";
    s.AddOn(kObjBody, "body", s.src.body, m.tree_bodyadr[t],
            Finding("sleep-ignored", LintSeverity::kWarning,
                    std::string("sleep=\"") + asked + "\", but the model's <option><flag sleep> is not enabled",
                    "sleeping is off unless the model enables it: the body never sleeps, and "
                    "sleep=\"init\" does not start it asleep.",
                    "add <option><flag sleep=\"enable\"/></option>, or drop the attribute."));
  }
}

// A keyframe whose qpos puts a limited joint outside its range: the limit pushes it back
// at the first step.
void CheckKeyQposRange(const Subject& s) {
  const Model& m = s.m;
  for (int k = 0; k < m.nkey; k++) {
    for (int j = 0; j < m.njnt; j++) {
      if (!m.jnt_limited[j] || (m.jnt_type[j] != kJointHinge && m.jnt_type[j] != kJointSlide)) continue;
      const double q = m.key_qpos[k * m.nq + m.jnt_qposadr[j]];
      const double lo = m.jnt_range[2 * j], hi = m.jnt_range[2 * j + 1];
      const double excess = std::max(lo - q, q - hi);
      if (excess <= 1e-9) continue;
      // (a little past the range, as a state saved from a simulation with soft limits
      // often is: a note; further: a warning)
      const bool slight = excess < 0.02 * (hi - lo);
      s.AddOn(kObjKey, "keyframe", s.src.key, k, Finding("key-outside-range",
                    slight ? LintSeverity::kNote : LintSeverity::kWarning,
                    s.Element(kObjJoint, "joint", j) + " at " + Num(q) + ", range [" + Num(lo) +
                        ", " + Num(hi) + "], " + Num(excess) + " past it",
                    std::string("the keyframe starts the joint outside its range") +
                        (slight ? " (slightly, as a state saved from a simulation with soft "
                                  "limits can be)" : "") +
                        ": the limit constraint pushes it back at the first step.",
                    "move the keyframe's qpos inside the range (or widen the range)."));
    }
  }
}

// The unit of an equality's violation: a joint equality's joint's, metres for connect and
// tendon, both for weld.
std::string EqualityUnit(const Model& m, int e) {
  if (m.eq_type[e] == kEqWeld) return "(m, rad)";
  if (m.eq_type[e] == kEqJoint && m.jnt_type[m.eq_obj1id[e]] == kJointHinge) return "rad";
  return "m";
}

// A keyframe whose qpos breaks an equality constraint (by more than 1 mm or 1 mrad, more
// than a state saved from a simulation holds): the constraint snaps it back at the first
// step. Each keyframe's rows are made by the engine (Forward at the keyframe).
void CheckKeyEqualities(const Subject& s) {
  const Model& m = s.m;
  if (m.neq == 0) return;
  Data d = MakeData(m);
  for (int k = 0; k < m.nkey; k++) {
    ResetDataKeyframe(m, d, k);
    Forward(m, d);
    std::vector<double> worst(m.neq, 0.0);
    for (int r = 0; r < d.nefc; r++) {
      if (d.efc_type[r] != kCnstrEquality) continue;
      worst[d.efc_id[r]] = std::max(worst[d.efc_id[r]], std::abs(d.efc_pos[r]));
    }
    for (int e = 0; e < m.neq; e++) {
      if (worst[e] <= 1e-3) continue;
      s.AddOn(kObjKey, "keyframe", s.src.key, k,
              Finding("key-breaks-equality", LintSeverity::kWarning,
                      s.Element(kObjEquality, "equality", e) + " is violated by " + Num(worst[e]) +
                          " " + EqualityUnit(m, e) + " at the keyframe",
                      "the keyframe's qpos does not satisfy the equality: the constraint snaps "
                      "the joints together at the first step, with a jolt.",
                      "set the keyframe's qpos so that the equality holds (for a joint "
                      "equality: q1 = polycoef(q2))."));
    }
  }
}

// ---------------------------------------------------------------- the spec's checks

// limited="false" beside a range: the range is ignored (joints here, actuators below).
void VisitJoints(const mjcf::BodySpec& body, std::vector<LintFinding>* out) {
  for (const auto& j : body.joints) {
    if (j.limited != mjcf::kFalse || !(j.range[0] < j.range[1])) continue;
    out->push_back({"range-ignored", LintSeverity::kWarning,
                    "joint" + (j.src.name.empty() ? std::string() : " \"" + j.src.name + "\""),
                    j.src.file, j.src.line,
                    "limited=\"false\", range [" + Num(j.range[0]) + ", " + Num(j.range[1]) + "]",
                    "the range is ignored: the joint is not limited.",
                    "remove limited=\"false\" (with autolimits the range then limits it).", "", -1});
  }
  for (const auto& child : body.bodies) VisitJoints(*child, out);
}

void CheckRangesSwitchedOff(const mjcf::ModelSpec& spec, std::vector<LintFinding>* out) {
  VisitJoints(spec.world, out);
  for (const mjcf::ActuatorSpec& a : spec.actuators) {
    const std::string element = a.src.tag + (a.src.name.empty() ? "" : " \"" + a.src.name + "\"");
    if (a.ctrllimited == mjcf::kFalse && a.ctrlrange[0] < a.ctrlrange[1]) {
      out->push_back({"range-ignored", LintSeverity::kWarning, element, a.src.file, a.src.line,
                      "ctrllimited=\"false\", ctrlrange [" + Num(a.ctrlrange[0]) + ", " +
                          Num(a.ctrlrange[1]) + "]",
                      "the ctrlrange is ignored: ctrl is not clamped.",
                      "remove ctrllimited=\"false\".", "", -1});
    }
    if (a.forcelimited == mjcf::kFalse && a.forcerange[0] < a.forcerange[1]) {
      out->push_back({"range-ignored", LintSeverity::kWarning, element, a.src.file, a.src.line,
                      "forcelimited=\"false\", forcerange [" + Num(a.forcerange[0]) + ", " +
                          Num(a.forcerange[1]) + "]",
                      "the forcerange is ignored: the force is not clamped.",
                      "remove forcelimited=\"false\".", "", -1});
    }
  }
}

// Default classes that no element uses.
void CheckUnusedClasses(const mjcf::ModelSpec& spec, std::vector<LintFinding>* out) {
  std::vector<mjcf::Source> unused = spec.unused_classes;
  std::sort(unused.begin(), unused.end(),
            [](const mjcf::Source& a, const mjcf::Source& b) { return a.line < b.line; });
  for (const mjcf::Source& c : unused) {
    out->push_back({"unused-class", LintSeverity::kNote, "default class \"" + c.name + "\"", c.file,
                    c.line, "no element names it (class= or childclass=), nor a class nested in it",
                    "its values reach no element: a misspelt class name elsewhere, or a class "
                    "left over.",
                    "name it where it was meant to apply, or remove it.", "", -1});
  }
}

// A model that follows MuJoCo 3.12 (Model::release): where it is, what that changes, and
// what to compare it with.
void CheckFollowsNewerMuJoCo(const Model& m, const mjcf::ModelSpec& spec,
                             std::vector<LintFinding>* out) {
  if (m.release != Release::k3_12) return;
  // (the construct the reader found, else the bending flex pinned to a static body)
  bool construct = !spec.newer_construct.tag.empty();
  mjcf::Source at = spec.newer_construct;
  if (!construct) {
    const mjcf::FlexSpec* pinned = compiler::FlexBendingOnStaticPin(spec, [&m](const std::string& name) {
      int id = m.NameToId(kObjBody, name);
      return id < 0 ? -1 : m.body_jntnum[id];
    });
    if (pinned) at = pinned->src;
  }
  std::string why = construct ? "<" + at.tag + "> uses what only MuJoCo 3.12 defines"
                              : "a bending flex pinned to a static body (MuJoCo 3.5.1 refuses it)";
  out->push_back({"follows-mujoco-3.12", LintSeverity::kNote,
                  "<" + at.tag + (at.name.empty() ? "" : " \"" + at.name + "\"") + ">", at.file,
                  at.line, why,
                  "MuJoCo 3.5.1 cannot run this model, so simlab follows MuJoCo 3.12 where the "
                  "two differ: flex contacts thinned to 50 per collision pair, 3.12's convex "
                  "collider (GJK, EPA), 3.12's solver iteration and rounding, implicitfast's "
                  "own solve of free bodies.",
                  "compare it with MuJoCo 3.12 or newer, not 3.5.1.", "", -1});
}

// A hinge range that reads like radians (within 2 pi, not in whole degrees) while the
// compiler reads degrees (the default): range="-1.57 1.57" is then +-1.57 degrees.
void VisitHingeRanges(const mjcf::BodySpec& body, std::vector<LintFinding>* out) {
  for (const auto& j : body.joints) {
    const double most = std::max(std::abs(j.range[0]), std::abs(j.range[1]));
    const bool whole = j.range[0] == std::round(j.range[0]) && j.range[1] == std::round(j.range[1]);
    if (j.type != kJointHinge || !(j.range[0] < j.range[1]) || most > 2 * M_PI + 1e-9 || whole) continue;
    const double rad = M_PI / 180;
    out->push_back({"range-in-degrees", LintSeverity::kNote,
                    "joint" + (j.src.name.empty() ? std::string() : " \"" + j.src.name + "\""),
                    j.src.file, j.src.line,
                    "range [" + Num(j.range[0]) + ", " + Num(j.range[1]) + "] with <compiler "
                    "angle=\"degree\"> (the default): [" + Num(j.range[0] * rad) + ", " +
                    Num(j.range[1] * rad) + "] rad",
                    "the range is read in degrees: if it was meant in radians, the joint can "
                    "barely move.",
                    "if so, write it in degrees, or set <compiler angle=\"radian\">.", "", -1});
  }
  for (const auto& child : body.bodies) VisitHingeRanges(*child, out);
}

void CheckRangesInDegrees(const mjcf::ModelSpec& spec, std::vector<LintFinding>* out) {
  if (spec.compiler.degree) VisitHingeRanges(spec.world, out);
}

// The model read and compiled, with its elements' sources.
struct Loaded {
  mjcf::ModelSpec spec;
  compiler::ElementSources sources;
  Model m;
};

Loaded Load(const std::string& path) {
  Loaded loaded{mjcf::ReadMjcfFile(path), {}, {}};
  loaded.m = compiler::Compile(loaded.spec, &loaded.sources);
  return loaded;
}

}  // namespace

int LintReport::Warnings() const {
  int n = 0;
  for (const LintFinding& f : findings) n += f.severity == LintSeverity::kWarning;
  return n;
}

const char* LintSeverityName(LintSeverity severity) {
  return severity == LintSeverity::kWarning ? "warning" : "note";
}

LintReport LintFile(const std::string& path, int key) {
  Loaded loaded = Load(path);
  const Model& m = loaded.m;
  if (key < -1 || key >= m.nkey) {
    throw Error(path + ": no keyframe " + std::to_string(key) + " (the model has " +
                std::to_string(m.nkey) + ")");
  }
  // The state the load checks read: the keyframe, at rest (gravity only in qfrc_bias).
  Data d = MakeData(m);
  if (key >= 0) ResetDataKeyframe(m, d, key);
  std::fill(d.qvel.begin(), d.qvel.end(), 0.0);
  Forward(m, d);

  LintReport report{path, key, {}};
  const Subject subject{m, d, loaded.sources, &report.findings};
  CheckBiasIgnored(subject);
  CheckServoTooWeak(subject);
  CheckZeroTarget(subject);
  CheckEulerFilter(subject);
  CheckEqualityStretch(subject);
  CheckKeyCtrlRange(subject);
  CheckKeyQposRange(subject);
  CheckKeyEqualities(subject);
  CheckServoStability(subject);
  CheckNearlyMassless(subject);
  CheckJointForceClamp(subject);
  CheckGeomsCollideWithNothing(subject);
  CheckSleepIgnored(subject);
  CheckRangesSwitchedOff(loaded.spec, &report.findings);
  CheckRangesInDegrees(loaded.spec, &report.findings);
  CheckUnusedClasses(loaded.spec, &report.findings);
  CheckFollowsNewerMuJoCo(m, loaded.spec, &report.findings);
  CheckGear(subject);
  return report;
}

std::string LintText(const LintReport& report) {
  std::string text;
  for (const LintFinding& f : report.findings) {
    text += f.file + ":" + std::to_string(f.line) + ": " + LintSeverityName(f.severity) + ": " +
            f.element + " [" + f.check + "]\n";
    text += "  " + f.numbers + "\n  " + f.meaning + "\n  fix: " + f.advice + "\n";
  }
  const int warnings = report.Warnings();
  const int notes = static_cast<int>(report.findings.size()) - warnings;
  text += report.file + (report.key >= 0 ? " (keyframe " + std::to_string(report.key) + ")" : "") +
          ": " + std::to_string(warnings) + " warning" + (warnings == 1 ? "" : "s") + ", " +
          std::to_string(notes) + " note" + (notes == 1 ? "" : "s") + "\n";
  return text;
}

}  // namespace simlab
