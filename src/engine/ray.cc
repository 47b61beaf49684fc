// Ray casting as MuJoCo 3.5's engine_ray.c: per geom type the smallest non-negative
// x with pnt + x vec on the surface, in the same arithmetic so distances and normals
// agree to the last bit where the formulas do. Meshes are tested triangle by triangle
// (MuJoCo walks its BVH; the nearest hit is the same).
#include "engine/ray.h"

#include <algorithm>
#include <cmath>

#include "engine/collision.h"
#include "math/math.h"

namespace simlab {

namespace {

// ---------------------------------------------------------------- helpers

// The ray in a frame at pos with orientation mat: lpnt = mat^T (pnt - pos), lvec = mat^T vec.
void ToLocal(const double pos[3], const double mat[9], const double pnt[3], const double vec[3],
             double lpnt[3], double lvec[3]) {
  double dif[3] = {pnt[0] - pos[0], pnt[1] - pos[1], pnt[2] - pos[2]};
  math::MulMatTVec3(lpnt, mat, dif);
  math::MulMatTVec3(lvec, mat, vec);
}

void ClearNormal(double normal[3]) {
  if (normal) math::Zero3(normal);
}

// Roots of a x^2 + 2 b x + c = 0 in x[0] <= x[1] (both -1 when there are none); returns
// the smaller non-negative root, or -1.
double QuadraticRoots(double a, double b, double c, double x[2]) {
  double det = b * b - a * c;
  if (det < 0 || a < kMinVal) {
    x[0] = x[1] = -1;
    return -1;
  }
  det = std::sqrt(det);
  x[0] = (-b - det) / a;
  x[1] = (-b + det) / a;
  if (x[0] >= 0) return x[0];
  if (x[1] >= 0) return x[1];
  return -1;
}

// Two unit vectors spanning the plane normal to lvec (MuJoCo's triangle-test basis).
void NormalPlaneBasis(const double lvec[3], double b0[3], double b1[3]) {
  b0[0] = b0[1] = b0[2] = 1;
  double ax = std::abs(lvec[0]), ay = std::abs(lvec[1]), az = std::abs(lvec[2]);
  if (ax >= ay && ax >= az) {
    b0[0] = 0;
  } else if (ay >= az) {
    b0[1] = 0;
  } else {
    b0[2] = 0;
  }
  double along = -math::Dot3(lvec, b0) / math::Dot3(lvec, lvec);
  for (int k = 0; k < 3; k++) b1[k] = b0[k] + along * lvec[k];
  math::Normalize3(b1);
  math::Cross3(b0, b1, lvec);
  math::Normalize3(b0);
}

// Ray against triangle v (local frame): the projection of each corner onto the plane
// normal to the ray decides inside/outside, then the ray meets the triangle's plane.
// normal (if given) gets the unit (v0-v2) x (v1-v2) when the plane is met.
double RayTriangle(const double v[3][3], const double lpnt[3], const double lvec[3],
                   const double b0[3], const double b1[3], double normal[3]) {
  double planar[3][2];
  for (int i = 0; i < 3; i++) {
    double dif[3] = {v[i][0] - lpnt[0], v[i][1] - lpnt[1], v[i][2] - lpnt[2]};
    planar[i][0] = math::Dot3(b0, dif);
    planar[i][1] = math::Dot3(b1, dif);
  }

  // All corners on one side of a basis axis: the ray passes by.
  for (int k = 0; k < 2; k++) {
    if ((planar[0][k] > 0 && planar[1][k] > 0 && planar[2][k] > 0) ||
        (planar[0][k] < 0 && planar[1][k] < 0 && planar[2][k] < 0)) {
      return -1;
    }
  }

  // Barycentric coordinates of the ray's trace: (p0-p2, p1-p2) t = -p2.
  double a00 = planar[0][0] - planar[2][0], a01 = planar[1][0] - planar[2][0];
  double a10 = planar[0][1] - planar[2][1], a11 = planar[1][1] - planar[2][1];
  double det = a00 * a11 - a01 * a10;
  if (std::abs(det) < kMinVal) return -1;
  double r0 = -planar[2][0], r1 = -planar[2][1];
  double t0 = (a11 * r0 - a01 * r1) / det;
  double t1 = (-a10 * r0 + a00 * r1) / det;
  if (t0 < 0 || t1 < 0 || t0 + t1 > 1) return -1;

  // Distance to the triangle's plane along the ray.
  double e0[3], e1[3], rel[3], nrm[3];
  math::Sub3(e0, v[0], v[2]);
  math::Sub3(e1, v[1], v[2]);
  math::Sub3(rel, lpnt, v[2]);
  math::Cross3(nrm, e0, e1);
  double denom = math::Dot3(lvec, nrm);
  if (std::abs(denom) < kMinVal) return -1;
  double x = -math::Dot3(rel, nrm) / denom;
  if (normal) {
    math::Normalize3(nrm);
    math::Copy3(normal, nrm);
  }
  return x;
}

// Ray against triangle v; a hit nearer than *x (or the first) replaces it, and its
// normal replaces local_normal when that is given.
void NearerTriangle(const double v[3][3], const double lpnt[3], const double lvec[3],
                    const double b0[3], const double b1[3], double* x, double local_normal[3]) {
  double tri_normal[3];
  double sol = RayTriangle(v, lpnt, lvec, b0, b1, local_normal ? tri_normal : nullptr);
  if (sol >= 0 && (*x < 0 || sol < *x)) {
    *x = sol;
    if (local_normal) math::Copy3(local_normal, tri_normal);
  }
}

// ---------------------------------------------------------------- primitives
//
// Each writes its normal on a hit only; RayPrimitive clears it first.

// Plane: the front face (local z up), within the size rectangle when it has one.
double RayPlane(const double pos[3], const double mat[9], const double size[3],
                const double pnt[3], const double vec[3], double normal[3]) {
  double lpnt[3], lvec[3];
  ToLocal(pos, mat, pnt, vec, lpnt, lvec);
  if (lvec[2] > -kMinVal) return -1;
  const double x = -lpnt[2] / lvec[2];
  if (x < 0) return -1;
  double p0 = lpnt[0] + x * lvec[0], p1 = lpnt[1] + x * lvec[1];
  if ((size[0] > 0 && std::abs(p0) > size[0]) || (size[1] > 0 && std::abs(p1) > size[1])) {
    return -1;
  }
  if (normal) {
    normal[0] = mat[2];
    normal[1] = mat[5];
    normal[2] = mat[8];
  }
  return x;
}

// Sphere of squared radius r2 centred at pos (also the bounding-sphere test of others).
double RaySphere(const double pos[3], double r2, const double pnt[3], const double vec[3],
                 double normal[3]) {
  double dif[3];
  math::Sub3(dif, pnt, pos);
  double roots[2];
  double x = QuadraticRoots(math::Dot3(vec, vec), math::Dot3(vec, dif),
                            math::Dot3(dif, dif) - r2, roots);
  if (normal && x >= 0) {
    double hit[3] = {pnt[0] + x * vec[0], pnt[1] + x * vec[1], pnt[2] + x * vec[2]};
    math::Sub3(normal, hit, pos);
    math::Normalize3(normal);
  }
  return x;
}

// The round side of a z-aligned cylinder or capsule of radius r: its root, or -1.
double RoundSide(double r, const double lpnt[3], const double lvec[3]) {
  double roots[2];
  return QuadraticRoots(lvec[0] * lvec[0] + lvec[1] * lvec[1],
                        lvec[0] * lpnt[0] + lvec[1] * lpnt[1],
                        lpnt[0] * lpnt[0] + lpnt[1] * lpnt[1] - r * r, roots);
}

// Capsule: round side between the caps, then the outer half of each cap sphere.
double RayCapsule(const double pos[3], const double mat[9], const double size[3],
                  const double pnt[3], const double vec[3], double normal[3]) {
  double reach = size[0] + size[1];
  if (RaySphere(pos, reach * reach, pnt, vec, nullptr) < 0) return -1;
  double lpnt[3], lvec[3];
  ToLocal(pos, mat, pnt, vec, lpnt, lvec);
  double x = -1;
  int part = 0;  // -1 bottom cap, 0 side, 1 top cap
  double sol = RoundSide(size[0], lpnt, lvec);
  if (sol >= 0 && std::abs(lpnt[2] + sol * lvec[2]) <= size[1]) x = sol;

  // Cap spheres: roots on the capsule's outer side of each cap centre.
  double a = lvec[0] * lvec[0] + lvec[1] * lvec[1] + lvec[2] * lvec[2];
  for (int side = 1; side >= -1; side -= 2) {
    double rel[3] = {lpnt[0], lpnt[1], lpnt[2] - side * size[1]};
    double roots[2];
    QuadraticRoots(a, lvec[0] * rel[0] + lvec[1] * rel[1] + lvec[2] * rel[2],
                   rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2] - size[0] * size[0], roots);
    for (double r : roots) {
      double z = lpnt[2] + r * lvec[2];
      bool outer = side > 0 ? z >= size[1] : z <= -size[1];
      if (r >= 0 && outer && (x < 0 || r < x)) {
        x = r;
        part = side;
      }
    }
  }

