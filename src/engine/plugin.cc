// Engine plugins (simlab/plugin.h): the registry of plugins by name, and the places the
// pipeline calls them, as MuJoCo does: init when a Data is made, reset at a reset
// (plugin_state is kept across it for the plugin's reset to set), actuator act_dot after
// the built-in dynamics and actuator forces after the built-in ones (both before the
// force clamps), passive forces at the end of the passive stage, advance after a step.
#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "simlab/plugin.h"
#include "simlab/simlab.h"

namespace simlab {

Plugin PidPlugin();                    // mujoco.pid (src/plugin/pid.cc)
std::vector<Plugin> SdfShapePlugins();  // mujoco.sdf.* (src/plugin/sdf_shapes.cc)
Plugin TouchGridPlugin();               // mujoco.sensor.touch_grid (src/plugin/touch_grid.cc)

namespace {

// The registered plugins, by slot; the first-party ones registered on first use.
struct Registry {
  std::mutex mutex;
  std::vector<std::unique_ptr<Plugin>> plugins;
};

Registry& TheRegistry() {
  static Registry registry;
  return registry;
}

// What an instance of a signed distance field plugin keeps: its attribute numbers, and
// the plugin (registered plugins stay where they are).
struct SdfInstance : PluginInstanceData {
  const Plugin* plugin = nullptr;
  std::vector<double> attributes;
  std::unique_ptr<PluginInstanceData> Clone() const override {
    return std::make_unique<SdfInstance>(*this);
  }
};

// A signed distance field plugin needs its field and box; simlab makes its instances
// (their attribute numbers, read when a Data is made), and one that only gives a field
// computes nothing in the pipeline.
Plugin CompleteSdfPlugin(Plugin plugin) {
  if (!plugin.sdf_distance || !plugin.sdf_gradient || !plugin.sdf_aabb) {
    throw Error("sdf plugin '" + plugin.name + "' needs sdf_distance, sdf_gradient and sdf_aabb");
  }
  if (plugin.sdf_defaults.size() != plugin.attributes.size()) {
    throw Error("sdf plugin '" + plugin.name + "' needs a default for each attribute");
  }
  if (plugin.init) throw Error("sdf plugin '" + plugin.name + "': simlab makes its instances (leave init unset)");
  if (!plugin.compute && plugin.capabilities == kPluginSdf) plugin.compute = [](const Model&, Data&, int, int) {};
  plugin.init = [](const Model& m, Data&, int instance) {
    auto data = std::make_unique<SdfInstance>();
    data->plugin = &PluginAt(m.plugin[instance]);
    std::vector<std::string> values;
    for (const std::string& key : data->plugin->attributes) values.push_back(PluginConfig(m, instance, key));
    data->attributes = SdfAttributes(*data->plugin, values);
    return std::unique_ptr<PluginInstanceData>(std::move(data));
  };
  return plugin;
}

// Adds a plugin under a name not taken yet; returns its slot.
int AddPlugin(const Plugin& given) {
  const Plugin plugin = (given.capabilities & kPluginSdf) ? CompleteSdfPlugin(given) : given;
  if (plugin.name.empty()) throw Error("a plugin needs a name");
  if (!plugin.compute) throw Error("plugin '" + plugin.name + "' has no compute");
  if ((plugin.capabilities & kPluginSensor) && !plugin.nsensordata) {
    throw Error("sensor plugin '" + plugin.name + "' has no nsensordata");
  }
  if (plugin.needstage < kStageNone || plugin.needstage > kStageAcc) {
    throw Error("plugin '" + plugin.name + "' has a needstage that is not a stage");
  }
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& p : r.plugins) {
    if (p->name == plugin.name) throw Error("plugin '" + plugin.name + "' is already registered");
  }
  r.plugins.push_back(std::make_unique<Plugin>(plugin));
  return static_cast<int>(r.plugins.size()) - 1;
}

void RegisterBuiltins() {
  static std::once_flag once;
  std::call_once(once, [] {
    AddPlugin(PidPlugin());
    AddPlugin(TouchGridPlugin());
    for (const Plugin& sdf : SdfShapePlugins()) AddPlugin(sdf);
  });
}

// Calls `call(instance, plugin)` for each instance whose plugin has the capability.
template <typename Call>
void ForInstances(const Model& m, int capability, Call call) {
  for (int i = 0; i < m.nplugin; i++) {
    const Plugin& plugin = PluginAt(m.plugin[i]);
    if (capability == 0 || (plugin.capabilities & capability)) call(i, plugin);
  }
}

}  // namespace

int RegisterPlugin(const Plugin& plugin) {
  RegisterBuiltins();
  return AddPlugin(plugin);
}

