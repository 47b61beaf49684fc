// The math of elliptic friction cones in the constraint solvers, checked against
// independent computations: the QCQP helpers against brute-force minimization and their
// optimality conditions, and the elliptic contact's cost update (forces, zones, cone
// Hessian) against finite differences of its cost.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/constraint.h"

namespace simlab {
namespace {

// ---------------------------------------------------------------- QCQP

struct Qcqp {
  int n;
  double A[25], b[5], d[5], r;
};

// A random problem: A = G G^T + 0.1 I (symmetric positive definite), b, d in [0.2, 1.5].
Qcqp RandomQcqp(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-1, 1), pos(0.2, 1.5);
  Qcqp q;
  q.n = n;
  double g[25];
  for (int k = 0; k < n * n; k++) g[k] = u(rng);
  for (int i = 0; i < n; i++) {
    for (int j = 0; j < n; j++) {
      double s = i == j ? 0.1 : 0;
      for (int k = 0; k < n; k++) s += g[i * n + k] * g[j * n + k];
      q.A[i * n + j] = s;
    }
    q.b[i] = 0.6 * u(rng);
    q.d[i] = pos(rng);
  }
  q.r = pos(rng);
  return q;
}

double Cost(const Qcqp& q, const double* x) {
  double c = 0;
  for (int i = 0; i < q.n; i++) {
    c += q.b[i] * x[i];
    for (int j = 0; j < q.n; j++) c += 0.5 * x[i] * q.A[i * q.n + j] * x[j];
  }
  return c;
}

// sum (x_i / d_i)^2 - r^2: <= 0 when feasible.
double Constraint(const Qcqp& q, const double* x) {
  double s = 0;
  for (int i = 0; i < q.n; i++) s += x[i] * x[i] / (q.d[i] * q.d[i]);
  return s - q.r * q.r;
}

// The best cost by brute force: projected gradient descent in the scaled coordinates
// y = x / d (where the feasible set is a ball), with a step below 1 / (largest
// eigenvalue); the problem is convex, so one start suffices.
double BruteForceCost(const Qcqp& q) {
  int n = q.n;
  double trace = 0;
  for (int i = 0; i < n; i++) trace += q.A[i * (n + 1)] * q.d[i] * q.d[i];
  double step = 1 / trace, x[5] = {0, 0, 0, 0, 0};
  for (int it = 0; it < 20000; it++) {
    for (int i = 0; i < n; i++) {
      double g = q.b[i];
      for (int j = 0; j < n; j++) g += q.A[i * n + j] * x[j];
      x[i] -= step * q.d[i] * q.d[i] * g;
    }
    double s = Constraint(q, x) + q.r * q.r;
    if (s > q.r * q.r) {
      for (int i = 0; i < n; i++) x[i] *= q.r / std::sqrt(s);
    }
  }
  return Cost(q, x);
}

// On the surface, optimality means the gradient A x + b points against the outward
// normal x / d^2: returns the cosine of their angle (-1 at the optimum).
double GradientNormalCosine(const Qcqp& q, const double* x) {
  double gg = 0, nn = 0, gn = 0;
  for (int i = 0; i < q.n; i++) {
    double g = q.b[i];
    for (int j = 0; j < q.n; j++) g += q.A[i * q.n + j] * x[j];
    double normal = x[i] / (q.d[i] * q.d[i]);
    gg += g * g;
    nn += normal * normal;
    gn += g * normal;
  }
  return gn / std::sqrt(gg * nn);
}

bool SolveQcqp(const Qcqp& q, double* x) {
  if (q.n == 2) return QCQP2(x, q.A, q.b, q.d, q.r);
  if (q.n == 3) return QCQP3(x, q.A, q.b, q.d, q.r);
  return QCQP(x, q.A, q.b, q.d, q.r, q.n);
}

TEST(SolverCone, QcqpMatchesBruteForce) {
  std::mt19937 rng(1);
  int active_count = 0;
  for (int n = 2; n <= 5; n++) {
    for (int trial = 0; trial < 25; trial++) {
      Qcqp q = RandomQcqp(rng, n);
      double x[5];
      bool active = SolveQcqp(q, x);
      active_count += active;

      // Feasible (on the surface within the solver's tolerance when active), and no
      // feasible point found by brute force costs less.
      EXPECT_LT(Constraint(q, x), 1e-6) << "n=" << n << " trial " << trial;
      if (active) {
        EXPECT_NEAR(Constraint(q, x), 0, 1e-6) << "n=" << n << " trial " << trial;
        EXPECT_NEAR(GradientNormalCosine(q, x), -1, 1e-6) << "n=" << n << " trial " << trial;
      }
      EXPECT_LE(Cost(q, x), BruteForceCost(q) + 1e-7) << "n=" << n << " trial " << trial;
    }
  }
  // Both cases were exercised.
  EXPECT_GT(active_count, 10);
  EXPECT_LT(active_count, 90);
}

TEST(SolverCone, QcqpInactiveIsUnconstrainedMinimum) {
  // A ball large enough that -A^-1 b lies inside: the answer solves A x = -b.
  Qcqp q;
  q.n = 3;
  double A[9] = {2, 0.5, 0.1, 0.5, 3, 0.2, 0.1, 0.2, 1.5};
  std::copy(A, A + 9, q.A);
  q.b[0] = 0.3, q.b[1] = -0.2, q.b[2] = 0.1;
  q.d[0] = q.d[1] = q.d[2] = 1;
  q.r = 10;
  for (int n : {3, 0}) {
    double x[3];
    bool active = n == 3 ? QCQP3(x, q.A, q.b, q.d, q.r) : QCQP(x, q.A, q.b, q.d, q.r, 3);
    EXPECT_FALSE(active);
    for (int i = 0; i < 3; i++) {
      double g = q.b[i];
      for (int j = 0; j < 3; j++) g += A[i * 3 + j] * x[j];
      EXPECT_NEAR(g, 0, 1e-12);
    }
  }
}

TEST(SolverCone, ClosedFormQcqpAgreesWithGeneral) {
  std::mt19937 rng(3);
  for (int n = 2; n <= 3; n++) {
    for (int trial = 0; trial < 50; trial++) {
      Qcqp q = RandomQcqp(rng, n);
      double closed[3], general[3];
      bool a1 = SolveQcqp(q, closed);
      bool a2 = QCQP(general, q.A, q.b, q.d, q.r, n);
      EXPECT_EQ(a1, a2);
      for (int i = 0; i < n; i++) EXPECT_NEAR(closed[i], general[i], 1e-9);
    }
  }
}

// ---------------------------------------------------------------- elliptic cost update

// One elliptic contact of dimension dim as the only rows.
struct ConeRows {
  Contact con;
  std::vector<double> D, R, floss;
  std::vector<int> type, id;