  if (normal && x >= 0) {
    double local[3] = {lpnt[0] + lvec[0] * x, lpnt[1] + lvec[1] * x,
                       part == 0 ? 0 : lpnt[2] + lvec[2] * x - size[1] * part};
    math::Normalize3(local);
    math::MulMatVec3(normal, mat, local);
  }
  return x;
}

// Ellipsoid: a sphere after scaling each local axis by 1/size.
double RayEllipsoid(const double pos[3], const double mat[9], const double size[3],
                    const double pnt[3], const double vec[3], double normal[3]) {
  double lpnt[3], lvec[3];
  ToLocal(pos, mat, pnt, vec, lpnt, lvec);
  double s[3] = {1 / (size[0] * size[0]), 1 / (size[1] * size[1]), 1 / (size[2] * size[2])};
  double a = s[0] * lvec[0] * lvec[0] + s[1] * lvec[1] * lvec[1] + s[2] * lvec[2] * lvec[2];
  double b = s[0] * lvec[0] * lpnt[0] + s[1] * lvec[1] * lpnt[1] + s[2] * lvec[2] * lpnt[2];
  double c = s[0] * lpnt[0] * lpnt[0] + s[1] * lpnt[1] * lpnt[1] + s[2] * lpnt[2] * lpnt[2] - 1;
  double roots[2];
  double x = QuadraticRoots(a, b, c, roots);
  if (normal && x >= 0) {
    double local[3];
    for (int k = 0; k < 3; k++) local[k] = s[k] * (lpnt[k] + x * lvec[k]);
    math::Normalize3(local);
    math::MulMatVec3(normal, mat, local);
  }
  return x;
}

// Cylinder: the two flat disks, then the round side between them.
double RayCylinder(const double pos[3], const double mat[9], const double size[3],
                   const double pnt[3], const double vec[3], double normal[3]) {
  if (RaySphere(pos, size[0] * size[0] + size[1] * size[1], pnt, vec, nullptr) < 0) return -1;
  double lpnt[3], lvec[3];
  ToLocal(pos, mat, pnt, vec, lpnt, lvec);
  double x = -1;
  int part = 0;  // -1 bottom, 0 side, 1 top
  if (std::abs(lvec[2]) > kMinVal) {
    for (int side = -1; side <= 1; side += 2) {
      double sol = (side * size[1] - lpnt[2]) / lvec[2];
      if (sol < 0) continue;
      double p0 = lpnt[0] + sol * lvec[0], p1 = lpnt[1] + sol * lvec[1];
      if (p0 * p0 + p1 * p1 <= size[0] * size[0] && (x < 0 || sol < x)) {
        x = sol;
        part = side;
      }
    }
  }
  double sol = RoundSide(size[0], lpnt, lvec);
  if (sol >= 0 && std::abs(lpnt[2] + sol * lvec[2]) <= size[1] && (x < 0 || sol < x)) {
    x = sol;
    part = 0;
  }

  if (normal && x >= 0) {
    double local[3] = {0, 0, static_cast<double>(part)};
    if (part == 0) {
      local[0] = lpnt[0] + lvec[0] * x;
      local[1] = lpnt[1] + lvec[1] * x;
      math::Normalize3(local);
    }
    math::MulMatVec3(normal, mat, local);
  }
  return x;
}

// Box: each face the ray crosses inside its rectangle. all (if given) gets the hit on
// each face (-x, +x, -y, +y, -z, +z), -1 where there is none.
double RayBox(const double pos[3], const double mat[9], const double size[3],
              const double pnt[3], const double vec[3], double all[6], double normal[3]) {
  if (all) std::fill(all, all + 6, -1.0);
  if (RaySphere(pos, size[0] * size[0] + size[1] * size[1] + size[2] * size[2], pnt, vec,
                nullptr) < 0) {
    return -1;
  }
  static constexpr int kFaceAxes[3][2] = {{1, 2}, {0, 2}, {0, 1}};
  double lpnt[3], lvec[3];
  ToLocal(pos, mat, pnt, vec, lpnt, lvec);
  double x = -1;
  int axis = -1, side_hit = 0;
  for (int i = 0; i < 3; i++) {
    if (std::abs(lvec[i]) <= kMinVal) continue;
    for (int side = -1; side <= 1; side += 2) {
      double sol = (side * size[i] - lpnt[i]) / lvec[i];
      if (sol < 0) continue;
      int j = kFaceAxes[i][0], k = kFaceAxes[i][1];
      if (std::abs(lpnt[j] + sol * lvec[j]) > size[j] || std::abs(lpnt[k] + sol * lvec[k]) > size[k]) {
        continue;
      }
      if (x < 0 || sol < x) {
        x = sol;
        axis = i;
        side_hit = side;
      }
      if (all) all[2 * i + (side + 1) / 2] = sol;
    }
  }
  if (normal && x >= 0) {
    double local[3] = {0, 0, 0};
    local[axis] = side_hit;
    math::MulMatVec3(normal, mat, local);
  }
  return x;
}

// ---------------------------------------------------------------- height fields

// The height field's grid and scale, read from the model.
struct HfieldGrid {
  int nrow, ncol;
  const double* size;  // x, y half-sizes, top height, base depth
  const double* data;  // normalized elevations, row-major from -y
  double dx, dy;       // grid spacing
  double Height(int r, int c) const { return data[r * ncol + c] * size[2]; }
  // Corner (r, c) of the grid in the geom frame.
  void Corner(int r, int c, double v[3]) const {
    v[0] = dx * c - size[0];
    v[1] = dy * r - size[1];
    v[2] = Height(r, c);
  }
};

// The range [lo, hi) of grid cells the segment from SX[0] to SX[1] (in cells) crosses,
// padded by one cell and clipped to the grid of n points.
void CellRange(const double s[2], int n, int* lo, int* hi) {
  *lo = std::max(0, static_cast<int>(std::floor(std::min(s[0], s[1]))) - 1);
  *hi = std::min(n - 1, static_cast<int>(std::ceil(std::max(s[0], s[1]))) + 1);
}

// The two triangles of each cell near the segment where the ray is inside the top
// box; updates x and the local normal (if given) with any nearer hit.
void HfieldTriangles(const HfieldGrid& g, const double lpnt[3], const double lvec[3],
                     const double seg[2], double* x, double local_normal[3]) {
  double b0[3], b1[3];
  NormalPlaneBasis(lvec, b0, b1);
  double sx[2], sy[2];
  for (int i = 0; i < 2; i++) {
    sx[i] = (lpnt[0] + seg[i] * lvec[0] + g.size[0]) / g.dx;
    sy[i] = (lpnt[1] + seg[i] * lvec[1] + g.size[1]) / g.dy;
  }
  int cmin, cmax, rmin, rmax;
  CellRange(sx, g.ncol, &cmin, &cmax);
  CellRange(sy, g.nrow, &rmin, &rmax);
  for (int r = rmin; r < rmax; r++) {
    for (int c = cmin; c < cmax; c++) {
      // Corners: (r,c), (r,c+1), (r+1,c+1), (r+1,c); triangles wound to face +z.
      double corner[4][3];
      g.Corner(r, c, corner[0]);
      g.Corner(r, c + 1, corner[1]);
      g.Corner(r + 1, c + 1, corner[2]);
      g.Corner(r + 1, c, corner[3]);
      static constexpr int kTriangles[2][3] = {{0, 1, 2}, {0, 2, 3}};
      for (const int* t : kTriangles) {
        double v[3][3];
        for (int k = 0; k < 3; k++) math::Copy3(v[k], corner[t[k]]);
        NearerTriangle(v, lpnt, lvec, b0, b1, x, local_normal);
      }
    }
  }
}

// The four vertical sides of the top box: a hit counts below the elevation profile
// along that edge of the grid.
void HfieldSides(const HfieldGrid& g, const double lpnt[3], const double lvec[3],
                 const double all[6], double* x, double local_normal[3]) {
  for (int i = 0; i < 4; i++) {
    if (all[i] < 0 || !(all[i] < *x || *x < 0)) continue;
    double z = (lpnt[2] + all[i] * lvec[2]) / g.size[2];
    double y, y0, z0, z1;
    if (i < 2) {
      // Sides normal to x: the first or last column, along y.
      int col = i == 1 ? g.ncol - 1 : 0;
      y = (lpnt[1] + all[i] * lvec[1] + g.size[1]) / g.dy;
      y0 = std::max(0.0, std::min(static_cast<double>(g.nrow - 2), std::floor(y)));
      z0 = g.data[static_cast<int>(std::lround(y0)) * g.ncol + col];
      z1 = g.data[static_cast<int>(std::lround(y0 + 1)) * g.ncol + col];
    } else {
      // Sides normal to y: the first or last row, along x.
      int row0 = i == 3 ? (g.nrow - 1) * g.ncol : 0;
      y = (lpnt[0] + all[i] * lvec[0] + g.size[0]) / g.dx;
      y0 = std::max(0.0, std::min(static_cast<double>(g.ncol - 2), std::floor(y)));
      z0 = g.data[static_cast<int>(std::lround(y0)) + row0];
      z1 = g.data[static_cast<int>(std::lround(y0 + 1)) + row0];
    }
    if (z < z0 * (y0 + 1 - y) + z1 * (y - y0)) {
      *x = all[i];
      math::Zero3(local_normal);
      local_normal[i / 2] = i % 2 ? 1 : -1;
    }
  }
}

}  // namespace

