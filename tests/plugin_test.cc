// Engine plugins: a passive-force plugin registered here (its config, state, reset and
// data copied with the Data), MuJoCo's mujoco.pid on small models against the servos it
// equals (MuJoCo's own pid_test numbers), and the loader's checks. Whole rollouts of
// mujoco.pid models are compared with native MuJoCo in tests/conformance/actuators312.
#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/plugin.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// test.spring: qfrc_passive -= k q on every dof; counts its calls in plugin_state[0] and
// keeps k in its data.
struct SpringData : PluginInstanceData {
  double k = 0;
  std::unique_ptr<PluginInstanceData> Clone() const override { return std::make_unique<SpringData>(*this); }
};

void RegisterTestSpring() {
  static bool done = false;
  if (done) return;
  done = true;
  Plugin p;
  p.name = "test.spring";
  p.capabilities = kPluginPassive;
  p.attributes = {"k", "unused"};
  p.nstate = [](const Model&, int) { return 2; };
  p.init = [](const Model& m, Data&, int i) {
    auto data = std::make_unique<SpringData>();
    std::string k = PluginConfig(m, i, "k");
    if (k.empty()) throw Error("test.spring needs k");
    data->k = std::stod(k);
    return std::unique_ptr<PluginInstanceData>(std::move(data));
  };
  p.reset = [](const Model&, double* state, PluginInstanceData*, int) { state[0] = 0, state[1] = 7; };
  p.compute = [](const Model& m, Data& d, int i, int) {
    double k = static_cast<const SpringData&>(*d.plugin_data[i].data).k;
    for (int v = 0; v < m.nv; v++) d.qfrc_passive[v] -= k * d.qpos[v];
    d.plugin_state[m.plugin_stateadr[i]] += 1;
  };
  RegisterPlugin(p);
}

const char* kSpring = R"(<mujoco><option gravity="0 0 0"/>
  <extension><plugin plugin="test.spring">
    <instance name="soft"><config key="k" value="3"/></instance>
  </plugin></extension>
  <worldbody><body><joint type="slide" axis="1 0 0"/><geom size=".1" mass="1"/></body></worldbody>
</mujoco>)";

TEST(Plugin, PassivePluginAddsItsForceAndKeepsItsState) {
  RegisterTestSpring();
  Model m = LoadXmlString(kSpring);
  ASSERT_EQ(m.nplugin, 1);
  EXPECT_EQ(m.npluginstate, 2);
  EXPECT_EQ(PluginConfig(m, 0, "k"), "3");
  EXPECT_EQ(PluginConfig(m, 0, "unused"), "");
  Data d = MakeData(m);
  EXPECT_EQ(d.plugin_state[1], 7);  // from its reset
  d.qpos[0] = 0.2;
  Forward(m, d);
  EXPECT_DOUBLE_EQ(d.qfrc_passive[0], -3 * 0.2);
  EXPECT_EQ(d.plugin_state[0], 1);
  // A copy of the Data has its own copy of the plugin's data, and steps alike.
  Data copy = d;
  Step(m, d);
  Step(m, copy);
  EXPECT_EQ(d.qpos[0], copy.qpos[0]);
  ResetData(m, d);
  EXPECT_EQ(d.plugin_state[0], 0);
}

// MuJoCo's pid_test PGain: kp alone is the position servo, exactly.
TEST(Plugin, PidGainIsThePositionServo) {
  Model m = LoadXmlString(R"(<mujoco><option gravity="0 0 0"/>
    <extension><plugin plugin="mujoco.pid"><instance name="p"><config key="kp" value="4"/></instance></plugin></extension>
    <worldbody><body><joint name="a" type="slide" axis="1 0 0"/><geom size=".1" mass="1"/></body>
    <body pos="1 0 0"><joint name="b" type="slide" axis="1 0 0"/><geom size=".1" mass="1"/></body></worldbody>
    <actuator><plugin joint="a" instance="p"/><position joint="b" kp="4"/></actuator></mujoco>)");
  EXPECT_EQ(m.actuator_plugin[0], 0);
  EXPECT_EQ(m.actuator_plugin[1], -1);
  Data d = MakeData(m);
  d.ctrl[0] = d.ctrl[1] = 1;
  for (int k = 0; k < 3; k++) {
    Step(m, d);
    EXPECT_EQ(d.actuator_force[0], d.actuator_force[1]);
    EXPECT_EQ(d.qpos[0], d.qpos[1]);
  }
}