int PluginSlot(const std::string& name) {
  RegisterBuiltins();
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (size_t k = 0; k < r.plugins.size(); k++) {
    if (r.plugins[k]->name == name) return static_cast<int>(k);
  }
  return -1;
}

const Plugin& PluginAt(int slot) {
  RegisterBuiltins();
  Registry& r = TheRegistry();
  std::lock_guard<std::mutex> lock(r.mutex);
  if (slot < 0 || slot >= static_cast<int>(r.plugins.size())) {
    throw Error("no plugin is registered in slot " + std::to_string(slot));
  }
  return *r.plugins[slot];
}

std::string PluginConfig(const Model& m, int instance, const std::string& key) {
  if (instance < 0 || instance >= m.nplugin) {
    throw Error("plugin instance " + std::to_string(instance) + " does not exist");
  }
  const Plugin& plugin = PluginAt(m.plugin[instance]);
  // (the values follow the plugin's attributes, each ended by '\0')
  size_t at = static_cast<size_t>(m.plugin_attradr[instance]);
  for (const std::string& attribute : plugin.attributes) {
    size_t end = m.plugin_attr.find('\0', at);
    if (attribute == key) return m.plugin_attr.substr(at, end - at);
    at = end + 1;
  }
  throw Error("plugin '" + plugin.name + "' has no attribute '" + key + "'");
}

std::vector<double> SdfAttributes(const Plugin& plugin, const std::vector<std::string>& values) {
  std::vector<double> numbers(plugin.attributes.size());
  for (size_t k = 0; k < numbers.size(); k++) {
    const std::string& text = k < values.size() ? values[k] : std::string();
    if (text.empty()) {
      numbers[k] = plugin.sdf_defaults[k];
      continue;
    }
    // (a number, as std::stod reads it: leading blanks and trailing text are allowed)
    char* end = nullptr;
    numbers[k] = std::strtod(text.c_str(), &end);
    if (end == text.c_str()) {
      throw Error("plugin '" + plugin.name + "': invalid attribute value for '" +
                  plugin.attributes[k] + "': '" + text + "'");
    }
  }
  return numbers;
}

SdfField SdfFieldOf(const Data& d, int instance) {
  const auto* data = dynamic_cast<const SdfInstance*>(d.plugin_data.at(instance).data.get());
  if (!data) throw Error("plugin instance " + std::to_string(instance) + " is not a signed distance field");
  return {data->plugin, data->attributes.data()};
}

SdfField SdfFieldOfGeom(const Model& m, const Data& d, int g) {
  return m.geom_plugin[g] >= 0 ? SdfFieldOf(d, m.geom_plugin[g]) : SdfField{};
}

double SdfPluginDistance(const Model&, const Data& d, int instance, const double point[3]) {
  return SdfFieldOf(d, instance).Distance(point);
}

void SdfPluginGradient(const Model&, const Data& d, int instance, double gradient[3],
                       const double point[3]) {
  SdfFieldOf(d, instance).Gradient(gradient, point);
}

// ---------------------------------------------------------------- pipeline hooks

void InitPlugins(const Model& m, Data& d) {
  d.plugin_data.assign(static_cast<size_t>(m.nplugin), PluginDataSlot{});
  ForInstances(m, 0, [&](int i, const Plugin& p) {
    if (!p.init) return;
    try {
      d.plugin_data[i].data = p.init(m, d, i);
    } catch (const PluginInitError&) {
      throw;
    } catch (const Error& e) {
      throw PluginInitError(i, e.what());
    }
  });
}

void ResetPlugins(const Model& m, Data& d) {
  ForInstances(m, 0, [&](int i, const Plugin& p) {
    if (p.reset) p.reset(m, d.plugin_state.data() + m.plugin_stateadr[i], d.plugin_data[i].data.get(), i);
  });
}

void PluginActDot(const Model& m, Data& d) {
  ForInstances(m, kPluginActuator, [&](int i, const Plugin& p) {
    if (p.actuator_act_dot) p.actuator_act_dot(m, d, i);
  });
}

void PluginActuatorForces(const Model& m, Data& d) {
  ForInstances(m, kPluginActuator,
               [&](int i, const Plugin& p) { p.compute(m, d, i, kPluginActuator); });
}

void PluginPassiveForces(const Model& m, Data& d) {
  ForInstances(m, kPluginPassive,
               [&](int i, const Plugin& p) { p.compute(m, d, i, kPluginPassive); });
}

void PluginAdvance(const Model& m, Data& d) {
  ForInstances(m, 0, [&](int i, const Plugin& p) {
    if (p.advance) p.advance(m, d, i);
  });
}

}  // namespace simlab