// ---------------------------------------------------------------- geoms

double RayPrimitive(const double pos[3], const double mat[9], const double size[3],
                    const double pnt[3], const double vec[3], int type, double normal[3]) {
  ClearNormal(normal);
  switch (type) {
    case kGeomPlane: return RayPlane(pos, mat, size, pnt, vec, normal);
    case kGeomSphere: return RaySphere(pos, size[0] * size[0], pnt, vec, normal);
    case kGeomCapsule: return RayCapsule(pos, mat, size, pnt, vec, normal);
    case kGeomEllipsoid: return RayEllipsoid(pos, mat, size, pnt, vec, normal);
    case kGeomCylinder: return RayCylinder(pos, mat, size, pnt, vec, normal);
    case kGeomBox: return RayBox(pos, mat, size, pnt, vec, nullptr, normal);
    default: return -1;
  }
}

// ---------------------------------------------------------------- flexes

namespace {

// The nearest hit so far on a flex: its distance (-1 for none), vertex and normal.
struct FlexHit {
  double x = -1;
  int vertid = -1;
  double normal[3] = {0, 0, 0};

  // Keeps sol when it is a hit nearer than the one kept.
  bool Nearer(double sol, const double sol_normal[3]) {
    if (sol < 0 || (x >= 0 && sol >= x)) return false;
    x = sol;
    math::Copy3(normal, sol_normal);
    return true;
  }
};

// Does the ray meet the box of flex f's vertices grown by its radius?
bool RayMeetsFlexBox(const Model& m, const Data& d, int f, const double pnt[3],
                     const double vec[3]) {
  const double* vert = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  double lo[3], hi[3];
  math::Copy3(lo, vert);
  math::Copy3(hi, vert);
  for (int i = 1; i < m.flex_vertnum[f]; i++) {
    for (int k = 0; k < 3; k++) {
      lo[k] = std::min(lo[k], vert[3 * i + k]);
      hi[k] = std::max(hi[k], vert[3 * i + k]);
    }
  }
  double pos[3], size[3];
  const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int k = 0; k < 3; k++) {
    lo[k] -= m.flex_radius[f];
    hi[k] += m.flex_radius[f];
    pos[k] = 0.5 * (lo[k] + hi[k]);
    size[k] = 0.5 * (hi[k] - lo[k]);
  }
  return RayBox(pos, identity, size, pnt, vec, nullptr, nullptr) >= 0;
}

