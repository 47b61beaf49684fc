// Sensors (MuJoCo's mjCSensor::Compile): resolve the sensorized and reference objects,
// check that each type is attached to what it can measure, give every sensor MuJoCo's
// data type, stage and output size (a plugin sensor's from its plugin), and lay out
// sensordata and the history buffer.
#include <algorithm>
#include <cstdint>
#include <string>

#include "compiler/compiler.h"
#include "mjcf/error.h"
#include "mjcf/limits.h"

namespace simlab::compiler {

using mjcf::SensorSpec;
using mjcf::ThrowAt;

namespace {

// The stage after which a sensor can be computed (MuJoCo's sensorNeedstage).
int NeedStage(int type) {
  switch (type) {
    case kSensTouch: case kSensAccelerometer: case kSensForce: case kSensTorque:
    case kSensActuatorFrc: case kSensJointActFrc: case kSensTendonActFrc:
    case kSensJointLimitFrc: case kSensTendonLimitFrc: case kSensFrameLinAcc:
    case kSensFrameAngAcc: case kSensContact: case kSensTactile:
      return kStageAcc;
    case kSensVelocimeter: case kSensGyro: case kSensJointVel: case kSensTendonVel:
    case kSensActuatorVel: case kSensBallAngVel: case kSensJointLimitVel:
    case kSensTendonLimitVel: case kSensFrameLinVel: case kSensFrameAngVel:
    case kSensSubtreeLinVel: case kSensSubtreeAngMom:
      return kStageVel;
    default:
      return kStagePos;
  }
}

// The kind of numbers a sensor reports (MuJoCo's sensorDatatype).
int SensorDataType(int type) {
  switch (type) {
    case kSensTouch: case kSensInsideSite: return kDataPositive;
    case kSensFrameXAxis: case kSensFrameYAxis: case kSensFrameZAxis: case kSensGeomNormal:
      return kDataAxis;
    case kSensBallQuat: case kSensFrameQuat: return kDataQuaternion;
    default: return kDataReal;
  }
}

// Number of set bits of a data mask, each field's width given.
int MaskedSize(int mask, const int* widths, int nfield) {
  int size = 0;
  for (int k = 0; k < nfield; k++) {
    if (mask & (1 << k)) size += widths[k];
  }
  return size;
}

// Numbers one contact adds to a contact sensor: found, force, torque, dist, pos,
// normal, tangent (MuJoCo's mju_condataSize).
int ContactDataSize(int mask) {
  static const int kWidths[kNConData] = {1, 3, 3, 1, 3, 3, 3};
  return MaskedSize(mask, kWidths, kNConData);
}

// Numbers one ray adds to a rangefinder: dist, dir, origin, point, normal, depth.
int RayDataSize(int mask) {
  static const int kWidths[kNRayData] = {1, 3, 3, 3, 3, 1};
  return MaskedSize(mask, kWidths, kNRayData);
}

// Rays a rangefinder casts: one from a site, one per pixel from a camera.
int64_t RayCount(const Model& m, const SensorSpec& s, int objid) {
  if (s.objtype != kObjCamera) return 1;
  return int64_t{m.cam_resolution[2 * objid]} * m.cam_resolution[2 * objid + 1];
}

// Output size (MuJoCo's mjs_sensorDim), in 64 bits: attributes can make it overflow an
// int (see CheckDataBudget).
int64_t SensorDim(const Model& m, const SensorSpec& s, int objid) {
  switch (s.type) {
    case kSensCamProjection: return 2;
    case kSensAccelerometer: case kSensVelocimeter: case kSensGyro: case kSensForce:
    case kSensTorque: case kSensMagnetometer: case kSensBallAngVel: case kSensFramePos:
    case kSensFrameXAxis: case kSensFrameYAxis: case kSensFrameZAxis: case kSensFrameLinVel:
    case kSensFrameAngVel: case kSensFrameLinAcc: case kSensFrameAngAcc: case kSensSubtreeCom:
    case kSensSubtreeLinVel: case kSensSubtreeAngMom: case kSensGeomNormal:
      return 3;
    case kSensBallQuat: case kSensFrameQuat: return 4;
    case kSensGeomFromTo: return 6;
    case kSensContact: return int64_t{s.intprm[2]} * ContactDataSize(s.intprm[0]);
    case kSensTactile: return 3 * m.mesh_vertnum[objid];
    case kSensRangefinder: return RayDataSize(s.intprm[0]) * RayCount(m, s, objid);
    case kSensUser: return s.dim;
    // (one number per force output: 3 for an orientation)
    case kSensActuatorPos: case kSensActuatorVel: case kSensActuatorFrc:
      return m.actuator_outnum[objid];
    default: return 1;
  }
}

// The id of the object a sensor names, or an error naming the sensor.
int Resolve(const Model& m, const SensorSpec& s, int type, const std::string& name,
            const char* role) {
  if (type == kObjUnknown) return -1;
  if (name.empty()) ThrowAt(s.src, std::string("missing name of ") + role + " in sensor");
  int id = m.NameToId(static_cast<ObjType>(type), name);
  if (id < 0) ThrowAt(s.src, std::string("unrecognized name '") + name + "' of " + role);
  return id;
}

bool HasFrame(int type) {
  return type == kObjBody || type == kObjXBody || type == kObjGeom || type == kObjSite ||
         type == kObjCamera;
}

// Joint sensors: scalar joints for most, ball joints for the ball sensors, limited
// joints for the limit sensors.
void CheckJoint(const Model& m, const SensorSpec& s, int id) {
  if (s.objtype != kObjJoint) ThrowAt(s.src, "sensor must be attached to joint");
  int type = m.jnt_type[id];
  bool ball = s.type == kSensBallQuat || s.type == kSensBallAngVel;
  bool limit = s.type == kSensJointLimitPos || s.type == kSensJointLimitVel ||
               s.type == kSensJointLimitFrc;
  if (ball && type != kJointBall) ThrowAt(s.src, "joint must be ball in sensor");
  if (!ball && !limit && type != kJointSlide && type != kJointHinge) {
    ThrowAt(s.src, "joint must be slide or hinge in sensor");
  }
  if (limit && !m.jnt_limited[id]) ThrowAt(s.src, "joint must be limited in sensor");
}

// What each type must be attached to (MuJoCo's checks in mjCSensor::Compile).
void CheckAttachment(const Model& m, const SensorSpec& s, int objid, int refid) {
  switch (s.type) {
    case kSensTouch: case kSensAccelerometer: case kSensVelocimeter: case kSensGyro:
    case kSensForce: case kSensTorque: case kSensMagnetometer: case kSensCamProjection:
      if (s.objtype != kObjSite) ThrowAt(s.src, "sensor must be attached to site");
      if (s.type == kSensCamProjection &&
          (m.cam_resolution[2 * refid] == 0 || m.cam_resolution[2 * refid + 1] == 0)) {
        ThrowAt(s.src, "camera projection sensor requires camera resolution");
      }
      break;
    case kSensJointPos: case kSensJointVel: case kSensJointActFrc: case kSensBallQuat:
    case kSensBallAngVel: case kSensJointLimitPos: case kSensJointLimitVel:
    case kSensJointLimitFrc:
      CheckJoint(m, s, objid);
      break;
    case kSensTendonLimitPos: case kSensTendonLimitVel: case kSensTendonLimitFrc:
      if (s.objtype == kObjTendon && !m.tendon_limited[objid]) {
        ThrowAt(s.src, "tendon must be limited in sensor");
      }
      [[fallthrough]];
    case kSensTendonPos: case kSensTendonVel: case kSensTendonActFrc:
      if (s.objtype != kObjTendon) ThrowAt(s.src, "sensor must be attached to tendon");
      break;
    case kSensActuatorPos: case kSensActuatorVel: case kSensActuatorFrc:
      if (s.objtype != kObjActuator) ThrowAt(s.src, "sensor must be attached to actuator");
      break;
    case kSensFramePos: case kSensFrameQuat: case kSensFrameXAxis: case kSensFrameYAxis:
    case kSensFrameZAxis: case kSensFrameLinVel: case kSensFrameAngVel:
    case kSensFrameLinAcc: case kSensFrameAngAcc: case kSensInsideSite:
      if (!HasFrame(s.objtype)) {
        ThrowAt(s.src, "sensor must be attached to (x)body, geom, site or camera");
      }
      if (s.type == kSensInsideSite && s.reftype != kObjSite) {
        ThrowAt(s.src, "sensor must be associated with a site");
      }
      break;
    case kSensSubtreeCom: case kSensSubtreeLinVel: case kSensSubtreeAngMom:
      if (s.objtype != kObjBody) ThrowAt(s.src, "sensor must be attached to body");
      break;
    case kSensGeomDist: case kSensGeomNormal: case kSensGeomFromTo:
      if (s.objtype == s.reftype && objid == refid) {
        ThrowAt(s.src, "1st body/geom must be different from 2nd body/geom");
      }
      for (auto [type, id] : {std::pair{s.objtype, objid}, {s.reftype, refid}}) {
        if (type == kObjGeom && m.geom_type[id] == kGeomHfield) {
          ThrowAt(s.src, "height fields are not supported in geom distance sensors");
        }
      }
      break;
    case kSensContact:
      if (s.intprm[1] < 0 || s.intprm[1] > 3) ThrowAt(s.src, "unknown reduction criterion");
      break;
    case kSensTactile:
      // Each taxel reads a normal and two tangents (9 numbers); MuJoCo would read past
      // the mesh's own normals otherwise.
      if (m.mesh_normalnum[objid] != 3 * m.mesh_vertnum[objid]) {
        ThrowAt(s.src, "tactile sensor mesh '" + s.objname + "' needs a normal and two tangents "
                       "per vertex (a builtin wedge or plate, or normal= with 9 numbers per vertex)");
      }
      break;
    case kSensUser:
      if (s.dim < 0) ThrowAt(s.src, "sensor dim must be non-negative in sensor");
      if (s.datatype == kDataAxis && s.dim != 3) {
        ThrowAt(s.src, "datatype AXIS requires dim=3 in sensor");
      }
      if (s.datatype == kDataQuaternion && s.dim != 4) {
        ThrowAt(s.src, "datatype QUATERNION requires dim=4 in sensor");
      }
      break;
    default: break;
  }
}

// A delay needs a history buffer, and a buffer holds at most 2^24 samples (its cursor
// is kept exactly in single precision). `buffer` names it in the message.
void CheckHistory(const mjcf::Source& src, double delay, int nsample, const char* buffer) {
  if (delay > 0 && nsample <= 0) ThrowAt(src, "setting delay > 0 without a history buffer");
  if (nsample > (1 << 24)) ThrowAt(src, std::string("at most 2^24 samples in ") + buffer);
}

// Checks of the filtering, delay and sampling attributes.
void CheckCommon(const SensorSpec& s, int nuser) {
  if (static_cast<int>(s.user.size()) > nuser) {
    ThrowAt(s.src, "user has more values than nuser_sensor in sensor");
  }
  if (s.noise < 0) ThrowAt(s.src, "negative noise in sensor");
  if (s.cutoff < 0) ThrowAt(s.src, "negative cutoff in sensor");
  if (s.interval[0] < 0) ThrowAt(s.src, "negative interval in sensor");
  if (s.interval[1] > 0) ThrowAt(s.src, "positive phase in sensor");
  if (s.interval[0] > 0 && s.interval[1] <= -s.interval[0]) {
    ThrowAt(s.src, "phase must be greater than -period in sensor");
  }
  CheckHistory(s.src, s.delay, s.nsample, "sensor history buffer");
}

// What makes a sensor's output as large as it is, for messages: the attribute for the
// sensors that have one, else the size itself.
std::string DimRequest(const SensorSpec& s, int64_t dim) {
  if (s.type == kSensUser) return mjcf::AttrText("dim", std::to_string(s.dim));
  if (s.type == kSensContact) return mjcf::AttrText("num", std::to_string(s.intprm[2]));
  return "an output of " + std::to_string(dim) + " numbers";
}

// sensordata (and a history buffer's values) must fit the budget of one array, checked
// before the sizes go into the model's ints and before Data allocates them. MuJoCo
// refuses sizes it cannot allocate with "sensordata too large".
void CheckDataBudget(const SensorSpec& s, int64_t dim, int64_t total) {
  uint64_t bytes = mjcf::MulBytes(static_cast<uint64_t>(dim), sizeof(double));
  if (dim < 0 || bytes > mjcf::kMaxArrayBytes) {
    ThrowAt(s.src, "sensordata too large: " +
                       mjcf::OverBudget(DimRequest(s, dim), bytes, "sensordata",
                                        mjcf::kMaxArrayBytes));
  }
  uint64_t all = mjcf::MulBytes(static_cast<uint64_t>(total), sizeof(double));
  if (all > mjcf::kMaxArrayBytes) {
    ThrowAt(s.src, "sensordata too large: the sensors up to this one ask for " +
                       mjcf::ByteSize(all) + " of sensordata, over the " +
                       mjcf::ByteSize(mjcf::kMaxArrayBytes) + " budget of one array");
  }
}

// A plugin sensor's instance and the stage its plugin gives it; returns the size the
// plugin gives it.
int64_t CompilePluginSensor(const mjcf::ModelSpec& spec, const SensorSpec& s, int i, Model* m) {
  int instance = PluginInstanceOf(spec, s.src, s.plugin, "sensor");
  const Plugin& plugin = PluginWith(*m, instance, kPluginSensor, s.src);
  m->sensor_plugin[i] = instance;
  m->sensor_needstage[i] = plugin.needstage;
  int dim = plugin.nsensordata(*m, instance, i);
  if (dim < 0) ThrowAt(s.src, "plugin '" + plugin.name + "' gave the sensor a negative size");
  return dim;
}

// One sensor's row of the model.
void CompileSensor(const mjcf::ModelSpec& spec, const SensorSpec& s, int i, int64_t adr, Model* m) {
  CheckCommon(s, m->nuser_sensor);
  int objid = Resolve(*m, s, s.objtype, s.objname, "sensorized object");
  int refid = Resolve(*m, s, s.reftype, s.refname, "reference object");
  if (s.objtype == kObjUnknown && s.type != kSensEPotential && s.type != kSensEKinetic &&
      s.type != kSensClock && s.type != kSensContact && s.type != kSensUser &&
      s.type != kSensPlugin) {
    ThrowAt(s.src, "invalid type in sensor");
  }
  if (s.reftype != kObjUnknown && s.type != kSensContact && s.type != kSensTactile &&
      !HasFrame(s.reftype)) {
    ThrowAt(s.src, "reference frame object must be (x)body, geom, site or camera in sensor");
  }
  CheckAttachment(*m, s, objid, refid);

  // Type, objects and the data type, stage and size MuJoCo gives the type.
  m->sensor_type[i] = s.type;
  m->sensor_objtype[i] = s.objtype;
  m->sensor_objid[i] = objid;
  m->sensor_reftype[i] = s.reftype;
  m->sensor_refid[i] = refid;
  for (int k = 0; k < kNSens; k++) m->sensor_intprm[kNSens * i + k] = s.intprm[k];
  bool user = s.type == kSensUser;
  m->sensor_datatype[i] = user ? s.datatype : SensorDataType(s.type);
  m->sensor_needstage[i] = user ? s.needstage : NeedStage(s.type);
  m->sensor_plugin[i] = -1;
  int64_t dim = s.type == kSensPlugin ? CompilePluginSensor(spec, s, i, m) : SensorDim(*m, s, objid);
  CheckDataBudget(s, dim, adr + dim);
  m->sensor_dim[i] = static_cast<int>(dim);
  int datatype = m->sensor_datatype[i];
  if (s.cutoff > 0 && (datatype == kDataQuaternion ||
                       (datatype == kDataAxis && s.type != kSensGeomNormal))) {
    ThrowAt(s.src, "cutoff applied to axis or quaternion datatype in sensor");
  }

  // Filtering, delay, sampling and user numbers.
  m->sensor_cutoff[i] = s.cutoff;
  m->sensor_noise[i] = s.noise;
  m->sensor_history[2 * i] = s.nsample;
  m->sensor_history[2 * i + 1] = s.interp;
  m->sensor_delay[i] = s.delay;
  m->sensor_interval[2 * i] = s.interval[0];
  m->sensor_interval[2 * i + 1] = s.interval[1];
  for (size_t k = 0; k < s.user.size(); k++) m->sensor_user[i * m->nuser_sensor + k] = s.user[k];
  m->sensor_names[i] = s.src.name;
}

// Actuators with a history buffer come first in it, then sensors; each takes
// [user, cursor, times(n), values(n x dim)] numbers (MuJoCo's layout).
// The buffer is counted in 64 bits and held to the budget of one array, naming the
// element whose buffer crosses it.
void LayoutHistory(const mjcf::ModelSpec& spec, Model* m) {
  int64_t adr = 0;
  auto grow = [&](const mjcf::Source& src, int64_t size) {
    adr += size;
    uint64_t bytes = mjcf::MulBytes(static_cast<uint64_t>(adr), sizeof(double));
    if (bytes > mjcf::kMaxArrayBytes) {
      ThrowAt(src, "history buffer too large: the buffers up to this element ask for " +
                       mjcf::ByteSize(bytes) + ", over the " +
                       mjcf::ByteSize(mjcf::kMaxArrayBytes) + " budget of one array");
    }
  };
  for (int i = 0; i < m->nactuator; i++) {
    const mjcf::ActuatorSpec& a = spec.actuators[i];
    CheckHistory(a.src, a.delay, a.nsample, "history buffer");
    m->actuator_history[2 * i] = a.nsample;
    m->actuator_history[2 * i + 1] = a.interp;
    m->actuator_delay[i] = a.delay;
    m->actuator_historyadr[i] = a.nsample > 0 ? static_cast<int>(adr) : -1;
    if (a.nsample > 0) grow(a.src, 2 + 2 * int64_t{a.nsample});
  }
  for (int i = 0; i < m->nsensor; i++) {
    int64_t n = m->sensor_history[2 * i];
    m->sensor_historyadr[i] = n > 0 ? static_cast<int>(adr) : -1;
    if (n > 0) grow(spec.sensors[i].src, 2 + n + n * m->sensor_dim[i]);
  }
  m->nhistory = static_cast<int>(adr);
}

}  // namespace

int NUserSensor(const mjcf::ModelSpec& spec) {
  if (spec.nuser_sensor >= 0) return spec.nuser_sensor;
  int n = 0;
  for (const SensorSpec& s : spec.sensors) n = std::max(n, static_cast<int>(s.user.size()));
  return n;
}

void CompileSensors(const mjcf::ModelSpec& spec, Model* m) {
  // Unique names, then each sensor, then the addresses of their outputs.
  // (objects are found by name through the model's hash, built here for them)
  m->IndexNames();
  NameIndex seen;
  int64_t adr = 0;
  for (size_t i = 0; i < spec.sensors.size(); i++) {
    const SensorSpec& s = spec.sensors[i];
    if (!seen.Insert(s.src.name, static_cast<int>(i))) {
      ThrowAt(s.src, "repeated sensor name '" + s.src.name + "'");
    }
    CompileSensor(spec, s, static_cast<int>(i), adr, m);
    adr += m->sensor_dim[i];
  }
  for (int i = 0, at = 0; i < m->nsensor; i++) {
    m->sensor_adr[i] = at;
    at += m->sensor_dim[i];
  }
  m->nsensordata = static_cast<int>(adr);
  LayoutHistory(spec, m);
}

}  // namespace simlab::compiler
