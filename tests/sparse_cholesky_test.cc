// The sparse reverse Cholesky of the Newton Hessian (engine/sparse_cholesky.h) against
// dense algebra: on matrices shaped as M + J^T D J (a dof tree's inertia plus rows that
// couple a few dofs each), the factor reproduces H, solves as a dense solve does, takes
// rank-one updates and downdates within its pattern, and adds no fill to a pure tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/sparse_cholesky.h"

namespace simlab {
namespace {

// A symmetric matrix (dense, n x n) and its pattern.
struct Problem {
  int n = 0;
  std::vector<double> h;            // values
  std::vector<char> nonzero;        // structural pattern
  std::vector<std::vector<int>> rows;  // the coupling rows' dofs (ascending)
};

// n dofs on a random tree (parent[i] < i), the inertia-like matrix of its chains (every
// dof couples to its ancestors) made positive definite, plus `coupling` rows of 2..4
// random dofs each added as v v^T.
Problem MakeProblem(int n, int coupling, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  Problem p;
  p.n = n;
  p.h.assign(n * n, 0.0);
  p.nonzero.assign(n * n, 0);
  std::vector<int> parent(n, -1);
  for (int i = 1; i < n; i++) parent[i] = std::uniform_int_distribution<int>(-1, i - 1)(rng);
  auto add_outer = [&](const std::vector<int>& dofs) {
    std::vector<double> v(dofs.size());
    for (double& x : v) x = value(rng);
    for (size_t a = 0; a < dofs.size(); a++) {
      for (size_t b = 0; b < dofs.size(); b++) {
        p.h[dofs[a] * n + dofs[b]] += v[a] * v[b];
        p.nonzero[dofs[a] * n + dofs[b]] = 1;
      }
    }
  };
  for (int i = 0; i < n; i++) {
    std::vector<int> chain;
    for (int j = i; j >= 0; j = parent[j]) chain.insert(chain.begin(), j);
    add_outer(chain);
    p.h[i * n + i] += 1;
  }
  for (int r = 0; r < coupling; r++) {
    std::vector<int> dofs;
    int size = std::uniform_int_distribution<int>(2, 4)(rng);
    while (static_cast<int>(dofs.size()) < size) {
      int d = std::uniform_int_distribution<int>(0, n - 1)(rng);
      if (std::find(dofs.begin(), dofs.end(), d) == dofs.end()) dofs.push_back(d);
    }
    std::sort(dofs.begin(), dofs.end());
    add_outer(dofs);
    p.rows.push_back(dofs);
  }
  return p;
}

// The factor, with its pattern's arrays.
struct Factor {
  std::vector<int> up_rownnz, up_rowadr, up_colind;
  std::vector<int> ints;  // rownnz/rowadr of L and LT, scratch
  std::vector<int> colind, lt_colind, lt_map;
  CholeskyPattern pattern;
  std::vector<double> L;
};

// Symbolic factorization of p's pattern.
void Analyse(const Problem& p, Factor& f) {
  int n = p.n;
  for (int r = 0; r < n; r++) {
    f.up_rowadr.push_back(static_cast<int>(f.up_colind.size()));
    for (int i = r + 1; i < n; i++) {
      if (p.nonzero[r * n + i]) f.up_colind.push_back(i);
    }
    f.up_rownnz.push_back(static_cast<int>(f.up_colind.size()) - f.up_rowadr.back());
  }
  RowPattern upper{n, f.up_rownnz.data(), f.up_rowadr.data(), f.up_colind.data()};
  f.ints.assign(8 * n, 0);
  int* at = f.ints.data();
  f.pattern.lower.rownnz = at;
  f.pattern.lower.rowadr = at + n;
  f.pattern.transposed.rownnz = at + 2 * n;
  f.pattern.transposed.rowadr = at + 3 * n;
  int nnz = CountCholesky(upper, f.pattern, at + 4 * n, at + 5 * n);
  f.colind.assign(nnz, -1);
  f.lt_colind.assign(nnz, -1);
  f.lt_map.assign(nnz, -1);
  f.pattern.lower.colind = f.colind.data();
  f.pattern.transposed.colind = f.lt_colind.data();
  f.pattern.lt_map = f.lt_map.data();
  FillCholesky(upper, f.pattern, at + 4 * n, at + 5 * n, at + 6 * n, at + 7 * n);
  f.L.assign(nnz, 0.0);
}

// Numeric factorization of the dense h.
int Numeric(const std::vector<double>& h, int n, Factor& f) {
  std::vector<double> dense(n, 0.0);
  return FactorCholesky(f.pattern, f.L.data(), 1e-15, dense.data(), [&](int r, double* row) {
    for (int j = 0; j <= r; j++) row[j] += h[r * n + j];
  });
}

// L^T L as a dense matrix.
std::vector<double> Product(const Factor& f, int n) {
  std::vector<double> dense_l(n * n, 0.0), out(n * n, 0.0);
  const RowPattern& low = f.pattern.lower;
  for (int r = 0; r < n; r++) {
    for (int q = low.rowadr[r]; q < low.rowadr[r] + low.rownnz[r]; q++) {
      dense_l[r * n + low.colind[q]] = f.L[q];
    }
  }
  for (int i = 0; i < n; i++) {
    for (int j = 0; j < n; j++) {
      for (int k = 0; k < n; k++) out[i * n + j] += dense_l[k * n + i] * dense_l[k * n + j];
    }
  }
  return out;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); i++) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

TEST(SparseCholesky, FactorReproducesTheMatrix) {
  for (unsigned seed = 1; seed <= 20; seed++) {
    Problem p = MakeProblem(24, 10, seed);
    Factor f;
    Analyse(p, f);
    ASSERT_EQ(Numeric(p.h, p.n, f), p.n);
    EXPECT_LT(MaxDifference(Product(f, p.n), p.h), 1e-11) << "seed " << seed;
    // Each row of L: columns ascending, the diagonal last.
    const RowPattern& low = f.pattern.lower;
    for (int r = 0; r < p.n; r++) {
      const int* cols = low.colind + low.rowadr[r];
      EXPECT_TRUE(std::is_sorted(cols, cols + low.rownnz[r]));
      EXPECT_EQ(cols[low.rownnz[r] - 1], r);
    }
  }
}

TEST(SparseCholesky, SolvesAsTheDenseMatrixMultiplies) {
  Problem p = MakeProblem(30, 12, 7);
  Factor f;
  Analyse(p, f);
  Numeric(p.h, p.n, f);
  std::vector<double> x(p.n), b(p.n, 0.0);
  for (int i = 0; i < p.n; i++) x[i] = std::sin(1.0 + i);
  for (int i = 0; i < p.n; i++) {
    for (int j = 0; j < p.n; j++) b[i] += p.h[i * p.n + j] * x[j];
  }
  std::vector<double> solved(p.n);
  SolveCholesky(f.pattern, f.L.data(), b.data(), solved.data());
  EXPECT_LT(MaxDifference(solved, x), 1e-10);
  SolveCholesky(f.pattern, f.L.data(), b.data(), b.data());  // in place
  EXPECT_LT(MaxDifference(b, x), 1e-10);
}

TEST(SparseCholesky, RankOneUpdatesMatchRefactoring) {
  Problem p = MakeProblem(20, 8, 3);
  Factor f;
  Analyse(p, f);
  Numeric(p.h, p.n, f);
  std::vector<double> scratch(p.n, 0.0), h = p.h;
  // Add then remove each coupling row, scaled: the factor follows H +/- x x^T.
  for (size_t k = 0; k < p.rows.size(); k++) {
    const std::vector<int>& dofs = p.rows[k];
    std::vector<double> x(dofs.size());
    for (size_t a = 0; a < dofs.size(); a++) x[a] = 0.3 * std::cos(double(k + a));
    for (bool plus : {true, false}) {
      for (size_t a = 0; a < dofs.size(); a++) {
        for (size_t b = 0; b < dofs.size(); b++) {
          h[dofs[a] * p.n + dofs[b]] += (plus ? 1 : -1) * x[a] * x[b];
        }
      }
      int rank = UpdateCholesky(f.pattern, f.L.data(), x.data(), dofs.data(),
                                static_cast<int>(dofs.size()), plus, scratch.data());
      EXPECT_EQ(rank, p.n);
      EXPECT_LT(MaxDifference(Product(f, p.n), h), 1e-11) << "row " << k << " plus " << plus;
    }
  }
}

TEST(SparseCholesky, TreeAloneFactorsWithoutFill) {
  Problem p = MakeProblem(40, 0, 11);
  Factor f;
  Analyse(p, f);
  int lower_entries = 0;
  for (int i = 0; i < p.n; i++) {
    for (int j = 0; j <= i; j++) lower_entries += p.nonzero[i * p.n + j];
  }
  EXPECT_EQ(f.pattern.nnz, lower_entries);
}

}  // namespace
}  // namespace simlab