// The distance between two points (MuJoCo's mju_dist3).
double Distance3(const double a[3], const double b[3]) {
  double dif[3];
  math::Sub3(dif, a, b);
  return std::sqrt(dif[0] * dif[0] + dif[1] * dif[1] + dif[2] * dif[2]);
}

// The point pnt + sol vec.
void PointAlong(const double pnt[3], const double vec[3], double sol, double point[3]) {
  for (int k = 0; k < 3; k++) point[k] = pnt[k] + vec[k] * sol;
}

// Each edge of flex f as a capsule of the flex's radius; the nearer end is the vertex.
void RayFlexEdges(const Model& m, const Data& d, int f, const double pnt[3], const double vec[3],
                  FlexHit* hit) {
  const double* vert = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  for (int e = m.flex_edgeadr[f]; e < m.flex_edgeadr[f] + m.flex_edgenum[f]; e++) {
    const int* ends = &m.flex_edge[2 * e];
    const double* v1 = vert + 3 * ends[0];
    const double* v2 = vert + 3 * ends[1];
    double pos[3], dif[3], size[3] = {m.flex_radius[f], 0, 0}, quat[4], mat[9], normal[3];
    for (int k = 0; k < 3; k++) pos[k] = (v1[k] + v2[k]) * 0.5;
    math::Sub3(dif, v2, v1);
    size[1] = 0.5 * math::Normalize3(dif);
    math::QuatZToVec(quat, dif);
    math::QuatToMat(mat, quat);
    double sol = RayPrimitive(pos, mat, size, pnt, vec, kGeomCapsule, normal);
    if (!hit->Nearer(sol, normal)) continue;
    double point[3];
    PointAlong(pnt, vec, sol, point);
    hit->vertid = Distance3(v1, point) < Distance3(v2, point) ? ends[0] : ends[1];
  }
}

