// Analytic narrow phase: planes, spheres, capsules and cylinders (MuJoCo's
// engine_collision_primitive.c). Each pair is reduced to a few point tests: a capsule is
// a segment with a radius, so capsule pairs find the nearest points of their segments
// and test two spheres there; a plane tests the lowest points of the other geom.
// Contacts keep MuJoCo's count, order and arithmetic, so positions, distances and
// normals agree to the last bits.
#include <algorithm>
#include <cmath>

#include "engine/collision.h"
#include "engine/collision_geom.h"
#include "math/math.h"

namespace simlab {

namespace {

using math::AddScaled3;
using math::Cross3;
using math::Dot3;
using math::Normalize3;
using math::Sub3;

// ---------------------------------------------------------------- point tests

// Signed height of `point` above a plane; writes the plane's normal.
double HeightAbovePlane(const GeomPose& plane, const double* point, double* normal) {
  double offset[3];
  ZAxisOf(plane, normal);
  Sub3(offset, point, plane.pos);
  return Dot3(offset, normal);
}

// A plane (given by its pose) against a sphere at `center` with `radius`: the contact
// sits halfway between the plane and the sphere's lowest point.
int PlaneSpherePoint(Contact* con, double margin, const GeomPose& plane,
                     const double* center, double radius) {
  double normal[3];
  double height = HeightAbovePlane(plane, center, normal);
  if (height > margin + radius) return 0;

  SetContactNormal(con[0], normal);
  con[0].dist = height - radius;
  double shift = -con[0].dist / 2 - radius;
  for (int i = 0; i < 3; i++) con[0].pos[i] = center[i] + normal[i] * shift;
  return 1;
}

// Two spheres (centres c1, c2). Concentric spheres take the normal from the cross
// product of the geoms' z axes (mat1, mat2), or the x axis when those are parallel.
int SphereSpherePoints(Contact* con, double margin, const double* c1, const double* mat1,
                       double r1, const double* c2, const double* mat2, double r2) {
  double apart[3];
  Sub3(apart, c1, c2);
  double dist_sqr = Dot3(apart, apart);
  double reach = margin + r1 + r2;
  if (dist_sqr > reach * reach) return 0;

  Contact& c = con[0];
  c.dist = std::sqrt(dist_sqr) - r1 - r2;
  double normal[3];
  Sub3(normal, c2, c1);
  if (Normalize3(normal) < kMinVal) {
    double z1[3] = {mat1[2], mat1[5], mat1[8]};
    double z2[3] = {mat2[2], mat2[5], mat2[8]};
    Cross3(normal, z1, z2);
    Normalize3(normal);
  }
  SetContactNormal(c, normal);
  double along = r1 + c.dist / 2;
  for (int i = 0; i < 3; i++) c.pos[i] = normal[i] * along + c1[i];
  return 1;
}

// A sphere against the segment of a capsule (centre, unit axis, half-length): the
// nearest point of the segment stands in for the capsule.
int SphereSegment(Contact* con, double margin, const double* center, const double* mat1,
                  double radius, const GeomPose& capsule) {
  double axis[3], offset[3], nearest[3];
  ZAxisOf(capsule, axis);
  double half = capsule.size[1];
  Sub3(offset, center, capsule.pos);
  double t = std::clamp(Dot3(axis, offset), -half, half);
  for (int i = 0; i < 3; i++) nearest[i] = axis[i] * t + capsule.pos[i];
  return SphereSpherePoints(con, margin, center, mat1, radius, nearest, capsule.mat,
                            capsule.size[0]);
}

// ---------------------------------------------------------------- cylinder helpers

// The rim point of a cylinder's disk nearest a plane: the radius-long vector from the
// disk's centre, in the plane of the disk, pointing most against the plane normal.
// `axis` points towards the plane (axis . normal = prjaxis <= 0).
void RimTowardsPlane(const GeomPose& cyl, const double* normal, const double* axis,
                     double prjaxis, double* rim) {
  double radius = cyl.size[0];
  for (int i = 0; i < 3; i++) rim[i] = axis[i] * prjaxis - normal[i];
  double len_sqr = Dot3(rim, rim);
  if (len_sqr >= kMinVal * kMinVal) {
    double scale = radius / std::sqrt(len_sqr);
    for (int i = 0; i < 3; i++) rim[i] *= scale;
  } else {
    // Disk parallel to the plane: any rim point, the cylinder's x axis.
    rim[0] = cyl.mat[0] * radius;
    rim[1] = cyl.mat[3] * radius;
    rim[2] = cyl.mat[6] * radius;
  }
}

// The two extra points of a plane-cylinder contact: on the near disk, 120 degrees to
// either side of the lowest rim point.
int CylinderSidePoints(Contact* con, const double* normal, const GeomPose& cyl,
                       const double* rim, const double* axis_scaled, double dist) {
  double side[3];
  Cross3(side, rim, axis_scaled);
  Normalize3(side);
  double side_len = cyl.size[0] * std::sqrt(3.0) / 2;
  for (int i = 0; i < 3; i++) side[i] *= side_len;

  for (int k = 0; k < 2; k++) {
    double sign = k == 0 ? 1 : -1;
    double point[3];
    for (int i = 0; i < 3; i++) {
      point[i] = cyl.pos[i] + sign * side[i];
      point[i] += axis_scaled[i];
      point[i] += rim[i] * -0.5;
    }
    PlaneContactAt(con[k], normal, point, dist);
  }
  return 2;
}

// A sphere over one cap of a cylinder: the cap is a plane facing out of the cylinder
// (on the side of the sphere's projection x), and the normal is turned to point from
// the sphere to the cylinder.
int SphereCylinderCap(Contact* con, double margin, const GeomPose& sphere,
                      const GeomPose& cyl, const double* axis, double x) {
  double sign = x > 0 ? 1 : -1;
  double cap_pos[3], cap_mat[9];
  for (int i = 0; i < 3; i++) cap_pos[i] = cyl.pos[i] + axis[i] * (sign * cyl.size[1]);
  // The bottom cap flips the x and z axes (columns 0 and 2).
  for (int i = 0; i < 9; i++) cap_mat[i] = i % 3 == 1 ? cyl.mat[i] : sign * cyl.mat[i];
  GeomPose cap = {cap_pos, cap_mat, cyl.size};
  int n = PlaneSpherePoint(con, margin, cap, sphere.pos, sphere.size[0]);
  if (n) {
    for (int i = 0; i < 3; i++) con[0].frame[i] = -con[0].frame[i];
  }
  return n;
}

// ---------------------------------------------------------------- capsule helpers

// Parallel capsule segments: test each end of one segment against the nearest point
// of the other, stopping once two contacts are found (MuJoCo's order: ends of the
// first capsule, then ends of the second).
int ParallelSegments(Contact* con, double margin, const GeomPose& c1, const GeomPose& c2,
                     const double* axis1, const double* axis2, double ma, double mb, double mc,
                     double u, double v) {
  int n = 0;
  double p1[3], p2[3];
  // Ends of capsule 1 (x1 = +1, then -1).
  for (int k = 0; k < 2; k++) {
    double sign = k == 0 ? 1 : -1;
    for (int i = 0; i < 3; i++) p1[i] = c1.pos[i] + sign * axis1[i];
    double x2 = std::clamp((v - sign * mb) / mc, -1.0, 1.0);
    for (int i = 0; i < 3; i++) p2[i] = axis2[i] * x2 + c2.pos[i];
    n += SphereSpherePoints(con + n, margin, p1, c1.mat, c1.size[0], p2, c2.mat, c2.size[0]);
  }
  // Ends of capsule 2 (x2 = +1, then -1), while fewer than two contacts.
  for (int k = 0; k < 2 && n < 2; k++) {
    double sign = k == 0 ? 1 : -1;
    for (int i = 0; i < 3; i++) p2[i] = c2.pos[i] + sign * axis2[i];
    double x1 = std::clamp((u - sign * mb) / ma, -1.0, 1.0);
    for (int i = 0; i < 3; i++) p1[i] = axis1[i] * x1 + c1.pos[i];
    n += SphereSpherePoints(con + n, margin, p1, c1.mat, c1.size[0], p2, c2.mat, c2.size[0]);
  }
  return n;
}

}  // namespace

// ---------------------------------------------------------------- plane pairs

int CollidePlaneSphere(const Model& m, const Data& d, Contact* con, int g1, int g2,
                       double margin) {
  GeomPose sphere = PoseOf(m, d, g2);
  return PlaneSpherePoint(con, margin, PoseOf(m, d, g1), sphere.pos, sphere.size[0]);
}

// Both end spheres of the capsule against the plane; contacts carry the capsule axis
// as their first tangent.
int CollidePlaneCapsule(const Model& m, const Data& d, Contact* con, int g1, int g2,
                        double margin) {
  GeomPose plane = PoseOf(m, d, g1), capsule = PoseOf(m, d, g2);
  double axis[3], end[3];
  ZAxisOf(capsule, axis);
  int n = 0;
  for (int k = 0; k < 2; k++) {
    double sign = k == 0 ? 1 : -1;
    for (int i = 0; i < 3; i++) end[i] = capsule.pos[i] + sign * (capsule.size[1] * axis[i]);
    int found = PlaneSpherePoint(con + n, margin, plane, end, capsule.size[0]);
    if (found) math::Copy3(con[n].frame + 3, axis);
    n += found;
  }
  return n;
}

// The lowest rim point of the near disk, then the same rim point on the far disk, then
// two more rim points of the near disk (when it reaches the plane at all).
int CollidePlaneCylinder(const Model& m, const Data& d, Contact* con, int g1, int g2,
                         double margin) {
  GeomPose plane = PoseOf(m, d, g1), cyl = PoseOf(m, d, g2);
  double normal[3], axis[3], rim[3];
  double center_height = HeightAbovePlane(plane, cyl.pos, normal);
  ZAxisOf(cyl, axis);

  // Make the axis point towards the plane.
  double prjaxis = Dot3(normal, axis);
  if (prjaxis > 0) {
    for (double& a : axis) a = -a;
    prjaxis = -prjaxis;
  }
  RimTowardsPlane(cyl, normal, axis, prjaxis, rim);
  double rim_height = Dot3(rim, normal);

  // Scale the axis to the half-height.
  for (double& a : axis) a *= cyl.size[1];
  prjaxis *= cyl.size[1];

  // Near disk's lowest point; none means no contacts at all.
  double near_dist = center_height + prjaxis + rim_height;
  if (near_dist > margin) return 0;
  double point[3];
  for (int i = 0; i < 3; i++) point[i] = cyl.pos[i] + rim[i] + axis[i];
  PlaneContactAt(con[0], normal, point, near_dist);
  int n = 1;

  // Far disk's lowest point.
  double far_dist = center_height - prjaxis + rim_height;
  if (far_dist <= margin) {
    for (int i = 0; i < 3; i++) point[i] = cyl.pos[i] + rim[i] - axis[i];
    PlaneContactAt(con[n++], normal, point, far_dist);
  }

  // Two more points of the near disk, halfway up its rim towards the plane.
  double side_dist = center_height + prjaxis + -rim_height * 0.5;
  if (side_dist <= margin) n += CylinderSidePoints(con + n, normal, cyl, rim, axis, side_dist);
  return n;
}

// The box corners below the plane (within margin), at most four, in corner order.
int CollidePlaneBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                    double margin) {
  GeomPose plane = PoseOf(m, d, g1), box = PoseOf(m, d, g2);
  double normal[3];
  double center_height = HeightAbovePlane(plane, box.pos, normal);

  int n = 0;
  for (int corner = 0; corner < 8; corner++) {
    double local[3], rel[3];
    for (int k = 0; k < 3; k++) local[k] = (corner >> k) & 1 ? box.size[k] : -box.size[k];
    math::MulMatVec3(rel, box.mat, local);
    // Skip corners above the margin or on the upper half of the box.
    double below = Dot3(normal, rel);
    if (center_height + below > margin || below > 0) continue;

    double point[3];
    math::Add3(point, rel, box.pos);
    PlaneContactAt(con[n], normal, point, center_height + below);
    if (++n >= 4) break;
  }
  return n;
}

