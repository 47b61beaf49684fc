// Scratch arrays for a stage, taken from Data::stack and returned when the frame ends.
//
//   StackFrame frame(d);
//   double* tmp = frame.Alloc(6 * m.nbody);   // valid until `frame` goes out of scope
//   double* out = frame.AllocToWrite(m.nv);   // the same, not cleared
#ifndef SIMLAB_ENGINE_STACK_H_
#define SIMLAB_ENGINE_STACK_H_

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "simlab/data.h"

namespace simlab {

class StackFrame {
 public:
  explicit StackFrame(Data& d) : d_(d), saved_(d.stack_top) {}
  ~StackFrame() {
    d_.stack_top = saved_;
    d_.stack_overflow -= overflowed_;
  }
  StackFrame(const StackFrame&) = delete;
  StackFrame& operator=(const StackFrame&) = delete;

  // n doubles, zero-initialized. MakeData sizes the stack for the model's stages; when
  // it is short (another integrator chosen since, many contacts), the frame allocates on
  // the heap (outer frames' pointers stay valid) and records the peak, to which the
  // stack grows before the next public call (GrowStack).
  double* Alloc(size_t n) {
    double* p = AllocToWrite(n);
    for (size_t k = 0; k < n; k++) p[k] = 0;
    return p;
  }

  // n doubles to be written before they are read (not cleared: their values are left
  // from earlier frames).
  double* AllocToWrite(size_t n) {
    double* p;
    if (d_.stack_top + n <= d_.stack.size()) {
      p = d_.stack.data() + d_.stack_top;
      d_.stack_top += n;
    } else {
      overflow_.push_back(std::make_unique<double[]>(n));
      p = overflow_.back().get();
      overflowed_ += n;
      d_.stack_overflow += n;
      d_.stack_peak = std::max(d_.stack_peak, d_.stack.size() + d_.stack_overflow);
    }
    return p;
  }

 private:
  Data& d_;
  size_t saved_;
  size_t overflowed_ = 0;
  std::vector<std::unique_ptr<double[]>> overflow_;
};

// Grows the stack to the peak a stage needed; only between public calls (no frame
// open), since it moves the stack.
inline void GrowStack(Data& d) {
  if (d.stack_top == 0 && d.stack_peak > d.stack.size()) d.stack.assign(d.stack_peak, 0.0);
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_STACK_H_
