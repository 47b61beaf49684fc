// Box narrow phase: sphere-box, capsule-box and box-box (MuJoCo's
// engine_collision_box.c). All three work in the frame of a box, where the box is the
// axis-aligned region |x_i| <= size_i. Contacts keep MuJoCo's count, order and
// arithmetic, so positions, distances and normals agree to the last bits; box-box
// contacts that fall outside the boxes are removed later by the collision driver.
#include <algorithm>
#include <cmath>

#include "engine/collision.h"
#include "engine/collision_geom.h"
#include "math/math.h"

namespace simlab {

namespace {

using math::Dot3;
using math::MulMatTVec3;
using math::MulMatVec3;
using math::Normalize3;
using math::Sub3;

// ---------------------------------------------------------------- sphere : box

// Clamps v into the box [-size, size] (only the axes with a positive size).
void ClampToBox(double* v, const double* size) {
  for (int i = 0; i < 3; i++) {
    if (size[i] <= 0) continue;
    if (v[i] < -size[i]) v[i] = -size[i];
    else if (v[i] > size[i]) v[i] = size[i];
  }
}

// A sphere centre inside the box: the nearest face gives the normal (pointing into
// the box) and the depth. `local` is the centre in the box frame; writes the contact
// point (box frame) and the world normal, returns the distance of the centre to the face.
double SphereInsideBox(Contact& con, const double* local, double radius, const GeomPose& box,
                       double* point) {
  const double* size = box.size;
  double closest = (size[0] + size[1] + size[2]) * 2;
  int face = 0;
  for (int i = 0; i < 6; i++) {
    double gap = std::abs((i % 2 ? 1 : -1) * size[i / 2] - local[i / 2]);
    if (closest > gap) {
      closest = gap;
      face = i;
    }
  }
  double inward[3] = {0, 0, 0};
  inward[face / 2] = face % 2 ? -1 : 1;
  for (int i = 0; i < 3; i++) point[i] = local[i] + inward[i] * ((radius - closest) / 2);
  MulMatVec3(con.frame, box.mat, inward);
  return closest;
}

// A sphere (centre, radius; mat only for the interface) against a box.
int SphereBoxPoint(Contact* con, double margin, const double* center, double radius,
                   const GeomPose& box) {
  double rel[3], local[3], clamped[3], toward[3];
  Sub3(rel, center, box.pos);
  MulMatTVec3(local, box.mat, rel);
  math::Copy3(clamped, local);
  ClampToBox(clamped, box.size);
  Sub3(toward, clamped, local);
  double dist = Normalize3(toward);
  if (dist - radius > margin) return 0;

  Contact& c = con[0];
  double point[3];
  if (dist <= kMinVal) {
    dist = -SphereInsideBox(c, local, radius, box, point);
  } else {
    // Halfway between the box surface and the sphere's deepest point.
    double deepest[3];
    for (int i = 0; i < 3; i++) deepest[i] = local[i] + toward[i] * radius;
    for (int i = 0; i < 3; i++) point[i] = 0 + clamped[i] * 0.5 + deepest[i] * 0.5;
    MulMatVec3(c.frame, box.mat, toward);
  }
  for (int i = 3; i < 9; i++) c.frame[i] = 0;
  double world[3];
  MulMatVec3(world, box.mat, point);
  math::Add3(c.pos, world, box.pos);
  c.dist = dist - radius;
  return 1;
}

// ---------------------------------------------------------------- capsule : box
//
// The capsule's segment is compared with the box in the box frame: first the nearest
// feature of the box (a face touched by a segment end, or an edge), then, when the
// segment lies along the box, a second point further along it. Both points become
// sphere-box tests.

// What part of the box is nearest the segment.
struct SegmentBoxNearest {
  double dist_sqr;     // squared distance of the nearest pair found
  double seg_pos;      // position on the segment, in [-1, 1]
  double box_pos = 0;  // position along the nearest edge, in [-1, 1]
  // -3 / -1: segment end -1 / +1 nearest a face; 0..8: an edge, coded
  // 3 * (segment clamp: 0 low end, 1 inside, 2 high end) + (edge clamp, likewise);
  // -4: nothing found.
  int type = -4;
  int face = -1;       // for ends: the one clamped axis of the face, or -1 when inside
  int corner = 0;      // for edges: the corner (bits: axes at +size) the edge starts or ends at
  int edge = 0;        // for edges: the edge's axis
};

// The capsule segment in the box frame.
struct LocalSegment {
  double center[3];
  double axis[3];       // unit axis
  double half_axis[3];  // axis * half-length
  double half_length;
  int axis_dir;         // bits: axes along which half_axis is positive
};

// Segment ends against the box faces: an end whose clamp moves at most one
// coordinate has a face (or the inside) as its nearest box feature.
void NearestFaceToEnds(const LocalSegment& seg, const double* size, SegmentBoxNearest& best) {
  for (int end = -1; end <= 1; end += 2) {
    double point[3], clamped[3];
    for (int i = 0; i < 3; i++) point[i] = seg.center[i] + seg.half_axis[i] * end;
    math::Copy3(clamped, point);
    int moved = 0, moved_axis = -1;
    for (int j = 0; j < 3; j++) {
      if (clamped[j] < -size[j]) {
        moved++;
        moved_axis = j;
        clamped[j] = -size[j];
      } else if (clamped[j] > size[j]) {
        moved++;
        moved_axis = j;
        clamped[j] = size[j];
      }
    }
    if (moved > 1) continue;
    double gap[3];
    Sub3(gap, clamped, point);
    double dist_sqr = Dot3(gap, gap);
    if (dist_sqr < best.dist_sqr) {
      best.dist_sqr = dist_sqr;
      best.seg_pos = end;
      best.type = -2 + end;
      best.face = moved_axis;
    }
  }
}

// Clamps one parameter of the segment-edge system to [-1, 1]; returns its clamp code
// (0 low, 1 inside, 2 high).
int ClampUnit(double& x) {
  if (x > 1) {
    x = 1;
    return 2;
  }
  if (x < -1) {
    x = -1;
    return 0;
  }
  return 1;
}

// The segment against one box edge (from `start`, the edge's midpoint, along axis j):
// nearest parameters x1 (edge) and x2 (segment), both clamped to [-1, 1], and their
// clamp codes. Returns false for a segment parallel to the edge.
bool SegmentEdge(const LocalSegment& seg, const double* size, const double* start, int j,
                 double& x1, double& x2, int& s1, int& s2) {
  double dif[3];
  Sub3(dif, start, seg.center);
  double ma = size[j] * size[j];
  double mb = -size[j] * seg.half_axis[j];
  double mc = seg.half_length * seg.half_length;
  double u = -size[j] * dif[j];
  double v = Dot3(seg.half_axis, dif);
  double det = ma * mc - mb * mb;
  if (std::abs(det) < kMinVal) return false;
  double inv_det = 1 / det;
  x1 = (mc * u - mb * v) * inv_det;
  x2 = (ma * v - mb * u) * inv_det;

  // Clip the edge parameter, re-solve the segment one, then the other way round.
  s1 = s2 = 1;
  if (x1 > 1) {
    x1 = 1;
    s1 = 2;
    x2 = (v - mb) * (1 / mc);
  } else if (x1 < -1) {
    x1 = -1;
    s1 = 0;
    x2 = (v + mb) * (1 / mc);
  }
  if (x2 > 1 || x2 < -1) {
    double sign = x2 > 1 ? 1 : -1;
    s2 = ClampUnit(x2);
    x1 = (u - sign * mb) * (1 / ma);
    if (x1 > 1 || x1 < -1) s1 = ClampUnit(x1);
  }
  return true;
}

// Segment against the twelve box edges; an edge wins only when clearly nearer.
void NearestEdge(const LocalSegment& seg, const double* size, SegmentBoxNearest& best) {
  for (int j = 0; j < 3; j++) {
    for (int corner = 0; corner < 8; corner++) {
      if (corner & (1 << j)) continue;
      // The edge's midpoint: the corner with coordinate j set to zero.
      double start[3];
      for (int k = 0; k < 3; k++) start[k] = ((corner >> k) & 1 ? 1 : -1) * size[k];
      start[j] = 0;

      double x1, x2;
      int s1, s2;
      if (!SegmentEdge(seg, size, start, j, x1, x2, s1, s2)) continue;
      double gap[3];
      Sub3(gap, start, seg.center);
      math::AddScaled3(gap, seg.half_axis, -x2);
      gap[j] += size[j] * x1;
      double dist_sqr = Dot3(gap, gap);
      if (dist_sqr < best.dist_sqr - kMinVal) {
        int code = s1 * 3 + s2;
        best.dist_sqr = dist_sqr;
        best.seg_pos = x2;
        best.box_pos = x1;
        best.corner = corner + (1 << j) * (code / 6);
        best.edge = j;
        best.type = code;
      }
    }
  }
}

// The three axes: `first`, then the two others in cyclic order.
void CyclicAxes(int first, int& next, int& after) {
  next = (first + 1) % 3;
  after = (first + 2) % 3;
}

// Nearest feature a box corner: a second point along the box edge or face the segment
// lies along, or none (returns -4) when the segment points at or away from the corner.
double SecondPointAtCorner(const LocalSegment& seg, const double* size,
                           const SegmentBoxNearest& best) {
  int rel = seg.axis_dir ^ best.corner;
  if (rel == 0 || rel == 7) return -4;
  double mul = 1, toward_end = 1 - best.seg_pos, away_end = 1 + best.seg_pos;
  if (rel == 3 || rel == 5 || rel == 6) {
    mul = -1;
    rel = 7 - rel;
    toward_end = 1 + best.seg_pos;
    away_end = 1 - best.seg_pos;
  }
  int ax = rel == 1 ? 0 : rel == 2 ? 1 : 2;
  int ax1, ax2;
  CyclicAxes(ax, ax1, ax2);

  double second;
  if (seg.axis[ax] * seg.axis[ax] > 0.5) {
    // Along the box edge: stop at its other corner.
    second = toward_end;
    double e = 2 * size[ax] / std::abs(seg.half_axis[ax]);
    if (e < second) second = e;
    return second * mul;
  }
  // Across a face: stop where the segment leaves it.
  second = away_end;
  double e = 2 * size[ax1] / std::abs(seg.half_axis[ax1]);
  if (e < second) second = e;
  e = 2 * size[ax2] / std::abs(seg.half_axis[ax2]);
  if (e < second) second = e;
  return second * -mul;
}

// Nearest feature the middle of a box edge: when the segment crosses the edge (an X,
// not a T) a second point along the face it lies closest to, else none (-4).
double SecondPointAtEdge(const LocalSegment& seg, const double* size,
                         const SegmentBoxNearest& best) {
  int rel = (seg.axis_dir ^ best.corner) & (7 - (1 << best.edge));
  if (rel != 1 && rel != 2 && rel != 4) return -4;
  int ax = best.edge, ax1, ax2;
  CyclicAxes(ax, ax1, ax2);
  // ax1: the face axis the segment is less inclined to; ax2 the third axis.
  if (std::abs(seg.axis[ax1]) > std::abs(seg.axis[ax2])) ax1 = ax2;
  ax2 = 3 - ax - ax1;

  double mul, second;
  if (rel & (1 << ax2)) {
    mul = 1;
    second = 1 - best.seg_pos;
  } else {
    mul = -1;
    second = 1 + best.seg_pos;
  }
  double e = 2 * size[ax2] / std::abs(seg.half_axis[ax2]);
  if (e < second) second = e;
  bool same = ((seg.axis_dir & (1 << ax)) != 0) == ((rel & (1 << ax2)) != 0);
  double along = same ? 1 - best.box_pos : 1 + best.box_pos;
  e = size[ax] * along / std::abs(seg.half_axis[ax]);
  if (e < second) second = e;
  return second * mul;
}

// Nearest feature a face under one segment end: a second point towards the other end,
// as far as the segment stays over the box; none (-4) when the end is inside the box.
double SecondPointAtFace(const LocalSegment& seg, const double* size,
                         const SegmentBoxNearest& best) {
  if (best.face == -1) return -4;
  double mul = best.type == -3 ? 1 : -1;
  double second = 2;
  double other_end[3];
  for (int i = 0; i < 3; i++) other_end[i] = seg.center[i] + seg.half_axis[i] * -mul;
  for (int i = 0; i < 3; i++) {
    if (i == best.face) continue;
    double e = (size[i] - other_end[i]) / seg.half_axis[i] * mul;
    if (e > 0 && e < second) second = e;
    e = (-size[i] - other_end[i]) / seg.half_axis[i] * mul;
    if (e > 0 && e < second) second = e;
  }
  return second * mul;
}

// The capsule in the box frame.
LocalSegment SegmentInBox(const GeomPose& capsule, const GeomPose& box) {
  LocalSegment seg;
  double rel[3], axis[3];
  Sub3(rel, capsule.pos, box.pos);
  MulMatTVec3(seg.center, box.mat, rel);
  ZAxisOf(capsule, axis);
  MulMatTVec3(seg.axis, box.mat, axis);
  seg.half_length = capsule.size[1];
  math::Scale3(seg.half_axis, seg.axis, seg.half_length);
  seg.axis_dir = 0;
  for (int i = 0; i < 3; i++) {
    if (seg.half_axis[i] > 0) seg.axis_dir += 1 << i;
  }
  return seg;
}

// Sphere-box test of the capsule's sphere at segment position t.
int CapsuleSphereAt(Contact* con, double margin, const LocalSegment& seg, double t,
                    const GeomPose& capsule, const GeomPose& box) {
  double local[3], world[3];
  math::Copy3(local, seg.center);
  math::AddScaled3(local, seg.half_axis, t);
  MulMatVec3(world, box.mat, local);
  for (int i = 0; i < 3; i++) world[i] += box.pos[i];
  return SphereBoxPoint(con, margin, world, capsule.size[0], box);
}

// ---------------------------------------------------------------- box : box
//
// Separating-axis test over the 15 axes (3 face normals of each box, 9 edge-edge
// cross products) picks the axis of least penetration. A face axis clips the other
// box's nearest face against that face; an edge axis clips around the two edges. The
// work happens in a frame turned so that the reference face's normal is +z.

// A signed axis permutation that turns a box face (0..5: axis, +3 for the negative
// side) to +z: (R v)_k = sign_k * v[index_k].
struct FaceTurn {
  int index[3];
  double sign[3];
};

FaceTurn TurnForFace(int face) {
  switch (face) {
    case 0: return {{2, 1, 0}, {-1, 1, 1}};
    case 1: return {{0, 2, 1}, {1, -1, 1}};
    case 3: return {{2, 1, 0}, {1, 1, -1}};
    case 4: return {{0, 2, 1}, {1, 1, -1}};
    case 5: return {{0, 1, 2}, {-1, 1, -1}};
    default: return {{0, 1, 2}, {1, 1, 1}};
  }
}

// r = R v
void TurnVec(double* r, const FaceTurn& t, const double* v) {
  for (int k = 0; k < 3; k++) r[k] = v[t.index[k]] * t.sign[k];
}
// r = R M (rows of M permuted and signed)
void TurnRows(double* r, const FaceTurn& t, const double* mat) {
  for (int k = 0; k < 3; k++) {
    for (int c = 0; c < 3; c++) r[3 * k + c] = mat[3 * t.index[k] + c] * t.sign[k];
  }
}
// r = R M^T
void TurnColumns(double* r, const FaceTurn& t, const double* mat) {
  for (int k = 0; k < 3; k++) {
    for (int c = 0; c < 3; c++) r[3 * k + c] = mat[3 * c + t.index[k]] * t.sign[k];
  }
}
// r = M R^T: back from the turned frame to the frame of M.
void UnturnMat(double* r, const double* mat, const FaceTurn& t) {
  for (int row = 0; row < 3; row++) {
    for (int k = 0; k < 3; k++) r[3 * row + k] = mat[3 * row + t.index[k]] * t.sign[k];
  }
}
// |R^T v|: sizes along the turned axes.
void TurnedSize(double* r, const FaceTurn& t, const double* size) {
  for (int k = 0; k < 3; k++) r[t.index[k]] = std::abs(size[k] * t.sign[k]);
}
void Transpose3(double* r, const double* m) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) r[3 * j + i] = m[3 * i + j];
  }
}