// ---------------------------------------------------------------- sphere pairs

int CollideSphereSphere(const Model& m, const Data& d, Contact* con, int g1, int g2,
                        double margin) {
  GeomPose s1 = PoseOf(m, d, g1), s2 = PoseOf(m, d, g2);
  return SphereSpherePoints(con, margin, s1.pos, s1.mat, s1.size[0], s2.pos, s2.mat,
                            s2.size[0]);
}

int CollideSphereCapsule(const Model& m, const Data& d, Contact* con, int g1, int g2,
                         double margin) {
  return SphereCapsulePoses(con, margin, PoseOf(m, d, g1), PoseOf(m, d, g2));
}

int SphereCapsulePoses(Contact* con, double margin, const GeomPose& sphere,
                       const GeomPose& capsule) {
  return SphereSegment(con, margin, sphere.pos, sphere.mat, sphere.size[0], capsule);
}

// By where the sphere's centre projects: beside the side (sphere against the nearest
// axis point, as a sphere of the cylinder's radius), over a cap (the cap as a plane),
// or beyond both (the rim point as a sphere of radius 0). A centre inside the cylinder
// goes to whichever surface is nearer.
int CollideSphereCylinder(const Model& m, const Data& d, Contact* con, int g1, int g2,
                          double margin) {
  GeomPose sphere = PoseOf(m, d, g1), cyl = PoseOf(m, d, g2);
  double radius = cyl.size[0], height = cyl.size[1];
  double axis[3], offset[3], along[3], across[3];
  ZAxisOf(cyl, axis);
  Sub3(offset, sphere.pos, cyl.pos);
  double x = Dot3(axis, offset);
  math::Scale3(along, axis, x);
  Sub3(across, offset, along);
  double across_sqr = Dot3(across, across);

  bool side = std::abs(x) < height;
  bool cap = across_sqr < radius * radius;
  if (side && cap) {
    // Centre inside: keep the nearer surface.
    if (height - std::abs(x) < radius - std::sqrt(across_sqr)) side = false;
    else cap = false;
  }

  if (side) {
    double nearest[3];
    math::Add3(nearest, along, cyl.pos);
    return SphereSpherePoints(con, margin, sphere.pos, sphere.mat, sphere.size[0], nearest,
                              cyl.mat, radius);
  }
  if (cap) return SphereCylinderCap(con, margin, sphere, cyl, axis, x);

  // Rim: the circle point nearest the sphere, as a sphere of radius 0.
  math::Scale3(across, across, radius / std::sqrt(across_sqr));
  double rim[3];
  math::Scale3(rim, axis, x > 0 ? height : -height);
  math::AddScaled3(rim, across, 1);
  math::AddScaled3(rim, cyl.pos, 1);
  return SphereSpherePoints(con, margin, sphere.pos, sphere.mat, sphere.size[0], rim, cyl.mat,
                            0);
}