// Each vertex of flex f as a sphere of the flex's radius.
void RayFlexVertices(const Model& m, const Data& d, int f, const double pnt[3],
                     const double vec[3], FlexHit* hit) {
  const double* vert = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  const double size[3] = {m.flex_radius[f], 0, 0};
  for (int v = 0; v < m.flex_vertnum[f]; v++) {
    double normal[3];
    double sol = RayPrimitive(vert + 3 * v, nullptr, size, pnt, vec, kGeomSphere, normal);
    if (hit->Nearer(sol, normal)) hit->vertid = v;
  }
}

// Each face of flex f's elements (a triangle, or a tetrahedron's four, of the layer asked
// for or, for the skin, of the outer layer); the nearest corner is the vertex.
void RayFlexFaces(const Model& m, const Data& d, int f, const RayFlexParts& parts,
                  const double pnt[3], const double vec[3], FlexHit* hit) {
  static constexpr int kTetFaces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  int dim = m.flex_dim[f];
  const double* vert = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  double b0[3], b1[3];
  NormalPlaneBasis(vec, b0, b1);
  for (int e = 0; e < m.flex_elemnum[f]; e++) {
    int layer = m.flex_elemlayer[m.flex_elemadr[f] + e];
    if (dim == 3 && ((parts.skin && layer > 0) || (!parts.skin && layer != parts.layer))) continue;
    const int* elem = &m.flex_elem[m.flex_elemdataadr[f] + e * (dim + 1)];
    for (int i = 0; i < (dim == 2 ? 1 : 4); i++) {
      double v[3][3], normal[3];
      for (int j = 0; j < 3; j++) math::Copy3(v[j], vert + 3 * elem[kTetFaces[i][j]]);
      double sol = RayTriangle(v, pnt, vec, b0, b1, normal);
      if (!hit->Nearer(sol, normal)) continue;
      double point[3], dist[3];
      PointAlong(pnt, vec, sol, point);
      for (int j = 0; j < 3; j++) dist[j] = Distance3(v[j], point);
      int corner = dist[0] <= dist[1] && dist[0] <= dist[2] ? 0 : (dist[1] <= dist[2] ? 1 : 2);
      hit->vertid = elem[kTetFaces[i][corner]];
    }
  }
}

}  // namespace

