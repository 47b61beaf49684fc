// The primal constraint solvers (MuJoCo mj_solPrimal, engine_solver.c): minimize
//
//   cost(a) = 0.5 (a - a0)^T M (a - a0) + s(J a - aref)
//
// over the acceleration a, starting from the warm start. Each iteration picks a search
// direction (Newton: -H^-1 grad with H = M + J^T D_active J, factored and then updated by
// rank-one changes as rows change state; CG: Polak-Ribiere on M^-1 grad), then an exact
// line search along it: the cost along a line is piecewise quadratic, so the search
// brackets the minimum with Newton steps on the one-dimensional derivative.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "math/dot.h"

namespace simlab {

using math::Dot;

// ---------------------------------------------------------------- row states and forces

void ConstraintUpdate(int ne, int nf, int nefc, const double* D, const double* R,
                      const double* frictionloss, const double* jar, int* state,
                      double* force, double* cost) {
  double s = 0;
  for (int i = 0; i < nefc; i++) {
    force[i] = -D[i] * jar[i];
    double quadratic = 0.5 * D[i] * jar[i] * jar[i];

    // Equality: always quadratic.
    if (i < ne) {
      s += quadratic;
      state[i] = kStateQuadratic;
      continue;
    }

    // Friction: quadratic near zero, linear (constant force) beyond R * frictionloss.
    if (i < ne + nf) {
      double f = frictionloss[i], bound = R[i] * f;
      if (jar[i] <= -bound) {
        s += -0.5 * bound * f - f * jar[i];
        force[i] = f;
        state[i] = kStateLinearNeg;
      } else if (jar[i] >= bound) {
        s += -0.5 * bound * f + f * jar[i];
        force[i] = -f;
        state[i] = kStateLinearPos;
      } else {
        s += quadratic;
        state[i] = kStateQuadratic;
      }
      continue;
    }

    // Limits and contacts: one-sided.
    if (jar[i] >= 0) {
      force[i] = 0;
      state[i] = kStateSatisfied;
    } else {
      s += quadratic;
      state[i] = kStateQuadratic;
    }
  }
  if (cost) *cost = s;
}

namespace {

// ---------------------------------------------------------------- small dense algebra

// res = M vec with the problem's block of M.
void MulSym(const ConstraintProblem& p, const double* vec, double* res) {
  MulSymLayout(p.nv, p.M_rownnz.data(), p.M_rowadr.data(), p.M_colind.data(), p.M.data(), vec,
               res);
}

// res (rows) = J vec.
void MulJ(const ConstraintProblem& p, const double* vec, double* res) {
  math::MulMatVec(res, p.J.data(), vec, p.nefc, p.nv);
}

// In-place dense Cholesky of the lower triangle; pivots below `mindiag` are raised to it.
// Returns the rank (MuJoCo mju_cholFactor).
int CholFactor(double* mat, int n, double mindiag) {
  int rank = n;
  for (int j = 0; j < n; j++) {
    double diag = mat[j * (n + 1)] - Dot(mat + j * n, mat + j * n, j);
    if (diag < mindiag) {
      diag = mindiag;
      rank--;
    }
    mat[j * (n + 1)] = std::sqrt(diag);
    double inv = 1 / mat[j * (n + 1)];
    for (int i = j + 1; i < n; i++) {
      mat[i * n + j] = (mat[i * n + j] - Dot(mat + i * n, mat + j * n, j)) * inv;
    }
  }
  return rank;
}

// res = (L L^T)^-1 vec.
void CholSolve(const double* mat, int n, const double* vec, double* res) {
  std::copy(vec, vec + n, res);
  for (int i = 0; i < n; i++) res[i] = (res[i] - Dot(mat + i * n, res, i)) / mat[i * (n + 1)];
  for (int i = n - 1; i >= 0; i--) {
    for (int j = i + 1; j < n; j++) res[i] -= mat[j * n + i] * res[j];
    res[i] /= mat[i * (n + 1)];
  }
}

// L L^T +/- x x^T, in place (x is overwritten); returns the rank (mju_cholUpdate).
int CholUpdate(double* mat, double* x, int n, bool plus) {
  int rank = n;
  for (int k = 0; k < n; k++) {
    if (x[k] == 0) continue;
    double lkk = mat[k * (n + 1)];
    double t = lkk * lkk + (plus ? x[k] * x[k] : -x[k] * x[k]);
    if (t < kMinVal) {
      t = kMinVal;
      rank--;
    }
    double r = std::sqrt(t), c = r / lkk, cinv = 1 / c, s = x[k] / lkk;
    mat[k * (n + 1)] = r;
    for (int i = k + 1; i < n; i++) {
      mat[i * n + k] = (mat[i * n + k] + (plus ? s : -s) * x[i]) * cinv;
    }
    for (int i = k + 1; i < n; i++) x[i] = c * x[i] - s * mat[i * n + k];
  }
  return rank;
}

// ---------------------------------------------------------------- solver state

struct Primal {
  ConstraintProblem& p;
  bool newton;
  std::vector<double> jaref, jv, ma, mv, grad, mgrad, search, quad;
  std::vector<double> hessian;  // Newton: Cholesky factor of M + J^T D_active J (nv x nv)
  double cost = 0;
  double quad_gauss[3] = {0, 0, 0};
  int ls_iter = 0;

