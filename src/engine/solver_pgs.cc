// Projected Gauss-Seidel on the dual problem (MuJoCo mj_solPGS, engine_solver.c):
//
//   minimize over f   0.5 f^T AR f + f^T b   with f in the feasible set of each row
//
// (friction rows within +-frictionloss, limits and pyramidal/frictionless contacts
// non-negative, an elliptic contact's forces inside its friction cone). One sweep
// minimizes over each row, or each elliptic contact's block of rows, in turn and
// projects; a step that would raise the cost is undone. Then qacc = qacc_smooth +
// M^-1 J^T f.
//
// An elliptic contact's block is updated in two moves: the normal force (alone when it is
// zero, else scaled along the current force "ray"), then the friction forces with the
// normal fixed, as the QCQP  min 0.5 x^T A x + x^T b  s.t.  sum (x_j / mu_j)^2 <= f_n^2.
#include <algorithm>
#include <cmath>
#include <functional>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "math/dot.h"

namespace simlab {

using math::Dot;

// ---------------------------------------------------------------- dual helpers

namespace {

// The zone of an elliptic contact's forces f (rows i..): inside the cone (no force
// pattern of a separating contact: satisfied), under its mirror (quadratic), between.
int EllipticDualState(const Contact& con, const double* f) {
  double scaled[6];
  scaled[0] = f[0] / con.mu;
  for (int j = 1; j < con.dim; j++) scaled[j] = f[j] / con.friction[j - 1];
  double N = scaled[0];
  double T = std::sqrt(Dot(scaled + 1, scaled + 1, con.dim - 1));
  if (con.mu * N >= T) return kStateSatisfied;
  if (N + con.mu * T <= 0) return kStateQuadratic;
  return kStateCone;
}

// Row states of a dual solution (MuJoCo dualState): friction signs are the primal's
// opposite; one-sided rows with a positive force are active; elliptic contacts by zone.
void DualState(Data& d) {
  for (int r = 0; r < d.nefc; r++) {
    int& state = d.efc_state[r];
    double f = d.efc_force[r];
    if (r < d.ne) {
      state = kStateQuadratic;
    } else if (r < d.ne + d.nf) {
      double loss = d.efc_frictionloss[r];
      state = f <= -loss ? kStateLinearPos : f >= loss ? kStateLinearNeg : kStateQuadratic;
    } else if (d.efc_type[r] == kCnstrContactElliptic) {
      const Contact& con = d.contact[d.efc_id[r]];
      int zone = EllipticDualState(con, &d.efc_force[r]);
      std::fill(&d.efc_state[r], &d.efc_state[r] + con.dim, zone);
      r += con.dim - 1;
    } else {
      state = f <= 0 ? kStateSatisfied : kStateQuadratic;
    }
  }
}

// Row r of AR times f.
double ARRowDot(const Model& m, const Data& d, int r, const double* f) {
  if (!SparseJacobian(m)) return Dot(&d.efc_AR[static_cast<size_t>(r) * d.nefc], f, d.nefc);
  int adr = d.efc_AR_rowadr[r];
  return math::DotSparse(&d.efc_AR[adr], f, d.efc_AR_rownnz[r], &d.efc_AR_colind[adr]);
}

}  // namespace

void InverseDiagAR(const Model& m, const Data& d, bool no_r, double* inv) {
  for (int r = 0; r < d.nefc; r++) {
    double diag = d.efc_AR[AREntry(m, d, r, r)];
    inv[r] = 1 / (no_r ? std::max(kMinVal, diag - d.efc_R[r]) : diag);
  }
}

void BlockAR(const Model& m, const Data& d, int start, int dim, bool no_r, double* block) {
  // (on compressed rows the block's rows share their columns: those of one constraint)
  for (int j = 0; j < dim; j++) {
    const double* row = &d.efc_AR[AREntry(m, d, start + j, start)];
    std::copy(row, row + dim, block + j * dim);
  }
  if (!no_r) return;
  for (int j = 0; j < dim; j++) {
    double& diag = block[j * (dim + 1)];
    diag = std::max(1e-10, diag - d.efc_R[start + j]);
  }
}

void Residual(const Model& m, const Data& d, int start, int dim, bool no_r, double* res) {
  for (int j = 0; j < dim; j++) {
    res[j] = d.efc_b[start + j] + ARRowDot(m, d, start + j, d.efc_force.data());
    if (no_r) res[j] -= d.efc_R[start + j] * d.efc_force[start + j];
  }
}

void MulAR(const Model& m, const Data& d, const double* f, double* res) {
  for (int r = 0; r < d.nefc; r++) res[r] = ARRowDot(m, d, r, f);
}

double CostChange(const double* A, double* force, const double* old, const double* res,
                  int dim) {
  double change;
  if (dim == 1) {
    double delta = force[0] - old[0];
    change = 0.5 * delta * delta * A[0] + delta * res[0];
  } else {
    // 0.5 delta^T A delta + delta . res, with MuJoCo's order of sums.
    double delta[6] = {};
    for (int j = 0; j < dim; j++) delta[j] = force[j] - old[j];
    double quadratic = 0;
    for (int j = 0; j < dim; j++) quadratic += delta[j] * Dot(A + j * dim, delta, dim);
    change = 0.5 * quadratic + Dot(delta, res, dim);
  }
  if (change > 1e-10) {
    std::copy(old, old + dim, force);
    change = 0;
  }
  return change;
}

void EllipticFriction(const double* A, const double* b, const double* mu, double fn, int dim,
                      double* friction_force) {
  int n = dim - 1;
  if (fn < kMinVal) {
    std::fill(friction_force, friction_force + n, 0.0);
    return;
  }
  double x[5];
  bool active = dim == 3   ? QCQP2(x, A, b, mu, fn)
                : dim == 4 ? QCQP3(x, A, b, mu, fn)
                           : QCQP(x, A, b, mu, fn, n);

  // On the cone: scale onto its surface, in case the QCQP stopped short.
  if (active) {
    double s = 0;
    for (int j = 0; j < n; j++) s += x[j] * x[j] / (mu[j] * mu[j]);
    s = std::sqrt(fn * fn / std::max(kMinVal, s));
    for (int j = 0; j < n; j++) x[j] *= s;
  }
  std::copy(x, x + n, friction_force);
}

namespace {

// ---------------------------------------------------------------- the sweep

// Row r's force: unconstrained minimum along the row, projected on its feasible set.
void UpdateScalar(Data& d, int r, double res, double ar_inv) {
  double& f = d.efc_force[r];
  f -= res * ar_inv;
  if (r >= d.ne && r < d.ne + d.nf) {
    f = std::clamp(f, -d.efc_frictionloss[r], d.efc_frictionloss[r]);
  } else if (r >= d.ne + d.nf) {
    f = std::max(0.0, f);
  }
}

// The normal force of the elliptic contact at row i: alone when it is (nearly) zero,
// else the best multiple of the current force vector (kept non-negative).
void UpdateEllipticNormal(Data& d, int i, int dim, const double* A, const double* res,
                          double ar_inv) {
  double* f = &d.efc_force[i];
  if (f[0] < kMinVal) {
    f[0] = std::max(0.0, f[0] - res[0] * ar_inv);
    std::fill(f + 1, f + dim, 0.0);
    return;
  }
  double ray[6], a_ray[6];
  std::copy(f, f + dim, ray);
  for (int j = 0; j < dim; j++) a_ray[j] = Dot(A + j * dim, ray, dim);
  double denom = Dot(ray, a_ray, dim);
  if (denom < kMinVal) return;
  double x = -Dot(ray, res, dim) / denom;
  if (f[0] + x * ray[0] < 0) x = -ray[0] / f[0];
  for (int j = 0; j < dim; j++) f[j] += x * ray[j];
}

// The elliptic contact's block at row i: normal move, then friction by the QCQP with the
// residual corrected for the forces' change so far (b_t - A_tt f_t,old + A_tn dfn).
void UpdateElliptic(Data& d, int i, int dim, const double* A, const double* res,
                    const double* old, double ar_inv) {
  UpdateEllipticNormal(d, i, dim, A, res, ar_inv);
  double* f = &d.efc_force[i];
  int n = dim - 1;
  double At[25], bt[5];
  for (int j = 0; j < n; j++) {
    std::copy(A + (j + 1) * dim + 1, A + (j + 1) * dim + dim, At + j * n);
    bt[j] = res[j + 1] - Dot(At + j * n, old + 1, n);
    bt[j] += A[(j + 1) * dim] * (f[0] - old[0]);
  }
  EllipticFriction(At, bt, d.contact[d.efc_id[i]].friction, f[0], dim, f + 1);
}

// One Gauss-Seidel sweep over the rows and elliptic blocks; returns the cost decrease.
double Sweep(const Model& m, Data& d, const double* ar_inv) {
  double improvement = 0;
  for (int i = 0; i < d.nefc; i++) {
    bool elliptic = d.efc_type[i] == kCnstrContactElliptic;
    int dim = elliptic ? d.contact[d.efc_id[i]].dim : 1;
    double res[6], old[6], A[36];
    Residual(m, d, i, dim, false, res);
    std::copy(&d.efc_force[i], &d.efc_force[i] + dim, old);
    if (elliptic) {
      BlockAR(m, d, i, dim, false, A);
      UpdateElliptic(d, i, dim, A, res, old, ar_inv[i]);
    } else {
      UpdateScalar(d, i, res[0], ar_inv[i]);
      A[0] = 1 / ar_inv[i];
    }
    improvement -= CostChange(A, &d.efc_force[i], old, res, dim);
    i += dim - 1;
  }
  return improvement;
}

}  // namespace

void RunDualSweeps(const Model& m, Data& d, int maxiter, double tolerance,
                   const std::function<double(int)>& sweep) {
  double scale = 1 / (m.stat.meaninertia * std::max(1, m.nv));
  DualState(d);
  int iter = 0;
  while (iter < maxiter) {
    double improvement = sweep(iter) * scale;
    DualState(d);
    iter++;
    if (improvement < tolerance) break;
  }
  d.solver_niter += iter;

  // Back to joint space: qfrc_constraint = J^T f, qacc = qacc_smooth + M^-1 qfrc_constraint.
  EfcMulTVec(m, d, d.efc_force.data(), d.qfrc_constraint.data());
  d.qacc = d.qfrc_constraint;
  SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), d.qacc.data());
  for (int v = 0; v < m.nv; v++) d.qacc[v] += d.qacc_smooth[v];
}

void SolvePGS(const Model& m, Data& d) {
  SolverFrame frame(d.solver_scratch);
  double* ar_inv = frame.Reals(d.nefc);
  InverseDiagAR(m, d, false, ar_inv);
  RunDualSweeps(m, d, m.opt.iterations, m.opt.tolerance,
                [&m, &d, ar_inv](int) { return Sweep(m, d, ar_inv); });
}

}  // namespace simlab
