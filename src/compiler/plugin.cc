// Plugin instances: their ids (the named instances of <extension> in order, then the
// implicit ones of the elements that configure their own), each one's registered
// plugin, its configuration flattened in the plugin's attribute order (plugin_attr),
// its plugin_state numbers, and the instance of each actuator and body that uses one
// (sensors' in sensor.cc, where their sizes are set).
#include <string>
#include <utility>
#include <vector>

#include "compiler/compiler.h"
#include "mjcf/error.h"
#include "simlab/plugin.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

// Instance `id` in compiled order.
const mjcf::PluginInstanceSpec& InstanceAt(const mjcf::ModelSpec& spec, int id) {
  int named = static_cast<int>(spec.plugin_instances.size());
  return id < named ? spec.plugin_instances[id] : spec.implicit_instances[id - named];
}

// The registered plugin `name`, which <extension> must declare.
int DeclaredPlugin(const mjcf::ModelSpec& spec, const mjcf::Source& where, const std::string& name) {
  bool declared = false;
  for (const auto& [plugin, src] : spec.active_plugins) declared = declared || plugin == name;
  if (!declared) ThrowAt(where, "plugin '" + name + "' is not declared in <extension>");
  return PluginSlot(name);
}

}  // namespace

int PluginInstanceOf(const mjcf::ModelSpec& spec, const mjcf::Source& user, const mjcf::PluginUse& use,
                     const std::string& kind) {
  if (use.instance.empty()) {
    if (use.plugin.empty()) ThrowAt(user, "neither 'plugin' nor 'instance' is specified for " + kind);
    return static_cast<int>(spec.plugin_instances.size()) + use.implicit_instance;
  }
  for (size_t k = 0; k < spec.plugin_instances.size(); k++) {
    const mjcf::PluginInstanceSpec& inst = spec.plugin_instances[k];
    if (inst.name != use.instance) continue;
    if (!use.plugin.empty() && use.plugin != inst.plugin) {
      ThrowAt(user, "instance '" + use.instance + "' is of plugin '" + inst.plugin + "', not '" +
                        use.plugin + "'");
    }
    return static_cast<int>(k);
  }
  ThrowAt(user, "unrecognized name '" + use.instance + "' for plugin instance");
}

namespace {

// The capability in words, for errors.
const char* CapabilityName(int capability) {
  return capability == kPluginActuator ? "actuators"
         : capability == kPluginSensor ? "sensors"
         : capability == kPluginSdf    ? "signed distance fields"
                                       : "passive forces";
}

}  // namespace

const Plugin& PluginWith(const Model& m, int instance, int capability, const mjcf::Source& user) {
  const Plugin& plugin = PluginAt(m.plugin[instance]);
  if (plugin.capabilities & capability) return plugin;
  ThrowAt(user, "plugin '" + plugin.name + "' does not support " + CapabilityName(capability));
}

namespace {

// The instance's config values in the plugin's attribute order ("" where not given);
// a key the plugin does not read is an error.
std::vector<std::string> ConfigValues(const mjcf::PluginInstanceSpec& inst, const Plugin& plugin) {
  for (const auto& [key, value] : inst.config) {
    bool known = false;
    for (const std::string& attribute : plugin.attributes) known = known || attribute == key;
    if (!known) ThrowAt(inst.src, "unrecognized attribute 'plugin:" + key + "' for plugin '" + plugin.name + "'");
  }
  std::vector<std::string> values;
  for (const std::string& attribute : plugin.attributes) {
    values.emplace_back();
    for (const auto& [key, value] : inst.config) {
      if (key == attribute) values.back() = value;
    }
  }
  return values;
}

// The config values flattened, each ended by '\0'.
std::string FlattenConfig(const mjcf::PluginInstanceSpec& inst, const Plugin& plugin) {
  std::string flat;
  for (const std::string& value : ConfigValues(inst, plugin)) flat += value + '\0';
  return plugin.attributes.empty() ? std::string(1, '\0') : flat;
}

}  // namespace