// The two boxes relative to each other.
struct BoxPair {
  GeomPose b1, b2;
  double pos21[3];  // box 2's centre in box 1's frame
  double pos12[3];  // box 1's centre in box 2's frame
  double rot[9];    // box 2's axes in box 1's frame (columns)
  double rott[9];   // rot transposed
  double rotabs[9], rottabs[9];
};

BoxPair RelativeBoxes(const GeomPose& b1, const GeomPose& b2) {
  BoxPair p{b1, b2, {}, {}, {}, {}, {}, {}};
  double tmp[3];
  Sub3(tmp, b2.pos, b1.pos);
  MulMatTVec3(p.pos21, b1.mat, tmp);
  Sub3(tmp, b1.pos, b2.pos);
  MulMatTVec3(p.pos12, b2.mat, tmp);
  math::MulMatTMat3(p.rot, b1.mat, b2.mat);
  Transpose3(p.rott, p.rot);
  for (int i = 0; i < 9; i++) {
    p.rotabs[i] = std::abs(p.rot[i]);
    p.rottabs[i] = std::abs(p.rott[i]);
  }
  return p;
}

// The axis of least penetration. code: 0..5 a face of box 1 (axis, +3 when box 2 lies
// on its negative side), 6..11 likewise of box 2, 12 + 3 i + j the cross product of box
// 1's axis i and box 2's axis j; -1 when separated.
struct BestAxis {
  int code = -1;
  double penetration;
  // Edge axes only: the normal in box 1's frame, the nearest edges (bits: axes at
  // +size) of box 1 and box 2, and whether box 2 lies on the negative side.
  double normal[3] = {0, 0, 0};
  int edge1 = 0, edge2 = 0;
  bool inverted = false;
};

