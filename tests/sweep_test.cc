// Sweep and prune keeps its sorted interval ends between steps and sorts the next step's
// from their order (SortEnds). The order is unique (keys are unique), so it is the one
// std::sort gives from any start, and a step's contacts are the same whether the sweep
// starts from last step's order or from nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "engine/collision_driver.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

// Keys for ties 0..n-1: a value (random, with repeats) above the tie.
std::vector<uint64_t> Keys(int n, std::mt19937& random) {
  std::uniform_int_distribution<uint64_t> value(0, static_cast<uint64_t>(n) / 4);
  std::vector<uint64_t> keys(n);
  for (int t = 0; t < n; t++) keys[t] = (value(random) << 32) | static_cast<uint32_t>(t);
  return keys;
}

// SortEnds from `start` (ties in some order) against std::sort of the same keys.
void ExpectResortsAsSort(std::vector<uint64_t> start, const std::vector<uint64_t>& keys) {
  std::vector<uint64_t> sorted = keys;
  std::sort(sorted.begin(), sorted.end());
  SortEnds(start, keys.size(), [&](uint32_t tie) { return keys[tie]; });
  EXPECT_EQ(start, sorted);
}

TEST(Sweep, ResortsToTheOneSortedOrderFromAnyStart) {
  std::mt19937 random(7);
  for (int n : {0, 1, 2, 17, 900}) {
    std::vector<uint64_t> keys = Keys(n, random);
    std::vector<uint64_t> ties(n);
    for (int t = 0; t < n; t++) ties[t] = static_cast<uint64_t>(t);
    // from nothing kept, in tie order, reversed, shuffled (far off: the fallback), and
    // nearly sorted
    ExpectResortsAsSort({}, keys);
    ExpectResortsAsSort(ties, keys);
    std::reverse(ties.begin(), ties.end());
    ExpectResortsAsSort(ties, keys);
    std::shuffle(ties.begin(), ties.end(), random);
    ExpectResortsAsSort(ties, keys);
    std::vector<uint64_t> near = keys;
    std::sort(near.begin(), near.end());
    for (int k = 0; k + 1 < n; k += 5) std::swap(near[k], near[k + 1]);
    ExpectResortsAsSort(near, keys);
  }
}

using ContactKey = std::tuple<int, int, int, int, int, int, double, double, double, double>;

std::vector<ContactKey> ContactsOf(const Data& d) {
  std::vector<ContactKey> keys;
  for (int i = 0; i < d.ncon; i++) {
    const Contact& c = d.contact[i];
    keys.emplace_back(c.geom[0], c.geom[1], c.flex[0], c.flex[1], c.elem[0], c.elem[1], c.dist,
                      c.pos[0], c.pos[1], c.pos[2]);
  }
  return keys;
}

// A thick cloth swept against itself, draped over a ball among boxes that tumble (it
// folds onto itself): every step, the contacts (in order) from the sweeps that kept their
// ends equal those from sweeps that start anew.
TEST(Sweep, ContactsDoNotDependOnTheOrderKeptFromTheLastStep) {
  Model m = LoadXmlString(R"(
    <mujoco>
      <option timestep="0.002"/>
      <worldbody>
        <geom type="plane" size="2 2 .1"/>
        <body pos=".5 -.4 .2"><freejoint/><geom type="box" size=".1 .1 .1"/></body>
        <body pos="-.45 .1 .2" euler="0 20 30"><freejoint/><geom type="box" size=".08 .08 .08"/></body>
        <geom type="sphere" size=".25" pos="0 0 .25"/>
        <body pos=".5 .4 .3"><freejoint/><geom type="sphere" size=".1"/></body>
        <flexcomp type="grid" count="12 12 1" spacing=".1 .1 .1" pos="0 0 .7" radius=".045"
                  mass="1" name="cloth" dim="2">
          <contact selfcollide="sap" condim="3"/>
          <edge equality="false" damping="1"/>
        </flexcomp>
      </worldbody>
    </mujoco>)");
  Data d = MakeData(m);
  int self_contacts = 0;
  for (int step = 0; step < 250; step++) {
    Data fresh = d;
    fresh.broadphase.ends.clear();
    fresh.broadphase.flex_ends.clear();
    Forward(m, fresh);
    Forward(m, d);
    ASSERT_EQ(ContactsOf(d), ContactsOf(fresh)) << "step " << step;
    for (int i = 0; i < d.ncon; i++) self_contacts += d.contact[i].flex[0] >= 0 && d.contact[i].flex[1] >= 0;
    Step(m, d);
  }
  EXPECT_GT(self_contacts, 1000);
}

// With fewer than two collidable bodies the sweep (and its frame) is skipped; the world's
// pairs do not come from it: a lone ball still meets the world's plane, at MuJoCo's
// sphere-plane contact (distance z - radius, normal up), and the bodies that cannot
// collide (inside the ball) meet nothing.
TEST(Sweep, ALoneCollidableBodyMeetsOnlyTheWorld) {
  Model m = LoadXmlString(R"(
    <mujoco>
      <worldbody>
        <geom type="plane" size="2 2 .1"/>
        <body pos="0 0 .09"><freejoint/><geom type="sphere" size=".1"/></body>
        <body pos="0 0 .1"><freejoint/><geom type="sphere" size=".2" contype="0" conaffinity="0"/></body>
        <body pos=".05 0 .1"><freejoint/><geom type="box" size=".1 .1 .1" contype="0" conaffinity="0"/></body>
      </worldbody>
    </mujoco>)");
  Data d = MakeData(m);
  Forward(m, d);
  EXPECT_EQ(d.broadphase.pairs, std::vector<int>{1});  // (world 0 << 16) + ball 1
  EXPECT_EQ(d.broadphase.bodies, std::vector<int>{1});
  ASSERT_EQ(d.ncon, 1);
  EXPECT_EQ(d.contact[0].geom[1], 1);
  EXPECT_NEAR(d.contact[0].dist, 0.09 - 0.1, 1e-12);
  EXPECT_EQ(d.contact[0].frame[2], 1.0);
}

}  // namespace
}  // namespace simlab
