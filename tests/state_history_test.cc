// The scrubbing history (simlab/state_history.h): a state loaded back is the state that
// was recorded, bit for bit, so stepping on from it repeats the same future; stepping on
// from the past drops the newer states; a full ring forgets the oldest.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "simlab/simlab.h"
#include "simlab/state_history.h"
#include "simlab/support.h"

namespace simlab {
namespace {

const std::string kGantry = std::string(SIMLAB_SOURCE_DIR) + "/models/gantry_gripper.xml";

std::vector<double> StateOf(const Model& m, const Data& d) {
  std::vector<double> state(StateSize(m, kStateIntegration));
  GetState(m, d, state.data(), kStateIntegration);
  return state;
}

// The gantry from its home keyframe, the grip closing, every state recorded.
struct Recorded {
  Model m = LoadXml(kGantry);
  Data d = MakeData(m);
  StateHistory history{m, 100};
  std::vector<std::vector<double>> states;

  explicit Recorded(int steps) {
    ResetDataKeyframe(m, d, 0);
    d.ctrl[3] = 0;
    history.Record(m, d);
    states.push_back(StateOf(m, d));
    for (int i = 0; i < steps; i++) {
      Step(m, d);
      history.Record(m, d);
      states.push_back(StateOf(m, d));
    }
  }
};

TEST(StateHistory, LoadsRecordedStatesBitForBit) {
  Recorded r(40);
  ASSERT_EQ(r.history.size(), 41);
  for (int back : {0, 1, 17, 40}) {
    r.history.Load(r.m, r.d, back);
    EXPECT_EQ(StateOf(r.m, r.d), r.states[40 - back]) << back;
    EXPECT_EQ(r.history.back(), back);
    EXPECT_EQ(r.history.TimeAt(back), r.d.time);
  }
  EXPECT_THROW(r.history.Load(r.m, r.d, 41), Error);
  EXPECT_THROW(r.history.Load(r.m, r.d, -1), Error);
}

TEST(StateHistory, SteppingOnFromThePastRepeatsTheFutureAndDropsTheNewer) {
  Recorded r(40);
  r.history.Load(r.m, r.d, 10);
  Forward(r.m, r.d);
  for (int i = 0; i < 10; i++) {
    Step(r.m, r.d);
    r.history.Record(r.m, r.d);
  }
  // (the same 10 steps again: the same state, and the history as long as before)
  EXPECT_EQ(StateOf(r.m, r.d), r.states[40]);
  EXPECT_EQ(r.history.size(), 41);
  EXPECT_EQ(r.history.back(), 0);
  // Loaded 5 back and recorded once: the 5 newer states are gone.
  r.history.Load(r.m, r.d, 5);
  r.history.Record(r.m, r.d);
  EXPECT_EQ(r.history.size(), 37);
}

TEST(StateHistory, AFullRingForgetsTheOldest) {
  Recorded r(250);
  EXPECT_EQ(r.history.size(), 100);
  r.history.Load(r.m, r.d, 99);
  EXPECT_EQ(StateOf(r.m, r.d), r.states[250 - 99]);
  r.history.Clear();
  EXPECT_EQ(r.history.size(), 0);
  EXPECT_THROW(r.history.Load(r.m, r.d, 0), Error);
}

TEST(StateHistory, CapacityCoversTheSecondsWithinTheMemory) {
  Model m = LoadXml(kGantry);
  EXPECT_EQ(StateHistory::CapacityFor(m, 10.0), static_cast<int>(10.0 / m.opt.timestep));
  const int state_bytes = 8 * StateSize(m, kStateIntegration);
  EXPECT_EQ(StateHistory::CapacityFor(m, 10.0, 100.0 * state_bytes), 100);
  EXPECT_EQ(StateHistory::CapacityFor(m, 0.0), 1);
}

}  // namespace
}  // namespace simlab
