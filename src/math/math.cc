// Implementations of the small math in math.h.
#include "math/math.h"

#include <cmath>
#include <utility>
#include <numbers>

namespace simlab::math {

namespace {
constexpr double kTiny = 1e-15;  // below this a norm counts as zero (mjMINVAL)
}  // namespace

// ---------------------------------------------------------------- vectors, matrices

double Normalize3(double* a) {
  double norm = Norm3(a);
  if (norm < kTiny) {
    a[0] = 1;
    a[1] = a[2] = 0;
  } else {
    double inv = 1 / norm;
    a[0] *= inv;
    a[1] *= inv;
    a[2] *= inv;
  }
  return norm;
}

void MulMat3(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    }
  }
}

void MulMatTMat3(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      r[3 * i + j] = a[i] * b[j] + a[3 + i] * b[3 + j] + a[6 + i] * b[6 + j];
    }
  }
}

void MulMatMatT3(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      r[3 * i + j] = a[3 * i] * b[3 * j] + a[3 * i + 1] * b[3 * j + 1] +
                     a[3 * i + 2] * b[3 * j + 2];
    }
  }
}

// ---------------------------------------------------------------- quaternions

double NormalizeQuat(double* q) {
  double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (norm < kTiny) {
    SetIdentityQuat(q);
  } else if (std::abs(norm - 1) > kTiny) {
    double inv = 1 / norm;
    for (int i = 0; i < 4; i++) q[i] *= inv;
  }
  return norm;
}

void MulQuat(double* r, const double* a, const double* b) {
  double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  r[0] = w;
  r[1] = x;
  r[2] = y;
  r[3] = z;
}

void RotVecQuat(double* r, const double* v, const double* q) {
  // Zero vector or identity rotation: nothing to rotate.
  if (v[0] == 0 && v[1] == 0 && v[2] == 0) {
    Zero3(r);
    return;
  }
  if (q[0] == 1 && q[1] == 0 && q[2] == 0 && q[3] == 0) {
    Copy3(r, v);
    return;
  }
  // t = w v + u x v;  r = v + 2 u x t, with u the vector part of q.
  double t[3] = {q[0] * v[0] + q[2] * v[2] - q[3] * v[1],
                 q[0] * v[1] + q[3] * v[0] - q[1] * v[2],
                 q[0] * v[2] + q[1] * v[1] - q[2] * v[0]};
  double x = v[0] + 2 * (q[2] * t[2] - q[3] * t[1]);
  double y = v[1] + 2 * (q[3] * t[0] - q[1] * t[2]);
  double z = v[2] + 2 * (q[1] * t[1] - q[2] * t[0]);
  r[0] = x;
  r[1] = y;
  r[2] = z;
}

void QuatToMat(double* m, const double* q) {
  if (q[0] == 1 && q[1] == 0 && q[2] == 0 && q[3] == 0) {
    for (int i = 0; i < 9; i++) m[i] = (i % 4 == 0) ? 1 : 0;
    return;
  }
  double ww = q[0] * q[0], wx = q[0] * q[1], wy = q[0] * q[2], wz = q[0] * q[3];
  double xx = q[1] * q[1], xy = q[1] * q[2], xz = q[1] * q[3];
  double yy = q[2] * q[2], yz = q[2] * q[3], zz = q[3] * q[3];
  m[0] = ww + xx - yy - zz;
  m[4] = ww - xx + yy - zz;
  m[8] = ww - xx - yy + zz;
  m[1] = 2 * (xy - wz);
  m[2] = 2 * (xz + wy);
  m[3] = 2 * (xy + wz);
  m[5] = 2 * (yz - wx);
  m[6] = 2 * (xz - wy);
  m[7] = 2 * (yz + wx);
}

void MatToQuat(double* q, const double* m) {
  // Pick the largest of the four components to divide by (numerically safest).
  double trace = m[0] + m[4] + m[8];
  if (trace > 0) {
    q[0] = 0.5 * std::sqrt(1 + trace);
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
  double s = std::sin(angle * 0.5);
  q[0] = std::cos(angle * 0.5);
  q[1] = axis[0] * s;
  q[2] = axis[1] * s;
  q[3] = axis[2] * s;
}

void QuatToVel(double* vel, const double* q, double dt) {
  double axis[3] = {q[1], q[2], q[3]};
  double sin_half = Normalize3(axis);
  double angle = 2 * std::atan2(sin_half, q[0]);
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

void QuatZ2Vec(double* q, const double* vec) {
  SetIdentityQuat(q);
  double vn[3] = {vec[0], vec[1], vec[2]};
  if (Normalize3(vn) < kTiny) return;
  // Rotate z onto vn about z x vn; parallel vectors need no rotation or a half turn.
  const double z[3] = {0, 0, 1};
  double axis[3];
  Cross3(axis, z, vn);
  double s = Normalize3(axis);
  if (std::abs(s) < kTiny) {
    if (Dot3(vn, z) < 0) {
      q[0] = 0;
      q[1] = 1;
    }
    return;
  }
  AxisAngleToQuat(q, axis, std::atan2(s, Dot3(vn, z)));
}

// ---------------------------------------------------------------- frames

void MulPose(double* pos, double* quat, const double* pos1, const double* quat1,
             const double* pos2, const double* quat2) {
  double p[3], q[4];
  RotVecQuat(p, pos2, quat1);
  Add3(p, p, pos1);
  MulQuat(q, quat1, quat2);
  Copy3(pos, p);
  CopyQuat(quat, q);
}

// ---------------------------------------------------------------- spatial algebra

void MulInertVec(double* r, const double* i, const double* v) {
  r[0] = i[0] * v[0] + i[3] * v[1] + i[4] * v[2] - i[8] * v[4] + i[7] * v[5];
  r[1] = i[3] * v[0] + i[1] * v[1] + i[5] * v[2] + i[8] * v[3] - i[6] * v[5];
  r[2] = i[4] * v[0] + i[5] * v[1] + i[2] * v[2] - i[7] * v[3] + i[6] * v[4];
  r[3] = i[8] * v[1] - i[7] * v[2] + i[9] * v[3];
  r[4] = i[6] * v[2] - i[8] * v[0] + i[9] * v[4];
  r[5] = i[7] * v[0] - i[6] * v[1] + i[9] * v[5];
}

void CrossMotion(double* r, const double* v, const double* m) {
  r[0] = -v[2] * m[1] + v[1] * m[2];
  r[1] = v[2] * m[0] - v[0] * m[2];
  r[2] = -v[1] * m[0] + v[0] * m[1];
  r[3] = -v[2] * m[4] + v[1] * m[5] - v[5] * m[1] + v[4] * m[2];
  r[4] = v[2] * m[3] - v[0] * m[5] + v[5] * m[0] - v[3] * m[2];
  r[5] = -v[1] * m[3] + v[0] * m[4] - v[4] * m[0] + v[3] * m[1];
}

void CrossForce(double* r, const double* v, const double* f) {
  r[0] = -v[2] * f[1] + v[1] * f[2] - v[5] * f[4] + v[4] * f[5];
  r[1] = v[2] * f[0] - v[0] * f[2] + v[5] * f[3] - v[3] * f[5];
  r[2] = -v[1] * f[0] + v[0] * f[1] - v[4] * f[3] + v[3] * f[4];
  r[3] = -v[2] * f[4] + v[1] * f[5];
  r[4] = v[2] * f[3] - v[0] * f[5];
  r[5] = -v[1] * f[3] + v[0] * f[4];
}

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
