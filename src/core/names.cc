// Names of enum values as MJCF writes them (sensor element tags, object types), and
// access to a sensor's output by its name (MuJoCo's data.sensor("name").data).
#include <cstdio>
#include <string>
#include <utility>

#include "simlab/simlab.h"

namespace simlab {

namespace {

// MJCF element tag per mjtSensor value, in enum order.
constexpr const char* kSensorTags[] = {
    "touch",          "accelerometer",  "velocimeter",    "gyro",
    "force",          "torque",         "magnetometer",   "rangefinder",
    "camprojection",  "jointpos",       "jointvel",       "tendonpos",
    "tendonvel",      "actuatorpos",    "actuatorvel",    "actuatorfrc",
    "jointactuatorfrc", "tendonactuatorfrc", "ballquat",  "ballangvel",
    "jointlimitpos",  "jointlimitvel",  "jointlimitfrc",  "tendonlimitpos",
    "tendonlimitvel", "tendonlimitfrc", "framepos",       "framequat",
    "framexaxis",     "frameyaxis",     "framezaxis",     "framelinvel",
    "frameangvel",    "framelinacc",    "frameangacc",    "subtreecom",
    "subtreelinvel",  "subtreeangmom",  "insidesite",     "distance",
    "normal",         "fromto",         "contact",        "e_potential",
    "e_kinetic",      "clock",          "tactile",        "plugin",
    "user"};

// MJCF keyword per mjtObj value, in enum order.
constexpr const char* kObjNames[] = {
    "unknown", "body",     "xbody",    "joint",   "dof",      "geom",  "site",
    "camera",  "light",    "flex",     "mesh",    "skin",     "hfield", "texture",
    "material", "pair",    "exclude",  "equality", "tendon",  "actuator", "sensor",
    "numeric", "text",     "tuple",    "key",     "plugin"};

// What each warning means, in mjtWarning order, then simlab's own.
constexpr const char* kWarningNames[] = {
    "inertia matrix is too close to singular",
    "contact buffer is full",
    "constraint buffer is full",
    "visual geom buffer is full",
    "bad qpos (NaN or too large): simulation reset",
    "bad qvel (NaN or too large): simulation reset",
    "bad qacc (NaN or too large): simulation reset",
    "bad ctrl (NaN or too large): controls zeroed",
    "line search objective is not convex",
    "engine error: simulation reset"};
static_assert(sizeof(kWarningNames) / sizeof(kWarningNames[0]) == kNumWarnings);

}  // namespace

const char* WarningName(int warning) {
  return warning >= 0 && warning < kNumWarnings ? kWarningNames[warning] : "unknown warning";
}

std::string WarningText(int warning, int info, double time) {
  char when[64];
  std::snprintf(when, sizeof(when), " (info %d, time %.4f)", info, time);
  return WarningName(warning) + std::string(when);
}

const char* SensorTypeName(int type) {
  constexpr int n = sizeof(kSensorTags) / sizeof(kSensorTags[0]);
  return type >= 0 && type < n ? kSensorTags[type] : "unknown";
}

const char* ObjTypeName(int type) {
  constexpr int n = sizeof(kObjNames) / sizeof(kObjNames[0]);
  return type >= 0 && type < n ? kObjNames[type] : "unknown";
}

ObjType ObjTypeFromName(const std::string& name) {
  // MJCF keywords.
  constexpr int n = sizeof(kObjNames) / sizeof(kObjNames[0]);
  for (int type = 1; type < n; type++) {
    if (name == kObjNames[type]) return static_cast<ObjType>(type);
  }
  // MuJoCo's field prefixes and Python view names.
  static const std::pair<const char*, ObjType> kAliases[] = {
      {"jnt", kObjJoint}, {"cam", kObjCamera}, {"eq", kObjEquality},
      {"keyframe", kObjKey}, {"ten", kObjTendon}};
  for (const auto& [alias, type] : kAliases) {
    if (name == alias) return type;
  }
  return kObjUnknown;
}

int SensorId(const Model& m, const std::string& name) {
  int id = NameToId(m, kObjSensor, name);
  if (id < 0) throw Error("no sensor named '" + name + "'");
  return id;
}

std::span<double> SensorData(const Model& m, Data& d, const std::string& name) {
  int id = SensorId(m, name);
  return {d.sensordata.data() + m.sensor_adr[id], static_cast<size_t>(m.sensor_dim[id])};
}

}  // namespace simlab
