// The actuators that give their joint or tendon target damping and armature (MuJoCo 3.7+
// jnt_actuatorid / tendon_actuatorid): -1 none, an id for exactly one, -2 for several,
// in which case every actuator on that target counts.
#ifndef SIMLAB_ENGINE_ACTUATOR_TARGET_H_
#define SIMLAB_ENGINE_ACTUATOR_TARGET_H_

#include "simlab/model.h"

namespace simlab {

// Calls visit(actuator, gear[0]^2) for each actuator contributing to joint or tendon `id`.
template <typename Visit>
void ForTargetActuators(const Model& m, bool tendon, int id, Visit visit) {
  int owner = tendon ? m.tendon_actuatorid[id] : m.jnt_actuatorid[id];
  if (owner == -1) return;
  for (int i = owner >= 0 ? owner : 0; i < (owner >= 0 ? owner + 1 : m.nactuator); i++) {
    int type = m.actuator_trntype[i];
    bool on_target = tendon ? type == kTrnTendon : (type == kTrnJoint || type == kTrnJointInParent);
    if (!on_target || m.actuator_trnid[2 * i] != id) continue;
    double gear = m.actuator_gear[6 * m.actuator_outadr[i]];
    visit(i, gear * gear);
  }
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_ACTUATOR_TARGET_H_
