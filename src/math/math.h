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
double Normalize3(double* a);

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
void MulMat3(double* r, const double* a, const double* b);
// r = A^T B (3x3)
void MulMatTMat3(double* r, const double* a, const double* b);
// r = A B^T (3x3)
void MulMatMatT3(double* r, const double* a, const double* b);

// ---------------------------------------------------------------- quaternions

inline void SetIdentityQuat(double* q) { q[0] = 1; q[1] = q[2] = q[3] = 0; }
inline void CopyQuat(double* r, const double* q) { r[0] = q[0]; r[1] = q[1]; r[2] = q[2]; r[3] = q[3]; }
// Normalizes in place; returns the norm before (a near-zero quaternion becomes identity).
double NormalizeQuat(double* q);
// r = a * b (Hamilton product)
void MulQuat(double* r, const double* a, const double* b);

// Eigen-decomposition of a symmetric 3x3 matrix by Jacobi rotations kept as a unit
// quaternion (MuJoCo's mju_eig3): eigenvalues in decreasing order, eigenvectors the
// columns of quat's rotation matrix. `normalize` renormalizes the quaternion after each
// rotation (the engine multiplies by the inverse norm, the compiler divides).
void Eig3(double eigval[3], double quat[4], const double mat[9], void (*normalize)(double* q));
// r = conj(q)
inline void NegQuat(double* r, const double* q) { r[0] = q[0]; r[1] = -q[1]; r[2] = -q[2]; r[3] = -q[3]; }
// r = q v q* (q unit)
void RotVecQuat(double* r, const double* v, const double* q);
// Rotation matrix of a unit quaternion.
void QuatToMat(double* mat, const double* q);
// Unit quaternion of a rotation matrix.
void MatToQuat(double* q, const double* mat);
// Rotation by `angle` (radians) about the unit axis.
void AxisAngleToQuat(double* q, const double* axis, double angle);
// The rotation vector (axis * angle) of a unit quaternion, angle in [-pi, pi].
void QuatToVel(double* vel, const double* q, double dt);
// qb^-1 qa as a rotation vector: the angular displacement from qb to qa.
void SubQuat(double* res, const double* qa, const double* qb);
// q <- q * exp(vel * scale / 2): integrate a body-frame angular velocity, normalized.
void QuatIntegrate(double* q, const double* vel, double scale);
// Minimal rotation that takes vector a to vector b (both nonzero).
void QuatZ2Vec(double* q, const double* vec);

// ---------------------------------------------------------------- frames

// Compose frames: (pos, quat) = (pos1, quat1) * (pos2, quat2).
void MulPose(double* pos, double* quat, const double* pos1, const double* quat1,
             const double* pos2, const double* quat2);

// ---------------------------------------------------------------- spatial algebra
//
// Spatial motion vectors (omega, v) and force vectors (torque, f), expressed at a
// common point. Body inertia in "cinert" form, 10 numbers: the 3x3 rotational inertia
// about the point (xx, yy, zz, xy, xz, yz), the first mass moment m*(c - p) (3), mass.

// r = inertia * vel (a spatial force)
void MulInertVec(double* r, const double* inert, const double* vel);
// r = v x m  (motion cross motion)
void CrossMotion(double* r, const double* v, const double* m);
// r = v x* f (motion cross force)
void CrossForce(double* r, const double* v, const double* f);
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
