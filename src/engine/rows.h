// Pointers to rows of Model and Data arrays that may be empty.
//
// &array[offset] reads array[offset] as a reference first, which is undefined behaviour
// when offset is not inside the array, and an array can be empty on ordinary models:
// ten_J and actuator_moment (ntendon x nv, nout x nv) of a model without dofs, the dof
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

// ---------------------------------------------------------------- rows with a pattern
// Dense rows that also keep the columns where they may be nonzero (actuator_moment and
// ten_J: row i's pattern is rownnz[i] ascending columns from colind[i * nv] on), so that
// the stages touch those columns only.

// The columns where `row` (n numbers) is nonzero, ascending, into `cols`; their count.
inline int NonzeroColumns(const double* row, int n, int* cols) {
  int count = 0;
  for (int v = 0; v < n; v++) {
    if (row[v] != 0) cols[count++] = v;
  }
  return count;
}

// row . vec over the pattern's n columns, summed in column order (as over every column:
// the others add exact zeros).
inline double PatternDot(const double* row, const int* cols, int n, const double* vec) {
  double s = 0;
  for (int k = 0; k < n; k++) s += row[cols[k]] * vec[cols[k]];
  return s;
}

// Zeroes `row` on its pattern's n columns: the whole row is zero then.
inline void ClearPattern(double* row, const int* cols, int n) {
  for (int k = 0; k < n; k++) row[cols[k]] = 0;
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_ROWS_H_
