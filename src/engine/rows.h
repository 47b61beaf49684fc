// Pointers to rows of Model and Data arrays that may be empty.
//
// &array[offset] reads array[offset] as a reference first, which is undefined behaviour
// when offset is not inside the array, and an array can be empty on ordinary models:
// ten_J and actuator_moment (ntendon x nv, nu x nv) of a model without dofs, the dof
// rows of a body without dofs (whose dofadr is -1). These helpers compute the pointer
// instead, the same address whenever the row exists.
#ifndef SIMLAB_ENGINE_ROWS_H_
#define SIMLAB_ENGINE_ROWS_H_

#include <cstddef>
#include <vector>

namespace simlab {

// Row i of a matrix stored row by row with `cols` numbers per row (cols may be 0).
template <typename T>
T* RowOf(std::vector<T>& matrix, int i, int cols) {
  return matrix.data() + static_cast<size_t>(i) * cols;
}
template <typename T>
const T* RowOf(const std::vector<T>& matrix, int i, int cols) {
  return matrix.data() + static_cast<size_t>(i) * cols;
}

// The rows of `num` consecutive dofs from dof `adr` on, in an array of `width` numbers
// per dof; null when num is 0 (then adr may be -1).
template <typename T>
const T* DofRows(const std::vector<T>& array, int adr, int width, int num) {
  return num > 0 ? RowOf(array, adr, width) : nullptr;
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_ROWS_H_
