// Sparse reverse Cholesky: the symbolic passes, the solve and the rank-one update (the
// numeric factor is a template in the header).
#include "engine/sparse_cholesky.h"

#include <algorithm>
#include <cmath>

#include "math/dot.h"
#include "simlab/model.h"

namespace simlab {

namespace {

// The elimination from the last row: for each row r (descending), every i > r with
// H(r, i) != 0 and the etree path above i up to r (parent[] points to smaller indices)
// gain L(i, r). visit(i, r) is called once for each such entry, in the order the rows i
// are reached.
template <class Visit>
void Eliminate(const RowPattern& upper, int* parent, int* flag, Visit visit) {
  for (int r = upper.n - 1; r >= 0; r--) {
    parent[r] = -1;
    flag[r] = r;
    for (int k = upper.rowadr[r]; k < upper.rowadr[r] + upper.rownnz[r]; k++) {
      for (int i = upper.colind[k]; flag[i] != r; i = parent[i]) {
        if (parent[i] == -1) parent[i] = r;
        flag[i] = r;
        visit(i, r);
      }
    }
  }
}

}  // namespace

int CountCholesky(const RowPattern& upper, CholeskyPattern& pattern, int* parent, int* flag) {
  RowPattern& low = pattern.lower;
  RowPattern& up = pattern.transposed;
  int n = upper.n;
  low.n = up.n = n;
  std::fill(low.rownnz, low.rownnz + n, 1);  // the diagonals
  std::fill(up.rownnz, up.rownnz + n, 1);
  Eliminate(upper, parent, flag, [&](int i, int r) {
    low.rownnz[i]++;
    up.rownnz[r]++;
  });
  int nnz = 0;
  for (int r = 0; r < n; r++) {
    low.rowadr[r] = nnz;
    nnz += low.rownnz[r];
  }
  for (int r = 0, adr = 0; r < n; r++) {
    up.rowadr[r] = adr;
    adr += up.rownnz[r];
  }
  pattern.nnz = nnz;
  return nnz;
}

void FillCholesky(const RowPattern& upper, CholeskyPattern& pattern, int* parent, int* flag,
                  int* cursor, int* lt_write) {
  RowPattern& low = pattern.lower;
  RowPattern& up = pattern.transposed;
  // Rows of L fill from their end (columns arrive descending), LT rows from their start;
  // each begins with its diagonal.
  for (int r = 0; r < low.n; r++) {
    int diag = low.rowadr[r] + low.rownnz[r] - 1;
    low.colind[diag] = r;
    cursor[r] = diag - 1;
    up.colind[up.rowadr[r]] = r;
    pattern.lt_map[up.rowadr[r]] = diag;
    lt_write[r] = up.rowadr[r] + 1;
  }
  Eliminate(upper, parent, flag, [&](int i, int r) {
    int at = cursor[i]--;
    low.colind[at] = r;
    up.colind[lt_write[r]] = i;
    pattern.lt_map[lt_write[r]++] = at;
  });
}

void SolveCholesky(const CholeskyPattern& pattern, const double* L, const double* vec,
                   double* x) {
  const RowPattern& low = pattern.lower;
  int n = low.n;
  if (x != vec) std::copy(vec, vec + n, x);
  // L^T y = vec, from the last row: each solved entry is taken out of those left of it.
  for (int i = n - 1; i >= 0; i--) {
    if (x[i] == 0) continue;
    int begin = low.rowadr[i], last = begin + low.rownnz[i] - 1;
    x[i] /= L[last];
    double xi = x[i];
    for (int q = begin; q < last; q++) x[low.colind[q]] -= L[q] * xi;
  }
  // L x = y, from the first row.
  for (int i = 0; i < n; i++) {
    int begin = low.rowadr[i], last = begin + low.rownnz[i] - 1;
    if (last > begin) x[i] -= math::DotSparse(L + begin, x, last - begin, low.colind + begin);
    x[i] /= L[last];
  }
}

int UpdateCholesky(const CholeskyPattern& pattern, double* L, const double* values,
                   const int* index, int nnz, bool plus, double* dense) {
  const RowPattern& low = pattern.lower;
  if (nnz == 0) return low.n;
  int start = index[nnz - 1];
  std::fill(dense, dense + start + 1, 0.0);
  for (int k = 0; k < nnz; k++) dense[index[k]] = values[k];
  // A Givens rotation per row from the last entry of x up: it folds x's entry into the
  // diagonal and passes the rest on to the columns left of it.
  int rank = low.n;
  for (int row = start; row >= 0; row--) {
    double xr = dense[row];
    if (xr == 0) continue;
    int begin = low.rowadr[row], last = begin + low.rownnz[row] - 1;
    double diag = L[last];
    double square = diag * diag + (plus ? xr * xr : -xr * xr);
    if (square < kMinVal) {
      square = kMinVal;
      rank--;
    }
    double root = std::sqrt(square);
    L[last] = root;
    double c = diag / root, s = -xr / root;
    double s_signed = plus ? -s : s;
    for (int q = begin; q < last; q++) {
      int j = low.colind[q];
      double lq = L[q], dj = dense[j];
      L[q] = c * lq + s_signed * dj;
      dense[j] = s * lq + c * dj;
    }
  }
  return rank;
}

}  // namespace simlab
