// Sparse "reverse" Cholesky factorization H = L^T L of a symmetric positive definite
// matrix, L lower triangular, eliminated from the last row to the first (MuJoCo's
// mju_cholFactorSymbolic / mju_cholFactorNumeric / mju_cholSolveSparse /
// mju_cholUpdateSparse, engine_util_solve.c). Eliminating from the last row means a
// matrix whose pattern follows a dof tree (ancestors before descendants, as the mass
// matrix) factors with no fill at all; the Newton Hessian M + J^T D J of a model that is
// sparse adds fill only where a row couples two branches.
//
// Layouts: L by rows, each row's columns ascending with the diagonal last; its transpose
// LT by rows (= L's columns), each starting with the diagonal, with lt_map[k] the index
// in L of LT's entry k.
#ifndef SIMLAB_ENGINE_SPARSE_CHOLESKY_H_
#define SIMLAB_ENGINE_SPARSE_CHOLESKY_H_

#include <cmath>

namespace simlab {

// A compressed-row pattern: row r has rownnz[r] columns colind[rowadr[r] ..].
struct RowPattern {
  int n = 0;
  int* rownnz = nullptr;
  int* rowadr = nullptr;
  int* colind = nullptr;
};

// The pattern of L and of its transpose.
struct CholeskyPattern {
  RowPattern lower;       // L
  RowPattern transposed;  // LT
  int* lt_map = nullptr;  // index in L of LT's entries
  int nnz = 0;
};

// Symbolic factorization from `upper`, the pattern of H strictly above the diagonal by
// rows (row r: the columns i > r with H(r, i) != 0). In two passes, as the caller takes
// the arrays: CountCholesky fills the row counts and addresses of L and LT (lower.rownnz,
// .rowadr, transposed.rownnz, .rowadr: n each) and returns the entries of L; then, with
// nnz entries given to lower.colind, transposed.colind and lt_map, FillCholesky writes
// them. `parent` and `flag` are n ints of scratch.
int CountCholesky(const RowPattern& upper, CholeskyPattern& pattern, int* parent, int* flag);
void FillCholesky(const RowPattern& upper, CholeskyPattern& pattern, int* parent, int* flag,
                  int* cursor, int* lt_write);

// Numeric factorization of H into L (pattern.nnz values). `load_row(r, dense)` adds row r
// of H, columns 0..r, into `dense` (n entries, zero on entry). Pivots below `mindiag` are
// raised to it. Returns the rank.
template <class LoadRow>
int FactorCholesky(const CholeskyPattern& pattern, double* L, double mindiag, double* dense,
                   LoadRow load_row);

// x = (L^T L)^-1 vec (x may be vec).
void SolveCholesky(const CholeskyPattern& pattern, const double* L, const double* vec,
                   double* x);

// L^T L +/- x x^T in place, for x with nnz entries `values` at the ascending columns
// `index` that lie within L's pattern (as any row of J does when H holds J^T D J). `dense`
// is n entries of scratch. Returns the rank.
int UpdateCholesky(const CholeskyPattern& pattern, double* L, const double* values,
                   const int* index, int nnz, bool plus, double* dense);

// ---------------------------------------------------------------- the numeric factor

template <class LoadRow>
int FactorCholesky(const CholeskyPattern& pattern, double* L, double mindiag, double* dense,
                   LoadRow load_row) {
  const RowPattern& low = pattern.lower;
  const RowPattern& up = pattern.transposed;
  int rank = low.n;
  for (int r = low.n - 1; r >= 0; r--) {
    load_row(r, dense);
    // Subtract L(c, r) L(c, 0..r) for the rows c > r below r's diagonal (LT's row r
    // after its diagonal); L(c, r) ends the part of row c that lies left of r.
    for (int k = up.rowadr[r] + 1; k < up.rowadr[r] + up.rownnz[r]; k++) {
      int at = pattern.lt_map[k];
      int c = up.colind[k];
      double lcr = L[at];
      for (int q = low.rowadr[c]; q <= at; q++) dense[low.colind[q]] -= lcr * L[q];
    }
    // The diagonal, then the row scaled by it; dense is left zero again.
    double diag = dense[r];
    if (diag < mindiag) {
      diag = mindiag;
      rank--;
    }
    double lrr = std::sqrt(diag), inv = 1 / lrr;
    int begin = low.rowadr[r], last = begin + low.rownnz[r] - 1;
    for (int q = begin; q < last; q++) {
      L[q] = dense[low.colind[q]] * inv;
      dense[low.colind[q]] = 0;
    }
    L[last] = lrr;
    dense[r] = 0;
  }
  return rank;
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_SPARSE_CHOLESKY_H_
