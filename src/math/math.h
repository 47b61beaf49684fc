// Small fixed-size math on raw double arrays, the layout Model and Data use.
//
// Conventions (as MuJoCo): vectors are double[3]; quaternions are double[4] (w, x, y, z)
// and rotate a vector v by q v q*; 3x3 matrices are row-major double[9]. Spatial
// vectors are double[6] with the rotational part first: motion (omega, v), force
// (torque, f). Functions write their result through the first argument; results may
// not alias inputs unless stated.
#ifndef SIMLAB_MATH_MATH_H_
#define SIMLAB_MATH_MATH_H_

#include <cmath>

namespace simlab::math {

// Below this a norm counts as zero (mjMINVAL).
inline constexpr double kTiny = 1e-15;

// ---------------------------------------------------------------- 3-vectors

inline void Copy3(double* r, const double* a) { r[0] = a[0]; r[1] = a[1]; r[2] = a[2]; }
inline void Zero3(double* r) { r[0] = r[1] = r[2] = 0; }
inline double Dot3(const double* a, const double* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double Norm3(const double* a) { return std::sqrt(Dot3(a, a)); }
inline void Add3(double* r, const double* a, const double* b) {
  r[0] = a[0] + b[0]; r[1] = a[1] + b[1]; r[2] = a[2] + b[2];
}
inline void Sub3(double* r, const double* a, const double* b) {
  r[0] = a[0] - b[0]; r[1] = a[1] - b[1]; r[2] = a[2] - b[2];
}
inline void Scale3(double* r, const double* a, double s) {
  r[0] = a[0] * s; r[1] = a[1] * s; r[2] = a[2] * s;
}
// r += a * s
inline void AddScaled3(double* r, const double* a, double s) {
  r[0] += a[0] * s; r[1] += a[1] * s; r[2] += a[2] * s;
}
inline void Cross3(double* r, const double* a, const double* b) {
  r[0] = a[1] * b[2] - a[2] * b[1];
  r[1] = a[2] * b[0] - a[0] * b[2];
  r[2] = a[0] * b[1] - a[1] * b[0];
}
// Normalizes in place; returns the norm before (a near-zero vector becomes x-axis).
inline double Normalize3(double* a) {
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

// ---------------------------------------------------------------- 3x3 matrices

// r = M v
inline void MulMatVec3(double* r, const double* mat, const double* v) {
  r[0] = mat[0] * v[0] + mat[1] * v[1] + mat[2] * v[2];
  r[1] = mat[3] * v[0] + mat[4] * v[1] + mat[5] * v[2];
  r[2] = mat[6] * v[0] + mat[7] * v[1] + mat[8] * v[2];
}
// r = M^T v
inline void MulMatTVec3(double* r, const double* mat, const double* v) {
  r[0] = mat[0] * v[0] + mat[3] * v[1] + mat[6] * v[2];
  r[1] = mat[1] * v[0] + mat[4] * v[1] + mat[7] * v[2];
  r[2] = mat[2] * v[0] + mat[5] * v[1] + mat[8] * v[2];
}
// r = A B (3x3)
inline void MulMat3(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    }
  }
}
// r = A^T B (3x3)
inline void MulMatTMat3(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      r[3 * i + j] = a[i] * b[j] + a[3 + i] * b[3 + j] + a[6 + i] * b[6 + j];
    }
  }
}
// r = A B^T (3x3)
inline void MulMatMatT3(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      r[3 * i + j] = a[3 * i] * b[3 * j] + a[3 * i + 1] * b[3 * j + 1] +
                     a[3 * i + 2] * b[3 * j + 2];
    }
  }
}

// ---------------------------------------------------------------- quaternions

inline void SetIdentityQuat(double* q) { q[0] = 1; q[1] = q[2] = q[3] = 0; }
inline void CopyQuat(double* r, const double* q) { r[0] = q[0]; r[1] = q[1]; r[2] = q[2]; r[3] = q[3]; }
// Normalizes in place; returns the norm before (a near-zero quaternion becomes identity).
inline double NormalizeQuat(double* q) {
  double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (norm < kTiny) {
    SetIdentityQuat(q);
  } else if (std::abs(norm - 1) > kTiny) {
    double inv = 1 / norm;
    for (int i = 0; i < 4; i++) q[i] *= inv;
  }
  return norm;
}
// r = q * (0, axis): a quaternion times a pure vector, summed as MuJoCo's mju_mulQuatAxis.
inline void MulQuatAxis(double* r, const double* q, const double* axis) {
  double w = -q[1] * axis[0] - q[2] * axis[1] - q[3] * axis[2];
  double x = q[0] * axis[0] + q[2] * axis[2] - q[3] * axis[1];
  double y = q[0] * axis[1] + q[3] * axis[0] - q[1] * axis[2];
  double z = q[0] * axis[2] + q[1] * axis[1] - q[2] * axis[0];
  r[0] = w, r[1] = x, r[2] = y, r[3] = z;
}
// r = a * b (Hamilton product)
inline void MulQuat(double* r, const double* a, const double* b) {
  double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
  double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
  double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
  double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
  r[0] = w;
  r[1] = x;
  r[2] = y;
  r[3] = z;
}

