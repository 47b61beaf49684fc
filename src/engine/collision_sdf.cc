// Signed-distance collisions (MuJoCo 3.5's mjc_SDF): a primitive, mesh or sdf geom (g1)
// against an sdf geom (g2) whose field is its mesh's octree (mesh_octree.cc).
//
// The two shapes' fields are combined into one function whose minimum lies where they
// overlap most: A + B + |max(A, B)|, A and B the distances to each. From points spread
// over the overlap of the two bounding boxes (a Halton sequence, opt.sdf_initpoints of
// them), gradient descent with a backtracking line search walks downhill
// (opt.sdf_iterations steps); one step on max(A, B) then moves the point into the
// intersection. Where that is inside both shapes, the point, projected on the
// mid-surface A = B, becomes a contact (repeated points are dropped) whose normal is the
// mid-surface's gradient. Each formula is MuJoCo's, in its order of operations, so that
// the contacts are MuJoCo's to the bit.
#include <algorithm>
#include <cmath>

#include "engine/collision.h"
#include "engine/engine.h"
#include "engine/ray.h"
#include "math/math.h"

namespace simlab {

namespace {

using namespace math;

// Which combination of the two fields (MuJoCo's mjtSDFType).
enum class Field { kCollision, kIntersection, kMidsurface };

// The two shapes: index 0 is g2 (the sdf), index 1 is g1, whose points are mapped into
// it by y = relmat x + relpos. `id` is a mesh id for an sdf geom, else the geom id; an
// sdf geom with a plugin has its field.
struct SdfPair {
  const Model* m = nullptr;
  const Data* d = nullptr;
  int id[2] = {-1, -1};
  SdfField field[2];
  int type[2] = {kGeomSdf, kGeomSdf};
  double relpos[3] = {0, 0, 0};
  double relmat[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
};

// v <- M v and v <- M^T v, in place.
void TurnInPlace(double v[3], const double mat[9]) {
  double r[3];
  MulMatVec3(r, mat, v);
  Copy3(v, r);
}
void TurnBackInPlace(double v[3], const double mat[9]) {
  double r[3];
  MulMatTVec3(r, mat, v);
  Copy3(v, r);
}

// ---------------------------------------------------------------- the mesh octree

// Moves p into the box (centre, half sizes) if outside (just past its side); returns
// the distance it was outside, or (inside) the largest, non-positive, side distance.
double IntoBox(double p[3], const double box[6]) {
  const double eps = 1e-6;
  double r[3] = {p[0] - box[0], p[1] - box[1], p[2] - box[2]};
  double q[3] = {std::abs(r[0]) - box[3], std::abs(r[1]) - box[4], std::abs(r[2]) - box[5]};
  if (q[0] <= 0 && q[1] <= 0 && q[2] <= 0) return std::max(q[0], std::max(q[1], q[2]));
  double sq = 0;
  for (int k = 0; k < 3; k++) {
    if (q[k] >= 0) {
      sq += q[k] * q[k];
      p[k] -= r[k] > 0 ? (q[k] + eps) : -(q[k] + eps);
    }
  }
  return std::sqrt(sq);
}

// The leaf cell holding p and its trilinear weights (w) or their gradients (dw).
int FindCell(const double* aabb, const int* child, const double p[3], double w[8],
             double dw[8][3]) {
  const double eps = 1e-8;
  int cell = 0;
  for (int level = 0; level < 100; level++) {
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
      lo[k] = aabb[6 * cell + k] - aabb[6 * cell + 3 + k];
      hi[k] = aabb[6 * cell + k] + aabb[6 * cell + 3 + k];
    }
    bool outside = false;
    for (int k = 0; k < 3; k++) outside = outside || p[k] + eps < lo[k] || p[k] - eps > hi[k];
    if (outside) return -1;  // (cannot happen after IntoBox; MuJoCo stops with an error)
    double c[3];
    for (int k = 0; k < 3; k++) c[k] = (p[k] - lo[k]) / (hi[k] - lo[k]);
    bool leaf = true;
    for (int j = 0; j < 8; j++) leaf = leaf && child[8 * cell + j] == -1;
    if (leaf) {
      for (int j = 0; j < 8; j++) {
        double fx = j & 1 ? c[0] : 1 - c[0], fy = j & 2 ? c[1] : 1 - c[1],
               fz = j & 4 ? c[2] : 1 - c[2];
        if (w) w[j] = fx * fy * fz;
        if (dw) {
          dw[j][0] = (j & 1 ? 1 : -1) * fy * fz;
          dw[j][1] = fx * (j & 2 ? 1 : -1) * fz;
          dw[j][2] = fx * fy * (j & 4 ? 1 : -1);
        }
      }
      return cell;
    }
    int slot = (c[0] < .5 ? 0 : 1) + 2 * (c[1] < .5 ? 0 : 1) + 4 * (c[2] < .5 ? 0 : 1);
    cell = child[8 * cell + slot];
    if (cell < 0) break;
  }
  return -1;
}

// A mesh's octree in the model: boxes, children, corner values from its first cell.
struct Octree {
  const double* aabb;
  const int* child;
  const double* coeff;
};
Octree OctreeOf(const Model& m, int mesh) {
  size_t adr = static_cast<size_t>(m.mesh_octadr[mesh]);
  return {&m.oct_aabb[6 * adr], &m.oct_child[8 * adr], &m.oct_coeff[8 * adr]};
}

double OctreeDistance(const Model& m, const double p[3], int mesh) {
  const Octree o = OctreeOf(m, mesh);
  double w[8], point[3] = {p[0], p[1], p[2]};
  double outside = IntoBox(point, o.aabb);
  int cell = FindCell(o.aabb, o.child, point, w, nullptr);
  if (cell < 0) return kMaxVal;
  double sdf = 0;
  for (int j = 0; j < 8; j++) sdf += w[j] * o.coeff[8 * cell + j];
  return outside > 0 ? sdf + outside : sdf;
}

// Analytic inside the octree's box, by finite differences outside it.
void OctreeGradient(const Model& m, double grad[3], const double point[3], int mesh) {
  Zero3(grad);
  const Octree o = OctreeOf(m, mesh);
  double p[3] = {point[0], point[1], point[2]};
  if (IntoBox(p, o.aabb) <= 0) {
    double dw[8][3];
    int cell = FindCell(o.aabb, o.child, p, nullptr, dw);
    if (cell < 0) return;
    for (int j = 0; j < 8; j++) {
      for (int k = 0; k < 3; k++) grad[k] += dw[j][k] * o.coeff[8 * cell + j];
    }
    return;
  }
  const double eps = 1e-8;
  double d0 = OctreeDistance(m, point, mesh);
  for (int k = 0; k < 3; k++) {
    double moved[3] = {point[0], point[1], point[2]};
    moved[k] += eps;
    grad[k] = (OctreeDistance(m, moved, mesh) - d0) / eps;
  }
}

// ---------------------------------------------------------------- meshes

// A mesh geom's "distance" as the reference build estimates it (its mjc_MeshSDF is
// mjc_SDF): the octree of the mesh numbered as the geom (the reference indexes the mesh
// arrays by the geom's id; simlab reads them only when that id is a mesh's), else the
// ray from the point (world frame) towards the world origin: the distance to the mesh
// along it, or, when the ray leaves past the origin, minus the distance back.

// The first ray: from point x of the geom's frame (a, in the world) towards the world
// origin (dir = -a, of length *reach); its parameter at the mesh (-1: none).
double RayTowardsOrigin(const SdfPair& s, int geom, const double x[3], double a[3], double dir[3],
                        double* reach) {
  const Data& d = *s.d;
  MulMatVec3(a, &d.geom_xmat[9 * geom], x);
  for (int k = 0; k < 3; k++) a[k] += d.geom_xpos[3 * geom + k];
  for (int k = 0; k < 3; k++) dir[k] = -a[k];
  *reach = Norm3(dir);
  return RayMesh(*s.m, d, geom, a, dir, nullptr);
}

double MeshRay(const SdfPair& s, int geom, const double x[3]) {
  double a[3], dir[3], reach;
  double dist = RayTowardsOrigin(s, geom, x, a, dir, &reach);
  if (dist > reach) {
    for (double& v : dir) v = -v;
    return -RayMesh(*s.m, *s.d, geom, a, dir, nullptr);
  }
  return dist;
}

bool MeshOctreeByGeomId(const Model& m, int geom) {
  return geom < m.nmesh && m.mesh_octnum[geom] > 0;
}

// ---------------------------------------------------------------- primitives

// A box's interior field direction: from the centre towards the corners, blended to
// the faces (MuJoCo's radialField3d).
void BoxField(double field[3], const double a[3], const double x[3], const double size[3]) {
  for (int k = 0; k < 3; k++) field[k] = -size[k] / a[k];
  Normalize3(field);
  for (int k = 0; k < 3; k++) {
    if (x[k] < 0) field[k] = -field[k];
  }
}

double Clip(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }
double Norm2(const double* v) { return std::sqrt(v[0] * v[0] + v[1] * v[1]); }

// Distance from x (in the shape's frame) to shape `which` of the pair.
double ShapeDistance(const SdfPair& s, int which, const double x[3]) {
  const Model& m = *s.m;
  int type = s.type[which], id = s.id[which];
  if (type == kGeomSdf) return SdfGeomDistance(m, s.field[which], id, x);
  if (type == kGeomMesh) {
    if (MeshOctreeByGeomId(m, id)) return OctreeDistance(m, x, id);
    return MeshRay(s, id, x);
  }
  const double* size = &m.geom_size[3 * id];
  double a[3], b[3];
  switch (type) {
    case kGeomPlane: return x[2];
    case kGeomSphere: return Norm3(x) - size[0];
    case kGeomBox: {
      for (int k = 0; k < 3; k++) a[k] = std::abs(x[k]) - size[k];
      if (a[0] >= 0 || a[1] >= 0 || a[2] >= 0) {
        for (int k = 0; k < 3; k++) b[k] = std::max(a[k], 0.0);
        return Norm3(b) + std::min(std::max(a[0], std::max(a[1], a[2])), 0.0);
      }
      BoxField(b, a, x, size);
      double t[3];
      for (int k = 0; k < 3; k++) t[k] = -a[k] / std::abs(b[k]);
      return -std::min(t[0], std::min(t[1], t[2])) * Norm3(b);
    }
    case kGeomCapsule:
      a[0] = x[0], a[1] = x[1], a[2] = x[2] - Clip(x[2], -size[1], size[1]);
      return Norm3(a) - size[0];
    case kGeomEllipsoid: {
      for (int k = 0; k < 3; k++) a[k] = x[k] / size[k];
      for (int k = 0; k < 3; k++) b[k] = a[k] / size[k];
      double k0 = Norm3(a), k1 = Norm3(b);
      return k0 * (k0 - 1.0) / k1;
    }
    case kGeomCylinder:
      a[0] = std::sqrt(x[0] * x[0] + x[1] * x[1]) - size[0];
      a[1] = std::abs(x[2]) - size[1];
      b[0] = std::max(a[0], 0.0), b[1] = std::max(a[1], 0.0);
      return std::min(std::max(a[0], a[1]), 0.0) + Norm2(b);
    default: return kMaxVal;
  }
}

void ShapeGradient(double g[3], const SdfPair& s, int which, const double x[3]) {
  const Model& m = *s.m;
  int type = s.type[which], id = s.id[which];
  if (type == kGeomSdf) {
    SdfGeomGradient(m, s.field[which], id, g, x);
    return;
  }
  if (type == kGeomMesh && MeshOctreeByGeomId(m, id)) {
    OctreeGradient(m, g, x, id);
    return;
  }
  if (type == kGeomMesh) {  // (the reference's: a sign in every direction, from the first ray)
    double a[3], dir[3], reach;
    double sign = RayTowardsOrigin(s, id, x, a, dir, &reach) > reach ? 1 : -1;
    g[0] = g[1] = g[2] = sign;
    return;
  }
  const double* size = &m.geom_size[3 * id];
  double a[3], b[3], c, e;
  switch (type) {
    case kGeomPlane: g[0] = g[1] = 0, g[2] = 1; break;
    case kGeomSphere:
      Copy3(g, x);
      c = Norm3(x);
      for (int k = 0; k < 3; k++) g[k] *= 1. / c;
      break;
    case kGeomBox: {
      Zero3(g);
      for (int k = 0; k < 3; k++) a[k] = std::abs(x[k]) - size[k];
      int i = a[0] > a[1] ? 0 : 1;
      int l = a[2] > a[i] ? 2 : i;
      if (a[l] < 0) {
        BoxField(g, a, x, size);
      } else {
        for (int k = 0; k < 3; k++) b[k] = std::max(a[k], 0.0);
        c = Norm3(b);
        for (int k = 0; k < 3; k++) g[k] = a[k] > 0 ? b[k] / c * x[k] / std::abs(x[k]) : 0;
      }
      break;
    }
    case kGeomCapsule:
      a[0] = x[0], a[1] = x[1], a[2] = x[2] - Clip(x[2], -size[1], size[1]);
      c = Norm3(a);
      for (int k = 0; k < 3; k++) g[k] = a[k] / c;
      break;
    case kGeomEllipsoid: {
      for (int k = 0; k < 3; k++) a[k] = x[k] / size[k];
      for (int k = 0; k < 3; k++) b[k] = a[k] / size[k];
      double k0 = Norm3(a), k1 = Norm3(b);
      double inv0 = 1. / k0, inv1 = 1. / k1;
      double d0 = (2. * k0 - 1.) * inv1, d1 = k0 * (k0 - 1.) * inv1 * inv1;
      for (int k = 0; k < 3; k++) {
        double gk0 = b[k] * inv0, gk1 = b[k] * inv1 / (size[k] * size[k]);
        g[k] = gk0 * d0 - gk1 * d1;
      }
      Normalize3(g);
      break;
    }
    case kGeomCylinder: {
      c = std::sqrt(x[0] * x[0] + x[1] * x[1]);
      e = std::abs(x[2]);
      a[0] = c - size[0], a[1] = e - size[1];
      double ga[3] = {x[0] / std::max(c, 1. / kMaxVal), x[1] / std::max(c, 1. / kMaxVal),
                      x[2] / std::max(e, 1. / kMaxVal)};
      int j = a[0] > a[1] ? 0 : 1;
      if (a[j] < 0) {
        g[0] = j == 0 ? ga[0] : 0;
        g[1] = j == 0 ? ga[1] : 0;
        g[2] = j == 1 ? ga[2] : 0;
      } else {
        b[0] = std::max(a[0], 0.0), b[1] = std::max(a[1], 0.0);
        double bn = std::max(Norm2(b), 1. / kMaxVal);
        g[0] = ga[0] * b[0] / bn;
        g[1] = ga[1] * b[0] / bn;
        g[2] = ga[2] * b[1] / bn;
      }
      break;
    }
    default: Zero3(g);
  }
}

// ---------------------------------------------------------------- the combined field

// x in shape 0's frame; y, the same point in shape 1's.
void OtherFrame(const SdfPair& s, const double x[3], double y[3]) {
  MulMatVec3(y, s.relmat, x);
  for (int k = 0; k < 3; k++) y[k] += s.relpos[k];
}

double FieldValue(const SdfPair& s, Field f, const double x[3]) {
  double y[3];
  OtherFrame(s, x, y);
  double A = ShapeDistance(s, 0, x), B = ShapeDistance(s, 1, y);
  switch (f) {
    case Field::kIntersection: return std::max(A, B);
    case Field::kMidsurface: return A - B;
    case Field::kCollision: return A + B + std::abs(std::max(A, B));
  }
  return kMaxVal;
}

void FieldGradient(const SdfPair& s, Field f, double grad[3], const double x[3]) {
  double y[3], g1[3], g2[3];
  OtherFrame(s, x, y);
  switch (f) {
    case Field::kIntersection: {
      bool first = ShapeDistance(s, 0, x) > ShapeDistance(s, 1, y);
      ShapeGradient(grad, s, first ? 0 : 1, first ? x : y);
      if (!first) TurnBackInPlace(grad, s.relmat);
      break;
    }
    case Field::kMidsurface:
      ShapeGradient(g1, s, 0, x);
      Normalize3(g1);
      ShapeGradient(g2, s, 1, y);
      TurnBackInPlace(g2, s.relmat);
      Normalize3(g2);
      Sub3(grad, g1, g2);
      Normalize3(grad);
      break;
    case Field::kCollision: {
      double A = ShapeDistance(s, 0, x), B = ShapeDistance(s, 1, y);
      ShapeGradient(g1, s, 0, x);
      ShapeGradient(g2, s, 1, y);
      TurnBackInPlace(g2, s.relmat);
      for (int k = 0; k < 3; k++) grad[k] = g1[k] + g2[k];
      const double* larger = A > B ? g1 : g2;
      double sign = std::max(A, B) > 0 ? 1 : -1;
      for (int k = 0; k < 3; k++) grad[k] += larger[k] * sign;
      break;
    }
  }
}

// Gradient descent with backtracking (Armijo) line search; returns the field's value.
// (Each step starts where the last line search stopped, whose value it already has: the
// same number MuJoCo computes again there.)
double Descend(double x[3], const SdfPair& s, Field f, int steps) {
  const double c = .1, rho = .5, alpha_min = 1e-4;
  double value = kMaxVal;
  for (int step = 0; step < steps; step++) {
    double grad[3];
    FieldGradient(s, f, grad, x);
    for (double gk : grad) {
      if (std::isnan(gk) || gk > kMaxVal || gk < -kMaxVal) return kMaxVal;
    }
    double x0[3] = {x[0], x[1], x[2]};
    double value0 = step > 0 ? value : FieldValue(s, f, x0);
    double alpha = 2.;
    double wolfe = -c * alpha * Dot3(grad, grad);
    do {
      alpha *= rho;
      wolfe *= rho;
      for (int k = 0; k < 3; k++) x[k] = x0[k] + grad[k] * -alpha;
      value = FieldValue(s, f, x);
    } while (alpha > alpha_min && value - value0 > wolfe);
    if (value0 < value) return value;
  }
  return value;
}

// ---------------------------------------------------------------- poses and contacts

// The pose (pos12, mat12) of frame 1 seen from frame 2: (pose2)^-1 (pose1).
void RelativePose(const double pos1[3], const double quat1[4], const double pos2[3],
                  const double quat2[4], double pos12[3], double mat12[9]) {
  double negquat[4], negpos[3], quat12[4];
  NegQuat(negquat, quat2);
  RotVecQuat(negpos, pos2, negquat);
  for (double& v : negpos) v *= -1;
  MulPose(pos12, quat12, negpos, negquat, pos1, quat1);
  QuatToMat(mat12, quat12);
}

// The van der Corput radical inverse of `index` in `base`.
double Halton(int index, int base) {
  double b = base, f = 1 / b, h = 0;
  for (int n = index; n > 0;) {
    int next = n / base;
    h += f * (n - next * base);
    f /= b;
    n = next;
  }
  return h;
}

// A contact at x (shape 0's frame) if the field is negative there and x is new.
int AddContact(double* points, Contact* con, const double x[3], const double pos2[3],
               const double quat2[4], double dist, int cnt, const SdfPair& s) {
  if (dist > 0) return cnt;
  for (int i = 0; i < cnt; i++) {
    double d[3] = {x[0] - points[3 * i], x[1] - points[3 * i + 1], x[2] - points[3 * i + 2]};
    if (std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) < kMinVal) return cnt;
  }
  Copy3(points + 3 * cnt, x);
  // The mid-surface's gradient (unit), turned into the sdf. (MuJoCo 3.5.1's release
  // normalizes it once more and drops degenerate ones; the reference build does not.)
  double normal[3];
  FieldGradient(s, Field::kMidsurface, normal, x);
  for (double& v : normal) v = -v;
  Contact& c = con[cnt];
  c.dist = dist;
  RotVecQuat(c.frame, normal, quat2);
  Zero3(c.frame + 3);
  CompleteContactFrame(c.frame);  // (a whole frame here; the driver completes it again)
  double half[3], at[3];
  for (int k = 0; k < 3; k++) half[k] = c.frame[k] * (-c.dist / 2);
  RotVecQuat(at, x, quat2);
  for (int k = 0; k < 3; k++) c.pos[k] = at[k] + pos2[k] + half[k];
  return cnt + 1;
}

}  // namespace

