// Actuator length ranges (MuJoCo mj_setLengthRange, with the <compiler><lengthrange>
// options). Muscles need the range of their actuator length to normalize it.
//
// Per actuator selected by `mode` (default: muscles only):
//   useexisting: a valid lengthrange given in the model is kept;
//   uselimit:    a limited joint or tendon target lends its range;
//   otherwise the range is found by simulation, as MuJoCo does: from qpos0, push the
//   actuator's transmission with a force that gives a fixed acceleration, with
//   velocities damped, contacts, gravity, springs, dampers, friction loss and actuation
//   off, until the mechanism rests against its limits; the length seen over the last
//   `interval` seconds gives the bound on that side.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "engine/engine.h"
#include "engine/rows.h"
#include "math/dot.h"
#include "mjcf/error.h"
#include "simlab/simlab.h"

namespace simlab::compiler {

namespace {
// Whether the lengthrange mode selects actuator i.
bool Selected(const mjcf::LengthRangeSpec& opt, const Model& m, int i) {
  bool muscle = m.actuator_gaintype[i] == kGainMuscle || m.actuator_biastype[i] == kBiasMuscle;
  bool user = m.actuator_gaintype[i] == kGainUser || m.actuator_biastype[i] == kBiasUser;
  switch (opt.mode) {
    case 0: return false;
    case 1: return muscle;
    case 2: return muscle || user;
    default: return true;
  }
}

// The range of a limited joint or tendon target, if there is one. (MuJoCo 3.5 reads the
// target id as actuator_trnid[i] rather than [2 i]; we read the actuator's own target.)
bool RangeFromLimit(const Model& m, int i, double* range) {
  int id = m.actuator_trnid[2 * i], type = m.actuator_trntype[i];
  const double* source = nullptr;
  if ((type == kTrnJoint || type == kTrnJointInParent) && m.jnt_limited[id]) {
    source = &m.jnt_range[2 * id];
  } else if (type == kTrnTendon && m.tendon_limited[id]) {
    source = &m.tendon_range[2 * id];
  }
  if (!source) return false;
  range[0] = source[0];
  range[1] = source[1];
  return true;
}

// One simulation step pushing actuator i towards side 0 (shorter) or 1 (longer);
// returns its length after the step (MuJoCo's evalAct).
double PushStep(const Model& m, Data& d, const mjcf::LengthRangeSpec& opt, int i, int side) {
  int nv = m.nv;
  double decay = std::exp(-m.opt.timestep / std::max(0.01, opt.timeconst));
  for (double& v : d.qvel) v *= decay;
  Step1(m, d);

  // qfrc_applied along the moment, scaled so that M^-1 qfrc has norm accel.
  int out = m.actuator_outadr[i];
  const double* moment = RowOf(d.actuator_moment, out, nv);
  std::copy(moment, moment + nv, d.qfrc_applied.begin());
  SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), d.qfrc_applied.data());
  auto norm_of_applied = [&d, nv] {
    return std::sqrt(math::Dot(d.qfrc_applied.data(), d.qfrc_applied.data(), nv));
  };
  double scale = (2 * side - 1) * opt.accel / std::max(kMinVal, norm_of_applied());
  for (int v = 0; v < nv; v++) d.qfrc_applied[v] = moment[v] * scale;
  double norm = norm_of_applied();
  if (opt.maxforce > 0 && norm > opt.maxforce) {
    for (double& f : d.qfrc_applied) f *= opt.maxforce / std::max(kMinVal, norm);
  }
  Step2(m, d);
  return d.actuator_length[out];
}

// Simulates both sides for actuator i of `sim`; writes lengthrange or throws.
void SimulateRange(const mjcf::ModelSpec& spec, const Model& sim, int i, double* range) {
  const mjcf::LengthRangeSpec& opt = spec.compiler.lengthrange;
  const mjcf::Source& src = spec.actuators[i].src;
  double lmin[2] = {0, 0}, lmax[2] = {0, 0};
  Data d = MakeData(sim);
  for (int side = 0; side < 2; side++) {
    ResetData(sim, d);
    bool seen = false;
    while (d.time < opt.inttotal) {
      double len = PushStep(sim, d, opt, i, side);
      if (d.time == 0) mjcf::ThrowAt(src, "unstable lengthrange simulation");
      if (d.time > opt.inttotal - opt.interval) {
        if (len < lmin[side] || !seen) lmin[side] = len;
        if (len > lmax[side] || !seen) lmax[side] = len;
        seen = true;
      }
    }
    range[side] = side == 0 ? lmin[0] : lmax[1];
  }

  // The two bounds must be ordered, and each side must have settled.
  double width = range[1] - range[0];
  if (width <= 0) {
    mjcf::ThrowAt(src, "invalid lengthrange (" + std::to_string(range[0]) + ", " +
                           std::to_string(range[1]) + ") found by simulation");
  }
  for (int side = 0; side < 2; side++) {
    if (lmax[side] - lmin[side] > opt.tolrange * width) {
      mjcf::ThrowAt(src, "the lengthrange simulation did not converge (" +
                             std::string(side ? "longer" : "shorter") +
                             " side); give the actuator a lengthrange or limit its joint");
    }
  }
}

}  // namespace

void ComputeLengthRanges(const mjcf::ModelSpec& spec, Model* m) {
  const mjcf::LengthRangeSpec& opt = spec.compiler.lengthrange;

  // The simulation model: only constraints (limits, equalities) and inertia act.
  Model sim = *m;
  sim.opt.disableflags = kDisableFrictionloss | kDisableContact | kDisableSpring |
                         kDisableDamper | kDisableGravity | kDisableActuation;
  if (opt.timestep > 0) sim.opt.timestep = opt.timestep;

  // (actuators of one force output: a length range is a scalar's)
  for (int i = 0; i < m->nactuator; i++) {
    if (m->actuator_outnum[i] != 1) continue;
    double* range = &m->actuator_lengthrange[2 * m->actuator_outadr[i]];
    if (!Selected(opt, *m, i)) continue;
    if (opt.useexisting && range[0] < range[1]) continue;
    if (opt.uselimit && RangeFromLimit(*m, i, range)) continue;
    SimulateRange(spec, sim, i, range);
  }
}

}  // namespace simlab::compiler
