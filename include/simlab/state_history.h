// The last seconds of a simulation, kept to be scrubbed back and forward as MuJoCo's
// simulate does (its history buffer): a ring of whole integration states
// (kStateIntegration: time, qpos, qvel, act, warm start, ctrl, applied forces, mocap...),
// one recorded after every step, from which any of them can be loaded back into Data.
//
//   simlab::StateHistory history(m, history.CapacityFor(m, 10.0));
//   history.Record(m, d);                  // after reset and after every step
//   history.Load(m, d, 25);                // d as it was 25 states before the newest
//   simlab::Forward(m, d);                 // (derived quantities, for drawing)
//   history.Record(m, d);                  // stepping on from there: the 25 newer states
//                                          // are dropped, a new future is recorded
#ifndef SIMLAB_STATE_HISTORY_H_
#define SIMLAB_STATE_HISTORY_H_

#include <utility>
#include <vector>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

class StateHistory {
 public:
  // Room for `capacity` states of model m (at least 1).
  StateHistory(const Model& m, int capacity);

  // States that cover `seconds` of simulation at m's timestep, but no more than fit in
  // `max_bytes`, and at least 1.
  static int CapacityFor(const Model& m, double seconds, double max_bytes = 64.0 * (1 << 20));

  // Appends d's state as the newest. After a Load, the states newer than the loaded one
  // are dropped first (stepping on from the past starts a new future). When full, the
  // oldest state is overwritten.
  void Record(const Model& m, const Data& d);

  // Writes the state `back` states before the newest into d (0: the newest) and
  // remembers it as the current one. Derived quantities are not recomputed (call
  // Forward). Throws Error for a `back` outside [0, size()).
  void Load(const Model& m, Data& d, int back);

  // Forgets every state.
  void Clear();

  int size() const { return count_; }
  int capacity() const { return capacity_; }
  // How many states before the newest the last Load went (0 after a Record).
  int back() const { return back_; }
  // The simulation time of the state `back` states before the newest.
  double TimeAt(int back) const;

 private:
  // The state held `back` states before the newest.
  const double* Slot(int back) const;
  double* Slot(int back) { return const_cast<double*>(std::as_const(*this).Slot(back)); }

  int state_size_;
  int capacity_;
  int count_ = 0;   // states held
  int newest_ = -1; // ring slot of the newest state
  int back_ = 0;
  std::vector<double> states_;  // capacity_ x state_size_
};

}  // namespace simlab

#endif  // SIMLAB_STATE_HISTORY_H_
