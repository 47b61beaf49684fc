// mujoco.sensor.touch_grid: the grid's size, and its configuration errors. (Readings equal
// to native MuJoCo's to the bit are conformance cases of tests/conformance/plugins.)
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "load_error.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// A box on a floor, and a touch grid on a site of the box (its contacts are the box's).
std::string Grid(const std::string& config, const std::string& on = "objtype='site' objname='eye'") {
  return "<mujoco><extension><plugin plugin='mujoco.sensor.touch_grid'><instance name='g'>" + config +
         "</instance></plugin></extension><worldbody><geom type='plane' size='1 1 .1'/>"
         "<body name='box' pos='0 0 .1'><freejoint/><geom type='box' size='.1 .1 .1'/>"
         "<site name='eye' pos='0 0 .2'/></body></worldbody>"
         "<sensor><plugin name='touch' instance='g' " + on + "/></sensor></mujoco>";
}

const std::string kGood = "<config key='size' value='4 3'/><config key='fov' value='60 45'/>"
                          "<config key='nchannel' value='2'/>";

TEST(TouchGrid, ReadsTheBodysContactsOnItsGrid) {
  Model m = LoadXmlString(Grid(kGood), "grid.xml");
  ASSERT_EQ(m.nsensordata, 2 * 4 * 3);
  Data d = MakeData(m);
  for (int i = 0; i < 200; i++) Step(m, d);
  // Resting: the four corner contacts below the site, seen straight ahead (the middle
  // columns of the grid), push up on the box: negative normal readings summing to its
  // weight, and no tangential force to speak of.
  double normal = 0, tangent = 0;
  for (int k = 0; k < 12; k++) normal += d.sensordata[k];
  for (int k = 12; k < 24; k++) tangent += std::abs(d.sensordata[k]);
  double weight = m.body_mass[1] * 9.81;
  EXPECT_NEAR(std::abs(normal), weight, 1e-3 * weight);
  EXPECT_LT(tangent, 1e-3 * weight);
}

TEST(TouchGrid, BadConfigurationsAreClearErrors) {
  struct Bad {
    std::string xml;
    std::vector<std::string> says;
  };
  const std::vector<Bad> cases = {
      {Grid("<config key='size' value='4'/><config key='fov' value='60 45'/>"),
       {"touch_grid", "both horizontal and vertical resolutions must be specified"}},
      {Grid("<config key='size' value='4 0'/><config key='fov' value='60 45'/>"),
       {"resolutions must be positive"}},
      {Grid("<config key='size' value='4 3'/><config key='fov' value='200 45'/>"),
       {"fov[0] must be in (0, 180] degrees"}},
      {Grid(kGood + "<config key='gamma' value='2'/>"), {"gamma must be in [0, 1]"}},
      {Grid("<config key='size' value='4 3'/><config key='fov' value='60 45'/><config key='nchannel' value='9'/>"),
       {"nchannel must be between 1 and 6"}},
      {Grid(kGood, "objtype='body' objname='box'"), {"the sensor must be attached to a site"}},
  };
  for (const Bad& bad : cases) test_util::ExpectMessageParts(test_util::XmlLoadError(bad.xml), bad.says, bad.xml);
}

}  // namespace
}  // namespace simlab