// Face axes of both boxes; false when one separates the boxes beyond the margin.
bool TestFaceAxes(const BoxPair& p, double margin, BestAxis& best) {
  double plen1[3], plen2[3];
  MulMatVec3(plen2, p.rotabs, p.b2.size);
  MulMatTVec3(plen1, p.rotabs, p.b1.size);
  for (int i = 0; i < 3; i++) {
    double c1 = -std::abs(p.pos21[i]) + p.b1.size[i] + plen2[i];
    double c2 = -std::abs(p.pos12[i]) + p.b2.size[i] + plen1[i];
    if (c1 < -margin || c2 < -margin) return false;
    if (c1 < best.penetration) {
      best.penetration = c1;
      best.code = i + 3 * (p.pos21[i] < 0);
    }
    if (c2 < best.penetration) {
      best.penetration = c2;
      best.code = i + 3 * (p.pos12[i] < 0) + 6;
    }
  }
  return true;
}

// The cross product of box 1's axis i with box 2's axis j, in box 1's frame.
void EdgeAxis(const BoxPair& p, int i, int j, double* axis) {
  const double* b = p.rott + 3 * j;
  math::Zero3(axis);
  if (i == 0) {
    axis[1] = -b[2];
    axis[2] = +b[1];
  } else if (i == 1) {
    axis[0] = +b[2];
    axis[2] = -b[0];
  } else {
    axis[0] = -b[1];
    axis[1] = +b[0];
  }
}

