// The friction QCQP of an elliptic contact (MuJoCo mju_QCQP2, mju_QCQP3, mju_QCQP in
// engine_util_solve.c), used by PGS and noslip:
//
//   minimize 0.5 x^T A x + x^T b   subject to   sum_j (x_j / d_j)^2 <= r^2.
//
// Substituting y_j = x_j / d_j makes the constraint a ball: A -> D A D, b -> D b. With a
// multiplier la >= 0 the minimizer is y(la) = -(A + la I)^-1 b, and the constraint
// function g(la) = |y(la)|^2 - r^2 is convex and decreasing, with g'(la) =
// -2 y^T (A + la I)^-1 y. Newton's method from la = 0 (at most 20 steps) stops when
// g < 1e-10 (inside the ball: at la = 0 the unconstrained minimum is feasible) or when the
// step is below 1e-10; A + la I must stay positive definite (else the answer is zero).
#include <algorithm>
#include <cmath>

#include "engine/constraint.h"
#include "math/dot.h"

namespace simlab {

namespace {

constexpr int kQcqpIterations = 20;
constexpr double kQcqpTolerance = 1e-10;

}  // namespace

bool QCQP2(double* res, const double* A, const double* b, const double* d, double r) {
  // Scaled problem.
  double b1 = b[0] * d[0], b2 = b[1] * d[1];
  double a11 = A[0] * d[0] * d[0], a22 = A[3] * d[1] * d[1], a12 = A[1] * d[0] * d[1];

  double la = 0, y1 = 0, y2 = 0;
  for (int iter = 0; iter < kQcqpIterations; iter++) {
    // (A + la I)^-1 by its adjugate; not positive definite: no answer.
    double det = (a11 + la) * (a22 + la) - a12 * a12;
    if (det < kQcqpTolerance) {
      res[0] = res[1] = 0;
      return false;
    }
    double inv = 1 / det;
    double p11 = (a22 + la) * inv, p22 = (a11 + la) * inv, p12 = -a12 * inv;

    // y = -P b and the constraint value; inside the ball: done.
    y1 = -p11 * b1 - p12 * b2;
    y2 = -p12 * b1 - p22 * b2;
    double g = y1 * y1 + y2 * y2 - r * r;
    if (g < kQcqpTolerance) break;

    // Newton step on la.
    double slope = -2.0 * (p11 * y1 * y1 + 2.0 * p12 * y1 * y2 + p22 * y2 * y2);
    double step = -g / slope;
    if (step < kQcqpTolerance) break;
    la += step;
  }
  res[0] = y1 * d[0];
  res[1] = y2 * d[1];
  return la != 0;
}

bool QCQP3(double* res, const double* A, const double* b, const double* d, double r) {
  // Scaled problem.
  double b1 = b[0] * d[0], b2 = b[1] * d[1], b3 = b[2] * d[2];
  double a11 = A[0] * d[0] * d[0], a22 = A[4] * d[1] * d[1], a33 = A[8] * d[2] * d[2];
  double a12 = A[1] * d[0] * d[1], a13 = A[2] * d[0] * d[2], a23 = A[5] * d[1] * d[2];

  double la = 0, y1 = 0, y2 = 0, y3 = 0;
  for (int iter = 0; iter < kQcqpIterations; iter++) {
    // Adjugate of A + la I and its determinant; not positive definite: no answer.
    double p11 = (a22 + la) * (a33 + la) - a23 * a23;
    double p22 = (a11 + la) * (a33 + la) - a13 * a13;
    double p33 = (a11 + la) * (a22 + la) - a12 * a12;
    double p12 = a13 * a23 - a12 * (a33 + la);
    double p13 = a12 * a23 - a13 * (a22 + la);
    double p23 = a12 * a13 - a23 * (a11 + la);
    double det = (a11 + la) * p11 + a12 * p12 + a13 * p13;
    if (det < kQcqpTolerance) {
      res[0] = res[1] = res[2] = 0;
      return false;
    }
    double inv = 1 / det;
    p11 *= inv;
    p22 *= inv;
    p33 *= inv;
    p12 *= inv;
    p13 *= inv;
    p23 *= inv;

    // y = -P b and the constraint value; inside the ball: done.
    y1 = -p11 * b1 - p12 * b2 - p13 * b3;
    y2 = -p12 * b1 - p22 * b2 - p23 * b3;
    y3 = -p13 * b1 - p23 * b2 - p33 * b3;
    double g = y1 * y1 + y2 * y2 + y3 * y3 - r * r;
    if (g < kQcqpTolerance) break;

    // Newton step on la.
    double slope = -2.0 * (p11 * y1 * y1 + p22 * y2 * y2 + p33 * y3 * y3) -
                   4.0 * (p12 * y1 * y2 + p13 * y1 * y3 + p23 * y2 * y3);
    double step = -g / slope;
    if (step < kQcqpTolerance) break;
    la += step;
  }
  res[0] = y1 * d[0];
  res[1] = y2 * d[1];
  res[2] = y3 * d[2];
  return la != 0;
}

bool QCQP(double* res, const double* A, const double* b, const double* d, double r, int n) {
  // Scaled problem (n <= 5).
  double as[25], bs[5];
  for (int i = 0; i < n; i++) {
    bs[i] = b[i] * d[i];
    for (int j = 0; j < n; j++) as[i * n + j] = A[i * n + j] * d[i] * d[j];
  }

  double la = 0;
  for (int iter = 0; iter < kQcqpIterations; iter++) {
    // Factor A + la I; rank lost: no answer.
    double factor[25];
    std::copy(as, as + n * n, factor);
    for (int i = 0; i < n; i++) factor[i * (n + 1)] += la;
    if (CholFactor(factor, n, kQcqpTolerance) < n) {
      std::fill(res, res + n, 0.0);
      return false;
    }

    // y = -(A + la I)^-1 b and the constraint value; inside the ball: done.
    CholSolve(factor, n, bs, res);
    for (int i = 0; i < n; i++) res[i] = -res[i];
    double g = math::Dot(res, res, n) - r * r;
    if (g < kQcqpTolerance) break;

    // Newton step on la.
    double py[5];
    CholSolve(factor, n, res, py);
    double slope = -2.0 * math::Dot(res, py, n);
    double step = -g / slope;
    if (step < kQcqpTolerance) break;
    la += step;
  }
  for (int i = 0; i < n; i++) res[i] *= d[i];
  return la != 0;
}

}  // namespace simlab