double RayFlex(const Model& m, const Data& d, int f, const RayFlexParts& parts,
               const double pnt[3], const double vec[3], int* vertid, double normal[3]) {
  ClearNormal(normal);
  if (!RayMeetsFlexBox(m, d, f, pnt, vec)) return -1;

  // Edges (a 2D or 3D flex's skin shows them too), else vertices; then faces.
  FlexHit hit;
  bool skin_edges = m.flex_dim[f] > 1 && parts.skin;
  if (parts.edges || skin_edges) {
    RayFlexEdges(m, d, f, pnt, vec, &hit);
  } else if (parts.vertices) {
    RayFlexVertices(m, d, f, pnt, vec, &hit);
  }
  if (m.flex_dim[f] > 1 && (parts.faces || parts.skin)) RayFlexFaces(m, d, f, parts, pnt, vec, &hit);
  if (hit.x >= 0) {
    if (normal) math::Copy3(normal, hit.normal);
    if (vertid) *vertid = hit.vertid;
  }
  return hit.x;
}

namespace {

// The ray in geom g's frame, after clearing the normal; false when it misses the geom's
// box (geom_size about its frame), as MuJoCo culls mesh and sdf geoms.
bool RayIntoGeomBox(const Model& m, const Data& d, int g, const double pnt[3], const double vec[3],
                    double normal[3], double lpnt[3], double lvec[3]) {
  ClearNormal(normal);
  const double* xpos = &d.geom_xpos[3 * g];
  const double* xmat = &d.geom_xmat[9 * g];
  if (RayBox(xpos, xmat, &m.geom_size[3 * g], pnt, vec, nullptr, nullptr) < 0) return false;
  ToLocal(xpos, xmat, pnt, vec, lpnt, lvec);
  return true;
}

}  // namespace