  explicit ConeRows(int dim) {
    con.dim = dim;
    double friction[5] = {0.8, 0.5, 0.05, 0.02, 0.03};
    std::copy(friction, friction + 5, con.friction);
    con.mu = 0.7;
    for (int j = 0; j < dim; j++) D.push_back(2.0 + 0.5 * j);
    R.assign(dim, 0.1);
    floss.assign(dim, 0.0);
    type.assign(dim, kCnstrContactElliptic);
    id.assign(dim, 0);
  }
  RowSet Rows() {
    return RowSet{0, 0, con.dim, D.data(), R.data(), floss.data(), type.data(), id.data(),
                  &con};
  }
  double CostAt(const std::vector<double>& jar, std::vector<double>* force, int* state) {
    std::vector<int> states(con.dim);
    std::vector<double> f(con.dim);
    double cost;
    ConstraintUpdate(Rows(), jar.data(), states.data(), f.data(), &cost, true);
    if (force) *force = f;
    if (state) *state = states[0];
    for (int s : states) EXPECT_EQ(s, states[0]);
    return cost;
  }
};

// jar in the middle zone: normal slightly negative, tangential large enough.
std::vector<double> MiddleZoneJar(int dim) {
  std::vector<double> jar(dim);
  jar[0] = -0.2;
  for (int j = 1; j < dim; j++) jar[j] = 0.3 * std::cos(1.3 * j) + 0.1 * j;
  return jar;
}

TEST(SolverCone, ForceIsMinusCostGradient) {
  for (int dim : {3, 4, 6}) {
    ConeRows rows(dim);
    std::vector<double> jar = MiddleZoneJar(dim), force;
    int state;
    rows.CostAt(jar, &force, &state);
    ASSERT_EQ(state, kStateCone) << dim;
    const double h = 1e-6;
    for (int j = 0; j < dim; j++) {
      std::vector<double> plus = jar, minus = jar;
      plus[j] += h;
      minus[j] -= h;
      double grad = (rows.CostAt(plus, nullptr, nullptr) - rows.CostAt(minus, nullptr, nullptr)) /
                    (2 * h);
      EXPECT_NEAR(force[j], -grad, 1e-7) << "dim " << dim << " row " << j;
    }
  }
}

TEST(SolverCone, ConeHessianIsForceJacobian) {
  for (int dim : {3, 4, 6}) {
    ConeRows rows(dim);
    std::vector<double> jar = MiddleZoneJar(dim);
    rows.CostAt(jar, nullptr, nullptr);
    std::vector<double> H(rows.con.H, rows.con.H + dim * dim);
    const double h = 1e-6;
    for (int j = 0; j < dim; j++) {
      std::vector<double> plus = jar, minus = jar, fp, fm;
      plus[j] += h;
      minus[j] -= h;
      rows.CostAt(plus, &fp, nullptr);
      rows.CostAt(minus, &fm, nullptr);
      for (int k = 0; k < dim; k++) {
        double dforce = (fp[k] - fm[k]) / (2 * h);
        EXPECT_NEAR(H[k * dim + j], -dforce, 1e-6) << "dim " << dim << " " << k << "," << j;
      }
    }
  }
}

TEST(SolverCone, ZonesAndCosts) {
  ConeRows rows(3);
  std::vector<double> force;
  int state;

  // Top zone (separating): no force, no cost.
  EXPECT_EQ(rows.CostAt({0.5, 0.1, -0.1}, &force, &state), 0);
  EXPECT_EQ(state, kStateSatisfied);
  for (double f : force) EXPECT_EQ(f, 0);

  // Bottom zone (deep in the mirrored cone): every row quadratic, force -D jar.
  std::vector<double> jar = {-1.0, 0.01, -0.02};
  double cost = rows.CostAt(jar, &force, &state);
  EXPECT_EQ(state, kStateQuadratic);
  double expect = 0;
  for (int j = 0; j < 3; j++) {
    expect += 0.5 * rows.D[j] * jar[j] * jar[j];
    EXPECT_DOUBLE_EQ(force[j], -rows.D[j] * jar[j]);
  }
  EXPECT_DOUBLE_EQ(cost, expect);

  // The middle zone's force lies on the dual cone's surface: |f_t / friction| = f_n.
  rows.CostAt(MiddleZoneJar(3), &force, &state);
  EXPECT_EQ(state, kStateCone);
  double t = std::hypot(force[1] / rows.con.friction[0], force[2] / rows.con.friction[1]);
  EXPECT_GT(force[0], 0);
  EXPECT_NEAR(t, force[0], 1e-12);
}

}  // namespace
}  // namespace simlab
