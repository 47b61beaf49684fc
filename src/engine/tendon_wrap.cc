// Tendon wrapping geometry (MuJoCo mju_wrap and its 2D helpers).
//
// Both end points are expressed in the geom's frame and projected onto a plane: for a
// sphere the plane through the centre and both points, for a cylinder the plane normal
// to its axis. In that plane the obstacle is a circle, and the path either leaves it
// alone or runs along the two tangent lines from the end points and the arc between
// the tangent points. A cylinder then lifts the tangent points along its axis in
// proportion to the path length, so the path becomes a helix.
#include "engine/tendon_wrap.h"

#include <cmath>
#include <numbers>

#include "math/elementary.h"
#include "math/math.h"
#include "simlab/model.h"

namespace simlab {

namespace {

using math::Cross3;
using math::Dot3;

double Dot2(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1]; }

// Normalizes a 2D vector in place (a near-zero one becomes the x axis).
void Normalize2(double* v) {
  double norm = std::sqrt(Dot2(v, v));
  if (norm < kMinVal) {
    v[0] = 1;
    v[1] = 0;
  } else {
    double inv = 1 / norm;
    v[0] *= inv;
    v[1] *= inv;
  }
}

// Do the 2D segments a0-a1 and b0-b1 cross?
bool SegmentsCross(const double* a0, const double* a1, const double* b0, const double* b1) {
  double det = (b1[1] - b0[1]) * (a1[0] - a0[0]) - (b1[0] - b0[0]) * (a1[1] - a0[1]);
  if (std::abs(det) < kMinVal) return false;
  double ta = ((b1[0] - b0[0]) * (a0[1] - b0[1]) - (b1[1] - b0[1]) * (a0[0] - b0[0])) / det;
  double tb = ((a1[0] - a0[0]) * (a0[1] - b0[1]) - (a1[1] - a0[1]) * (a0[0] - b0[0])) / det;
  return ta >= 0 && ta <= 1 && tb >= 0 && tb <= 1;
}

// Length of the arc of the circle from p0 to p1; `long_way` picks the direction
// (solution 1 turns one way, solution 0 the other).
double ArcLength(const double* p0, const double* p1, bool long_way, double radius) {
  double u0[2] = {p0[0], p0[1]}, u1[2] = {p1[0], p1[1]};
  Normalize2(u0);
  Normalize2(u1);
  double angle = math::Acos(Dot2(u0, u1));
  double turn = p0[1] * p1[0] - p0[0] * p1[1];
  if ((turn > 0 && long_way) || (turn < 0 && !long_way)) angle = 2 * std::numbers::pi - angle;
  return radius * angle;
}

// Tangent points of the two candidate paths from end point e (2D) to the circle:
// sign +1 and -1 turn opposite ways. `first` tells which end of the path e is.
void TangentPoint(double* out, const double* e, double sq, double root, double radius,
                  double sign, bool first) {
  double r2 = radius * radius;
  double s = first ? sign : -sign;
  out[0] = (e[0] * r2 + s * radius * e[1] * root) / sq;
  out[1] = (e[1] * r2 - s * radius * e[0] * root) / sq;
}

// Wrap around a circle at the origin, seen from outside. end = (x0, y0, x1, y1).
// Returns the arc length and the tangent points in pnt, or -1 if the straight segment
// is fine (misses the circle, or passes on the side point's side).
double WrapCircle(double pnt[4], const double end[4], const double* side, double radius) {
  double sq0 = Dot2(end, end), sq1 = Dot2(end + 2, end + 2), r2 = radius * radius;
  if (sq0 < r2 || sq1 < r2 || radius < kMinVal) return -1;
  double dif[2] = {end[2] - end[0], end[3] - end[1]};
  double dd = Dot2(dif, dif);
  if (dd < kMinVal) return -1;

  // Closest point of the segment to the centre: no contact, no wrap.
  double a = -(dif[0] * end[0] + dif[1] * end[1]) / dd;
  a = a < 0 ? 0 : (a > 1 ? 1 : a);
  double closest[2] = {a * dif[0] + end[0], a * dif[1] + end[1]};
  if (Dot2(closest, closest) > r2 && (!side || Dot2(side, closest) >= 0)) return -1;

  // The two candidate paths; prefer the one toward the side point, else the shorter
  // one, and never one whose tangent lines cross.
  double root0 = std::sqrt(sq0 - r2), root1 = std::sqrt(sq1 - r2);
  double sol[2][4], score[2];
  for (int i = 0; i < 2; i++) {
    double sign = i == 0 ? 1 : -1;
    TangentPoint(sol[i], end, sq0, root0, radius, sign, true);
    TangentPoint(sol[i] + 2, end + 2, sq1, root1, radius, sign, false);
    double t[2];
    if (side) {
      t[0] = sol[i][0] + sol[i][2];
      t[1] = sol[i][1] + sol[i][3];
      Normalize2(t);
      score[i] = Dot2(t, side);
    } else {
      t[0] = sol[i][0] - sol[i][2];
      t[1] = sol[i][1] - sol[i][3];
      score[i] = -Dot2(t, t);
    }
    if (SegmentsCross(end, sol[i], end + 2, sol[i] + 2)) score[i] = -10000;
  }
  int best = score[0] > score[1] ? 0 : 1;
  for (int k = 0; k < 4; k++) pnt[k] = sol[best][k];
  if (SegmentsCross(end, pnt, end + 2, pnt + 2)) return -1;
  return ArcLength(sol[best], sol[best] + 2, best == 1, radius);
}

// Residual of the inside-wrap equation asin(A z) + asin(B z) - 2 asin(z) + G.
double InsideResidual(double z, double A, double B, double G) {
  return math::Asin(A * z) + math::Asin(B * z) - 2 * math::Asin(z) + G;
}

// Wrap through a circle whose side point lies inside: the path touches the circle at
// one point (pnt holds it twice). Returns 0, or -1 when there is no wrap.
double WrapInside(double pnt[4], const double end[4], double radius) {
  constexpr int kMaxIter = 20;
  constexpr double kZInit = 1 - 1e-7;
  constexpr double kTolerance = 1e-6;
  double len0 = std::sqrt(Dot2(end, end)), len1 = std::sqrt(Dot2(end + 2, end + 2));
  double dif[2] = {end[2] - end[0], end[3] - end[1]};
  double dd = Dot2(dif, dif);
  if (len0 <= radius || len1 <= radius || radius < kMinVal || len0 < kMinVal || len1 < kMinVal) {
    return -1;
  }

  // A segment through the circle does not wrap.
  if (dd > kMinVal) {
    double a = -(dif[0] * end[0] + dif[1] * end[1]) / dd;
    if (a > 0 && a < 1) {
      double p[2] = {end[0] + a * dif[0], end[1] + a * dif[1]};
      if (std::sqrt(Dot2(p, p)) <= radius) return -1;
    }
  }

  // Fallback answer: the direction of the ends' midpoint, on the circle.
  pnt[0] = 0.5 * (end[0] + end[2]);
  pnt[1] = 0.5 * (end[1] + end[3]);
  Normalize2(pnt);
  pnt[0] *= radius;
  pnt[1] *= radius;
  pnt[2] = pnt[0];
  pnt[3] = pnt[1];

  // Solve for z = sin of the contact angle by Newton's method from just below 1.
  double A = radius / len0, B = radius / len1;
  double cos_g = (len0 * len0 + len1 * len1 - dd) / (2 * len0 * len1);
  if (cos_g < -1 + kMinVal) return -1;
  if (cos_g > 1 - kMinVal) return 0;
  double G = math::Acos(cos_g);
  double z = kZInit;
  double f = InsideResidual(z, A, B, G);
  if (f > 0) return 0;
  int iter = 0;
  for (; iter < kMaxIter && std::abs(f) > kTolerance; iter++) {
    double df = A / std::max(kMinVal, std::sqrt(1 - z * z * A * A)) +
                B / std::max(kMinVal, std::sqrt(1 - z * z * B * B)) -
                2 / std::max(kMinVal, std::sqrt(1 - z * z));
    if (df > -kMinVal) return 0;
    double next = z - f / df;
    if (next > z) return 0;
    z = next;
    f = InsideResidual(z, A, B, G);
    if (f > kTolerance) return 0;
  }
  if (iter >= kMaxIter) return 0;

  // Rotate the unit direction of one end by the contact angle.
  double dir[2], angle;
  if (end[0] * end[3] - end[1] * end[2] > 0) {
    dir[0] = end[0];
    dir[1] = end[1];
    angle = math::Asin(z) - math::Asin(A * z);
  } else {
    dir[0] = end[2];
    dir[1] = end[3];
    angle = math::Asin(z) - math::Asin(B * z);
  }
  Normalize2(dir);
  pnt[0] = radius * (math::Cos(angle) * dir[0] - math::Sin(angle) * dir[1]);
  pnt[1] = radius * (math::Sin(angle) * dir[0] + math::Cos(angle) * dir[1]);
  pnt[2] = pnt[0];
  pnt[3] = pnt[1];
  return 0;
}

// The wrapping plane's axes in the geom frame: the plane of the centre and both points
// for a sphere (a fixed choice when they are collinear), the xy plane for a cylinder.
void WrapPlane(double axis0[3], double axis1[3], const double* p0, const double* p1, int type) {
  if (type != kWrapSphere) {
    axis0[0] = 1, axis0[1] = 0, axis0[2] = 0;
    axis1[0] = 0, axis1[1] = 1, axis1[2] = 0;
    return;
  }
  math::Copy3(axis0, p0);
  math::Normalize3(axis0);
  double normal[3];
  Cross3(normal, p0, p1);
  if (math::Normalize3(normal) < kMinVal) {
    // Collinear: any normal; zero the largest component of (1, 1, 1) first.
    int big = 0;
    double ax = std::abs(axis0[0]), ay = std::abs(axis0[1]), az = std::abs(axis0[2]);
    if (ay > ax && ay > az) big = 1;
    if (az > ax && az > ay) big = 2;
    axis1[0] = axis1[1] = axis1[2] = 1;
    axis1[big] = 0;
    Cross3(normal, axis0, axis1);
    math::Normalize3(normal);
  }
  Cross3(axis1, normal, axis0);
  math::Normalize3(axis1);
}

// A world point in the geom frame.
void ToLocal(double* local, const double* point, const double* xpos, const double* xmat) {
  double dif[3];
  math::Sub3(dif, point, xpos);
  math::MulMatTVec3(local, xmat, dif);
}

}  // namespace