// Edge-edge axes; an edge axis must beat a face axis by a relative 1e-12. False when
// one separates the boxes beyond the margin.
bool TestEdgeAxes(const BoxPair& p, double margin, BestAxis& best) {
  const double* size1 = p.b1.size;
  const double* size2 = p.b2.size;
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      double axis[3];
      EdgeAxis(p, i, j, axis);
      double len = Normalize3(axis);
      if (len < kMinVal) continue;
      double center = Dot3(p.pos21, axis);
      double reach = 0;
      for (int k = 0; k < 3; k++) {
        if (k != i) reach += size1[k] * std::abs(axis[k]);
      }
      for (int k = 0; k < 3; k++) {
        if (k != j) reach += size2[k] * p.rotabs[3 * i + 3 - k - j] / len;
      }
      reach -= std::abs(center);
      if (reach < -margin) return false;
      if (reach >= best.penetration * (1 - 1e-12)) continue;

      best.penetration = reach;
      best.code = 12 + i * 3 + j;
      math::Copy3(best.normal, axis);
      best.inverted = center < 0;
      best.edge1 = best.edge2 = 0;
      for (int k = 0; k < 3; k++) {
        if (k != i && ((axis[k] > 0) ^ (center < 0))) best.edge1 += 1 << k;
      }
      for (int k = 0; k < 3; k++) {
        if (k == j) continue;
        bool up = (p.rot[3 * i + 3 - k - j] > 0) ^ (center < 0) ^ ((k - j + 3) % 3 == 1);
        if (up) best.edge2 += 1 << k;
      }
    }
  }
  return true;
}

