// Standalone free bodies under implicitfast, as MuJoCo 3.12 steps them (see the header).
#include "engine/free_body_implicit.h"

#include <cmath>
#include <utility>

#include "math/math.h"

namespace simlab {

namespace {

// The world-frame inertia about the centre of mass: Xi diag(inertia) Xi^T, symmetric.
void WorldInertia(const double* Xi, const double* inertia, double Iw[9]) {
  double XiI[9];
  for (int i = 0; i < 3; i++) {
    for (int k = 0; k < 3; k++) XiI[3 * i + k] = Xi[3 * i + k] * inertia[k];
  }
  Iw[0] = XiI[0] * Xi[0] + XiI[1] * Xi[1] + XiI[2] * Xi[2];
  Iw[4] = XiI[3] * Xi[3] + XiI[4] * Xi[4] + XiI[5] * Xi[5];
  Iw[8] = XiI[6] * Xi[6] + XiI[7] * Xi[7] + XiI[8] * Xi[8];
  Iw[1] = Iw[3] = XiI[0] * Xi[3] + XiI[1] * Xi[4] + XiI[2] * Xi[5];
  Iw[2] = Iw[6] = XiI[0] * Xi[6] + XiI[1] * Xi[7] + XiI[2] * Xi[8];
  Iw[5] = Iw[7] = XiI[3] * Xi[6] + XiI[4] * Xi[7] + XiI[5] * Xi[8];
}

// The derivatives of a free body's bias force by its angular velocity (dofs in the body
// frame R): `lin` for the linear rows (to be scaled by -mass) and `rot` for the angular
// ones, with s the centre of mass's offset from the joint and Xi the inertia frame.
void BiasVelocityBlocks(double mass, const double* R, const double* Xi, const double* inertia,
                        const double* s, const double* qvel_rot, double lin[9], double rot[9]) {
  double w[3], Iw[9], ws[3], Iww[3];
  math::MulMatVec3(w, R, qvel_rot);
  WorldInertia(Xi, inertia, Iw);
  math::Cross3(ws, w, s);
  math::MulMatVec3(Iww, Iw, w);

  // K = [w x s]_x + [w]_x [s]_x = s w^T - (w . s) I + [ws]_x; lin = K R.
  double w_dot_s = w[0] * s[0] + w[1] * s[1] + w[2] * s[2];
  double K[9] = {s[0] * w[0] - w_dot_s, s[0] * w[1] - ws[2],  s[0] * w[2] + ws[1],
                 s[1] * w[0] + ws[2],  s[1] * w[1] - w_dot_s, s[1] * w[2] - ws[0],
                 s[2] * w[0] - ws[1],  s[2] * w[1] + ws[0],  s[2] * w[2] - w_dot_s};
  math::MulMat3(lin, K, R);

  // C = -mass [s]_x K + [w]_x Iw - [Iw w]_x, column by column; rot = R^T C R.
  double C[9];
  for (int c = 0; c < 3; c++) {
    double sK[3] = {s[1] * K[6 + c] - s[2] * K[3 + c], s[2] * K[c] - s[0] * K[6 + c],
                    s[0] * K[3 + c] - s[1] * K[c]};
    double wI[3] = {w[1] * Iw[6 + c] - w[2] * Iw[3 + c], w[2] * Iw[c] - w[0] * Iw[6 + c],
                    w[0] * Iw[3 + c] - w[1] * Iw[c]};
    C[c] = -mass * sK[0] + wI[0] + (c == 1 ? Iww[2] : (c == 2 ? -Iww[1] : 0));
    C[3 + c] = -mass * sK[1] + wI[1] + (c == 0 ? -Iww[2] : (c == 2 ? Iww[0] : 0));
    C[6 + c] = -mass * sK[2] + wI[2] + (c == 0 ? Iww[1] : (c == 1 ? -Iww[0] : 0));
  }
  double RtC[9];
  math::MulMatTMat3(RtC, R, C);
  math::MulMat3(rot, RtC, R);
}

// A = M - h qDeriv - h d(bias)/d(qvel) for free joint j's dofs (row-major 6 x 6), when
// its body is a standalone free body and awake (mjd_freeMhat).
bool FreeBodyStepMatrix(const Model& m, const Data& d, int j, double h, double A[36]) {
  int body = m.jnt_bodyid[j], adr = m.jnt_dofadr[j];
  if (!IsStandaloneFreeBody(m, body) || !d.tree_awake[m.dof_treeid[adr]]) return false;
  for (int k = 0; k < 36; k++) A[k] = 0;
  for (int r = 0; r < 6; r++) {
    int rowadr = m.M_rowadr[adr + r];
    for (int k = 0; k < m.M_rownnz[adr + r]; k++) {
      int c = m.M_colind[rowadr + k] - adr;
      A[6 * r + c] = A[6 * c + r] = d.M[rowadr + k];
    }
  }
  for (int r = 0; r < 6; r++) {
    int rowadr = m.D_rowadr[adr + r];
    for (int k = 0; k < m.D_rownnz[adr + r]; k++) {
      A[6 * r + m.D_colind[rowadr + k] - adr] -= h * d.qDeriv[rowadr + k];
    }
  }
  double s[3], lin[9], rot[9];
  math::Sub3(s, &d.xipos[3 * body], &d.xpos[3 * body]);
  double mass = m.body_mass[body];
  BiasVelocityBlocks(mass, &d.xmat[9 * body], &d.ximat[9 * body], &m.body_inertia[3 * body], s,
                     &d.qvel[adr + 3], lin, rot);
  double h_mass = -h * mass;
  for (int r = 0; r < 3; r++) {
    for (int c = 0; c < 3; c++) {
      A[6 * r + 3 + c] += h_mass * lin[3 * r + c];
      A[6 * (3 + r) + 3 + c] += h * rot[3 * r + c];
    }
  }
  return true;
}

// LU factorization of a 6 x 6 matrix in place with partial pivoting (row k swapped with
// pivot[k]); false when a column has no pivot above kMinVal.
bool FactorLU6(double A[36], int pivot[6]) {
  for (int k = 0; k < 6; k++) {
    pivot[k] = k;
    double largest = std::abs(A[6 * k + k]);
    int row = k;
    for (int i = k + 1; i < 6; i++) {
      if (std::abs(A[6 * i + k]) > largest) {
        largest = std::abs(A[6 * i + k]);
        row = i;
      }
    }
    if (largest < kMinVal) return false;
    if (row != k) {
      pivot[k] = row;
      for (int c = 0; c < 6; c++) std::swap(A[6 * k + c], A[6 * row + c]);
    }
    double inverse = 1.0 / A[6 * k + k];
    for (int i = k + 1; i < 6; i++) {
      A[6 * i + k] *= inverse;
      double factor = A[6 * i + k];
      for (int c = k + 1; c < 6; c++) A[6 * i + c] -= factor * A[6 * k + c];
    }
  }
  return true;
}

// x = A^-1 b from FactorLU6's factors: the row swaps and L forward, then U backward.
void SolveLU6(double x[6], const double LU[36], const double b[6], const int pivot[6]) {
  for (int i = 0; i < 6; i++) x[i] = b[i];
  for (int i = 0; i < 6; i++) {
    if (pivot[i] != i) std::swap(x[i], x[pivot[i]]);
    for (int c = 0; c < i; c++) x[i] -= LU[6 * i + c] * x[c];
  }
  for (int i = 5; i >= 0; i--) {
    for (int c = i + 1; c < 6; c++) x[i] -= LU[6 * i + c] * x[c];
    x[i] /= LU[6 * i + i];
  }
}

}  // namespace

bool IsStandaloneFreeBody(const Model& m, int body) {
  if (m.body_jntnum[body] != 1 || m.jnt_type[m.body_jntadr[body]] != kJointFree) return false;
  int adr = m.jnt_dofadr[m.body_jntadr[body]];
  return m.tree_dofnum[m.dof_treeid[adr]] == 6 && m.body_subtreemass[body] == m.body_mass[body];
}

bool SolvesFreeBodiesApart(const Model& m) {
  return m.release == Release::k3_12 && m.opt.integrator == kIntegratorImplicitFast;
}

void SolveFreeBodies(const Model& m, const Data& d, const double* qfrc, double* qacc) {
  for (int j = 0; j < m.njnt; j++) {
    double A[36];
    int pivot[6];
    if (!FreeBodyStepMatrix(m, d, j, m.opt.timestep, A) || !FactorLU6(A, pivot)) continue;
    int adr = m.jnt_dofadr[j];
    double x[6];
    SolveLU6(x, A, qfrc + adr, pivot);
    for (int k = 0; k < 6; k++) qacc[adr + k] = x[k];
  }
}

}  // namespace simlab
