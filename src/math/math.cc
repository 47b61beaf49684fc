// The larger functions of math.h (the small, hot ones are inline there).
#include "math/math.h"

#include <cmath>
#include <numbers>
#include <utility>

#include "math/elementary.h"

namespace simlab::math {

// ---------------------------------------------------------------- quaternions

void MatToQuat(double* q, const double* m) {
  // Pick the largest of the four components to divide by (numerically safest); sums in
  // MuJoCo's order (mju_mat2Quat).
  if (m[0] + m[4] + m[8] > 0) {
    q[0] = 0.5 * std::sqrt(1 + m[0] + m[4] + m[8]);
    q[1] = 0.25 * (m[7] - m[5]) / q[0];
    q[2] = 0.25 * (m[2] - m[6]) / q[0];
    q[3] = 0.25 * (m[3] - m[1]) / q[0];
  } else if (m[0] > m[4] && m[0] > m[8]) {
    q[1] = 0.5 * std::sqrt(1 + m[0] - m[4] - m[8]);
    q[0] = 0.25 * (m[7] - m[5]) / q[1];
    q[2] = 0.25 * (m[1] + m[3]) / q[1];
    q[3] = 0.25 * (m[2] + m[6]) / q[1];
  } else if (m[4] > m[8]) {
    q[2] = 0.5 * std::sqrt(1 - m[0] + m[4] - m[8]);
    q[0] = 0.25 * (m[2] - m[6]) / q[2];
    q[1] = 0.25 * (m[1] + m[3]) / q[2];
    q[3] = 0.25 * (m[5] + m[7]) / q[2];
  } else {
    q[3] = 0.5 * std::sqrt(1 - m[0] - m[4] + m[8]);
    q[0] = 0.25 * (m[3] - m[1]) / q[3];
    q[1] = 0.25 * (m[2] + m[6]) / q[3];
    q[2] = 0.25 * (m[5] + m[7]) / q[3];
  }
  NormalizeQuat(q);
}

void AxisAngleToQuat(double* q, const double* axis, double angle) {
  if (angle == 0) {
    SetIdentityQuat(q);
    return;
  }

  double s = math::Sin(angle * 0.5);
  q[0] = math::Cos(angle * 0.5);
  q[1] = axis[0] * s;
  q[2] = axis[1] * s;
  q[3] = axis[2] * s;
}

void QuatZToVec(double* q, const double* vec) {
  static constexpr double kZ[3] = {0, 0, 1};
  q[0] = 1;
  q[1] = q[2] = q[3] = 0;
  double dir[3] = {vec[0], vec[1], vec[2]}, axis[3];
  if (Normalize3(dir) < kTiny) return;
  Cross3(axis, kZ, dir);
  double sin_angle = Normalize3(axis);
  // (parallel: nothing to turn, or a half turn about x when opposite)
  if (std::abs(sin_angle) < kTiny) {
    if (Dot3(dir, kZ) < 0) q[0] = 0, q[1] = 1;
    return;
  }
  AxisAngleToQuat(q, axis, Atan2(sin_angle, Dot3(dir, kZ)));
}

void QuatToVel(double* vel, const double* q, double dt) {
  double axis[3] = {q[1], q[2], q[3]};
  double sin_half = Normalize3(axis);
  double angle = 2 * math::Atan2(sin_half, q[0]);
  // A rotation past pi is the shorter rotation the other way.
  if (angle > std::numbers::pi) angle -= 2 * std::numbers::pi;
  Scale3(vel, axis, angle / dt);
}

void SubQuat(double* res, const double* qa, const double* qb) {
  double qneg[4], qdif[4];
  NegQuat(qneg, qb);
  MulQuat(qdif, qneg, qa);
  QuatToVel(res, qdif, 1);
}

void QuatIntegrate(double* q, const double* vel, double scale) {
  double axis[3] = {vel[0], vel[1], vel[2]};
  double angle = scale * Normalize3(axis);
  double qrot[4];
  AxisAngleToQuat(qrot, axis, angle);
  NormalizeQuat(q);
  MulQuat(q, q, qrot);
}

// ---------------------------------------------------------------- spatial algebra

void InertCom(double* res, const double* inert, const double* mat, const double* dif,
              double mass) {
  // Rotational part: R diag(inert) R^T, then the parallel-axis term m (|d|^2 I - d d^T).
  double t[9] = {mat[0] * inert[0], mat[3] * inert[0], mat[6] * inert[0],
                 mat[1] * inert[1], mat[4] * inert[1], mat[7] * inert[1],
                 mat[2] * inert[2], mat[5] * inert[2], mat[8] * inert[2]};
  res[0] = mat[0] * t[0] + mat[1] * t[3] + mat[2] * t[6];
  res[1] = mat[3] * t[1] + mat[4] * t[4] + mat[5] * t[7];
  res[2] = mat[6] * t[2] + mat[7] * t[5] + mat[8] * t[8];
  res[3] = mat[0] * t[1] + mat[1] * t[4] + mat[2] * t[7];
  res[4] = mat[0] * t[2] + mat[1] * t[5] + mat[2] * t[8];
  res[5] = mat[3] * t[2] + mat[4] * t[5] + mat[5] * t[8];
  res[0] += mass * (dif[1] * dif[1] + dif[2] * dif[2]);
  res[1] += mass * (dif[0] * dif[0] + dif[2] * dif[2]);
  res[2] += mass * (dif[0] * dif[0] + dif[1] * dif[1]);
  res[3] -= mass * dif[0] * dif[1];
  res[4] -= mass * dif[0] * dif[2];
  res[5] -= mass * dif[1] * dif[2];
  // First mass moment and mass.
  res[6] = mass * dif[0];
  res[7] = mass * dif[1];
  res[8] = mass * dif[2];
  res[9] = mass;
}

void TransformSpatial(double* res, const double* vec, bool is_force, const double* newpos,
                      const double* oldpos, const double* rot_new_to_old) {
  // Move the reference point: force keeps f and shifts torque; motion keeps w.
  double moved[6] = {vec[0], vec[1], vec[2], vec[3], vec[4], vec[5]};
  double dif[3], cross[3];
  Sub3(dif, newpos, oldpos);
  if (is_force) {
    Cross3(cross, dif, vec + 3);
    Sub3(moved, vec, cross);
  } else {
    Cross3(cross, dif, vec);
    Sub3(moved + 3, vec + 3, cross);
  }
  // Then rotate into the new frame, if asked.
  if (rot_new_to_old) {
    MulMatTVec3(res, rot_new_to_old, moved);
    MulMatTVec3(res + 3, rot_new_to_old, moved + 3);
  } else {
    for (int i = 0; i < 6; i++) res[i] = moved[i];
  }
}

namespace {

constexpr double kEigEps = 1e-12;  // Jacobi convergence threshold (1000 mjMINVAL)

// One Jacobi step: the rotation (a quaternion about axis k) that zeroes the largest
// off-diagonal entry D(r, c) of D = V^T A V; false when converged.
bool JacobiRotation(const double d[9], double rot[4], void (*normalize)(double* q)) {
  int r = 1, c = 2, k = 0;
  if (std::abs(d[1]) > std::abs(d[2]) && std::abs(d[1]) > std::abs(d[5])) {
    r = 0, c = 1, k = 2;
  } else if (std::abs(d[2]) > std::abs(d[5])) {
    r = 0, c = 2, k = 1;
  }
  if (std::abs(d[3 * r + c]) < kEigEps) return false;

  // Symmetric Schur decomposition of the 2x2 block, as a half-angle rotation.
  double tau = (d[4 * c] - d[4 * r]) / (2 * d[3 * r + c]);
  double t = tau >= 0 ? 1.0 / (tau + std::sqrt(1 + tau * tau))
                      : -1.0 / (-tau + std::sqrt(1 + tau * tau));
  double cs = 1.0 / std::sqrt(1 + t * t);
  if (cs > 1.0 - kEigEps) return false;
  double s = std::sqrt(0.5 - 0.5 * cs);
  rot[1] = rot[2] = rot[3] = 0;
  rot[k + 1] = (tau >= 0) ? -s : s;
  if (k == 1) rot[k + 1] = -rot[k + 1];
  rot[0] = std::sqrt(1.0 - rot[k + 1] * rot[k + 1]);
  normalize(rot);
  return true;
}

}  // namespace

void Eig3(double eigval[3], double quat[4], const double mat[9], void (*normalize)(double* q)) {
  SetIdentityQuat(quat);
  for (int iter = 0; iter < 500; iter++) {
    // D = V^T A V with V the rotation of quat.
    double v[9], tmp[9], d[9];
    QuatToMat(v, quat);
    MulMatTMat3(tmp, v, mat);
    MulMat3(d, tmp, v);
    eigval[0] = d[0];
    eigval[1] = d[4];
    eigval[2] = d[8];
    double rot[4], q[4];
    if (!JacobiRotation(d, rot, normalize)) break;
    MulQuat(q, quat, rot);
    CopyQuat(quat, q);
    normalize(quat);
  }

  // Sort in decreasing order by swaps (0,1), (1,2), (0,1), each a quarter turn.
  for (int j = 0; j < 3; j++) {
    int a = j % 2;
    if (eigval[a] + kEigEps < eigval[a + 1]) {
      std::swap(eigval[a], eigval[a + 1]);
      double rot[4] = {0.707106781186548, 0, 0, 0}, q[4];
      rot[(a + 2) % 3 + 1] = rot[0];
      MulQuat(q, quat, rot);
      CopyQuat(quat, q);
      normalize(quat);
    }
  }
}

}  // namespace simlab::math
