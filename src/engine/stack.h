// Scratch arrays for a stage, taken from Data::stack and returned when the frame ends.
//
//   StackFrame frame(d);
//   double* tmp = frame.Alloc(6 * m.nbody);   // valid until `frame` goes out of scope
#ifndef SIMLAB_ENGINE_STACK_H_
#define SIMLAB_ENGINE_STACK_H_

#include <cstddef>
#include <memory>
#include <vector>

#include "simlab/data.h"

namespace simlab {

class StackFrame {
 public:
  explicit StackFrame(Data& d) : d_(d), saved_(d.stack_top) {}
  ~StackFrame() { d_.stack_top = saved_; }
  StackFrame(const StackFrame&) = delete;
  StackFrame& operator=(const StackFrame&) = delete;

  // n doubles, zero-initialized. MakeData sizes the stack for every stage; should it
  // ever be short, the frame allocates on the heap (outer frames' pointers stay valid).
  double* Alloc(size_t n) {
    double* p;
    if (d_.stack_top + n <= d_.stack.size()) {
      p = d_.stack.data() + d_.stack_top;
      d_.stack_top += n;
    } else {
      overflow_.push_back(std::make_unique<double[]>(n));
      p = overflow_.back().get();
    }
    for (size_t k = 0; k < n; k++) p[k] = 0;
    return p;
  }

 private:
  Data& d_;
  size_t saved_;
  std::vector<std::unique_ptr<double[]>> overflow_;
};

}  // namespace simlab

#endif  // SIMLAB_ENGINE_STACK_H_
