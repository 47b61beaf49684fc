// Actuator transmissions (MuJoCo mj_transmission): each actuator's length l(q) and
// moment arms dl/dq (a row of actuator_moment, nu x nv dense). The actuator's force p
// reaches the joints as qfrc_actuator = moment^T p.
//
//   joint (hinge/slide): l = gear0 q, moment = gear0 at the joint's dof
//   joint (ball):        l = gear . rotvec(q), moment = gear (3 dofs)
//   joint (free):        l = 0, moment = gear (6 dofs); jointinparent rotates the
//                        rotational gear into the parent (world) frame
//   tendon:              l = gear0 ten_length, moment = gear0 ten_J
#include <algorithm>

#include "engine/engine.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// Transmission through joint `id` for actuator i.
void JointTransmission(const Model& m, Data& d, int i, int id, double* moment) {
  const double* gear = &m.actuator_gear[6 * i];
  bool in_parent = m.actuator_trntype[i] == kTrnJointInParent;
  int qadr = m.jnt_qposadr[id], dadr = m.jnt_dofadr[id];
  switch (m.jnt_type[id]) {
    case kJointSlide:
    case kJointHinge:
      d.actuator_length[i] = d.qpos[qadr] * gear[0];
      moment[dadr] = gear[0];
      break;
    case kJointBall: {
      double quat[4], axis[3], gear_axis[3];
      CopyQuat(quat, &d.qpos[qadr]);
      math::NormalizeQuat(quat);
      QuatToVel(axis, quat, 1);
      if (in_parent) {
        NegQuat(quat, quat);
        RotVecQuat(gear_axis, gear, quat);
      } else {
        Copy3(gear_axis, gear);
      }
      d.actuator_length[i] = Dot3(axis, gear_axis);
      Copy3(moment + dadr, gear_axis);
      break;
    }
    case kJointFree: {
      double gear_axis[3];
      if (in_parent) {
        double quat[4];
        CopyQuat(quat, &d.qpos[qadr + 3]);
        math::NormalizeQuat(quat);
        NegQuat(quat, quat);
        RotVecQuat(gear_axis, gear + 3, quat);
      } else {
        Copy3(gear_axis, gear + 3);
      }
      d.actuator_length[i] = 0;
      Copy3(moment + dadr, gear);
      Copy3(moment + dadr + 3, gear_axis);
      break;
    }
  }
}

}  // namespace

void Transmission(const Model& m, Data& d) {
  for (int i = 0; i < m.nu; i++) {
    double* moment = &d.actuator_moment[static_cast<size_t>(i) * m.nv];
    std::fill(moment, moment + m.nv, 0.0);
    int id = m.actuator_trnid[2 * i];
    switch (m.actuator_trntype[i]) {
      case kTrnJoint:
      case kTrnJointInParent:
        JointTransmission(m, d, i, id, moment);
        break;
      case kTrnTendon: {
        double gear = m.actuator_gear[6 * i];
        d.actuator_length[i] = d.ten_length[id] * gear;
        const double* jac = &d.ten_J[static_cast<size_t>(id) * m.nv];
        for (int v = 0; v < m.nv; v++) moment[v] = jac[v] * gear;
        break;
      }
      default:
        // Site, slider-crank and body transmissions are compiled but rejected by the
        // loader until their Jacobians exist; nothing reaches here.
        d.actuator_length[i] = 0;
    }
  }
}

}  // namespace simlab