  Primal(ConstraintProblem& problem, bool is_newton)
      : p(problem), newton(is_newton), jaref(p.nefc), jv(p.nefc), ma(p.nv), mv(p.nv),
        grad(p.nv), mgrad(p.nv), search(p.nv), quad(3 * static_cast<size_t>(p.nefc)) {
    if (newton) hessian.assign(static_cast<size_t>(p.nv) * p.nv, 0.0);
  }
};

// Row states, forces, qfrc_constraint and the total cost at the current iterate.
void UpdateConstraint(Primal& s) {
  ConstraintProblem& p = s.p;
  ConstraintUpdate(p.ne, p.nf, p.nefc, p.D.data(), p.R.data(), p.frictionloss.data(),
                   s.jaref.data(), p.state.data(), p.force.data(), &s.cost);
  math::MulMatTVec(p.qfrc_constraint.data(), p.J.data(), p.force.data(), p.nefc, p.nv);
  double gauss = 0;
  for (int v = 0; v < p.nv; v++) {
    gauss += 0.5 * (s.ma[v] - p.qfrc_smooth[v]) * (p.qacc[v] - p.qacc_smooth[v]);
  }
  s.quad_gauss[0] = gauss;
  s.cost += gauss;
}

// grad = M a - qfrc_smooth - qfrc_constraint, and the preconditioned gradient.
void UpdateGradient(Primal& s) {
  ConstraintProblem& p = s.p;
  for (int v = 0; v < p.nv; v++) s.grad[v] = s.ma[v] - p.qfrc_smooth[v] - p.qfrc_constraint[v];
  if (s.newton) {
    CholSolve(s.hessian.data(), p.nv, s.grad.data(), s.mgrad.data());
  } else {
    s.mgrad = s.grad;
    SolveSparseLayout(p.nv, p.M_rownnz.data(), p.M_rowadr.data(), p.M_colind.data(),
                      p.qLD.data(), p.qLDiagInv.data(), s.mgrad.data());
  }
}

// H = M + J^T D J over the rows in the quadratic state, factored (lower triangle).
void FactorHessian(Primal& s) {
  ConstraintProblem& p = s.p;
  int nv = p.nv;
  std::vector<double>& h = s.hessian;
  std::fill(h.begin(), h.end(), 0.0);
  for (int r = 0; r < p.nefc; r++) {
    if (p.state[r] != kStateQuadratic) continue;
    const double* row = &p.J[static_cast<size_t>(r) * nv];
    for (int i = 0; i < nv; i++) {
      double scaled = row[i] * p.D[r];
      if (row[i] == 0) continue;
      for (int j = 0; j <= i; j++) h[i * nv + j] += scaled * row[j];
    }
  }
  for (int i = 0; i < nv; i++) {
    for (int k = p.M_rowadr[i]; k < p.M_rowadr[i] + p.M_rownnz[i]; k++) {
      h[i * nv + p.M_colind[k]] += p.M[k];
    }
  }
  CholFactor(h.data(), nv, kMinVal);
}

// Rank-one updates of the factor for rows that entered or left the quadratic state; a
// full refactorization if an update loses rank.
void UpdateHessian(Primal& s, const std::vector<int>& oldstate) {
  ConstraintProblem& p = s.p;
  std::vector<double> vec(p.nv);
  for (int r = 0; r < p.nefc; r++) {
    bool was = oldstate[r] == kStateQuadratic, is = p.state[r] == kStateQuadratic;
    if (was == is) continue;
    const double* row = &p.J[static_cast<size_t>(r) * p.nv];
    double sqrt_d = std::sqrt(p.D[r]);
    for (int v = 0; v < p.nv; v++) vec[v] = row[v] * sqrt_d;
    if (CholUpdate(s.hessian.data(), vec.data(), p.nv, is) < p.nv) {
      FactorHessian(s);
      return;
    }
  }
}

// ---------------------------------------------------------------- line search

struct LinePoint {
  double alpha = 0;
  double cost = 0;
  double deriv[2] = {0, 0};  // first and second derivative along the line
};

// Per-row quadratics along the search line: cost_r(alpha) = q0 + q1 alpha + q2 alpha^2.
void PrepareLine(Primal& s) {
  ConstraintProblem& p = s.p;
  int nv = p.nv;
  s.quad_gauss[1] = Dot(s.search.data(), s.ma.data(), nv) -
                    Dot(p.qfrc_smooth.data(), s.search.data(), nv);
  s.quad_gauss[2] = 0.5 * Dot(s.search.data(), s.mv.data(), nv);
  for (int r = 0; r < p.nefc; r++) {
    double dj = p.D[r] * s.jaref[r];
    s.quad[3 * r] = 0.5 * s.jaref[r] * dj;
    s.quad[3 * r + 1] = s.jv[r] * dj;
    s.quad[3 * r + 2] = 0.5 * s.jv[r] * p.D[r] * s.jv[r];
  }
}

// Cost and its derivatives at alpha along the search direction.
void EvalLine(Primal& s, LinePoint* point) {
  ConstraintProblem& p = s.p;
  double alpha = point->alpha;
  double total[3] = {s.quad_gauss[0], s.quad_gauss[1], s.quad_gauss[2]};
  auto add = [&total](const double* q) {
    total[0] += q[0];
    total[1] += q[1];
    total[2] += q[2];
  };
  for (int r = 0; r < p.nefc; r++) {
    double x = s.jaref[r] + alpha * s.jv[r];
    if (r < p.ne) {
      add(&s.quad[3 * r]);
    } else if (r < p.ne + p.nf) {
      // Friction: quadratic inside the bound, linear outside.
      double f = p.frictionloss[r], bound = p.R[r] * f;
      if (-bound < x && x < bound) {
        add(&s.quad[3 * r]);
      } else if (x <= -bound) {
        double q[3] = {f * (-0.5 * bound - s.jaref[r]), -f * s.jv[r], 0};
        add(q);
      } else {
        double q[3] = {f * (-0.5 * bound + s.jaref[r]), f * s.jv[r], 0};
        add(q);
      }
    } else if (x < 0) {
      add(&s.quad[3 * r]);
    }
  }
  point->cost = alpha * alpha * total[2] + alpha * total[1] + total[0];
  point->deriv[0] = 2 * alpha * total[2] + total[1];
  point->deriv[1] = 2 * total[2];
  if (point->deriv[1] <= 0) {
    std::fprintf(stderr, "simlab warning: line search objective is not convex\n");
    point->deriv[1] = kMinVal;
  }
  s.ls_iter++;
}

// Replaces bracket end `end` by a candidate on the same side of the minimum with a
// smaller |derivative|; then the Newton point from it. Returns whether it moved.
bool UpdateBracket(Primal& s, LinePoint* end, const LinePoint candidates[3], LinePoint* next) {
  bool moved = false;
  for (int i = 0; i < 3; i++) {
    double dc = candidates[i].deriv[0], de = end->deriv[0];
    if ((de < 0 && dc < 0 && de < dc) || (de > 0 && dc > 0 && de > dc)) {
      *end = candidates[i];
      moved = true;
    }
  }
  if (moved) {
    next->alpha = end->alpha - end->deriv[0] / end->deriv[1];
    EvalLine(s, next);
  }
  return moved;
}

// The step length along `search` (0: no improvement possible). MuJoCo's PrimalSearch.
double LineSearch(const Model& m, Primal& s) {
  ConstraintProblem& p = s.p;
  int ls_iterations = m.opt.ls_iterations;
  s.ls_iter = 0;
  double snorm = std::sqrt(Dot(s.search.data(), s.search.data(), p.nv));
  if (snorm < kMinVal) return 0;
  double gtol = m.opt.tolerance * m.opt.ls_tolerance * snorm / p.scale;

  MulSym(p, s.search.data(), s.mv.data());
  MulJ(p, s.search.data(), s.jv.data());
  PrepareLine(s);

  // A first Newton step from alpha = 0.
  LinePoint p0, p1;
  EvalLine(s, &p0);
  p1.alpha = p0.alpha - p0.deriv[0] / p0.deriv[1];
  EvalLine(s, &p1);
  if (std::abs(p1.deriv[0]) < gtol) return p1.alpha;

  // One-sided Newton steps until the derivative changes sign.
  int dir = p1.deriv[0] < 0 ? 1 : -1;
  LinePoint p2 = p0;
  while (p1.deriv[0] * dir <= -gtol && s.ls_iter < ls_iterations) {
    p2 = p1;
    p1.alpha -= p1.deriv[0] / p1.deriv[1];
    EvalLine(s, &p1);
    if (std::abs(p1.deriv[0]) < gtol) return p1.alpha;
  }
  if (s.ls_iter >= ls_iterations) return p1.alpha;

  // Bracketed search between p1 and p2.
  LinePoint p2next = p1, p1next;
  p1next.alpha = p1.alpha - p1.deriv[0] / p1.deriv[1];
  EvalLine(s, &p1next);
  while (s.ls_iter < ls_iterations) {
    LinePoint mid;
    mid.alpha = 0.5 * (p1.alpha + p2.alpha);
    EvalLine(s, &mid);
    LinePoint candidates[3] = {p1next, p2next, mid};

    // Converged candidate with the lowest cost wins.
    int best = -1;
    for (int i = 0; i < 3; i++) {
      if (std::abs(candidates[i].deriv[0]) < gtol &&
          (best == -1 || candidates[i].cost < candidates[best].cost)) {
        best = i;
      }
    }
    if (best >= 0) return candidates[best].alpha;

    bool moved1 = UpdateBracket(s, &p1, candidates, &p1next);
    bool moved2 = UpdateBracket(s, &p2, candidates, &p2next);
    if (!moved1 && !moved2) return mid.alpha;
  }

  // Out of iterations: the better bracket end, if it improves on the start.
  if (p1.cost <= p2.cost && p1.cost < p0.cost) return p1.alpha;
  if (p2.cost <= p1.cost && p2.cost < p0.cost) return p2.alpha;
  return 0;
}

}  // namespace

// ---------------------------------------------------------------- the iteration

void SolvePrimal(const Model& m, ConstraintProblem& p, bool newton) {
  int nv = p.nv, nefc = p.nefc;
  Primal s(p, newton);
  std::vector<double> gradold, mgradold;
  std::vector<int> oldstate(nefc);

  // Start: M a, J a - aref, states, gradient, direction = -preconditioned gradient.
  MulSym(p, p.qacc.data(), s.ma.data());
  MulJ(p, p.qacc.data(), s.jaref.data());
  for (int r = 0; r < nefc; r++) s.jaref[r] -= p.aref[r];
  UpdateConstraint(s);
  if (newton) FactorHessian(s);
  UpdateGradient(s);
  for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v];

