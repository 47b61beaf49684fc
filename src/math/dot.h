// Dot products of long vectors (and the dense matrix-vector products built on them), summed
// in a fixed order: four interleaved partial sums,
// combined as (s0 + s2) + (s1 + s3), then the remainder. MuJoCo sums this way (its
// vectorized and scalar builds agree), and a constraint solver that stops at a tolerance
// amplifies the last bit of difference, so the engine uses the same order.
#ifndef SIMLAB_MATH_DOT_H_
#define SIMLAB_MATH_DOT_H_

namespace simlab::math {

// a . b over n entries; a remainder of 2 or 3 entries is summed first, then added.
inline double Dot(const double* a, const double* b, int n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  int i = 0;
  for (; i <= n - 4; i += 4) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
    s2 += a[i + 2] * b[i + 2];
    s3 += a[i + 3] * b[i + 3];
  }
  double s = (s0 + s2) + (s1 + s3);
  int rest = n - i;
  if (rest == 3) s += a[i] * b[i] + a[i + 1] * b[i + 1] + a[i + 2] * b[i + 2];
  if (rest == 2) s += a[i] * b[i] + a[i + 1] * b[i + 1];
  if (rest == 1) s += a[i] * b[i];
  return s;
}

// a . b over 6 entries, in Dot's order (MuJoCo's mji_dot6), without its loop.
inline double Dot6(const double* a, const double* b) {
  return ((a[0] * b[0] + a[2] * b[2]) + (a[1] * b[1] + a[3] * b[3])) + (a[4] * b[4] + a[5] * b[5]);
}

// a . x[ind] over n entries of a; the remainder is added one entry at a time.
inline double DotSparse(const double* a, const double* x, int n, const int* ind) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  int i = 0;
  for (; i <= n - 4; i += 4) {
    s0 += a[i] * x[ind[i]];
    s1 += a[i + 1] * x[ind[i + 1]];
    s2 += a[i + 2] * x[ind[i + 2]];
    s3 += a[i + 3] * x[ind[i + 3]];
  }
  double s = (s0 + s2) + (s1 + s3);
  for (; i < n; i++) s += a[i] * x[ind[i]];
  return s;
}

// res (rows) = mat vec, for a row-major rows x cols matrix (each row a Dot).
inline void MulMatVec(double* res, const double* mat, const double* vec, int rows, int cols) {
  for (int r = 0; r < rows; r++) res[r] = Dot(mat + static_cast<long>(r) * cols, vec, cols);
}

// res (cols) = mat^T vec: rows added in order, rows with a zero entry of vec skipped.
inline void MulMatTVec(double* res, const double* mat, const double* vec, int rows, int cols) {
  for (int c = 0; c < cols; c++) res[c] = 0;
  for (int r = 0; r < rows; r++) {
    if (vec[r] == 0) continue;
    const double* row = mat + static_cast<long>(r) * cols;
    for (int c = 0; c < cols; c++) res[c] += row[c] * vec[r];
  }
}

}  // namespace simlab::math

#endif  // SIMLAB_MATH_DOT_H_