double RayMesh(const Model& m, const Data& d, int geom, const double pnt[3], const double vec[3],
               double normal[3]) {
  double lpnt[3], lvec[3], b0[3], b1[3];
  if (!RayIntoGeomBox(m, d, geom, pnt, vec, normal, lpnt, lvec)) return -1;
  const double* xmat = &d.geom_xmat[9 * geom];

  // Every triangle, in the geom frame; the nearest hit wins.
  NormalPlaneBasis(lvec, b0, b1);
  const int mesh = m.geom_dataid[geom];
  const double* vert = &m.mesh_vert[3 * m.mesh_vertadr[mesh]];
  const int* face = &m.mesh_face[3 * m.mesh_faceadr[mesh]];
  double x = -1, local_normal[3] = {0, 0, 0};
  for (int f = 0; f < m.mesh_facenum[mesh]; f++) {
    double v[3][3];
    for (int k = 0; k < 3; k++) math::Copy3(v[k], vert + 3 * face[3 * f + k]);
    NearerTriangle(v, lpnt, lvec, b0, b1, &x, normal ? local_normal : nullptr);
  }
  if (normal && x >= 0) math::MulMatVec3(normal, xmat, local_normal);
  return x;
}

double RaySdf(const Model& m, const Data& d, int geom, const double pnt[3], const double vec[3],
              double normal[3]) {
  double lpnt[3], lvec[3], p[3];
  if (!RayIntoGeomBox(m, d, geom, pnt, vec, normal, lpnt, lvec)) return -1;
  const double* xmat = &d.geom_xmat[9 * geom];

  // March along the unit direction by the field's distance, at most 40 times, until
  // within 1e-7 of the surface (or 1e6 away from it).
  const SdfField field = SdfFieldOfGeom(m, d, geom);
  const int mesh = m.geom_dataid[geom];
  math::Normalize3(lvec);
  double total = 0;
  for (int i = 0; i < 40; i++) {
    for (int k = 0; k < 3; k++) p[k] = lpnt[k] + lvec[k] * total;
    double step = std::abs(SdfGeomDistance(m, field, mesh, p));
    total += step;
    if (step < 1e-7) {
      if (normal) {
        for (int k = 0; k < 3; k++) p[k] = lpnt[k] + lvec[k] * total;
        double local[3];
        SdfGeomGradient(m, field, mesh, local, p);
        math::Normalize3(local);
        math::MulMatVec3(normal, xmat, local);
      }
      return total;
    }
    if (step > 1e6) break;
  }
  return -1;
}

