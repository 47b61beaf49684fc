// Engine plugins: a passive-force plugin registered here (its config, state, reset and
// data copied with the Data), sensor plugins (sizes, stages, cutoffs) and body
// attachment, MuJoCo's mujoco.pid on small models against the servos it equals (MuJoCo's
// own pid_test numbers), and the loader's checks. Whole rollouts of
// mujoco.pid models are compared with native MuJoCo in tests/conformance/actuators312.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

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

// test.gauge: a sensor plugin of the velocity stage. Each of its sensors reads, when it
// names a joint (objtype/objname), that joint's qpos and qvel (2 numbers), else the time
// (1 number); plugin_state[0] counts its computations, which must see the velocity
// stage's subtree momenta already computed.
void RegisterTestGauge(const std::string& name, int needstage) {
  if (PluginSlot(name) >= 0) return;
  Plugin p;
  p.name = name;
  p.capabilities = kPluginSensor;
  p.needstage = needstage;
  p.nstate = [](const Model&, int) { return 1; };
  p.nsensordata = [](const Model& m, int, int sensor) {
    return m.sensor_objtype[sensor] == kObjJoint ? 2 : 1;
  };
  p.compute = [](const Model& m, Data& d, int i, int capability) {
    ASSERT_EQ(capability, kPluginSensor);
    d.plugin_state[m.plugin_stateadr[i]] += 1;
    for (int s = 0; s < m.nsensor; s++) {
      if (m.sensor_plugin[s] != i) continue;
      double* out = &d.sensordata[m.sensor_adr[s]];
      int j = m.sensor_objid[s];
      if (m.sensor_objtype[s] == kObjJoint) {
        out[0] = d.qpos[m.jnt_qposadr[j]];
        out[1] = d.qvel[m.jnt_dofadr[j]];
      } else {
        out[0] = d.time;
      }
    }
  };
  RegisterPlugin(p);
}

const char* kGauge = R"(<mujoco><option gravity="0 0 0"/>
  <extension><plugin plugin="test.gauge">
    <instance name="g"/>
  </plugin><plugin plugin="test.spring"/></extension>
  <worldbody>
    <body name="b"><plugin plugin="test.spring"><config key="k" value="1"/></plugin>
      <joint name="x" type="slide" axis="1 0 0"/><geom size=".1" mass="1"/></body>
  </worldbody>
  <sensor>
    <jointpos joint="x"/>
    <plugin name="xv" instance="g" objtype="joint" objname="x" cutoff="0.5"/>
    <plugin name="t" plugin="test.gauge"/>
    <jointvel joint="x"/>
  </sensor>
</mujoco>)";

TEST(Plugin, SensorPluginWritesItsSensorsAtItsStage) {
  RegisterTestSpring();
  RegisterTestGauge("test.gauge", kStageVel);
  Model m = LoadXmlString(kGauge);
  // Instances: g (named), then the body's and the sensor's own, in the order they are read
  // (sensors before the world body, as MuJoCo reads the sections).
  ASSERT_EQ(m.nplugin, 3);
  EXPECT_EQ(m.plugin[0], PluginSlot("test.gauge"));
  EXPECT_EQ(m.plugin[1], PluginSlot("test.gauge"));
  EXPECT_EQ(m.plugin[2], PluginSlot("test.spring"));
  EXPECT_EQ(m.body_plugin[0], -1);
  EXPECT_EQ(m.body_plugin[1], 2);
  EXPECT_EQ(m.sensor_type[1], kSensPlugin);
  EXPECT_EQ((std::vector<int>{m.sensor_plugin[0], m.sensor_plugin[1], m.sensor_plugin[2], m.sensor_plugin[3]}),
            (std::vector<int>{-1, 0, 1, -1}));
  EXPECT_EQ((std::vector<int>{m.sensor_dim[0], m.sensor_dim[1], m.sensor_dim[2], m.sensor_dim[3]}),
            (std::vector<int>{1, 2, 1, 1}));
  EXPECT_EQ((std::vector<int>{m.sensor_adr[0], m.sensor_adr[1], m.sensor_adr[2], m.sensor_adr[3]}),
            (std::vector<int>{0, 1, 3, 4}));
  EXPECT_EQ(m.nsensordata, 5);
  EXPECT_EQ(m.sensor_needstage[1], kStageVel);

  Data d = MakeData(m);
  d.qpos[0] = 0.2;
  d.qvel[0] = 3;
  Forward(m, d);
  EXPECT_EQ(d.sensordata[0], 0.2);
  EXPECT_EQ(d.sensordata[1], 0.2);
  EXPECT_EQ(d.sensordata[2], 0.5);  // qvel 3, cut off at 0.5
  EXPECT_EQ(d.sensordata[3], 0.0);  // the time
  EXPECT_EQ(d.sensordata[4], 3.0);
  EXPECT_EQ(d.plugin_state[m.plugin_stateadr[0]], 1);
  EXPECT_EQ(d.plugin_state[m.plugin_stateadr[1]], 1);
  EXPECT_TRUE(d.flg_subtreevel);
  Step(m, d);
  Step(m, d);
  EXPECT_DOUBLE_EQ(d.sensordata[3], m.opt.timestep);  // read at the start of the second step

  // Sensors disabled: the plugin is not called.
  m.opt.disableflags |= kDisableSensor;
  double calls = d.plugin_state[m.plugin_stateadr[0]];
  Forward(m, d);
  EXPECT_EQ(d.plugin_state[m.plugin_stateadr[0]], calls);
}