// The contact points found in a turned frame: position (turned frame, z relative to
// the reference face) and distance.
struct ClipPoints {
  double point[kMaxContactPair][3];
  double depth[kMaxContactPair];
  int n = 0;
};

// Writes the clipped points as contacts: back to world through `back` (turned frame to
// world rotation) and `origin`, the reference face lifted by hz, all with one normal.
int EmitContacts(Contact* con, ClipPoints& pts, const double* back, const double* origin,
                 double hz, const double* normal) {
  for (int i = 0; i < pts.n; i++) {
    SetContactNormal(con[i], normal);
    con[i].dist = pts.depth[i];
    pts.point[i][2] += hz;
    double world[3];
    MulMatVec3(world, back, pts.point[i]);
    math::Add3(con[i].pos, world, origin);
  }
  return pts.n;
}

// Corner i (0..3) of the rectangle |x| <= ext[0], |y| <= ext[1].
void RectCorner(int i, const double* ext, double& x, double& y) {
  x = i / 2 ? ext[0] : -ext[0];
  y = i % 2 ? ext[1] : -ext[1];
}

// Coordinates (u, v) of point (x, y) in the parallelogram at pts[0] spanned by the xy
// parts of pts[1] and pts[2], whose determinant is `det`.
void ParallelogramCoords(const double pts[][3], double x, double y, double det, double& u,
                         double& v) {
  double a = pts[1][0], b = pts[2][0], c = pts[1][1], d = pts[2][1];
  double dx = x - pts[0][0], dy = y - pts[0][1];
  u = (dx * d - dy * b) * (1 / det);
  v = (dy * a - dx * c) * (1 / det);
}

// The determinant of the parallelogram's edge vectors pts[1], pts[2] (xy parts).
double ParallelogramDet(const double pts[][3]) {
  return pts[1][0] * pts[2][1] - pts[2][0] * pts[1][1];
}

// Where the 2D segment from `start` along `dir` (xy) crosses the lines x = +-ext[0]
// (q = 0) or y = +-ext[1] (q = 1) within the rectangle: calls add(c, q, l, c2) with the
// segment parameter c, the line coordinate l and the other coordinate c2.
template <typename Add>
void CrossRectangle(const double* start, const double* dir, const double* ext, Add add) {
  for (int q = 0; q < 2; q++) {
    double a = start[q], b = dir[q], c = start[1 - q], d = dir[1 - q];
    if (std::abs(b) <= kMinVal) continue;
    for (int j = -1; j <= 1; j += 2) {
      double l = ext[q] * j;
      double t = (l - a) * (1 / b);
      if (t < 0 || t > 1) continue;
      double c2 = c + d * t;
      if (std::abs(c2) > ext[1 - q]) continue;
      add(t, q, l, c2);
    }
  }
}

// A face contact's frame: turned so the reference face (of box 2 when on_box2) faces
// +z. r: the incident box's axes as rows of rt (r = rt^T), p: its centre relative to the
// face's centre, ext: the reference box's half sizes.
struct FaceFrame {
  FaceTurn turn;
  bool on_box2;
  double r[9], rt[9], p[3], ext[3];
  const double* inc_size;  // the incident box's half sizes
};

FaceFrame FaceContactFrame(const BoxPair& bp, const BestAxis& best) {
  FaceFrame f;
  f.turn = TurnForFace(best.code % 6);
  f.on_box2 = best.code >= 6;
  f.inc_size = f.on_box2 ? bp.b1.size : bp.b2.size;
  double ref_size[3];
  if (f.on_box2) {
    TurnColumns(f.r, f.turn, bp.rot);
    TurnVec(f.p, f.turn, bp.pos12);
    TurnVec(ref_size, f.turn, bp.b2.size);
  } else {
    TurnRows(f.r, f.turn, bp.rot);
    TurnVec(f.p, f.turn, bp.pos21);
    TurnVec(ref_size, f.turn, bp.b1.size);
  }
  Transpose3(f.rt, f.r);
  for (int i = 0; i < 3; i++) f.ext[i] = std::abs(ref_size[i]);
  f.p[2] -= f.ext[2];
  return f;
}

// The incident box's lowest corner (pts[0]) and its edges from there that are not too
// steep to the face (pts[1], pts[2]); pts[3..5] are the other corners of that face.
// Returns 1 + the number of edges.
int IncidentFace(const FaceFrame& f, double pts[6][3]) {
  int low = 0;
  for (int i = 0; i < 3; i++) {
    if (f.r[6 + i] < 0) low += 1 << i;
  }
  math::Copy3(pts[0], f.p);
  for (int i = 0; i < 3; i++) {
    math::AddScaled3(pts[0], f.rt + 3 * i, f.inc_size[i] * ((low & (1 << i)) ? 1 : -1));
  }
  int m = 1;
  for (int i = 0; i < 3; i++) {
    if (std::abs(f.r[6 + i]) < 0.5) {
      math::Scale3(pts[m++], f.rt + 3 * i, f.inc_size[i] * ((low & (1 << i)) ? -2 : 2));
    }
  }
  math::Add3(pts[3], pts[0], pts[1]);
  math::Add3(pts[4], pts[0], pts[2]);
  math::Add3(pts[5], pts[3], pts[2]);
  return m;
}