// ---------------------------------------------------------------- capsule pairs

// The nearest points of the two segments, as spheres; parallel segments test their ends.
int CollideCapsuleCapsule(const Model& m, const Data& d, Contact* con, int g1, int g2,
                          double margin) {
  return CapsuleCapsulePoses(con, margin, PoseOf(m, d, g1), PoseOf(m, d, g2));
}

int CapsuleCapsulePoses(Contact* con, double margin, const GeomPose& c1, const GeomPose& c2) {
  double axis1[3], axis2[3], apart[3];
  ZAxisOf(c1, axis1);
  ZAxisOf(c2, axis2);
  math::Scale3(axis1, axis1, c1.size[1]);
  math::Scale3(axis2, axis2, c2.size[1]);
  Sub3(apart, c1.pos, c2.pos);

  // Nearest points p1 + x1 axis1, p2 + x2 axis2 solve a 2x2 system.
  double ma = Dot3(axis1, axis1);
  double mb = -Dot3(axis1, axis2);
  double mc = Dot3(axis2, axis2);
  double u = -Dot3(axis1, apart);
  double v = Dot3(axis2, apart);
  double det = ma * mc - mb * mb;
  if (std::abs(det) < kMinVal) {
    return ParallelSegments(con, margin, c1, c2, axis1, axis2, ma, mb, mc, u, v);
  }

  // Solve, then clip to the segments (clipping one end re-solves the other).
  double x1 = (mc * u - mb * v) / det;
  double x2 = (ma * v - mb * u) / det;
  if (x1 > 1) {
    x1 = 1;
    x2 = (v - mb) / mc;
  } else if (x1 < -1) {
    x1 = -1;
    x2 = (v + mb) / mc;
  }
  if (x2 > 1) {
    x2 = 1;
    x1 = std::clamp((u - mb) / ma, -1.0, 1.0);
  } else if (x2 < -1) {
    x2 = -1;
    x1 = std::clamp((u + mb) / ma, -1.0, 1.0);
  }
  double p1[3], p2[3];
  for (int i = 0; i < 3; i++) {
    p1[i] = axis1[i] * x1 + c1.pos[i];
    p2[i] = axis2[i] * x2 + c2.pos[i];
  }
  return SphereSpherePoints(con, margin, p1, c1.mat, c1.size[0], p2, c2.mat, c2.size[0]);
}

}  // namespace simlab
