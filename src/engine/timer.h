// The profiler's timers: one StageTimer times the scope it lives in into d.timer[kind]
// when the Data has a clock (d.timer_clock), and costs a branch when it has none.
//
//   StageTimer timer(d, kTimerPosition);   // until the end of the block
#ifndef SIMLAB_ENGINE_TIMER_H_
#define SIMLAB_ENGINE_TIMER_H_

#include "simlab/data.h"

namespace simlab {

class StageTimer {
 public:
  StageTimer(Data& d, Timer kind) : d_(d), kind_(kind) {
    if (d.timer_clock) start_ = d.timer_clock();
  }
  ~StageTimer() {
    if (!d_.timer_clock) return;
    d_.timer[kind_].duration += d_.timer_clock() - start_;
    d_.timer[kind_].number++;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  Data& d_;
  Timer kind_;
  double start_ = 0;
};

}  // namespace simlab

#endif  // SIMLAB_ENGINE_TIMER_H_