TEST(Plugin, SensorPluginOfNoStageRunsWithPositionsWithoutCutoff) {
  RegisterTestGauge("test.gauge_none", kStageNone);
  Model m = LoadXmlString(R"(<mujoco>
    <extension><plugin plugin="test.gauge_none"/></extension>
    <worldbody><body><joint name="x" type="slide"/><geom size=".1"/></body></worldbody>
    <sensor><plugin plugin="test.gauge_none" objtype="joint" objname="x" cutoff="0.1"/></sensor>
  </mujoco>)");
  EXPECT_EQ(m.sensor_needstage[0], kStageNone);
  Data d = MakeData(m);
  d.qpos[0] = 0.7;
  d.qvel[0] = 0.3;
  Forward(m, d);
  // (MuJoCo applies the cutoffs of the stage's sensors, and these have none)
  EXPECT_EQ(d.sensordata[0], 0.7);
  EXPECT_EQ(d.sensordata[1], 0.3);
}

TEST(Plugin, BodyPluginIsAttachedToItsBody) {
  RegisterTestSpring();
  Model m = LoadXmlString(R"(<mujoco>
    <extension><plugin plugin="test.spring"><instance name="s"><config key="k" value="2"/></instance></plugin></extension>
    <worldbody>
      <body name="a"><joint type="slide"/><geom size=".1"/></body>
      <body name="b"><frame><plugin instance="s"/></frame><joint type="slide"/><geom size=".1"/></body>
    </worldbody>
  </mujoco>)");
  EXPECT_EQ((std::vector<int>{m.body_plugin[0], m.body_plugin[1], m.body_plugin[2]}), (std::vector<int>{-1, -1, 0}));
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

TEST(Plugin, BadSensorAndBodyPluginsAreClearErrors) {
  RegisterTestSpring();
  RegisterTestGauge("test.gauge", kStageVel);
  auto model = [](const std::string& body, const std::string& sensor) {
    return "<mujoco><extension><plugin plugin='test.gauge'><instance name='g'/></plugin>"
           "<plugin plugin='test.spring'><instance name='s'><config key='k' value='1'/></instance></plugin>"
           "<plugin plugin='mujoco.pid'/></extension>"
           "<worldbody><body>" + body + "<joint name='j' type='slide'/><geom size='.1'/></body></worldbody>"
           "<sensor>" + sensor + "</sensor></mujoco>";
  };
  struct Bad {
    std::string xml;
    std::vector<std::string> says;
  };
  const Bad cases[] = {
      {model("", "<plugin/>"), {"bad.xml:1", "neither 'plugin' nor 'instance' is specified for sensor"}},
      {model("", "<plugin instance='s'/>"), {"does not support sensors"}},
      {model("", "<plugin plugin='mujoco.pid'/>"), {"does not support sensors"}},
      {model("", "<plugin instance='q'/>"), {"unrecognized name 'q'"}},
      {model("", "<plugin instance='g' objtype='joint'/>"), {"objtype is specified but objname is not"}},
      {model("", "<plugin instance='g' refname='j'/>"), {"refname is specified but reftype is not"}},
      {model("", "<plugin instance='g' objtype='joint' objname='nope'/>"), {"unrecognized name 'nope'"}},
      {model("", "<plugin instance='g' objtype='gizmo' objname='j'/>"), {"unknown object type 'gizmo'"}},
      {model("", "<plugin instance='g' reftype='joint' refname='j'/>"), {"reference frame object"}},
      {model("", "<plugin instance='g' delay='1'/>"), {"delay"}},
      {model("", "<plugin instance='g'><config key='k' value='1'/></plugin>"), {"config belongs to instance 'g'"}},
      {model("<plugin instance='g'/>", ""), {"does not support passive forces"}},
      {model("<plugin/>", ""), {"neither 'plugin' nor 'instance' is specified for body"}},
      {model("<plugin instance='s'/><plugin instance='s'/>", ""), {"at most one plugin"}},
      {"<mujoco><extension><plugin plugin='test.gauge'><instance name='g'/></plugin></extension>"
       "<worldbody><replicate count='2'><body><plugin plugin='test.gauge'/><geom size='.1'/></body></replicate>"
       "</worldbody></mujoco>", {"plugin inside <replicate>", "not supported yet"}},
      {model("<geom size='.1'><plugin instance='s'/></geom>", ""),
       {"<geom>", "plugin 'test.spring' does not support signed distance fields"}},
      {model("<geom size='.1'><plugin plugin='p'/></geom>", ""), {"plugin 'p' is not declared in <extension>"}},
      {model("<geom size='.1'><plugin instance='s'/><plugin instance='s'/></geom>", ""), {"a geom has at most one plugin"}},
      {"<mujoco><asset><mesh name='m' vertex='0 0 0 1 0 0 0 1 0 0 0 1'><plugin instance='s'/></mesh></asset></mujoco>",
       {"<mesh name=\"m\">", "a mesh made by a plugin has no file, vertex, face or builtin"}},
      {model("<geom size='.1'><site/></geom>", ""), {"unknown element <site> in <geom>"}},
  };
  for (const Bad& bad : cases) test_util::ExpectMessageParts(test_util::XmlLoadError(bad.xml), bad.says, bad.xml);
}

}  // namespace
}  // namespace simlab