double SdfGeomDistance(const Model& m, const SdfField& field, int mesh, const double x[3]) {
  return field.plugin ? field.Distance(x) : OctreeDistance(m, x, mesh);
}

void SdfGeomGradient(const Model& m, const SdfField& field, int mesh, double gradient[3],
                     const double x[3]) {
  if (field.plugin) {
    field.Gradient(gradient, x);
  } else {
    OctreeGradient(m, gradient, x, mesh);
  }
}

double MeshOctreeDistance(const Model& m, int mesh, const double x[3]) {
  return OctreeDistance(m, x, mesh);
}

int CollideSdf(const Model& m, const Data& d, Contact* con, int g1, int g2, double margin) {
  (void)margin;  // (MuJoCo's sdf collider takes touching points only)
  const double* pos1 = &d.geom_xpos[3 * g1];
  const double* pos2 = &d.geom_xpos[3 * g2];
  const double* box1 = &m.geom_aabb[6 * g1];
  const double* box2 = &m.geom_aabb[6 * g2];

  // Frames between the two geoms (offset2, rotation2: g1 seen from itself, near the
  // identity, kept because MuJoCo maps the starting points through it).
  double quat1[4], quat2[4], offset2[3], rotation2[9], offset21[3], rotation21[9], offset12[3],
      rotation12[9];
  MatToQuat(quat1, &d.geom_xmat[9 * g1]);
  MatToQuat(quat2, &d.geom_xmat[9 * g2]);
  RelativePose(pos1, quat1, pos1, quat1, offset2, rotation2);
  RelativePose(pos2, quat2, pos1, quat1, offset21, rotation21);
  RelativePose(pos1, quat1, pos2, quat2, offset12, rotation12);

  // The overlap of the two boxes in g1's frame; none: no contact.
  double lo1[3] = {kMaxVal, kMaxVal, kMaxVal}, hi1[3] = {-kMaxVal, -kMaxVal, -kMaxVal};
  double lo2[3] = {kMaxVal, kMaxVal, kMaxVal}, hi2[3] = {-kMaxVal, -kMaxVal, -kMaxVal};
  for (int i = 0; i < 8; i++) {
    double v1[3], v2[3];
    for (int k = 0; k < 3; k++) {
      bool upper = i & (1 << k);
      v1[k] = upper ? box1[k] + box1[3 + k] : box1[k] - box1[3 + k];
      v2[k] = upper ? box2[k] + box2[3 + k] : box2[k] - box2[3 + k];
    }
    TurnInPlace(v2, rotation21);
    for (int k = 0; k < 3; k++) v2[k] += offset21[k];
    for (int k = 0; k < 3; k++) {
      lo1[k] = std::min(lo1[k], v1[k]), hi1[k] = std::max(hi1[k], v1[k]);
      lo2[k] = std::min(lo2[k], v2[k]), hi2[k] = std::max(hi2[k], v2[k]);
    }
  }
  double lo[3], hi[3];
  for (int k = 0; k < 3; k++) lo[k] = std::max(lo1[k], lo2[k]), hi[k] = std::min(hi1[k], hi2[k]);
  if (hi[0] < lo[0] || hi[1] < lo[1] || hi[2] < lo[2]) return 0;

  // The pair's shapes: g2's octree, and g1's primitive or octree.
  SdfPair s;
  s.m = &m;
  s.d = &d;
  s.type[0] = m.geom_type[g2], s.id[0] = m.geom_dataid[g2];
  s.type[1] = m.geom_type[g1], s.id[1] = m.geom_type[g1] == kGeomSdf ? m.geom_dataid[g1] : g1;
  s.field[0] = SdfFieldOfGeom(m, d, g2);
  if (m.geom_type[g1] == kGeomSdf) s.field[1] = SdfFieldOfGeom(m, d, g1);
  Copy3(s.relpos, offset21);
  std::copy(rotation21, rotation21 + 9, s.relmat);

  // Descents from points spread over the overlap.
  double points[3 * kMaxContactPair];
  int cnt = 0;
  for (int i = 0; i < m.opt.sdf_initpoints && cnt < kMaxContactPair; i++) {
    double x[3] = {lo[0] + (hi[0] - lo[0]) * Halton(i, 2), lo[1] + (hi[1] - lo[1]) * Halton(i, 3),
                   lo[2] + (hi[2] - lo[2]) * Halton(i, 5)};
    double y[3];
    MulMatVec3(y, rotation2, x);
    for (int k = 0; k < 3; k++) y[k] += offset2[k];
    MulMatVec3(x, rotation12, y);
    for (int k = 0; k < 3; k++) x[k] += offset12[k];
    Descend(x, s, Field::kCollision, m.opt.sdf_iterations);
    double dist = Descend(x, s, Field::kIntersection, 1);
    cnt = AddContact(points, con, x, pos2, quat2, dist, cnt, s);
  }
  return cnt;
}

}  // namespace simlab