// MuJoCo's pid_test ITerm: under gravity, P alone sags by g / kp, the integral removes the
// sag, and imax (a force limit of 5) leaves part of it.
TEST(Plugin, PidIntegralRemovesTheSag) {
  Model m = LoadXmlString(R"(<mujoco><option gravity="0 0 -10" timestep="0.001"/>
    <extension><plugin plugin="mujoco.pid">
      <instance name="pid2"><config key="kp" value="40"/><config key="ki" value="40"/><config key="kd" value="4"/></instance>
      <instance name="pid3"><config key="kp" value="40"/><config key="ki" value="40"/><config key="kd" value="4"/><config key="imax" value="5"/></instance>
      <instance name="pid1"><config key="kp" value="40"/><config key="kd" value="4"/></instance>
    </plugin></extension>
    <worldbody>
      <body><joint name="j1" type="slide" axis="0 0 1"/><geom size=".1" mass="1"/></body>
      <body pos="1 0 0"><joint name="j2" type="slide" axis="0 0 1"/><geom size=".1" mass="1"/></body>
      <body pos="2 0 0"><joint name="j3" type="slide" axis="0 0 1"/><geom size=".1" mass="1"/></body>
    </worldbody><contact><exclude body1="world" body2="world"/></contact>
    <actuator><plugin joint="j1" instance="pid1"/><plugin joint="j2" instance="pid2" actdim="1"/>
      <plugin joint="j3" instance="pid3" actdim="1"/></actuator></mujoco>)");
  Data d = MakeData(m);
  for (double& u : d.ctrl) u = 1;
  for (int k = 0; k < 10000; k++) Step(m, d);
  EXPECT_NEAR(d.qpos[0], 1 - 10.0 / 40, 1e-5);
  EXPECT_NEAR(d.qpos[1], 1, 1e-5);
  EXPECT_NEAR(d.qpos[2], 1 - (10 - 0.125 * 40) / 40, 1e-5);
}

TEST(Plugin, BadPluginsAreClearErrors) {
  RegisterTestSpring();
  const std::string pid_instance =
      R"(<extension><plugin plugin="mujoco.pid"><instance name="p">%</instance></plugin></extension>)";
  auto model = [](const std::string& extension, const std::string& actuator) {
    return "<mujoco>" + extension +
           "<worldbody><body><joint name='j' type='slide'/><geom size='.1'/></body></worldbody>"
           "<actuator>" + actuator + "</actuator></mujoco>";
  };
  auto with = [](std::string text, const std::string& fill) { return text.replace(text.find('%'), 1, fill); };
  struct Bad {
    std::string xml;
    std::vector<std::string> says;
  };
  const Bad cases[] = {
      {model(R"(<extension><plugin plugin="no.such"/></extension>)", ""), {"no.such", "not registered"}},
      {model("", "<plugin joint='j' plugin='mujoco.pid'/>"), {"not declared in <extension>"}},
      {model(with(pid_instance, ""), "<plugin joint='j' instance='q'/>"), {"unrecognized name 'q'"}},
      {model(with(pid_instance, "<config key='kq' value='1'/>"), "<plugin joint='j' instance='p'/>"),
       {"plugin:kq"}},
      {model(with(pid_instance, "<config key='ki' value='4'/><config key='imax' value='-1'/>"),
             "<plugin joint='j' instance='p' actdim='1'/>"), {"bad.xml:1", "negative imax"}},
      {model(with(pid_instance, "<config key='slewmax' value='1'/>"), "<plugin joint='j' instance='p'/>"),
       {"actdim=\"1\""}},
      {model(with(pid_instance, "<config key='kp' value='four'/>"), "<plugin joint='j' instance='p'/>"),
       {"not a number"}},
      {model(R"(<extension><plugin plugin="test.spring"><instance name="s"><config key="k" value="1"/></instance></plugin></extension>)",
             "<plugin joint='j' instance='s'/>"), {"does not support actuators"}},
      {model(R"(<extension><plugin plugin="test.spring"><instance name="s"/></plugin></extension>)", ""),
       {"test.spring needs k"}},
      {model("", "<plugin joint='j'/>"), {"neither 'plugin' nor 'instance'"}},
  };
  for (const Bad& bad : cases) test_util::ExpectMessageParts(test_util::XmlLoadError(bad.xml), bad.says, bad.xml);
}

}  // namespace
}  // namespace simlab