  int iter = 0;
  while (iter < m.opt.iterations) {
    double alpha = LineSearch(m, s);
    if (alpha == 0) break;

    // Move along the line; update states, Hessian and gradient.
    for (int v = 0; v < nv; v++) {
      p.qacc[v] += alpha * s.search[v];
      s.ma[v] += alpha * s.mv[v];
    }
    for (int r = 0; r < nefc; r++) s.jaref[r] += alpha * s.jv[r];
    if (!newton) {
      gradold = s.grad;
      mgradold = s.mgrad;
    }
    oldstate = p.state;
    double oldcost = s.cost;
    UpdateConstraint(s);
    if (newton) UpdateHessian(s, oldstate);
    UpdateGradient(s);

    // Stop when neither the cost nor the gradient (scaled) is worth another step.
    double improvement = p.scale * (oldcost - s.cost);
    double gradient = p.scale * std::sqrt(Dot(s.grad.data(), s.grad.data(), nv));
    iter++;
    if (improvement < m.opt.tolerance || gradient < m.opt.tolerance) break;

    // Next direction: Newton, or Polak-Ribiere conjugate gradient (reset when negative).
    if (newton) {
      for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v];
    } else {
      std::vector<double> mgrad_change(nv);
      for (int v = 0; v < nv; v++) mgrad_change[v] = s.mgrad[v] - mgradold[v];
      double beta = Dot(s.grad.data(), mgrad_change.data(), nv) /
                    std::max(kMinVal, Dot(gradold.data(), mgradold.data(), nv));
      beta = std::max(0.0, beta);
      for (int v = 0; v < nv; v++) s.search[v] = -s.mgrad[v] + beta * s.search[v];
    }
  }
  p.niter = iter;
}

}  // namespace simlab
