// Engine plugins (MuJoCo's mjpPlugin): code registered by name that computes actuator
// forces, sensor values or passive forces, configured per instance in MJCF:
//
//   <extension><plugin plugin="mujoco.pid">
//     <instance name="arm"><config key="kp" value="40"/></instance>
//   </plugin></extension>
//   <actuator><plugin joint="shoulder" instance="arm" actdim="1"/></actuator>
//
// (or an implicit instance: <plugin plugin="mujoco.pid" joint="j"><config .../></plugin>).
// Sensors are <sensor><plugin instance=... [objtype objname reftype refname]/>, and a
// body's <plugin instance=.../> attaches an instance to it (Model::body_plugin).
// A plugin keeps its numbers in d.plugin_state (plugin_stateadr/statenum per instance),
// or in d.act for an actuator plugin's states (its actdim), and anything else in the
// PluginInstanceData its init returns. Register a plugin before loading the models that
// use it:
//
//   simlab::Plugin p;
//   p.name = "my.spring";
//   p.capabilities = simlab::kPluginPassive;
//   p.attributes = {"stiffness"};
//   p.compute = [](const Model& m, Data& d, int instance, int capability) { ... };
//   simlab::RegisterPlugin(p);
//
// A signed distance field plugin (kPluginSdf) gives an sdf geom its shape:
//
//   <extension><plugin plugin="mujoco.sdf.torus">
//     <instance name="torus"><config key="radius1" value="0.35"/></instance>
//   </plugin></extension>
//   <asset><mesh name="torus"><plugin instance="torus"/></mesh></asset>
//   <geom type="sdf" mesh="torus"><plugin instance="torus"/></geom>
//
// The mesh is the field's zero level set (marching cubes in the plugin's box), which
// gives the geom its mass and bounds; contacts come from the field itself.
//
// MuJoCo's first-party plugins are registered already: mujoco.pid and the signed distance
// fields mujoco.sdf.torus, .bolt, .nut, .gear and .bowl.
#ifndef SIMLAB_PLUGIN_H_
#define SIMLAB_PLUGIN_H_

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "simlab/data.h"
#include "simlab/model.h"
#include "simlab/simlab.h"

namespace simlab {

// What a plugin computes (mjtPluginCapabilityBit).
enum PluginCapability : int {
  kPluginActuator = 1,
  kPluginSensor = 2,
  kPluginPassive = 4,
  kPluginSdf = 8,
};

struct Plugin {
  std::string name;                     // unique, e.g. "mujoco.pid"
  int capabilities = 0;                 // PluginCapability bits
  std::vector<std::string> attributes;  // the config keys it reads, in their order
  // Sensors: the stage whose results compute reads (kStagePos, kStageVel or kStageAcc;
  // kStageNone is computed with kStagePos, but its sensors' cutoffs are not applied, as
  // in MuJoCo).
  int needstage = kStageNone;

  // Numbers of plugin_state the instance keeps (none when unset).
  std::function<int(const Model& m, int instance)> nstate;
  // Sensors: the numbers sensor `sensor_id` (a sensor of this instance) outputs; required
  // of a sensor plugin. Called when the model is compiled.
  std::function<int(const Model& m, int instance, int sensor_id)> nsensordata;
  // Makes the instance's data when a Data is made; throws simlab::Error on a bad
  // configuration (the model then fails to load, with the message).
  std::function<std::unique_ptr<PluginInstanceData>(const Model& m, Data& d, int instance)> init;
  // Back to the initial state at a reset: its plugin_state numbers and its data.
  std::function<void(const Model& m, double* state, PluginInstanceData* data, int instance)> reset;
  // Actuators: act_dot of its states, after the built-in dynamics and before the forces.
  std::function<void(const Model& m, Data& d, int instance)> actuator_act_dot;
  // The computation for one capability: actuator_force of its actuators (clamped to their
  // forcerange afterwards), sensordata of its sensors (at sensor_adr, after the built-in
  // sensors of its needstage; their cutoffs apply afterwards), or additions to
  // qfrc_passive.
  std::function<void(const Model& m, Data& d, int instance, int capability)> compute;
  // After a step has advanced the state and time.
  std::function<void(const Model& m, Data& d, int instance)> advance;

  // Signed distance fields: the numbers of the attributes when not configured (each
  // attribute is a number; SdfAttributes reads them); the distance and its gradient at a
  // point of the geom's frame; the box that holds the shape, centre then half-sizes.
  std::vector<double> sdf_defaults;
  std::function<double(const double point[3], const double* attributes)> sdf_distance;
  std::function<void(double gradient[3], const double point[3], const double* attributes)>
      sdf_gradient;
  std::function<void(double aabb[6], const double* attributes)> sdf_aabb;
};

// A plugin's init refused its instance's configuration (InitPlugins, when a Data is made).
class PluginInitError : public Error {
 public:
  PluginInitError(int instance_id, const std::string& what) : Error(what), instance(instance_id) {}
  int instance;
};

// Registers a plugin and returns its slot (Model::plugin holds slots); a name already
// registered is an error.
int RegisterPlugin(const Plugin& plugin);

// The plugin registered under `name` (its slot), or -1.
int PluginSlot(const std::string& name);

// The plugin in a slot (throws simlab::Error for a slot that is not registered).
const Plugin& PluginAt(int slot);

// Instance `instance`'s value for config key `key`: "" when not given; throws
// simlab::Error for a key the plugin does not declare (MuJoCo mj_getPluginConfig).
std::string PluginConfig(const Model& m, int instance, const std::string& key);

// A signed distance field plugin's attribute numbers for its config values (in the
// plugin's attribute order; "" takes the default); throws simlab::Error for a value that
// is not a number.
std::vector<double> SdfAttributes(const Plugin& plugin, const std::vector<std::string>& values);

// Distance and gradient of the field of sdf plugin instance `instance` in Data `d`.
double SdfPluginDistance(const Model& m, const Data& d, int instance, const double point[3]);
void SdfPluginGradient(const Model& m, const Data& d, int instance, double gradient[3],
                       const double point[3]);

}  // namespace simlab

#endif  // SIMLAB_PLUGIN_H_
