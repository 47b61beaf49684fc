// Sensors (MuJoCo's mj_sensorPos, mj_sensorVel, mj_sensorAcc): after each stage of the
// pipeline, every sensor whose needstage is that stage writes its sensor_dim numbers at
// sensor_adr in d.sensordata, then its cutoff clamps them; user sensors are written by
// Data::sensor_callback, plugin sensors by their plugins, after the built-in ones. The
// simple types (reading a quantity the pipeline already has) are computed here; families
// with more work call their own files through the dispatch below. Noise is stored in the
// model but never applied, as in MuJoCo.
#include <algorithm>

#include "engine/engine.h"
#include "engine/sensor.h"
#include "engine/sleep.h"
#include "math/math.h"
#include "simlab/plugin.h"

namespace simlab {

namespace {

// The cutoff clamps real outputs to [-cutoff, cutoff] and positive outputs to at most
// cutoff; contact and fromto sensors use their cutoff otherwise (MuJoCo's apply_cutoff).
void ApplyCutoff(const Model& m, int i, double* out) {
  double cutoff = m.sensor_cutoff[i];
  int type = m.sensor_type[i];
  if (cutoff <= 0 || type == kSensContact || type == kSensGeomFromTo) return;
  for (int j = 0; j < m.sensor_dim[i]; j++) {
    if (m.sensor_datatype[i] == kDataReal) {
      out[j] = std::clamp(out[j], -cutoff, cutoff);
    } else if (m.sensor_datatype[i] == kDataPositive) {
      out[j] = std::min(cutoff, out[j]);
    }
  }
}

// The limit row of a joint or tendon, or -1 when the limit is not active.
int LimitRow(const Data& d, int cnstr_type, int id) {
  for (int j = d.ne + d.nf; j < d.nefc; j++) {
    if (d.efc_type[j] == cnstr_type && d.efc_id[j] == id) return j;
  }
  return -1;
}

// A field of the limit row, or 0 when the limit is not active.
double LimitValue(const Data& d, int cnstr_type, int id, const std::vector<double>& field) {
  int row = LimitRow(d, cnstr_type, id);
  return row < 0 ? 0 : field[row];
}

// framepos and the frame axes, in the world or in the reference object's frame.
void FramePosOrAxis(const Model& m, const Data& d, int i, double* out) {
  int type = m.sensor_type[i];
  ObjectFrame obj = GetObjectFrame(m, d, m.sensor_objtype[i], m.sensor_objid[i]);
  double v[3];
  if (type == kSensFramePos) {
    math::Copy3(v, obj.pos);
  } else {
    int axis = type - kSensFrameXAxis;
    v[0] = obj.mat[axis];
    v[1] = obj.mat[axis + 3];
    v[2] = obj.mat[axis + 6];
  }
  if (m.sensor_refid[i] < 0) return math::Copy3(out, v);
  ObjectFrame ref = GetObjectFrame(m, d, m.sensor_reftype[i], m.sensor_refid[i]);
  if (type == kSensFramePos) math::Sub3(v, v, ref.pos);
  math::MulMatTVec3(out, ref.mat, v);
}

// framequat: the object's orientation, relative to the reference object's if given.
void FrameQuat(const Model& m, const Data& d, int i, double* out) {
  double obj[4];
  ObjectQuat(m, d, m.sensor_objtype[i], m.sensor_objid[i], obj);
  if (m.sensor_refid[i] < 0) return math::CopyQuat(out, obj);
  double ref[4];
  ObjectQuat(m, d, m.sensor_reftype[i], m.sensor_refid[i], ref);
  math::NegQuat(ref, ref);
  math::MulQuat(out, ref, obj);
}

// framelinvel / frameangvel: the object's velocity in the world, or relative to the
// reference object and expressed in its frame (with the rotating-frame term).
void FrameVelocity(const Model& m, const Data& d, int i, double* out) {
  double vel[6];
  ObjectVelocity(m, d, m.sensor_objtype[i], m.sensor_objid[i], vel, false);
  if (m.sensor_refid[i] >= 0) {
    ObjectFrame obj = GetObjectFrame(m, d, m.sensor_objtype[i], m.sensor_objid[i]);
    ObjectFrame ref = GetObjectFrame(m, d, m.sensor_reftype[i], m.sensor_refid[i]);
    double ref_vel[6], rel[6], r[3], cross[3];
    ObjectVelocity(m, d, m.sensor_reftype[i], m.sensor_refid[i], ref_vel, false);
    for (int k = 0; k < 6; k++) rel[k] = vel[k] - ref_vel[k];
    math::Sub3(r, obj.pos, ref.pos);
    math::Cross3(cross, r, ref_vel);
    math::Add3(rel + 3, rel + 3, cross);
    math::MulMatTVec3(vel, ref.mat, rel);
    math::MulMatTVec3(vel + 3, ref.mat, rel + 3);
  }
  math::Copy3(out, m.sensor_type[i] == kSensFrameLinVel ? vel + 3 : vel);
}

// Position-stage sensors.
void ComputePos(const Model& m, Data& d, int i, double* out) {
  int id = m.sensor_objid[i];
  switch (m.sensor_type[i]) {
    case kSensMagnetometer:
      math::MulMatTVec3(out, &d.site_xmat[9 * id], m.opt.magnetic.data());
      break;
    case kSensJointPos: out[0] = d.qpos[m.jnt_qposadr[id]]; break;
    case kSensTendonPos: out[0] = d.ten_length[id]; break;
    case kSensActuatorPos: std::copy_n(&d.actuator_length[m.actuator_outadr[id]], m.sensor_dim[i], out); break;
    case kSensBallQuat:
      math::CopyQuat(out, &d.qpos[m.jnt_qposadr[id]]);
      math::NormalizeQuat(out);
      break;
    case kSensJointLimitPos:
    case kSensTendonLimitPos: {
      int cnstr = m.sensor_type[i] == kSensJointLimitPos ? kCnstrLimitJoint : kCnstrLimitTendon;
      int row = LimitRow(d, cnstr, id);
      out[0] = row < 0 ? 0 : d.efc_pos[row] - d.efc_margin[row];
      break;
    }
    case kSensFramePos:
    case kSensFrameXAxis:
    case kSensFrameYAxis:
    case kSensFrameZAxis: FramePosOrAxis(m, d, i, out); break;
    case kSensFrameQuat: FrameQuat(m, d, i, out); break;
    case kSensSubtreeCom: math::Copy3(out, &d.subtree_com[3 * id]); break;
    case kSensClock: out[0] = d.time; break;
    case kSensCamProjection: CamProjectionSensor(m, d, i, out); break;
    case kSensInsideSite: InsideSiteSensor(m, d, i, out); break;
    case kSensRangefinder: RangefinderSensor(m, d, i, out); break;
    case kSensGeomDist:
    case kSensGeomNormal:
    case kSensGeomFromTo: GeomDistanceSensor(m, d, i, out); break;
    case kSensEPotential:
    case kSensEKinetic: EnergySensor(m, d, i, out); break;
    default: break;
  }
}

// Velocity-stage sensors.
void ComputeVel(const Model& m, Data& d, int i, double* out) {
  int id = m.sensor_objid[i];
  double vel[6];
  switch (m.sensor_type[i]) {
    case kSensVelocimeter:
    case kSensGyro:
      ObjectVelocity(m, d, kObjSite, id, vel, true);
      math::Copy3(out, m.sensor_type[i] == kSensVelocimeter ? vel + 3 : vel);
      break;
    case kSensJointVel: out[0] = d.qvel[m.jnt_dofadr[id]]; break;
    case kSensTendonVel: out[0] = d.ten_velocity[id]; break;
    case kSensActuatorVel: std::copy_n(&d.actuator_velocity[m.actuator_outadr[id]], m.sensor_dim[i], out); break;
    case kSensBallAngVel: math::Copy3(out, &d.qvel[m.jnt_dofadr[id]]); break;
    case kSensJointLimitVel: out[0] = LimitValue(d, kCnstrLimitJoint, id, d.efc_vel); break;
    case kSensTendonLimitVel: out[0] = LimitValue(d, kCnstrLimitTendon, id, d.efc_vel); break;
    case kSensFrameLinVel:
    case kSensFrameAngVel: FrameVelocity(m, d, i, out); break;
    case kSensSubtreeLinVel:
    case kSensSubtreeAngMom: SubtreeMomentumSensor(m, d, i, out); break;
    default: break;
  }
}

// Acceleration-stage sensors.
void ComputeAcc(const Model& m, Data& d, int i, double* out) {
  int id = m.sensor_objid[i];
  switch (m.sensor_type[i]) {
    case kSensActuatorFrc: std::copy_n(&d.actuator_force[m.actuator_outadr[id]], m.sensor_dim[i], out); break;
    case kSensJointActFrc: out[0] = d.qfrc_actuator[m.jnt_dofadr[id]]; break;
    case kSensTendonActFrc: {
      // Every actuator pulling on the tendon.
      double force = 0;
      for (int u = 0; u < m.nactuator; u++) {
        if (m.actuator_trntype[u] == kTrnTendon && m.actuator_trnid[2 * u] == id) {
          force += d.actuator_force[m.actuator_outadr[u]];
        }
      }
      out[0] = force;
      break;
    }
    case kSensJointLimitFrc: out[0] = LimitValue(d, kCnstrLimitJoint, id, d.efc_force); break;
    case kSensTendonLimitFrc: out[0] = LimitValue(d, kCnstrLimitTendon, id, d.efc_force); break;
    case kSensTouch: TouchSensor(m, d, i, out); break;
    case kSensContact: ContactSensor(m, d, i, out); break;
    case kSensTactile: TactileSensor(m, d, i, out); break;
    case kSensAccelerometer: AccelerometerSensor(m, d, i, out); break;
    case kSensForce:
    case kSensTorque: ForceTorqueSensor(m, d, i, out); break;
    case kSensFrameLinAcc:
    case kSensFrameAngAcc: FrameAccSensor(m, d, i, out); break;
    default: break;
  }
}

// What user and plugin sensors of a stage may read beyond the stage itself: the
// subtree momenta at the velocity stage, the bodies' accelerations and interaction
// forces at the acceleration stage (MuJoCo computes them for those sensors first).
void PrepareStage(const Model& m, Data& d, int stage) {
  if (stage == kStageVel && !d.flg_subtreevel) SubtreeVel(m, d);
  if (stage == kStageAcc && !d.flg_rnepost) RnePostConstraint(m, d);
}

// Plugin sensors: each sensor plugin instance of the stage writes all its sensors, then
// their cutoffs apply (MuJoCo's compute_plugin_sensors: a plugin of needstage none runs
// with the position stage, and its sensors, whose stage is none, keep their numbers).
void PluginSensorStage(const Model& m, Data& d, int stage) {
  for (int i = 0; i < m.nplugin; i++) {
    const Plugin& plugin = PluginAt(m.plugin[i]);
    int runs_at = plugin.needstage == kStageNone ? kStagePos : plugin.needstage;
    if (!(plugin.capabilities & kPluginSensor) || runs_at != stage) continue;
    PrepareStage(m, d, stage);
    plugin.compute(m, d, i, kPluginSensor);
    for (int j = 0; j < m.nsensor; j++) {
      if (m.sensor_plugin[j] == i && m.sensor_needstage[j] == stage) {
        ApplyCutoff(m, j, &d.sensordata[m.sensor_adr[j]]);
      }
    }
  }
}

// The sensors of one stage: built-in ones computed, user sensors zeroed and filled by
// the callback, then the plugins' (MuJoCo's mj_sensorPos/Vel/Acc).
void SensorStage(const Model& m, Data& d, int stage) {
  if (m.opt.disableflags & kDisableSensor) return;
  bool any_user = false, any_asleep = AnyAsleep(m, d);
  for (int i = 0; i < m.nsensor; i++) {
    if (m.sensor_needstage[i] != stage || m.sensor_type[i] == kSensPlugin) continue;
    // (a sleeping sensor keeps its last output)
    if (any_asleep && ElementSleepState(m, d, kObjSensor, i) == kAsleep) continue;
    double* out = &d.sensordata[m.sensor_adr[i]];
    if (m.sensor_type[i] == kSensUser) {
      std::fill(out, out + m.sensor_dim[i], 0.0);
      any_user = true;
    } else {
      ComputeOrReadSensor(m, d, i, out);
    }
  }

  // User sensors: the callback writes them, then their cutoffs apply.
  if (any_user) {
    PrepareStage(m, d, stage);
    if (d.sensor_callback) d.sensor_callback(m, d, stage);
    for (int i = 0; i < m.nsensor; i++) {
      if (m.sensor_type[i] == kSensUser && m.sensor_needstage[i] == stage) {
        ApplyCutoff(m, i, &d.sensordata[m.sensor_adr[i]]);
      }
    }
  }
  if (m.nplugin > 0) PluginSensorStage(m, d, stage);
}

}  // namespace

void ComputeSensor(const Model& m, Data& d, int i, double* out) {
  switch (m.sensor_needstage[i]) {
    case kStagePos: ComputePos(m, d, i, out); break;
    case kStageVel: ComputeVel(m, d, i, out); break;
    default: ComputeAcc(m, d, i, out); break;
  }
  ApplyCutoff(m, i, out);
}

void SensorPos(const Model& m, Data& d) { SensorStage(m, d, kStagePos); }
void SensorVel(const Model& m, Data& d) { SensorStage(m, d, kStageVel); }
void SensorAcc(const Model& m, Data& d) { SensorStage(m, d, kStageAcc); }

// ---------------------------------------------------------------- object frames

ObjectFrame GetObjectFrame(const Model& m, const Data& d, int objtype, int objid) {
  ObjectFrame f;
  switch (objtype) {
    case kObjXBody:
      f = {&d.xpos[3 * objid], &d.xmat[9 * objid], objid};
      break;
    case kObjBody:
      f = {&d.xipos[3 * objid], &d.ximat[9 * objid], objid};
      break;
    case kObjGeom:
      f = {&d.geom_xpos[3 * objid], &d.geom_xmat[9 * objid], m.geom_bodyid[objid]};
      break;
    case kObjSite:
      f = {&d.site_xpos[3 * objid], &d.site_xmat[9 * objid], m.site_bodyid[objid]};
      break;
    case kObjCamera:
      f = {&d.cam_xpos[3 * objid], &d.cam_xmat[9 * objid], m.cam_bodyid[objid]};
      break;
    default: break;
  }
  return f;
}

void ObjectQuat(const Model& m, const Data& d, int objtype, int objid, double quat[4]) {
  switch (objtype) {
    case kObjXBody: math::CopyQuat(quat, &d.xquat[4 * objid]); break;
    case kObjBody: math::MulQuat(quat, &d.xquat[4 * objid], &m.body_iquat[4 * objid]); break;
    case kObjGeom:
      math::MulQuat(quat, &d.xquat[4 * m.geom_bodyid[objid]], &m.geom_quat[4 * objid]);
      break;
    case kObjSite:
      math::MulQuat(quat, &d.xquat[4 * m.site_bodyid[objid]], &m.site_quat[4 * objid]);
      break;
    case kObjCamera:
      // The camera's rest orientation on its body (tracking modes are not applied).
      math::MulQuat(quat, &d.xquat[4 * m.cam_bodyid[objid]], &m.cam_quat[4 * objid]);
      break;
    default: break;
  }
}

void ObjectVelocity(const Model& m, const Data& d, int objtype, int objid, double res[6],
                    bool local) {
  // A body welded to the world does not move; the others' cvel moves to the object.
  ObjectFrame f = GetObjectFrame(m, d, objtype, objid);
  if (m.body_weldid[f.body] == 0) return std::fill(res, res + 6, 0.0);
  const double* com = &d.subtree_com[3 * m.body_rootid[f.body]];
  math::TransformSpatial(res, &d.cvel[6 * f.body], false, f.pos, com, local ? f.mat : nullptr);
}

void ObjectAcceleration(const Model& m, const Data& d, int objtype, int objid, double res[6],
                        bool local) {
  // cacc moved to the object, plus the rotating frame's term w x v on the linear part.
  ObjectFrame f = GetObjectFrame(m, d, objtype, objid);
  if (m.body_weldid[f.body] == 0) return std::fill(res, res + 6, 0.0);
  const double* com = &d.subtree_com[3 * m.body_rootid[f.body]];
  const double* rot = local ? f.mat : nullptr;
  double vel[6], correction[3];
  math::TransformSpatial(res, &d.cacc[6 * f.body], false, f.pos, com, rot);
  math::TransformSpatial(vel, &d.cvel[6 * f.body], false, f.pos, com, rot);
  math::Cross3(correction, vel, vel + 3);
  math::Add3(res + 3, res + 3, correction);
}

}  // namespace simlab
