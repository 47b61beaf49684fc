// An engine plugin of our own: a stiffening spring, registered from C++ and configured
// from MJCF. Attached to bodies (a body's <plugin instance=.../>), it adds to
// qfrc_passive, for each hinge and slide joint of those bodies,
//
//   f = -k1 q - k3 q^3
//
// with k1 and k3 from the instance's <config>; and as a sensor (<sensor><plugin>) it
// reports the energy stored in those springs, k1 q^2 / 2 + k3 q^4 / 4. It keeps the
// largest |f| it has applied in plugin_state, and its config in its instance data.
// Build and run:
//
//   cmake --build build --target plugin_spring && build/plugin_spring
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "simlab/plugin.h"
#include "simlab/simlab.h"

namespace {

// The instance's constants, read once when a Data is made.
struct SpringConfig : simlab::PluginInstanceData {
  double k1 = 0, k3 = 0;
  std::unique_ptr<simlab::PluginInstanceData> Clone() const override {
    return std::make_unique<SpringConfig>(*this);
  }
};

double ConfigNumber(const simlab::Model& m, int instance, const char* key) {
  std::string text = simlab::PluginConfig(m, instance, key);
  if (text.empty()) return 0;
  try {
    return std::stod(text);
  } catch (const std::exception&) {
    throw simlab::Error(std::string("example.spring: ") + key + " = '" + text + "' is not a number");
  }
}

// Calls `spring(q, dof)` for each hinge and slide joint of the bodies the instance is
// attached to.
template <typename Spring>
void ForSprungJoints(const simlab::Model& m, const simlab::Data& d, int instance, Spring spring) {
  for (int j = 0; j < m.njnt; j++) {
    if (m.body_plugin[m.jnt_bodyid[j]] != instance) continue;
    if (m.jnt_type[j] != simlab::kJointHinge && m.jnt_type[j] != simlab::kJointSlide) continue;
    spring(d.qpos[m.jnt_qposadr[j]], m.jnt_dofadr[j]);
  }
}

// Passive: the springs' forces, and the largest so far in plugin_state.
void AddSpringForces(const simlab::Model& m, simlab::Data& d, int instance) {
  const auto& c = static_cast<const SpringConfig&>(*d.plugin_data[instance].data);
  double& largest = d.plugin_state[m.plugin_stateadr[instance]];
  ForSprungJoints(m, d, instance, [&](double q, int dof) {
    double f = -c.k1 * q - c.k3 * q * q * q;
    d.qfrc_passive[dof] += f;
    largest = std::max(largest, std::abs(f));
  });
}

// Sensor: each of the instance's sensors reads the energy of its springs.
void SpringEnergySensors(const simlab::Model& m, simlab::Data& d, int instance) {
  const auto& c = static_cast<const SpringConfig&>(*d.plugin_data[instance].data);
  double energy = 0;
  ForSprungJoints(m, d, instance, [&](double q, int) {
    energy += c.k1 * q * q / 2 + c.k3 * q * q * q * q / 4;
  });
  for (int s = 0; s < m.nsensor; s++) {
    if (m.sensor_plugin[s] == instance) d.sensordata[m.sensor_adr[s]] = energy;
  }
}

simlab::Plugin SpringPlugin() {
  simlab::Plugin p;
  p.name = "example.spring";
  p.capabilities = simlab::kPluginPassive | simlab::kPluginSensor;
  p.attributes = {"k1", "k3"};
  p.needstage = simlab::kStagePos;
  p.nstate = [](const simlab::Model&, int) { return 1; };
  p.nsensordata = [](const simlab::Model&, int, int) { return 1; };
  p.init = [](const simlab::Model& m, simlab::Data&, int instance) {
    auto config = std::make_unique<SpringConfig>();
    config->k1 = ConfigNumber(m, instance, "k1");
    config->k3 = ConfigNumber(m, instance, "k3");
    return std::unique_ptr<simlab::PluginInstanceData>(std::move(config));
  };
  p.reset = [](const simlab::Model&, double* state, simlab::PluginInstanceData*, int) { state[0] = 0; };
  p.compute = [](const simlab::Model& m, simlab::Data& d, int instance, int capability) {
    if (capability == simlab::kPluginPassive) AddSpringForces(m, d, instance);
    if (capability == simlab::kPluginSensor) SpringEnergySensors(m, d, instance);
  };
  return p;
}

const char* kModel = R"(
<mujoco>
  <option gravity="0 0 0"/>
  <extension>
    <plugin plugin="example.spring">
      <instance name="stiffening"><config key="k1" value="2"/><config key="k3" value="40"/></instance>
    </plugin>
  </extension>
  <worldbody>
    <body>
      <plugin instance="stiffening"/>
      <joint name="slide" type="slide" axis="1 0 0"/>
      <geom type="box" size=".1 .1 .1" mass="1"/>
    </body>
  </worldbody>
  <sensor>
    <plugin name="spring_energy" instance="stiffening"/>
  </sensor>
</mujoco>)";

}  // namespace

int main() {
  simlab::RegisterPlugin(SpringPlugin());
  simlab::Model m = simlab::LoadXmlString(kModel, "spring.xml");
  simlab::Data d = simlab::MakeData(m);
  std::printf("plugin instances %d, state numbers %d\n", m.nplugin, m.npluginstate);
  // Released from 0.5 it oscillates faster than the linear spring's period 2 pi / sqrt(2).
  d.qpos[0] = 0.5;
  simlab::Forward(m, d);
  double energy0 = simlab::SensorData(m, d, "spring_energy")[0];
  std::printf("spring energy at 0.5 m %.4f J (sensor spring_energy)\n", energy0);
  double previous = d.qpos[0], first_return = -1;
  while (d.time < 10 && first_return < 0) {
    simlab::Step(m, d);
    if (previous > 0 && d.qpos[0] <= 0) first_return = d.time;
    previous = d.qpos[0];
  }
  std::printf("first pass through 0 at t = %.3f s (linear spring alone: %.3f s)\n", first_return,
              std::acos(-1.0) / 2 / std::sqrt(2.0));
  std::printf("largest spring force so far %.3f N (plugin_state)\n", d.plugin_state[0]);
  double kinetic = 0.5 * d.qvel[0] * d.qvel[0];
  std::printf("at 0: spring energy %.4f J, kinetic %.4f J (of %.4f J)\n", d.sensordata[0], kinetic, energy0);
  return 0;
}