double WrapAroundGeom(double wpnt[6], const double x0[3], const double x1[3],
                      const double xpos[3], const double xmat[9], double radius, int type,
                      const double* side) {
  double p[2][3];
  ToLocal(p[0], x0, xpos, xmat);
  ToLocal(p[1], x1, xpos, xmat);
  if (math::Norm3(p[0]) < kMinVal || math::Norm3(p[1]) < kMinVal) return -1;

  // Project both points (and the side point, scaled onto the circle) into the plane.
  double axis[2][3];
  WrapPlane(axis[0], axis[1], p[0], p[1], type);
  double end[4] = {Dot3(p[0], axis[0]), Dot3(p[0], axis[1]), Dot3(p[1], axis[0]),
                   Dot3(p[1], axis[1])};
  double s[3] = {0, 0, 0}, side2d[2] = {0, 0};
  if (side) {
    ToLocal(s, side, xpos, xmat);
    side2d[0] = Dot3(s, axis[0]);
    side2d[1] = Dot3(s, axis[1]);
    Normalize2(side2d);
    side2d[0] *= radius;
    side2d[1] *= radius;
  }

  // Wrap in 2D: through the circle for an inside side point, around it otherwise.
  double pnt[4];
  double length = (side && math::Norm3(s) < radius)
                      ? WrapInside(pnt, end, radius)
                      : WrapCircle(pnt, end, side ? side2d : nullptr, radius);
  if (length < 0) return -1;

  // Back to 3D in the geom frame.
  double res[6];
  for (int i = 0; i < 2; i++) {
    for (int k = 0; k < 3; k++) {
      res[3 * i + k] = axis[0][k] * pnt[2 * i] + axis[1][k] * pnt[2 * i + 1];
    }
  }

  // Cylinder: heights along the axis in proportion to the path length (a helix).
  if (type == kWrapCylinder) {
    double dx0 = p[0][0] - res[0], dy0 = p[0][1] - res[1];
    double dx1 = p[1][0] - res[3], dy1 = p[1][1] - res[4];
    double l0 = std::sqrt(dx0 * dx0 + dy0 * dy0), l1 = std::sqrt(dx1 * dx1 + dy1 * dy1);
    double rise = p[1][2] - p[0][2], total = l0 + length + l1;
    res[2] = p[0][2] + rise * l0 / total;
    res[5] = p[0][2] + rise * (l0 + length) / total;
    double height = std::abs(res[5] - res[2]);
    length = std::sqrt(length * length + height * height);
  }

  // To the world frame.
  for (int i = 0; i < 2; i++) {
    math::MulMatVec3(wpnt + 3 * i, xmat, res + 3 * i);
    for (int k = 0; k < 3; k++) wpnt[3 * i + k] += xpos[k];
  }
  return length;
}

}  // namespace simlab