// Clips the incident face (m - 1 edges) against the reference face: edges crossing
// its border, its corners under the incident face, the incident corners over it.
void ClipIncidentFace(const double pts[6][3], int m, const double* ext, ClipPoints& clip) {
  double lines[4][6];
  int nlines = 0;
  auto add_line = [&](const double* start, const double* dir) {
    math::Copy3(lines[nlines], start);
    math::Copy3(lines[nlines++] + 3, dir);
  };
  if (m > 1) add_line(pts[0], pts[1]);
  if (m > 2) {
    add_line(pts[0], pts[2]);
    add_line(pts[3], pts[2]);
    add_line(pts[4], pts[1]);
  }
  for (int i = 0; i < nlines; i++) {
    CrossRectangle(lines[i], lines[i] + 3, ext, [&](double t, int, double, double) {
      math::Copy3(clip.point[clip.n], lines[i]);
      math::AddScaled3(clip.point[clip.n++], lines[i] + 3, t);
    });
  }

  // Reference face corners inside the incident face (a parallelogram).
  double det = ParallelogramDet(pts);
  for (int i = 0; i < 4 && m > 2; i++) {
    double cx, cy, u, v;
    RectCorner(i, ext, cx, cy);
    ParallelogramCoords(pts, cx, cy, det, u, v);
    if (u <= 0 || v <= 0 || u >= 1 || v >= 1) continue;
    double* q = clip.point[clip.n++];
    q[0] = cx;
    q[1] = cy;
    q[2] = pts[0][2] + u * pts[1][2] + v * pts[2][2];
  }

  // Incident face corners over the reference face (the lowest corner always).
  for (int i = 0; i < (1 << (m - 1)); i++) {
    const double* q = pts[i == 0 ? 0 : i + 2];
    if (i && (q[0] <= -ext[0] || q[0] >= ext[0])) continue;
    if (i && (q[1] <= -ext[1] || q[1] >= ext[1])) continue;
    math::Copy3(clip.point[clip.n++], q);
  }
}

// Keeps the points within the margin; each contact lies halfway down to the face.
void KeepWithinMargin(ClipPoints& clip, double margin) {
  int kept = 0;
  for (int i = 0; i < clip.n; i++) {
    if (clip.point[i][2] > margin) continue;
    if (kept != i) math::Copy3(clip.point[kept], clip.point[i]);
    clip.depth[kept] = clip.point[kept][2];
    clip.point[kept][2] *= 0.5;
    kept++;
  }
  clip.n = kept;
}

// Face contact: the incident box's face nearest the reference face, clipped to it.
int BoxFaceContacts(Contact* con, const BoxPair& bp, const BestAxis& best, double margin) {
  FaceFrame f = FaceContactFrame(bp, best);
  double pts[6][3] = {};
  int m = IncidentFace(f, pts);
  ClipPoints clip;
  ClipIncidentFace(pts, m, f.ext, clip);
  KeepWithinMargin(clip, margin);

  // Back to world; the normal is the face's, pointing from box 1 to box 2.
  double back[9], normal[3];
  UnturnMat(back, f.on_box2 ? bp.b2.mat : bp.b1.mat, f.turn);
  double flip = f.on_box2 ? -1 : 1;
  for (int i = 0; i < 3; i++) normal[i] = flip * back[3 * i + 2];
  return EmitContacts(con, clip, back, f.on_box2 ? bp.b2.pos : bp.b1.pos, f.ext[2], normal);
}

// The reference face and frame of an edge-edge contact: box 1's face adjacent to its
// nearest edge that the edge axis is least inclined to; fills the turn, box 2's
// position, the normal and rotation in the turned frame, and box 1's extents there.
struct EdgeFrame {
  FaceTurn turn;
  double p[3], rnorm[3], r[9], rt[9], ext[3];
  int ax1, ax2;  // box 2's other axes: ax1 the one more aligned with box 1's edge
};

EdgeFrame EdgeContactFrame(const BoxPair& bp, const BestAxis& best) {
  int code = best.code - 12;
  int q1 = code / 3, q2 = code % 3;
  EdgeFrame f;
  // The two other axes of each box (in MuJoCo's order), the better aligned first.
  static const int kOther[3][2] = {{1, 2}, {0, 2}, {1, 0}};
  f.ax1 = kOther[q2][0];
  f.ax2 = kOther[q2][1];
  int pax1 = kOther[q1][0], pax2 = kOther[q1][1];
  if (bp.rotabs[3 * q1 + f.ax1] < bp.rotabs[3 * q1 + f.ax2]) {
    f.ax1 = f.ax2;
    f.ax2 = 3 - q2 - f.ax1;
  }
  if (bp.rottabs[3 * q2 + pax1] < bp.rottabs[3 * q2 + pax2]) {
    pax1 = pax2;
    pax2 = 3 - q1 - pax1;
  }
  int face = (best.edge1 & (1 << pax2)) ? pax2 : pax2 + 3;

  f.turn = TurnForFace(face);
  TurnVec(f.p, f.turn, bp.pos21);
  TurnVec(f.rnorm, f.turn, best.normal);
  TurnRows(f.r, f.turn, bp.rot);
  TurnedSize(f.ext, f.turn, bp.b1.size);
  Transpose3(f.rt, f.r);
  f.p[2] -= f.ext[2];
  return f;
}

