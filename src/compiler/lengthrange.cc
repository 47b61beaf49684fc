// Actuator length ranges (MuJoCo mj_setLengthRange, with the <compiler><lengthrange>
// options). Muscles need the range of their actuator length to normalize it.
//
// Per actuator selected by `mode` (default: muscles only):
//   useexisting: a valid lengthrange given in the model is kept;
//   uselimit:    a limited joint or tendon target lends its range;
//   otherwise MuJoCo finds the range by simulation: pushing the actuator each way with
//   a constant acceleration until it rests against the limits. That needs the limit
//   constraints, which the engine does not have yet, so such a model is rejected.
#include <string>

#include "compiler/compiler.h"
#include "mjcf/error.h"

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

}  // namespace

void ComputeLengthRanges(const mjcf::ModelSpec& spec, Model* m) {
  const mjcf::LengthRangeSpec& opt = spec.compiler.lengthrange;
  for (int i = 0; i < m->nu; i++) {
    double* range = &m->actuator_lengthrange[2 * i];
    if (!Selected(opt, *m, i)) continue;
    if (opt.useexisting && range[0] < range[1]) continue;
    if (opt.uselimit && RangeFromLimit(*m, i, range)) continue;
    mjcf::ThrowAt(spec.actuators[i].src,
                  "computing the actuator lengthrange by simulation is not supported yet "
                  "(it needs limit constraints); set lengthrange on the actuator");
  }
}

}  // namespace simlab::compiler