double RayHfield(const Model& m, const Data& d, int geom, const double pnt[3],
                 const double vec[3], double normal[3]) {
  ClearNormal(normal);
  const int h = m.geom_dataid[geom];
  HfieldGrid g{m.hfield_nrow[h], m.hfield_ncol[h], &m.hfield_size[4 * h],
               &m.hfield_data[m.hfield_adr[h]], 0, 0};
  g.dx = (2.0 * g.size[0]) / (g.ncol - 1);
  g.dy = (2.0 * g.size[1]) / (g.nrow - 1);
  const double* xpos = &d.geom_xpos[3 * geom];
  const double* xmat = &d.geom_xmat[9 * geom];

  // The base box below z = 0 and the top box holding the surface, in the geom frame.
  const double zaxis[3] = {xmat[2], xmat[5], xmat[8]};
  double base_size[3] = {g.size[0], g.size[1], g.size[3] * 0.5};
  double top_size[3] = {g.size[0], g.size[1], g.size[2] * 0.5};
  double base_pos[3], top_pos[3];
  for (int k = 0; k < 3; k++) {
    base_pos[k] = xpos[k] - zaxis[k] * g.size[3] * 0.5;
    top_pos[k] = xpos[k] + zaxis[k] * g.size[2] * 0.5;
  }
  double base_normal[3];
  double x = RayBox(base_pos, xmat, base_size, pnt, vec, nullptr, normal ? base_normal : nullptr);
  double all[6];
  double top = RayBox(top_pos, xmat, top_size, pnt, vec, all, nullptr);
  if (top < 0) {
    if (normal && x >= 0) math::Copy3(normal, base_normal);
    return x;
  }

  // The stretch of the ray inside the top box: from its entry (or the ray's start) to
  // its farthest face crossing.
  double lpnt[3], lvec[3];
  ToLocal(xpos, xmat, pnt, vec, lpnt, lvec);
  double seg[2] = {0, top};
  for (double a : all) {
    if (a > seg[1]) {
      seg[0] = top;
      seg[1] = a;
    }
  }
  double local_normal[3] = {0, 0, 0};
  if (normal && x >= 0) math::MulMatTVec3(local_normal, xmat, base_normal);
  HfieldTriangles(g, lpnt, lvec, seg, &x, normal ? local_normal : nullptr);
  HfieldSides(g, lpnt, lvec, all, &x, local_normal);
  if (normal && x >= 0) math::MulMatVec3(normal, xmat, local_normal);
  return x;
}

// ---------------------------------------------------------------- all geoms

namespace {

// True if the filter (or the geom's transparency) hides geom g from rays.
bool RayHidden(const Model& m, int g, const RayFilter& filter) {
  int body = m.geom_bodyid[g];
  if (body == filter.bodyexclude) return true;
  if (m.geom_rgba[4 * g + 3] == 0) return true;
  if (!filter.include_static && m.body_weldid[body] == 0) return true;
  if (!filter.geomgroup) return false;
  int group = std::min(kNGroup - 1, std::max(0, m.geom_group[g]));
  return filter.geomgroup[group] == 0;
}

}  // namespace

double Ray(const Model& m, const Data& d, const double pnt[3], const double vec[3],
           const RayFilter& filter, int* geomid, double normal[3]) {
  double best = -1, hit_normal[3];
  if (geomid) *geomid = -1;
  ClearNormal(normal);
  if (math::Norm3(vec) < kMinVal) return -1;
  for (int g = 0; g < m.ngeom; g++) {
    if (RayHidden(m, g, filter)) continue;
    double* n = normal ? hit_normal : nullptr;
    double x;
    switch (m.geom_type[g]) {
      case kGeomMesh: x = RayMesh(m, d, g, pnt, vec, n); break;
      case kGeomHfield: x = RayHfield(m, d, g, pnt, vec, n); break;
      case kGeomSdf: x = RaySdf(m, d, g, pnt, vec, n); break;
      default:
        x = RayPrimitive(&d.geom_xpos[3 * g], &d.geom_xmat[9 * g], &m.geom_size[3 * g], pnt, vec,
                         m.geom_type[g], n);
    }
    if (x >= 0 && (best < 0 || x < best)) {
      best = x;
      if (geomid) *geomid = g;
      if (normal) math::Copy3(normal, hit_normal);
    }
  }
  return best;
}

}  // namespace simlab
