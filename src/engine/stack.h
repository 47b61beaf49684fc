// Scratch arrays for a stage, taken from Data::stack and returned when the frame ends.
//
//   StackFrame frame(d);
//   double* tmp = frame.Alloc(6 * m.nbody);   // valid until `frame` goes out of scope
//   double* out = frame.AllocToWrite(m.nv);   // the same, not cleared
#ifndef SIMLAB_ENGINE_STACK_H_
#define SIMLAB_ENGINE_STACK_H_

#include <algorithm>
#include <cstddef>
#include <vector>

#include "simlab/data.h"

namespace simlab {

class StackFrame {
 public:
  explicit StackFrame(Data& d)
      : d_(d), saved_(d.stack_top), saved_blocks_(d.stack_blocks.size()) {}
  ~StackFrame() {
    d_.stack_top = saved_;
    if (d_.stack_blocks.size() > saved_blocks_) ReleaseBlocks();
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
    if (d_.stack_top + n > d_.stack.size()) return AllocBlock(n);
    double* p = d_.stack.data() + d_.stack_top;
    d_.stack_top += n;
    return p;
  }

 private:
  // The rare paths out of line, so that a frame's taking and ending stay a few
  // instructions inline: a heap block when the stack is short, and its release.
  [[gnu::noinline]] double* AllocBlock(size_t n) {
    d_.stack_blocks.emplace_back(n);
    size_t in_use = d_.stack.size();
    for (const std::vector<double>& block : d_.stack_blocks) in_use += block.size();
    d_.stack_peak = std::max(d_.stack_peak, in_use);
    return d_.stack_blocks.back().data();
  }
  [[gnu::noinline]] void ReleaseBlocks() { d_.stack_blocks.resize(saved_blocks_); }

  Data& d_;
  size_t saved_;
  size_t saved_blocks_;
};

// Grows the stack to the peak a stage needed; only between public calls (no frame
// open), since it moves the stack.
inline void GrowStack(Data& d) {
  if (d.stack_top == 0 && d.stack_peak > d.stack.size()) d.stack.assign(d.stack_peak, 0.0);
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_STACK_H_
