// The noslip post-pass (MuJoCo mj_solNoSlip, engine_solver.c), run after the main solver
// when opt.noslip_iterations > 0. Soft contacts slip a little because of the regularizer
// R; noslip re-solves only the frictional forces of the dual problem without R,
//
//   minimize 0.5 f^T A f + f^T (b + R f_main)   (A = J M^-1 J^T, normal forces fixed),
//
// by Gauss-Seidel: friction-loss rows within +-frictionloss; each pair of opposite edges
// of a pyramidal contact exchanging force with their sum kept; an elliptic contact's
// friction forces by the QCQP inside the cone of its (fixed) normal force. Then joint
// space as PGS. Sweeps stop when the cost decrease, scaled by the total inertia, falls
// below opt.noslip_tolerance.
#include <algorithm>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "math/dot.h"

namespace simlab {

namespace {

// Friction-loss rows: unconstrained minimum along each row, clamped to its interval.
// (The sweeps subtract their cost changes from one running sum, in MuJoCo's order.)
void SweepFrictionLoss(const Model& m, Data& d, const double* ar_inv, double* improvement) {
  for (int r = d.ne; r < d.ne + d.nf; r++) {
    double res;
    Residual(m, d, r, 1, true, &res);
    double old = d.efc_force[r];
    double loss = d.efc_frictionloss[r];
    d.efc_force[r] = std::clamp(old - res * ar_inv[r], -loss, loss);
    double delta = d.efc_force[r] - old;
    *improvement -= 0.5 * delta * delta / ar_inv[r] + delta * res;
  }
}

// Rows j, j+1 (opposite edges of a pyramid): f_j = mid + y, f_j+1 = mid - y with their sum
// 2 mid fixed, y minimizing the pair's quadratic within [-mid, mid]; returns the change.
double UpdateEdgePair(const Model& m, Data& d, int j) {
  double res[2], old[2], A[4], b[2];
  Residual(m, d, j, 2, true, res);
  std::copy(&d.efc_force[j], &d.efc_force[j] + 2, old);
  BlockAR(m, d, j, 2, true, A);
  for (int k = 0; k < 2; k++) b[k] = res[k] - math::Dot(A + 2 * k, old, 2);

  double* f = &d.efc_force[j];
  double mid = 0.5 * (f[0] + f[1]);
  double curvature = A[0] + A[3] - A[1] - A[2];
  double slope = mid * (A[0] - A[3]) + b[0] - b[1];
  if (curvature < kMinVal) {
    f[0] = f[1] = mid;
  } else {
    double y = -slope / curvature;
    if (y < -mid) {
      f[0] = 0;
      f[1] = 2 * mid;
    } else if (y > mid) {
      f[0] = 2 * mid;
      f[1] = 0;
    } else {
      f[0] = mid + y;
      f[1] = mid - y;
    }
  }
  return CostChange(A, f, old, res, 2);
}

// The friction rows i+1.. of an elliptic contact at row i, normal force fixed.
double UpdateEllipticFriction(const Model& m, Data& d, int i, int dim) {
  int n = dim - 1;
  double res[5], old[5], A[25], b[5];
  Residual(m, d, i + 1, n, true, res);
  std::copy(&d.efc_force[i + 1], &d.efc_force[i + 1] + n, old);
  BlockAR(m, d, i + 1, n, true, A);
  for (int j = 0; j < n; j++) b[j] = res[j] - math::Dot(A + j * n, old, n);
  double* f = &d.efc_force[i];
  EllipticFriction(A, b, d.contact[d.efc_id[i]].friction, f[0], dim, f + 1);
  return CostChange(A, f + 1, old, res, n);
}

// Contact rows: pyramidal edge pairs and elliptic friction blocks (frictionless skipped).
void SweepContacts(const Model& m, Data& d, double* improvement) {
  for (int i = d.ne + d.nf; i < d.nefc; i++) {
    int type = d.efc_type[i];
    if (type != kCnstrContactPyramidal && type != kCnstrContactElliptic) continue;
    int dim = d.contact[d.efc_id[i]].dim;
    if (type == kCnstrContactPyramidal) {
      for (int j = i; j < i + 2 * (dim - 1); j += 2) *improvement -= UpdateEdgePair(m, d, j);
      i += 2 * (dim - 1) - 1;
    } else {
      *improvement -= UpdateEllipticFriction(m, d, i, dim);
      i += dim - 1;
    }
  }
}

}  // namespace

void SolveNoSlip(const Model& m, Data& d) {
  SolverFrame frame(d.solver_scratch);
  double* ar_inv = frame.Reals(d.nefc);
  InverseDiagAR(m, d, true, ar_inv);
  auto sweep = [&m, &d, ar_inv](int iter) {
    // The first sweep also counts removing R from the cost.
    double improvement = 0;
    if (iter == 0) {
      for (int r = 0; r < d.nefc; r++) {
        improvement += 0.5 * d.efc_force[r] * d.efc_force[r] * d.efc_R[r];
      }
    }
    SweepFrictionLoss(m, d, ar_inv, &improvement);
    SweepContacts(m, d, &improvement);
    return improvement;
  };
  RunDualSweeps(m, d, m.opt.noslip_iterations, m.opt.noslip_tolerance, sweep);
}

}  // namespace simlab
