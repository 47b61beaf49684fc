// `simlab explain`: each actuator read as p = a u + b0 + b1 l + b2 l', on the lesson's
// bench and on the lesson's trap (a general with biasprm but no biastype).
#include "explain.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "simlab/simlab.h"

namespace simlab::apps {
namespace {

const std::string kBench = std::string(SIMLAB_SOURCE_DIR) + "/models/actuator_bench.xml";

bool Contains(const std::string& text, const std::string& piece) {
  return text.find(piece) != std::string::npos;
}

// The position servo's whole block, as a reader sees it.
TEST(Explain, BenchPositionServoBlock) {
  Model m = LoadXml(kBench);
  EXPECT_EQ(ExplainActuator(m, 1),
            "actuator 1 \"position\", reads as: position (kp 10, kv 1)\n"
            "  law           p = 10 u - 10 l - 1 l'\n"
            "  a (gain)      fixed: a = gainprm[0] = 10\n"
            "  b (bias)      affine: b0 = 0, b1 = -10, b2 = -1\n"
            "  u             ctrl[1] (no activation state)\n"
            "  dynamics      none: u = ctrl, no state\n"
            "  transmission  joint \"position_hinge\" (hinge), gear 1: l = 1 q, joint force = 1 p\n"
            "  clamps        ctrlrange: off\n"
            "                forcerange: on  [-3, 3]  clamps p\n"
            "                actuatorfrcrange of joint \"position_hinge\": off\n");
}

// A pid: its inputs as named setpoints at their ctrl entries, the law over the setpoints
// it has, its integral and each input's range.
TEST(Explain, PidNamesItsSetpoints) {
  Model m = LoadXmlString(
      "<mujoco><compiler autolimits='true'/><worldbody><body><joint name='h'/>"
      "<geom size='.1'/></body></worldbody><actuator><motor joint='h'/>"
      "<pid name='servo' joint='h' kp='20' kv='2' ki='5' imax='0.5' input='pos ff' "
      "ctrlrange='-1 1' ffrange='-3 3'/></actuator></mujoco>");
  std::string text = ExplainActuator(m, 1);
  EXPECT_TRUE(Contains(text, "reads as: pid (kp 20, kv 2, ki 5, imax 0.5; inputs pos ff)")) << text;
  EXPECT_TRUE(Contains(text, "law           p = 20 (qref - l) + ff - 2 l' + 5 w\n")) << text;
  EXPECT_TRUE(Contains(text, "u             qref = ctrl[1], ff = ctrl[2]; the absent ones are 0"))
      << text;
  EXPECT_TRUE(Contains(text, "pid: w' = qref - l, the integral, stops growing past imax = 0.5")) << text;
  EXPECT_TRUE(Contains(text, "ctrl[2]: on  [-3, 3]  clamps this input")) << text;
  EXPECT_TRUE(Contains(ExplainModel(m), "2 actuator(s)"));
}

// A DC motor: constants, inputs, states and the law it follows without inductance.
TEST(Explain, DcmotorListsItsStates) {
  Model m = LoadXmlString(
      "<mujoco><worldbody><body><joint name='h'/><geom size='.1'/></body></worldbody>"
      "<actuator><dcmotor joint='h' motorconst='0.05' resistance='2' input='pos voltage' "
      "controller='1 0.5' thermal='10 5'/></actuator></mujoco>");
  std::string text = ExplainActuator(m, 0);
  EXPECT_TRUE(Contains(text, "reads as: dcmotor (K 0.05, R 2, controller kp 1 ki 0.5 kd 0, thermal; "
                             "inputs pos voltage)")) << text;
  EXPECT_TRUE(Contains(text, "p = K / R (V - K l') with K 0.05, R 2")) << text;
  EXPECT_TRUE(Contains(text, "qref = ctrl[0], V = ctrl[1]; the absent ones are 0")) << text;
  EXPECT_TRUE(Contains(text, "dcmotor: states position error integral, winding temperature")) << text;
}

// An actuator computed by a plugin reads as that plugin, with its configuration.
TEST(Explain, PluginActuatorNamesItsPlugin) {
  Model m = LoadXmlString(
      "<mujoco><extension><plugin plugin='mujoco.pid'><instance name='p'>"
      "<config key='kp' value='20'/><config key='kd' value='1.5'/></instance></plugin></extension>"
      "<worldbody><body><joint name='h'/><geom size='.1'/></body></worldbody>"
      "<actuator><plugin joint='h' instance='p'/></actuator></mujoco>");
  std::string text = ExplainActuator(m, 0);
  EXPECT_TRUE(Contains(text, "reads as: plugin \"mujoco.pid\"")) << text;
  EXPECT_TRUE(Contains(text, "p computed by plugin \"mujoco.pid\" (instance 0: kp 20, kd 1.5)")) << text;
  EXPECT_FALSE(Contains(text, "a (gain)")) << text;
}

// Every bench actuator: its shortcut, law, gear, dynamics and clamps.
TEST(Explain, BenchReadsAsTheLessonsTable) {
  std::ostringstream out;
  EXPECT_EQ(RunExplain(kBench, out), 0);
  std::string text = out.str();
  EXPECT_TRUE(Contains(text, "4 actuator(s), each an instance of p = a u + b0 + b1 l + b2 l'"));
  EXPECT_TRUE(Contains(text, "actuator 0 \"motor\", reads as: motor\n  law           p = 1 u\n"));
  EXPECT_TRUE(Contains(text, "gear 2: l = 2 q, joint force = 2 p"));
  EXPECT_TRUE(Contains(text, "ctrlrange: on  [-1, 1]"));
  EXPECT_TRUE(Contains(text, "actuator 2 \"velocity\", reads as: velocity (kv 3)\n"
                             "  law           p = 3 u - 3 l'\n"));
  EXPECT_TRUE(Contains(text, "actuator 3 \"filter\", reads as: general with filter dynamics\n"
                             "  law           p = 5 w\n"));
  EXPECT_TRUE(Contains(text, "act[0], the activation w"));
  EXPECT_TRUE(Contains(text, "filter: w' = (ctrl - w) / tau, tau = 0.1 s"));
  EXPECT_TRUE(Contains(text, "actrange: off"));
}

// The lesson's trap: biasprm compiled, biastype none, so no bias; stated plainly.
TEST(Explain, GeneralWithBiasprmButNoBiastype) {
  Model m = LoadXmlString(
      "<mujoco><worldbody><body><joint name=\"j\" axis=\"0 0 1\"/><geom size=\"0.1\"/>"
      "</body></worldbody><actuator>"
      "<general name=\"trap\" joint=\"j\" gainprm=\"4\" biasprm=\"0 0 -4\"/>"
      "<general name=\"fixed\" joint=\"j\" gainprm=\"4\" biastype=\"affine\" biasprm=\"0 0 -4\"/>"
      "</actuator></mujoco>");
  std::string trap = ExplainActuator(m, 0), fixed = ExplainActuator(m, 1);
  EXPECT_TRUE(Contains(trap, "reads as: general\n"));
  EXPECT_TRUE(Contains(trap, "law           p = 4 u\n"));
  EXPECT_TRUE(Contains(trap, "b (bias)      none: biasprm [0 0 -4] ignored"));
  EXPECT_TRUE(Contains(trap, "biastype=\"affine\""));
  // Written out with its biastype, the same numbers are the velocity servo.
  EXPECT_TRUE(Contains(fixed, "reads as: velocity (kv 4)\n"));
  EXPECT_TRUE(Contains(fixed, "law           p = 4 u - 4 l'\n"));
}

// Other shortcuts and transmissions: intvelocity, position with timeconst on a tendon,
// damper, joint actuatorfrcrange.
TEST(Explain, ShortcutsTendonAndJointClamp) {
  Model m = LoadXmlString(
      "<mujoco><worldbody>"
      "<body><joint name=\"j\" axis=\"0 0 1\" actuatorfrcrange=\"-2 2\"/><geom size=\"0.1\"/></body>"
      "<body pos=\"1 0 0\"><joint name=\"k\" type=\"slide\"/><geom size=\"0.1\"/></body>"
      "</worldbody><tendon><fixed name=\"t\"><joint joint=\"j\" coef=\"0.5\"/>"
      "<joint joint=\"k\" coef=\"0.5\"/></fixed></tendon><actuator>"
      "<intvelocity joint=\"k\" kp=\"5\" actrange=\"-1 1\"/>"
      "<position tendon=\"t\" kp=\"5\" timeconst=\"0.2\" ctrlrange=\"0 1\"/>"
      "<damper joint=\"k\" kv=\"2\" ctrlrange=\"0 1\"/>"
      "<motor joint=\"j\"/>"
      "</actuator></mujoco>");
  std::string text = ExplainModel(m);
  EXPECT_TRUE(Contains(text, "reads as: intvelocity (kp 5, kv 0)"));
  EXPECT_TRUE(Contains(text, "dynamics      integrator: w' = ctrl"));
  EXPECT_TRUE(Contains(text, "actrange: on  [-1, 1]"));
  EXPECT_TRUE(Contains(text, "reads as: position with timeconst 0.2 (kp 5, kv 0)"));
  EXPECT_TRUE(Contains(text, "filterexact: w' = (ctrl - w) / tau, tau = 0.2 s"));
  EXPECT_TRUE(Contains(text, "transmission  tendon \"t\", gear 1"));
  EXPECT_TRUE(Contains(text, "reads as: damper (kv 2)"));
  EXPECT_TRUE(Contains(text, "affine: a = 0 - 2 l'"));
  EXPECT_TRUE(Contains(text, "actuatorfrcrange of joint \"j\": on  [-2, 2]"));
  EXPECT_TRUE(Contains(text, "(unnamed)"));
}

}  // namespace
}  // namespace simlab::apps

