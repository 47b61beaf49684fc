// Orientation alternatives, frames, and principal axes.
#include "compiler/orientation.h"

#include <cmath>
#include <numbers>

#include "math/elementary.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

double NormalizeVec(double* v, int n) {
  double sq = 0;
  for (int i = 0; i < n; i++) sq += v[i] * v[i];
  if (sq < kEps) return 0;
  double norm = std::sqrt(sq);
  if (std::abs(norm - 1) > kEps) {
    for (int i = 0; i < n; i++) v[i] /= norm;
  }
  return norm;
}

void OffCenter(double res[6], double mass, const double d[3]) {
  res[0] = mass * (d[1] * d[1] + d[2] * d[2]);
  res[1] = mass * (d[0] * d[0] + d[2] * d[2]);
  res[2] = mass * (d[0] * d[0] + d[1] * d[1]);
  res[3] = -mass * d[0] * d[1];
  res[4] = -mass * d[0] * d[2];
  res[5] = -mass * d[1] * d[2];
}

void ZAxisQuat(double quat[4], const double vec[3]) {
  // The axis z x vec (the x axis when vec is along z), the angle between them; vec as
  // given, unnormalized, as MuJoCo's compiler (mjuu_z2quat) computes it.
  const double z[3] = {0, 0, 1};
  math::Cross3(quat + 1, z, vec);
  double s = NormalizeVec(quat + 1, 3);
  if (s < 1e-10) {
    quat[1] = 1;
    quat[2] = quat[3] = 0;
  }
  double angle = math::Atan2(s, vec[2]);
  quat[0] = math::Cos(angle / 2);
  for (int k = 1; k < 4; k++) quat[k] *= math::Sin(angle / 2);
}

// ---------------------------------------------------------------- alternatives

namespace {

// axisangle: rotation about a (normalized) axis.
const char* FromAxisAngle(double* quat, bool degree, const std::array<double, 4>& aa) {
  double axis[3] = {aa[0], aa[1], aa[2]};
  double angle = degree ? aa[3] / 180.0 * kPi : aa[3];
  if (NormalizeVec(axis, 3) < kEps) return "axisangle too small";
  quat[0] = math::Cos(angle / 2);
  for (int i = 0; i < 3; i++) quat[i + 1] = math::Sin(angle / 2) * axis[i];
  return nullptr;
}

// xyaxes: x axis, and y made orthogonal to it; z = x cross y.
const char* FromXYAxes(double* quat, const std::array<double, 6>& xy) {
  double x[3] = {xy[0], xy[1], xy[2]}, y[3] = {xy[3], xy[4], xy[5]}, z[3];
  if (NormalizeVec(x, 3) < kEps) return "xaxis too small";
  double d = math::Dot3(x, y);
  for (int i = 0; i < 3; i++) y[i] -= x[i] * d;
  if (NormalizeVec(y, 3) < kEps) return "yaxis too small";
  math::Cross3(z, x, y);
  if (NormalizeVec(z, 3) < kEps) return "cross(xaxis, yaxis) too small";
  double mat[9] = {x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]};
  math::MatToQuat(quat, mat);
  return nullptr;
}

// zaxis: the minimal rotation taking z to the given direction.
const char* FromZAxis(double* quat, const std::array<double, 3>& za) {
  double z[3] = {za[0], za[1], za[2]};
  if (NormalizeVec(z, 3) < kEps) return "zaxis too small";
  ZAxisQuat(quat, z);
  return nullptr;
}

// euler: three rotations; lowercase axes move with the body (post-multiply),
// uppercase axes are fixed (pre-multiply).
const char* FromEuler(double* quat, bool degree, const std::string& seq,
                      const std::array<double, 3>& euler) {
  math::SetIdentityQuat(quat);
  for (int i = 0; i < 3; i++) {
    double angle = degree ? euler[i] / 180.0 * kPi : euler[i];
    double rot[4] = {math::Cos(angle / 2), 0, 0, 0}, tmp[4];
    char axis = seq[i];
    int k = (axis == 'x' || axis == 'X') ? 1 : (axis == 'y' || axis == 'Y') ? 2 : 3;
    rot[k] = math::Sin(angle / 2);
    if (axis == 'x' || axis == 'y' || axis == 'z') {
      math::MulQuat(tmp, quat, rot);
    } else {
      math::MulQuat(tmp, rot, quat);
    }
    NormalizeVec(tmp, 4);  // (each product normalized, as MuJoCo's compiler does)
    math::CopyQuat(quat, tmp);
  }
  NormalizeVec(quat, 4);
  return nullptr;
}

}  // namespace

