// Plugin instances: their ids (the named instances of <extension> in order, then the
// implicit ones of the elements that configure their own), each one's registered
// plugin, its configuration flattened in the plugin's attribute order (plugin_attr),
// its plugin_state numbers, and each actuator's instance.
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

// The instance actuator `a` uses: its named instance, or its own.
int ActuatorInstance(const mjcf::ModelSpec& spec, const mjcf::ActuatorSpec& a) {
  if (a.instance.empty()) {
    if (a.plugin.empty()) ThrowAt(a.src, "neither 'plugin' nor 'instance' is specified for actuator");
    return static_cast<int>(spec.plugin_instances.size()) + a.implicit_instance;
  }
  for (size_t k = 0; k < spec.plugin_instances.size(); k++) {
    const mjcf::PluginInstanceSpec& inst = spec.plugin_instances[k];
    if (inst.name != a.instance) continue;
    if (!a.plugin.empty() && a.plugin != inst.plugin) {
      ThrowAt(a.src, "instance '" + a.instance + "' is of plugin '" + inst.plugin + "', not '" +
                         a.plugin + "'");
    }
    return static_cast<int>(k);
  }
  ThrowAt(a.src, "unrecognized name '" + a.instance + "' for plugin instance");
}

// The instance's config values in the plugin's attribute order, each ended by '\0'.
std::string FlattenConfig(const mjcf::PluginInstanceSpec& inst, const Plugin& plugin) {
  for (const auto& [key, value] : inst.config) {
    bool known = false;
    for (const std::string& attribute : plugin.attributes) known = known || attribute == key;
    if (!known) ThrowAt(inst.src, "unrecognized attribute 'plugin:" + key + "' for plugin '" + plugin.name + "'");
  }
  std::string flat;
  for (const std::string& attribute : plugin.attributes) {
    for (const auto& [key, value] : inst.config) {
      if (key == attribute) flat += value;
    }
    flat += '\0';
  }
  return plugin.attributes.empty() ? std::string(1, '\0') : flat;
}

}  // namespace

void CompilePlugins(const mjcf::ModelSpec& spec, Model* m) {
  for (const auto& [name, src] : spec.active_plugins) {
    if (PluginSlot(name) < 0) ThrowAt(src, "plugin '" + name + "' is not registered");
  }
  // Instances: plugin slot, configuration, state.
  m->plugin_attr.clear();
  int state = 0;
  for (int i = 0; i < m->nplugin; i++) {
    const mjcf::PluginInstanceSpec& inst = InstanceAt(spec, i);
    int slot = DeclaredPlugin(spec, inst.src, inst.plugin);
    const Plugin& plugin = PluginAt(slot);
    m->plugin[i] = slot;
    m->plugin_attradr[i] = static_cast<int>(m->plugin_attr.size());
    m->plugin_attr += FlattenConfig(inst, plugin);
  }
  // Actuators computed by a plugin.
  for (int i = 0; i < m->nactuator; i++) {
    const mjcf::ActuatorSpec& a = spec.actuators[i];
    m->actuator_plugin[i] = a.is_plugin ? ActuatorInstance(spec, a) : -1;
    if (!a.is_plugin) continue;
    const Plugin& plugin = PluginAt(m->plugin[m->actuator_plugin[i]]);
    if (!(plugin.capabilities & kPluginActuator)) {
      ThrowAt(a.src, "plugin '" + plugin.name + "' does not support actuators");
    }
  }
  // (the state sizes may depend on the actuators)
  for (int i = 0; i < m->nplugin; i++) {
    const Plugin& plugin = PluginAt(m->plugin[i]);
    m->plugin_stateadr[i] = state;
    m->plugin_statenum[i] = plugin.nstate ? plugin.nstate(*m, i) : 0;
    if (m->plugin_statenum[i] < 0) ThrowAt(InstanceAt(spec, i).src, "plugin '" + plugin.name + "' asked for negative state");
    state += m->plugin_statenum[i];
  }
  m->npluginstate = state;
}

const mjcf::Source& PluginInstanceSource(const mjcf::ModelSpec& spec, int instance) {
  return InstanceAt(spec, instance).src;
}

}  // namespace simlab::compiler