void CompilePlugins(const mjcf::ModelSpec& spec, const CompileState& state, Model* m) {
  for (const auto& [name, src] : spec.active_plugins) {
    if (PluginSlot(name) < 0) ThrowAt(src, "plugin '" + name + "' is not registered");
  }
  // Instances: plugin slot, configuration, state.
  m->plugin_attr.clear();
  int stateadr = 0;
  for (int i = 0; i < m->nplugin; i++) {
    const mjcf::PluginInstanceSpec& inst = InstanceAt(spec, i);
    int slot = DeclaredPlugin(spec, inst.src, inst.plugin);
    const Plugin& plugin = PluginAt(slot);
    m->plugin[i] = slot;
    m->plugin_attradr[i] = static_cast<int>(m->plugin_attr.size());
    m->plugin_attr += FlattenConfig(inst, plugin);
  }
  // Actuators computed by a plugin, and bodies a (passive) plugin is attached to.
  for (int i = 0; i < m->nactuator; i++) {
    const mjcf::ActuatorSpec& a = spec.actuators[i];
    m->actuator_plugin[i] = -1;
    if (!a.plugin.active) continue;
    m->actuator_plugin[i] = PluginInstanceOf(spec, a.src, a.plugin, "actuator");
    PluginWith(*m, m->actuator_plugin[i], kPluginActuator, a.src);
  }
  for (int i = 0; i < m->nbody; i++) {
    const mjcf::BodySpec& b = *state.bodies[i].spec;
    m->body_plugin[i] = -1;
    if (!b.plugin.active) continue;
    m->body_plugin[i] = PluginInstanceOf(spec, b.src, b.plugin, "body");
    PluginWith(*m, m->body_plugin[i], kPluginPassive, b.src);
  }
  // Geoms whose shape a signed distance field plugin gives.
  for (int i = 0; i < m->ngeom; i++) {
    const mjcf::GeomSpec& g = *state.geoms[i].spec;
    m->geom_plugin[i] = -1;
    if (!g.plugin.active) continue;
    m->geom_plugin[i] = PluginInstanceOf(spec, g.src, g.plugin, "geom");
    PluginWith(*m, m->geom_plugin[i], kPluginSdf, g.src);
  }
  // (the state sizes may depend on the actuators)
  for (int i = 0; i < m->nplugin; i++) {
    const Plugin& plugin = PluginAt(m->plugin[i]);
    m->plugin_stateadr[i] = stateadr;
    m->plugin_statenum[i] = plugin.nstate ? plugin.nstate(*m, i) : 0;
    if (m->plugin_statenum[i] < 0) ThrowAt(InstanceAt(spec, i).src, "plugin '" + plugin.name + "' asked for negative state");
    stateadr += m->plugin_statenum[i];
  }
  m->npluginstate = stateadr;
}

const Plugin& SdfPluginOf(const mjcf::ModelSpec& spec, const mjcf::Source& user,
                          const mjcf::PluginUse& use, std::vector<double>* attributes) {
  const mjcf::PluginInstanceSpec& inst = InstanceAt(spec, PluginInstanceOf(spec, user, use, user.tag));
  int slot = DeclaredPlugin(spec, inst.src, inst.plugin);
  if (slot < 0) ThrowAt(inst.src, "plugin '" + inst.plugin + "' is not registered");
  const Plugin& plugin = PluginAt(slot);
  if (!(plugin.capabilities & kPluginSdf)) {
    ThrowAt(user, "plugin '" + plugin.name + "' does not support signed distance fields");
  }
  try {
    *attributes = SdfAttributes(plugin, ConfigValues(inst, plugin));
  } catch (const Error& e) {
    ThrowAt(inst.src, e.what());
  }
  return plugin;
}

const mjcf::Source& PluginInstanceSource(const mjcf::ModelSpec& spec, int instance) {
  return InstanceAt(spec, instance).src;
}

}  // namespace simlab::compiler
