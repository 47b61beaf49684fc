// MJCF reader: engine plugins. <extension> names the plugins a model uses and their
// named instances with <config key value> pairs; <actuator><plugin> is an actuator whose
// force a plugin computes, <sensor><plugin> a sensor whose numbers it computes, and a
// body's <plugin> attaches an instance to the body; each refers to a named instance or
// configures its own.
#include <string>
#include <utility>
#include <vector>

#include "mjcf/error.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

std::vector<std::pair<std::string, std::string>> Reader::ReadConfigs(const XmlElement& e) const {
  std::vector<std::pair<std::string, std::string>> config;
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() != "config") Unknown(c);
    c.CheckAttributes({"key", "value"});
    std::string key, value;
    if (!c.Text("key", &key) || key.empty()) c.Fail("a config needs a key");
    if (!c.Text("value", &value)) c.Fail("config '" + key + "' needs a value");
    for (const auto& [k, v] : config) {
      if (k == key) c.Fail("duplicate config key: " + key);
    }
    config.emplace_back(key, value);
  }
  return config;
}

void Reader::Extension(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement p = Element(n);
    if (p.tag() != "plugin") Unknown(p);
    p.CheckAttributes({"plugin"});
    std::string plugin;
    if (!p.Text("plugin", &plugin) || plugin.empty()) p.Fail("missing the plugin's name (plugin=)");
    spec_->active_plugins.emplace_back(plugin, p.src());
    for (pugi::xml_node m : p.node().children()) {
      if (m.type() != pugi::node_element) continue;
      XmlElement inst = Element(m);
      if (inst.tag() != "instance") Unknown(inst);
      inst.CheckAttributes({"name"});
      PluginInstanceSpec spec;
      spec.src = inst.src();
      spec.plugin = plugin;
      if (!inst.Text("name", &spec.name) || spec.name.empty()) inst.Fail("a plugin instance needs a name");
      for (const PluginInstanceSpec& other : spec_->plugin_instances) {
        if (other.name == spec.name) inst.Fail("repeated plugin instance name '" + spec.name + "'");
      }
      spec.config = ReadConfigs(inst);
      spec_->plugin_instances.push_back(std::move(spec));
    }
  }
}

void Reader::ReadPluginUse(const XmlElement& e, const std::string& user, PluginUse* use) {
  use->active = true;
  e.Text("plugin", &use->plugin);
  e.Text("instance", &use->instance);
  if (use->plugin.empty() && use->instance.empty()) {
    e.Fail("neither 'plugin' nor 'instance' is specified for " + user);
  }
  auto config = ReadConfigs(e);
  if (!use->instance.empty()) {
    // (a named instance has its configuration in <extension>)
    if (!config.empty()) e.Fail("config belongs to instance '" + use->instance + "' in <extension>");
    return;
  }
  PluginInstanceSpec implicit;
  implicit.src = e.src();
  implicit.plugin = use->plugin;
  implicit.config = std::move(config);
  spec_->implicit_instances.push_back(std::move(implicit));
  use->implicit_instance = static_cast<int>(spec_->implicit_instances.size()) - 1;
}

void Reader::ReadOwnPlugin(const XmlElement& e, const std::string& owner, PluginUse* use) {
  e.CheckAttributes({"plugin", "instance"});
  if (use->active) e.Fail("a " + owner + " has at most one plugin");
  ReadPluginUse(e, owner, use);
}

void Reader::ReadPluginActuator(const XmlElement& e, ActuatorSpec* act) {
  ReadActuator(e, act, false);
  ReadPluginUse(e, "actuator", &act->plugin);
}

}  // namespace simlab::mjcf