namespace simlab::apps {
namespace {

// Each sensor reads as its type, object, reference and place in sensordata.
TEST(Explain, SensorsListTheirPlaceInSensordata) {
  Model m = LoadXmlString(
      "<mujoco><worldbody><site name=\"o\"/><body name=\"b\"><joint name=\"j\"/>"
      "<geom size=\".1\"/><site name=\"s\"/></body></worldbody><sensor>"
      "<jointpos name=\"angle\" joint=\"j\" cutoff=\"2\"/>"
      "<framepos objtype=\"site\" objname=\"s\" reftype=\"site\" refname=\"o\" noise=\"0.1\"/>"
      "</sensor></mujoco>");
  EXPECT_EQ(ExplainSensor(m, 0),
            "sensor 0 \"angle\": jointpos of joint \"j\" -> sensordata[0], after the position "
            "stage, cutoff 2\n");
  EXPECT_EQ(ExplainSensor(m, 1),
            "sensor 1 (unnamed): framepos of site \"s\" relative to site \"o\" -> "
            "sensordata[1..3], after the position stage, noise 0.1 (stored, not applied)\n");
  EXPECT_NE(ExplainModel(m).find("2 sensor(s), 4 number(s) in sensordata"), std::string::npos);
}

}  // namespace
}  // namespace simlab::apps