// Box 2's face edges (pts: corner 0 and the two edge vectors, projected; axi: the same
// unprojected) crossing the border of the reference face, within the margin; each
// contact lies halfway between the crossing and its unprojected point.
int EdgeCrossings(ClipPoints& clip, const double pts[3][3], const double axi[3][3],
                  const double* ext, double innorm, double margin) {
  double lines[4][6], unproj[4][6];
  auto set = [](double* line, const double* start, const double* dir) {
    math::Copy3(line, start);
    math::Copy3(line + 3, dir);
  };
  // The edge from corner 0 along each edge vector, and the opposite two edges.
  double p01[3], p02[3], a01[3], a02[3];
  math::Add3(p01, pts[0], pts[1]);
  math::Add3(p02, pts[0], pts[2]);
  math::Add3(a01, axi[0], axi[1]);
  math::Add3(a02, axi[0], axi[2]);
  set(lines[0], pts[0], pts[1]);
  set(unproj[0], axi[0], axi[1]);
  set(lines[1], pts[0], pts[2]);
  set(unproj[1], axi[0], axi[2]);
  set(lines[2], p01, pts[2]);
  set(unproj[2], a01, axi[2]);
  set(lines[3], p02, pts[1]);
  set(unproj[3], a02, axi[1]);

  for (int i = 0; i < 4; i++) {
    const double* u = unproj[i];
    CrossRectangle(lines[i], lines[i] + 3, ext, [&](double t, int q, double l, double c2) {
      if ((u[2] + u[5] * t) * innorm > margin) return;
      double* pt = clip.point[clip.n];
      math::Scale3(pt, u, 0.5);
      math::AddScaled3(pt, u + 3, 0.5 * t);
      pt[q] += 0.5 * l;
      pt[1 - q] += 0.5 * c2;
      clip.depth[clip.n++] = pt[2] * innorm * 2;
    });
  }
  return clip.n;
}

// Reference face corners over box 2's face (all when no edge crossed, else only those
// strictly over it), each paired with the nearest point of box 2's face. As MuJoCo
// does, the parallelogram's determinant is replaced by the last corner's squared
// distance once a corner passes the range test.
int EdgeFaceCorners(ClipPoints& clip, const double pts[3][3], const double pu[4][3],
                    const double* ext, int nl, double margin) {
  double det = ParallelogramDet(pts);
  for (int i = 0; i < 4; i++) {
    double cx, cy, u, v;
    RectCorner(i, ext, cx, cy);
    ParallelogramCoords(pts, cx, cy, det, u, v);
    bool u_out = u < 0 || u > 1, v_out = v < 0 || v > 1;
    if (nl == 0 ? (u_out && v_out) : (u_out || v_out)) continue;
    u = std::clamp(u, 0.0, 1.0);
    v = std::clamp(v, 0.0, 1.0);

    double under[3], gap[3];
    math::Scale3(under, pu[0], 1 - u - v);
    math::AddScaled3(under, pu[1], u);
    math::AddScaled3(under, pu[2], v);
    double* pt = clip.point[clip.n];
    pt[0] = cx;
    pt[1] = cy;
    pt[2] = 0;
    Sub3(gap, pt, under);
    det = Dot3(gap, gap);
    if (under[2] > 0 && det > margin * margin) continue;
    math::AddScaled3(pt, under, 1);
    math::Scale3(pt, pt, 0.5);
    clip.depth[clip.n++] = std::sqrt(det) * (under[2] < 0 ? -1 : 1);
  }
  return clip.n;
}

// Box 2's face corners (flat: projected xy, pu: unprojected) over the reference face,
// paired with the nearest point of the face; nl and nf count the earlier contacts.
void EdgeIncidentCorners(ClipPoints& clip, const double flat[4][2], const double pu[4][3],
                         const double* ext, double innorm, int nl, int nf, double margin) {
  for (int i = 0; i < 4; i++) {
    double x = flat[i][0], y = flat[i][1];
    bool x_out = x < -ext[0] || x > ext[0], y_out = y < -ext[1] || y > ext[1];
    if (nl == 0 ? (nf != 0 && x_out && y_out) : (x_out || y_out)) continue;

    // Squared distance to the face: outside the rectangle, then along the normal.
    double dist_sqr = 0;
    double nearest[3] = {flat[i][0] * 0.5, flat[i][1] * 0.5, 0};
    for (int j = 0; j < 2; j++) {
      if (flat[i][j] < -ext[j]) {
        dist_sqr += (flat[i][j] + ext[j]) * (flat[i][j] + ext[j]);
        nearest[j] = -ext[j] * 0.5;
      } else if (flat[i][j] > ext[j]) {
        dist_sqr += (flat[i][j] - ext[j]) * (flat[i][j] - ext[j]);
        nearest[j] = +ext[j] * 0.5;
      }
    }
    dist_sqr += pu[i][2] * innorm * pu[i][2] * innorm;
    if (pu[i][2] > 0 && dist_sqr > margin * margin) continue;

    math::AddScaled3(nearest, pu[i], 0.5);
    math::Copy3(clip.point[clip.n], nearest);
    clip.depth[clip.n++] = std::sqrt(dist_sqr) * (pu[i][2] < 0 ? -1 : 1);
  }
}

