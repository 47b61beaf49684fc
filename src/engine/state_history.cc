// StateHistory: a ring of integration states (see simlab/state_history.h).
#include "simlab/state_history.h"

#include <algorithm>
#include <string>

#include "simlab/simlab.h"
#include "simlab/support.h"

namespace simlab {

StateHistory::StateHistory(const Model& m, int capacity)
    : state_size_(StateSize(m, kStateIntegration)), capacity_(std::max(1, capacity)) {
  states_.resize(static_cast<size_t>(capacity_) * state_size_);
}

int StateHistory::CapacityFor(const Model& m, double seconds, double max_bytes) {
  const double bytes_per_state = 8.0 * StateSize(m, kStateIntegration);
  const double by_time = m.opt.timestep > 0 ? seconds / m.opt.timestep : 1.0;
  const double by_memory = max_bytes / std::max(8.0, bytes_per_state);
  return static_cast<int>(std::clamp(std::min(by_time, by_memory), 1.0, 1e8));
}

const double* StateHistory::Slot(int back) const {
  const int slot = ((newest_ - back) % capacity_ + capacity_) % capacity_;
  return states_.data() + static_cast<size_t>(slot) * state_size_;
}

void StateHistory::Record(const Model& m, const Data& d) {
  // (a loaded past state becomes the newest: the states after it are dropped)
  if (back_ > 0) {
    newest_ = ((newest_ - back_) % capacity_ + capacity_) % capacity_;
    count_ -= back_;
    back_ = 0;
  }
  newest_ = (newest_ + 1) % capacity_;
  count_ = std::min(count_ + 1, capacity_);
  GetState(m, d, Slot(0), kStateIntegration);
}

void StateHistory::Load(const Model& m, Data& d, int back) {
  if (back < 0 || back >= count_) {
    throw Error("history: no state " + std::to_string(back) + " steps back (" +
                std::to_string(count_) + " states kept)");
  }
  SetState(m, d, Slot(back), kStateIntegration);
  back_ = back;
}

double StateHistory::TimeAt(int back) const {
  if (back < 0 || back >= count_) return 0;
  return Slot(back)[0];  // (time is the state's first number)
}

void StateHistory::Clear() {
  count_ = 0;
  newest_ = -1;
  back_ = 0;
}

}  // namespace simlab
