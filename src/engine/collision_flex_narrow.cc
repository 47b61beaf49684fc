// Narrow phase of flex elements and vertices (MuJoCo's mjraw_SphereTriangle,
// mjraw_BoxTriangle, mjraw_CapsuleTriangle, mjc_ConvexElem with mjc_fixNormal and
// mjc_HFieldElem), in MuJoCo's arithmetic so that contacts agree to the bit.
#include <algorithm>
#include <cmath>

#include "engine/collision_flex.h"
#include "engine/collision_gjk.h"
#include "math/math.h"

namespace simlab {

namespace {

using math::Dot3;

// The sign of the area of the planar triangle p1 p2 p3: 1, -1 or 0.
double AreaSign(const double* p1, const double* p2, const double* p3) {
  double area = (p1[0] - p3[0]) * (p2[1] - p3[1]) - (p2[0] - p3[0]) * (p1[1] - p3[1]);
  return area > 0 ? 1 : (area < 0 ? -1 : 0);
}

// The point of segment u v nearest p (all planar) into res; returns its distance to p.
double NearestOnSegment(double* res, const double* p, const double* u, const double* v) {
  double uv[2] = {v[0] - u[0], v[1] - u[1]};
  double up[2] = {p[0] - u[0], p[1] - u[1]};
  double a = (uv[0] * up[0] + uv[1] * up[1]) / std::max(kMinVal, uv[0] * uv[0] + uv[1] * uv[1]);
  if (a <= 0) {
    res[0] = u[0];
    res[1] = u[1];
  } else if (a >= 1) {
    res[0] = v[0];
    res[1] = v[1];
  } else {
    res[0] = u[0] + a * uv[0];
    res[1] = u[1] + a * uv[1];
  }
  return std::sqrt((res[0] - p[0]) * (res[0] - p[0]) + (res[1] - p[1]) * (res[1] - p[1]));
}

// The point of triangle (0, a, b) (origin at its first corner) nearest the point s, from
// s's projection p on the triangle's plane (plane axes v1 along a, v2; n its normal).
void NearestOnTriangle(double* x, const double* p, const double* v1, const double* v2,
                       double len_a, const double* b) {
  double o2[2] = {0, 0};
  double a2[2] = {len_a, 0};
  double b2[2] = {Dot3(v1, b), Dot3(v2, b)};
  double p2[2] = {Dot3(v1, p), Dot3(v2, p)};
  double sign1 = AreaSign(p2, o2, a2), sign2 = AreaSign(p2, a2, b2), sign3 = AreaSign(p2, b2, o2);
  if (sign1 == sign2 && sign2 == sign3) {
    math::Copy3(x, p);
    return;
  }
  // Outside: the nearest point of the three sides.
  double near[3][2], dist[3];
  dist[0] = NearestOnSegment(near[0], p2, o2, a2);
  dist[1] = NearestOnSegment(near[1], p2, a2, b2);
  dist[2] = NearestOnSegment(near[2], p2, b2, o2);
  int best = (dist[0] < dist[1] && dist[0] < dist[2]) ? 0 : (dist[1] < dist[2] ? 1 : 2);
  for (int k = 0; k < 3; k++) x[k] = v1[k] * near[best][0];
  for (int k = 0; k < 3; k++) x[k] = x[k] + v2[k] * near[best][1];
}

// ---------------------------------------------------------------- flex shapes for GJK

// The support point of a flex element (its vertex farthest along dir, the first of
// equals) or vertex, pushed out by the rounding.
void FlexSupport(double res[3], ccd::ConvexShape* s, const double dir[3]) {
  math::Copy3(res, s->flexpoint[0]);
  double best = Dot3(res, dir);
  for (int i = 1; i < s->nflexpoint; i++) {
    double dot = Dot3(s->flexpoint[i], dir);
    if (dot > best) {
      best = dot;
      math::Copy3(res, s->flexpoint[i]);
    }
  }
  for (int k = 0; k < 3; k++) res[k] = res[k] + dir[k] * s->radius;
}

// Element e (or, with e < 0, vertex v) of flex f as a convex shape inflated by margin/2;
// its centre is the element's box centre (or the vertex).
ccd::ConvexShape FlexShape(const Model& m, const Data& d, int f, int e, int v, double margin) {
  ccd::ConvexShape s;
  s.geom = -1;
  s.type = -1;  // none of the geom types: no special cases in GJK
  s.margin = margin;
  s.model = &m;
  s.support = FlexSupport;
  s.radius = m.flex_radius[f] + 0.5 * margin;
  const double* xpos = &d.flexvert_xpos[3 * static_cast<size_t>(m.flex_vertadr[f])];
  if (e >= 0) {
    int dim = m.flex_dim[f];
    const int* vert = &m.flex_elem[m.flex_elemdataadr[f] + e * (dim + 1)];
    for (int i = 0; i <= dim && i < 4; i++) s.flexpoint[i] = xpos + 3 * vert[i];
    s.nflexpoint = std::min(dim + 1, 4);
    math::Copy3(s.pos, &d.flexelem_aabb[6 * static_cast<size_t>(m.flex_elemadr[f] + e)]);
  } else {
    s.flexpoint[0] = xpos + 3 * v;
    s.nflexpoint = 1;
    math::Copy3(s.pos, s.flexpoint[0]);
  }
  return s;
}

// ---------------------------------------------------------------- normal from a geom

// The outward normal of an ellipsoid (semi-axes size) near a point pos inside it: rays
// along the normal until it settles (mjc_ellipsoidInside). 0 when none was found.
int EllipsoidNormalInside(double* nrm, const double* pos, const double* size) {
  const double s2inv[3] = {1 / (size[0] * size[0]), 1 / (size[1] * size[1]),
                           1 / (size[2] * size[2])};
  double c = pos[0] * pos[0] * s2inv[0] + pos[1] * pos[1] * s2inv[1] +
             pos[2] * pos[2] * s2inv[2] - 1;
  if (c > 0) return 0;
  math::Normalize3(nrm);
  for (int iter = 0; iter < 30; iter++) {
    double a = nrm[0] * nrm[0] * s2inv[0] + nrm[1] * nrm[1] * s2inv[1] + nrm[2] * nrm[2] * s2inv[2];
    double b = pos[0] * nrm[0] * s2inv[0] + pos[1] * nrm[1] * s2inv[1] + pos[2] * nrm[2] * s2inv[2];
    double det = b * b - a * c;
    if (det < kMinVal || a < kMinVal) return iter > 0;
    double x = (-b + std::sqrt(det)) / a;
    if (x < 0) return iter > 0;
    double point[3], normal[3];
    for (int k = 0; k < 3; k++) point[k] = pos[k] + nrm[k] * x;
    for (int k = 0; k < 3; k++) normal[k] = point[k] * s2inv[k];
    math::Normalize3(normal);
    double dif[3];
    math::Sub3(dif, nrm, normal);
    double change = math::Norm3(dif);
    math::Copy3(nrm, normal);
    if (change < 1e-6) break;
  }
  return 1;
}

// The same for a point outside: the nearest surface point by Newton steps on the
// multiplier (mjc_ellipsoidOutside).
int EllipsoidNormalOutside(double* nrm, const double* pos, const double* size) {
  const double s2[3] = {size[0] * size[0], size[1] * size[1], size[2] * size[2]};
  const double ps2[3] = {pos[0] * pos[0] * s2[0], pos[1] * pos[1] * s2[1], pos[2] * pos[2] * s2[2]};
  double la = 0;
  for (int iter = 0; iter < 30; iter++) {
    double r[3] = {1 / (s2[0] + la), 1 / (s2[1] + la), 1 / (s2[2] + la)};
    double val = ps2[0] * r[0] * r[0] + ps2[1] * r[1] * r[1] + ps2[2] * r[2] * r[2] - 1;
    if (val < 1e-6) break;
    double deriv = -2 * (ps2[0] * r[0] * r[0] * r[0] + ps2[1] * r[1] * r[1] * r[1] +
                         ps2[2] * r[2] * r[2] * r[2]);
    if (deriv > -kMinVal) break;
    double delta = -val / deriv;
    if (delta < 1e-6) break;
    la += delta;
  }
  for (int k = 0; k < 3; k++) nrm[k] = pos[k] / (s2[k] + la);
  math::Normalize3(nrm);
  return 1;
}

// Replaces a contact's normal by the surface normal of a rounded geom g (sphere,
// capsule, ellipsoid, cylinder side) at the contact point, when it has one
// (mjc_fixNormal with one geom).
void NormalFromGeom(const Model& m, const Data& d, Contact* con, int g) {
  if (g < 0) return;
  int type = m.geom_type[g];
  if (type != kGeomSphere && type != kGeomCapsule && type != kGeomEllipsoid &&
      type != kGeomCylinder) {
    return;
  }
  const double* mat = &d.geom_xmat[9 * g];
  const double* size = &m.geom_size[3 * g];
  double dif[3], pos[3], nrm[3];
  math::Sub3(dif, con->pos, &d.geom_xpos[3 * g]);
  math::MulMatTVec3(pos, mat, dif);
  math::MulMatTVec3(nrm, mat, con->frame);
  bool processed = false;
  if (type == kGeomSphere) {
    math::Copy3(nrm, pos);
    processed = true;
  } else if (type == kGeomCapsule) {
    if (pos[2] < -size[1]) {
      nrm[2] = pos[2] + size[1];
    } else if (pos[2] > size[1]) {
      nrm[2] = pos[2] - size[1];
    } else {
      nrm[2] = 0;
    }
    nrm[0] = pos[0];
    nrm[1] = pos[1];
    processed = true;
  } else if (type == kGeomEllipsoid) {
    if (size[0] >= kMinVal && size[1] >= kMinVal && size[2] >= kMinVal) {
      double dst = pos[0] * pos[0] / (size[0] * size[0]) + pos[1] * pos[1] / (size[1] * size[1]) +
                   pos[2] * pos[2] / (size[2] * size[2]);
      processed = dst <= 1 ? EllipsoidNormalInside(nrm, pos, size)
                           : EllipsoidNormalOutside(nrm, pos, size);
    }
  } else if (std::abs(pos[2]) <= 0.95 * size[1]) {
    // cylinder: the round wall, unless the flat wall is not 4x farther
    double to_flat = std::abs(size[1] - std::abs(pos[2]));
    double to_round = std::abs(size[0] - std::sqrt(pos[0] * pos[0] + pos[1] * pos[1]));
    if (!(to_flat < 0.25 * to_round)) {
      nrm[0] = pos[0];
      nrm[1] = pos[1];
      nrm[2] = 0;
      processed = true;
    }
  }
  if (!processed) return;
  math::Normalize3(nrm);
  math::MulMatVec3(con->frame, mat, nrm);
  math::Zero3(con->frame + 3);
}

}  // namespace

// ---------------------------------------------------------------- triangles

int SphereTriangle(Contact* con, double margin, const double* s, double rs, const double* t1,
                   const double* t2, const double* t3, double rt) {
  double rbound = margin + rs + rt;
  // Triangle (O, A, B) with t1 at the origin; sphere centre S.
  double sc[3], a[3], b[3];
  math::Sub3(sc, s, t1);
  math::Sub3(a, t2, t1);
  math::Sub3(b, t3, t1);
  double n[3];
  math::Cross3(n, a, b);
  math::Normalize3(n);
  double dist_plane = Dot3(n, sc);
  if (std::abs(dist_plane) > rbound) return 0;

  // The projection of S on the plane, the plane's axes, the nearest triangle point.
  double p[3], v1[3], v2[3], x[3];
  for (int k = 0; k < 3; k++) p[k] = sc[k] + n[k] * -dist_plane;
  math::Copy3(v1, a);
  double len_a = math::Normalize3(v1);
  math::Cross3(v2, n, a);
  math::Normalize3(v2);
  NearestOnTriangle(x, p, v1, v2, len_a, b);

  double nrm[3];
  math::Sub3(nrm, x, sc);
  double dist = math::Normalize3(nrm);
  if (dist > rbound) return 0;
  con[0].dist = dist - rs - rt;
  double along = rs + con[0].dist / 2;
  for (int k = 0; k < 3; k++) con[0].pos[k] = s[k] + nrm[k] * along;
  math::Copy3(con[0].frame, nrm);
  math::Zero3(con[0].frame + 3);
  return 1;
}

int BoxTriangle(Contact* con, double margin, const double* pos, const double* mat,
                const double* size, const double* t1, const double* t2, const double* t3,
                double rt) {
  int cnt = 0;
  const double* corner_of_triangle[3] = {t1, t2, t3};

  // The triangle's corners against the box's nearest face.
  for (const double* vert : corner_of_triangle) {
    double diff[3], local[3];
    math::Sub3(diff, vert, pos);
    math::MulMatTVec3(local, mat, diff);
    int axis = 0;
    double depth = std::abs(local[0]) - size[0];
    for (int j = 1; j < 3; j++) {
      double val = std::abs(local[j]) - size[j];
      if (val > depth) {
        depth = val;
        axis = j;
      }
    }
    if (depth - rt > margin) continue;
    bool inside = true;
    for (int j = 0; j < 3 && inside; j++) inside = std::abs(local[j]) <= size[j] + margin + rt;
    if (!inside || cnt >= kMaxContactPair) continue;
    double normal_local[3] = {0, 0, 0};
    normal_local[axis] = local[axis] > 0 ? 1 : -1;
    Contact& c = con[cnt++];
    math::MulMatVec3(c.frame, mat, normal_local);
    c.dist = depth - rt;
    double offset = rt + c.dist * 0.5;
    for (int k = 0; k < 3; k++) c.pos[k] = vert[k] + c.frame[k] * -offset;
    math::Zero3(c.frame + 3);
  }

  // The box's corners against the triangle.
  for (int i = 0; i < 8 && cnt < kMaxContactPair; i++) {
    double vec[3] = {i & 1 ? size[0] : -size[0], i & 2 ? size[1] : -size[1],
                     i & 4 ? size[2] : -size[2]};
    double corner[3];
    math::MulMatVec3(corner, mat, vec);
    math::Add3(corner, corner, pos);
    cnt += SphereTriangle(con + cnt, margin, corner, 0, t1, t2, t3, rt);
  }
  return cnt;
}

int CapsuleTriangle(Contact* con, double margin, const double* pos, const double* mat,
                    const double* size, const double* t1, const double* t2, const double* t3,
                    double rt) {
  double radius = size[0], len = size[1];
  double axis[3] = {mat[2], mat[5], mat[8]};
  double p1[3], p2[3];
  for (int k = 0; k < 3; k++) p1[k] = pos[k] + axis[k] * -len;
  for (int k = 0; k < 3; k++) p2[k] = pos[k] + axis[k] * len;

  // The end spheres against the triangle.
  int cnt = SphereTriangle(con, margin, p1, radius, t1, t2, t3, rt);
  cnt += SphereTriangle(con + cnt, margin, p2, radius, t1, t2, t3, rt);

  // The triangle's corners against the inside of the segment.
  const double* corners[3] = {t1, t2, t3};
  for (const double* vert : corners) {
    if (cnt >= kMaxContactPair) break;
    double vec[3], ab[3];
    math::Sub3(vec, vert, p1);
    math::Sub3(ab, p2, p1);
    double t = Dot3(vec, ab) / (4 * len * len);
    if (t <= kMinVal || t >= 1 - kMinVal) continue;
    double closest[3];
    for (int k = 0; k < 3; k++) closest[k] = p1[k] + ab[k] * t;
    math::Sub3(vec, vert, closest);
    double dist = math::Normalize3(vec);
    if (dist > radius + rt + margin) continue;
    Contact& c = con[cnt++];
    c.dist = dist - radius - rt;
    math::Copy3(c.frame, vec);
    math::Zero3(c.frame + 3);
    for (int k = 0; k < 3; k++) c.pos[k] = closest[k] + vert[k];
    for (int k = 0; k < 3; k++) c.pos[k] = c.pos[k] + vec[k] * (radius - rt);
    for (int k = 0; k < 3; k++) c.pos[k] = c.pos[k] * 0.5;
  }
  return cnt;
}

// ---------------------------------------------------------------- convex

int ConvexElem(const Model& m, const Data& d, Contact* con, int g1, int f1, int e1, int v1,
               int f2, int e2, double margin) {
  ccd::ConvexShape s1 = g1 >= 0 ? ccd::GeomShape(m, d, g1, margin)
                                : FlexShape(m, d, f1, e1, v1, margin);
  ccd::ConvexShape s2 = FlexShape(m, d, f2, e2, -1, margin);
  int n = QueryContacts(m, &s1, &s2, con, 1, margin);
  // Against a triangle, a rounded geom's own normal.
  bool flat = (f1 >= 0 && m.flex_dim[f1] == 2) || (f2 >= 0 && m.flex_dim[f2] == 2);
  if (flat) {
    for (int i = 0; i < n; i++) NormalFromGeom(m, d, con + i, g1);
  }
  return n;
}

// ---------------------------------------------------------------- height fields

int HFieldElem(const Model& m, const Data& d, Contact* con, int g, int f, int e,
               double margin) {
  // The element in the field's frame: its vertices and its box's centre (GJK's start).
  const double* hpos = &d.geom_xpos[3 * g];
  const double* hmat = &d.geom_xmat[9 * g];
  ccd::ConvexShape elem = FlexShape(m, d, f, e, -1, margin);
  double local[4][3], dif[3];
  for (int i = 0; i < elem.nflexpoint; i++) {
    math::Sub3(dif, elem.flexpoint[i], hpos);
    math::MulMatTVec3(local[i], hmat, dif);
    elem.flexpoint[i] = local[i];
  }
  math::Sub3(dif, elem.pos, hpos);
  math::MulMatTVec3(elem.pos, hmat, dif);

  // Its box there: the vertices' only (neither radius nor margin).
  double lo[3], hi[3];
  math::Copy3(lo, local[0]);
  math::Copy3(hi, local[0]);
  for (int i = 1; i < elem.nflexpoint; i++) {
    for (int k = 0; k < 3; k++) {
      lo[k] = std::min(lo[k], local[i][k]);
      hi[k] = std::max(hi[k], local[i][k]);
    }
  }
  return CollideHFieldShape(m, d, con, g, &elem, lo, hi, margin);
}

}  // namespace simlab