// Eigen-decomposition of a symmetric 3x3 matrix by Jacobi rotations kept as a unit
// quaternion (MuJoCo's mju_eig3): eigenvalues in decreasing order, eigenvectors the
// columns of quat's rotation matrix. `normalize` renormalizes the quaternion after each
// rotation (the engine multiplies by the inverse norm, the compiler divides).
void Eig3(double eigval[3], double quat[4], const double mat[9], void (*normalize)(double* q));
// r = conj(q)
inline void NegQuat(double* r, const double* q) { r[0] = q[0]; r[1] = -q[1]; r[2] = -q[2]; r[3] = -q[3]; }
// r = q v q* (q unit)
inline void RotVecQuat(double* r, const double* v, const double* q) {
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
// Rotation matrix of a unit quaternion.
inline void QuatToMat(double* m, const double* q) {
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
// Unit quaternion of a rotation matrix.
void MatToQuat(double* q, const double* mat);
// Rotation by `angle` (radians) about the unit axis.
void AxisAngleToQuat(double* q, const double* axis, double angle);
// The rotation taking the z axis to vec's direction (MuJoCo mju_quatZ2Vec): identity for
// a vector too short, 180 degrees about x for -z.
void QuatZToVec(double* q, const double* vec);
// The rotation vector (axis * angle) of a unit quaternion, angle in [-pi, pi].
void QuatToVel(double* vel, const double* q, double dt);
// qb^-1 qa as a rotation vector: the angular displacement from qb to qa.
void SubQuat(double* res, const double* qa, const double* qb);
// q <- q * exp(vel * scale / 2): integrate a body-frame angular velocity, normalized.
void QuatIntegrate(double* q, const double* vel, double scale);

// ---------------------------------------------------------------- frames

// Compose frames: (pos, quat) = (pos1, quat1) * (pos2, quat2), the quaternion
// normalized (MuJoCo's mju_mulPose).
inline void MulPose(double* pos, double* quat, const double* pos1, const double* quat1,
                    const double* pos2, const double* quat2) {
  double p[3], q[4];
  RotVecQuat(p, pos2, quat1);
  Add3(p, p, pos1);
  MulQuat(q, quat1, quat2);
  NormalizeQuat(q);
  Copy3(pos, p);
  CopyQuat(quat, q);
}

// ---------------------------------------------------------------- spatial algebra
//
// Spatial motion vectors (omega, v) and force vectors (torque, f), expressed at a
// common point. Body inertia in "cinert" form, 10 numbers: the 3x3 rotational inertia
// about the point (xx, yy, zz, xy, xz, yz), the first mass moment m*(c - p) (3), mass.

// r = inertia * vel (a spatial force)
inline void MulInertVec(double* r, const double* i, const double* v) {
  r[0] = i[0] * v[0] + i[3] * v[1] + i[4] * v[2] - i[8] * v[4] + i[7] * v[5];
  r[1] = i[3] * v[0] + i[1] * v[1] + i[5] * v[2] + i[8] * v[3] - i[6] * v[5];
  r[2] = i[4] * v[0] + i[5] * v[1] + i[2] * v[2] - i[7] * v[3] + i[6] * v[4];
  r[3] = i[8] * v[1] - i[7] * v[2] + i[9] * v[3];
  r[4] = i[6] * v[2] - i[8] * v[0] + i[9] * v[4];
  r[5] = i[7] * v[0] - i[6] * v[1] + i[9] * v[5];
}
// r = v x m  (motion cross motion); the rotational part of the linear rows is summed
// first and the rest added after, MuJoCo's grouping (the last bit depends on it).
inline void CrossMotion(double* r, const double* v, const double* m) {
  r[0] = -v[2] * m[1] + v[1] * m[2];
  r[1] = v[2] * m[0] - v[0] * m[2];
  r[2] = -v[1] * m[0] + v[0] * m[1];
  r[3] = -v[2] * m[4] + v[1] * m[5];
  r[4] = v[2] * m[3] - v[0] * m[5];
  r[5] = -v[1] * m[3] + v[0] * m[4];
  r[3] += -v[5] * m[1] + v[4] * m[2];
  r[4] += v[5] * m[0] - v[3] * m[2];
  r[5] += -v[4] * m[0] + v[3] * m[1];
}
// r = v x* f (motion cross force), grouped as MuJoCo's: the angular rows get their
// translational terms added in a second sum.
inline void CrossForce(double* r, const double* v, const double* f) {
  r[0] = -v[2] * f[1] + v[1] * f[2];
  r[1] = v[2] * f[0] - v[0] * f[2];
  r[2] = -v[1] * f[0] + v[0] * f[1];
  r[3] = -v[2] * f[4] + v[1] * f[5];
  r[4] = v[2] * f[3] - v[0] * f[5];
  r[5] = -v[1] * f[3] + v[0] * f[4];
  r[0] += -v[5] * f[4] + v[4] * f[5];
  r[1] += v[5] * f[3] - v[3] * f[5];
  r[2] += -v[4] * f[3] + v[3] * f[4];
}
// The cinert of a body with principal inertia `inert` (3) in a frame rotated by `mat`
// (local to world), its centre of mass at `dif` from the reference point.
void InertCom(double* res, const double* inert, const double* mat, const double* dif,
              double mass);
// The spatial vector (motion, or force if `is_force`) `vec` given at `oldpos`, moved to
// `newpos` and, if `rot_new_to_old` is not null, rotated into the new frame.
void TransformSpatial(double* res, const double* vec, bool is_force, const double* newpos,
                      const double* oldpos, const double* rot_new_to_old);

}  // namespace simlab::math

#endif  // SIMLAB_MATH_MATH_H_