const char* ResolveOrientation(double* quat, bool degree, const std::string& eulerseq,
                               const mjcf::Orientation& alt) {
  switch (alt.kind) {
    case mjcf::OrientKind::kQuat: return nullptr;
    case mjcf::OrientKind::kAxisAngle: return FromAxisAngle(quat, degree, alt.axisangle);
    case mjcf::OrientKind::kXYAxes: return FromXYAxes(quat, alt.xyaxes);
    case mjcf::OrientKind::kZAxis: return FromZAxis(quat, alt.zaxis);
    case mjcf::OrientKind::kEuler: return FromEuler(quat, degree, eulerseq, alt.euler);
  }
  return nullptr;
}

// ---------------------------------------------------------------- frames

// As MuJoCo's compiler accumulates frames (its user-side mjuu_frameaccum), to the bit:
// the position rotated through the frame's rotation matrix, the product of quaternions
// normalized.
void AccumulateChild(const double fpos[3], const double fquat[4], double pos[3], double quat[4]) {
  double mat[9], rotated[3], q[4];
  math::QuatToMat(mat, fquat);
  math::MulMatVec3(rotated, mat, pos);
  for (int k = 0; k < 3; k++) pos[k] = fpos[k] + rotated[k];
  math::MulQuat(q, fquat, quat);
  NormalizeVec(q, 4);
  math::CopyQuat(quat, q);
}

void FramePose(const mjcf::FrameSpec& frame, const mjcf::CompilerSpec& model, double pos[3],
               double quat[4]) {
  // This frame's own pose, under the settings of the model it was written in.
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(frame.compiler, model);
  math::Copy3(pos, frame.pos.data());
  math::CopyQuat(quat, frame.quat.data());
  if (const char* err = ResolveOrientation(quat, c.degree, c.eulerseq, frame.alt)) {
    mjcf::ThrowAt(frame.src, std::string("orientation error: ") + err);
  }

  // Composed with the enclosing frames.
  if (frame.parent) {
    double ppos[3], pquat[4];
    FramePose(*frame.parent, model, ppos, pquat);
    AccumulateChild(ppos, pquat, pos, quat);
  }
  NormalizeVec(quat, 4);
}

// ---------------------------------------------------------------- inertia

void GlobalInertia(double global[6], const double local[3], const double quat[4]) {
  double r[9];
  math::QuatToMat(r, quat);
  // R diag(local) R^T, upper triangle.
  // (each product grouped as MuJoCo's compiler groups it)
  auto entry = [&](int i, int j) {
    return r[3 * i] * (r[3 * j] * local[0]) + r[3 * i + 1] * (r[3 * j + 1] * local[1]) +
           r[3 * i + 2] * (r[3 * j + 2] * local[2]);
  };
  global[0] = entry(0, 0);
  global[1] = entry(1, 1);
  global[2] = entry(2, 2);
  global[3] = entry(0, 1);
  global[4] = entry(0, 2);
  global[5] = entry(1, 2);
}

void Eig3(double eigval[3], double quat[4], const double mat[9]) {
  // The compiler's variant: quaternions normalized by division, as MuJoCo's compiler.
  math::Eig3(eigval, quat, mat, [](double* q) { NormalizeVec(q, 4); });
}

const char* FullInertia(double quat[4], double inertia[3], const double full[6]) {
  double mat[9] = {full[0], full[3], full[4], full[3], full[1], full[5],
                   full[4], full[5], full[2]};
  double eigval[3], q[4];
  Eig3(eigval, q, mat);
  if (eigval[2] < kEps) return "inertia must have positive eigenvalues";
  math::CopyQuat(quat, q);
  for (int i = 0; i < 3; i++) inertia[i] = eigval[i];
  return nullptr;
}

}  // namespace simlab::compiler