// Box 2's face along its nearest edge, in the turned frame of box 1: the nearest edge
// (corners 0, 1) and the parallel edge across the face (corners 2, 3).
void Box2FaceCorners(const BoxPair& bp, const BestAxis& best, const EdgeFrame& f,
                     double corner[4][3]) {
  int q2 = (best.code - 12) % 3;
  const double* size2 = bp.b2.size;
  double s1 = (best.edge2 & (1 << f.ax1)) ? 1 : -1;
  double s2 = (best.edge2 & (1 << f.ax2)) ? 1 : -1;
  for (int side = 0; side < 2; side++) {
    double* e0 = corner[2 * side];
    double* e1 = corner[2 * side + 1];
    math::Copy3(e0, f.p);
    math::AddScaled3(e0, f.rt + 3 * f.ax1, size2[f.ax1] * (side ? -s1 : s1));
    math::AddScaled3(e0, f.rt + 3 * f.ax2, size2[f.ax2] * s2);
    math::Copy3(e1, e0);
    math::AddScaled3(e0, f.rt + 3 * q2, size2[q2]);
    math::AddScaled3(e1, f.rt + 3 * q2, -size2[q2]);
  }
}

// Edge contact: box 2's face along its nearest edge, projected along the normal onto
// box 1's reference face and clipped against it, plus corners of either face.
int BoxEdgeContacts(Contact* con, const BoxPair& bp, const BestAxis& best, double margin) {
  EdgeFrame f = EdgeContactFrame(bp, best);
  const double* ext = f.ext;
  double corner[4][3];
  Box2FaceCorners(bp, best, f, corner);
  double axi[3][3];
  math::Copy3(axi[0], corner[0]);
  Sub3(axi[1], corner[1], corner[0]);
  Sub3(axi[2], corner[2], corner[0]);
  if (std::abs(f.rnorm[2]) < kMinVal) return 0;
  double innorm = (1 / f.rnorm[2]) * (best.inverted ? -1 : 1);

  // Project the face corners along the normal onto the plane z = 0 (pu keeps them).
  double pu[4][3], flat[4][2];
  for (int i = 0; i < 4; i++) {
    double t = -corner[i][2] * (1 / f.rnorm[2]);
    math::Copy3(pu[i], corner[i]);
    math::AddScaled3(corner[i], f.rnorm, t);
    flat[i][0] = corner[i][0];
    flat[i][1] = corner[i][1];
  }
  double pts[3][3];
  math::Copy3(pts[0], corner[0]);
  Sub3(pts[1], corner[1], corner[0]);
  Sub3(pts[2], corner[2], corner[0]);

  ClipPoints clip;
  int nl = EdgeCrossings(clip, pts, axi, ext, innorm, margin);
  int nf = EdgeFaceCorners(clip, pts, pu, ext, nl, margin);
  EdgeIncidentCorners(clip, flat, pu, ext, innorm, nl, nf, margin);

  // Back to world; the normal points from box 1 to box 2.
  double back[9], normal[3];
  UnturnMat(back, bp.b1.mat, f.turn);
  MulMatVec3(normal, back, f.rnorm);
  math::Scale3(normal, normal, best.inverted ? -1 : 1);
  return EmitContacts(con, clip, back, bp.b1.pos, ext[2], normal);
}

}  // namespace

// ---------------------------------------------------------------- public pairs

int CollideSphereBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                     double margin) {
  GeomPose sphere = PoseOf(m, d, g1);
  return SphereBoxPoint(con, margin, sphere.pos, sphere.size[0], PoseOf(m, d, g2));
}

int CollideCapsuleBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                      double margin) {
  return CapsuleBoxPoses(con, margin, PoseOf(m, d, g1), PoseOf(m, d, g2));
}

int CapsuleBoxPoses(Contact* con, double margin, const GeomPose& capsule, const GeomPose& box) {
  LocalSegment seg = SegmentInBox(capsule, box);
  const double* size = box.size;

  // Nearest box feature: faces under the ends, then edges.
  SegmentBoxNearest best;
  best.dist_sqr = margin + 2 * (capsule.size[0] + seg.half_length + size[0] + size[1] +
                                size[2]);
  best.seg_pos = 0;
  NearestFaceToEnds(seg, size, best);
  NearestEdge(seg, size, best);
  if (best.type == -4) return 0;

  // A second point along the segment, where the segment lies along the box.
  double second;
  if (best.type < 0) second = SecondPointAtFace(seg, size, best);
  else if (best.type / 3 != 1) second = SecondPointAtCorner(seg, size, best);
  else second = SecondPointAtEdge(seg, size, best);

  int n = CapsuleSphereAt(con, margin, seg, best.seg_pos, capsule, box);
  if (second > -3) {
    n += CapsuleSphereAt(con + n, margin, seg, second + best.seg_pos, capsule, box);
  }
  return n;
}

int CollideBoxBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                  double margin) {
  BoxPair bp = RelativeBoxes(PoseOf(m, d, g1), PoseOf(m, d, g2));
  BestAxis best;
  best.penetration = margin;
  for (int i = 0; i < 3; i++) best.penetration += bp.b1.size[i] * 3 + bp.b2.size[i] * 3;
  if (!TestFaceAxes(bp, margin, best) || !TestEdgeAxes(bp, margin, best)) return 0;
  if (best.code == -1) return 0;
  if (best.code < 12) return BoxFaceContacts(con, bp, best, margin);
  return BoxEdgeContacts(con, bp, best, margin);
}

}  // namespace simlab
