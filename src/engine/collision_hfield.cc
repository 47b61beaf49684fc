// Height fields against convex geoms (MuJoCo's mjc_ConvexHField) and against flex
// elements (mjc_HFieldElem, whose shape collision_flex_narrow.cc builds).
//
// The height field is a grid of elevations; each grid cell is split into two triangles,
// and each triangle, extruded down to the field's base, is a convex prism. The convex
// shape is expressed in the height field's frame, its bounding box picks the cells below
// it, and GJK/EPA (collision_gjk.cc) runs once per prism: every penetrating prism gives
// one contact, in the order of the grid walk (rows, then columns, then the two triangles
// of a cell), at most kMaxContactPair of them.
//
// Margins as MuJoCo: the prisms' tops are raised by the margin, the shape is inflated by
// half the margin, and the reported distance is the penetration of these inflated shapes
// (no margin is added back).
#include <algorithm>
#include <cmath>

#include "engine/collision.h"
#include "engine/collision_gjk.h"
#include "math/math.h"

namespace simlab {

namespace {

using ccd::ConvexShape;

// One height field as the prisms need it.
struct HFieldGrid {
  int nrow, ncol;
  const double* size;  // x and y half-extents, top z, base depth
  const double* data;  // elevations in [0, 1], row-major (row = y, column = x)
  double dx, dy;       // grid spacing

  double X(int col) const { return dx * col - size[0]; }
  double Y(int row) const { return dy * row - size[1]; }
  double Z(int row, int col) const { return data[row * ncol + col] * size[2]; }
};

HFieldGrid GridOf(const Model& m, int g) {
  int h = m.geom_dataid[g];
  HFieldGrid grid;
  grid.nrow = m.hfield_nrow[h];
  grid.ncol = m.hfield_ncol[h];
  grid.size = &m.hfield_size[4 * h];
  grid.data = &m.hfield_data[m.hfield_adr[h]];
  grid.dx = (2.0 * grid.size[0]) / (grid.ncol - 1);
  grid.dy = (2.0 * grid.size[1]) / (grid.nrow - 1);
  return grid;
}

// ---------------------------------------------------------------- prisms

// A triangle of the grid extruded to the base: vertices 0-2 at depth -size[3], 3-5
// above them at their elevation plus the margin. Vertices arrive one grid point at a
// time along a strip of two rows; each new one pushes out the oldest.
struct Prism {
  double v[6][3] = {};
};

void PushGridPoint(Prism* p, const HFieldGrid& grid, int row, int col, double margin) {
  // shift the bottom and the top triangles by one vertex
  for (int k : {0, 1, 3, 4}) math::Copy3(p->v[k], p->v[k + 1]);

  // the new vertex last (the bottom one keeps the base depth)
  p->v[2][0] = p->v[5][0] = grid.X(col);
  p->v[2][1] = p->v[5][1] = grid.Y(row);
  p->v[5][2] = grid.Z(row, col) + margin;
}

// The prism's mean vertex (the starting point of GJK).
void PrismCentre(const Prism& p, double* centre) {
  math::Zero3(centre);
  for (const double* v : p.v) {
    for (int k = 0; k < 3; k++) centre[k] += v[k];
  }
  math::Scale3(centre, centre, 1.0 / 6.0);
}

// Support of a prism (its six vertices in shape->vert): the best of the bottom triangle
// when dir points down, else of the top triangle; the first of equals wins.
void PrismSupport(double res[3], ConvexShape* s, const double dir[3]) {
  int first = dir[2] < 0 ? 0 : 3;
  int ibest = first;
  double best = math::Dot3(s->vert + 3 * first, dir);
  for (int i = first + 1; i < first + 3; i++) {
    double proj = math::Dot3(s->vert + 3 * i, dir);
    if (proj > best) {
      best = proj;
      ibest = i;
    }
  }
  math::Copy3(res, s->vert + 3 * ibest);
}

// The prism as a convex shape of the hfield geom g (no margin of its own: it is in the
// raised top).
ConvexShape PrismShape(const Prism& p, int g) {
  ConvexShape s;
  s.geom = g;
  s.type = kGeomHfield;
  s.support = PrismSupport;
  s.vert = p.v[0];
  s.nvert = 6;
  return s;
}

// ---------------------------------------------------------------- early outs

// The geom's bounding sphere (grown by the margin) misses the field's box.
bool SphereMissesBox(const HFieldGrid& grid, const double* pos, double radius) {
  const double* size = grid.size;
  return size[0] < pos[0] - radius || -size[0] > pos[0] + radius ||
         size[1] < pos[1] - radius || -size[1] > pos[1] + radius ||
         size[2] < pos[2] - radius || -size[3] > pos[2] + radius;
}

// The geom's axis-aligned box in the field's frame, from its support points along +x,
// -x, +y, -y, +z, -z (in this order: mesh supports warm-start from the previous one).
struct Bounds {
  double lo[3], hi[3];
};

Bounds SupportBounds(ConvexShape* s) {
  Bounds b;
  for (int axis = 0; axis < 3; axis++) {
    double dir[3] = {0, 0, 0}, res[3];
    dir[axis] = 1;
    s->support(res, s, dir);
    b.hi[axis] = res[axis];
    dir[axis] = -1;
    s->support(res, s, dir);
    b.lo[axis] = res[axis];
  }
  return b;
}

bool BoundsMissBox(const HFieldGrid& grid, const Bounds& b, double margin) {
  const double* size = grid.size;
  return b.lo[0] - margin > size[0] || b.hi[0] + margin < -size[0] ||
         b.lo[1] - margin > size[1] || b.hi[1] + margin < -size[1] ||
         b.lo[2] - margin > size[2] || b.hi[2] + margin < -size[3];
}

// The grid points under the shape's box: columns [cmin, cmax], rows [rmin, rmax].
struct SubGrid {
  int cmin, cmax, rmin, rmax;
};

// A whole grid coordinate as an int, clamped to [lo, hi] first: a double outside int's
// range (under a huge geom) or NaN has no int value. Starts are clamped to [0, n] and
// ends to [-1, n - 1] for n grid points, so an empty sub-grid stays empty.
int GridIndex(double whole, int lo, int hi) {
  if (!(whole > lo)) return lo;  // NaN too
  if (whole > hi) return hi;
  return static_cast<int>(whole);
}

SubGrid CellsUnder(const HFieldGrid& grid, const Bounds& b) {
  const double* size = grid.size;
  auto scaled = [](double v, double half, int n) { return (v + half) / (2.0 * half) * (n - 1); };
  SubGrid s;
  int ncol = grid.ncol, nrow = grid.nrow;
  s.cmin = GridIndex(std::floor(scaled(b.lo[0], size[0], ncol)), 0, ncol);
  s.cmax = GridIndex(std::ceil(scaled(b.hi[0], size[0], ncol)), -1, ncol - 1);
  s.rmin = GridIndex(std::floor(scaled(b.lo[1], size[1], nrow)), 0, nrow);
  s.rmax = GridIndex(std::ceil(scaled(b.hi[1], size[1], nrow)), -1, nrow - 1);
  return s;
}

// ---------------------------------------------------------------- one prism

// GJK/EPA between the prism and the shape (both in the field's frame). On penetration
// writes the contact in world coordinates (field pose pos1, mat1) and returns true.
bool PrismContact(const Model& m, const Prism& p, int g1, ConvexShape* shape,
                  const double* pos1, const double* mat1, Contact* con) {
  ConvexShape prism = PrismShape(p, g1);
  PrismCentre(p, prism.pos);
  ccd::CcdConfig config = ccd::ModelConfig(m, 1, 0);
  ccd::CcdStatus status;
  double dist = ccd::Collide(config, &status, &prism, shape);
  if (!(dist < 0)) return false;

  // normal from the prism's witness point to the shape's, contact halfway between
  double normal[3], mid[3];
  math::Sub3(normal, status.x1, status.x2);
  math::Normalize3(normal);
  for (int k = 0; k < 3; k++) mid[k] = 0.5 * (status.x1[k] + status.x2[k]);
  con->dist = dist;
  math::MulMatVec3(con->frame, mat1, normal);
  math::MulMatVec3(con->pos, mat1, mid);
  for (int k = 0; k < 3; k++) con->pos[k] += pos1[k];
  math::Zero3(con->frame + 3);
  return true;
}

}  // namespace

// ---------------------------------------------------------------- entry points

int CollideHFieldShape(const Model& m, const Data& d, Contact* con, int g1,
                       ccd::ConvexShape* shape, const double lo[3], const double hi[3],
                       double margin) {
  const double* pos1 = &d.geom_xpos[3 * g1];
  const double* mat1 = &d.geom_xmat[9 * g1];
  HFieldGrid grid = GridOf(m, g1);

  // the shape's box must reach the field
  Bounds bounds;
  math::Copy3(bounds.lo, lo);
  math::Copy3(bounds.hi, hi);
  if (BoundsMissBox(grid, bounds, margin)) return 0;
  SubGrid sub = CellsUnder(grid, bounds);
  // no column under the shape (it overhangs an edge within the margin): no prism, and
  // the walk's first points would lie outside the grid
  if (sub.cmin > sub.cmax) return 0;

  // walk the strip of each row pair: point (r+1, c) then (r, c) closes two prisms
  Prism prism;
  for (int k = 0; k < 3; k++) prism.v[k][2] = -grid.size[3];
  int ncon = 0;
  for (int r = sub.rmin; r < sub.rmax; r++) {
    PushGridPoint(&prism, grid, r + 1, sub.cmin, margin);
    PushGridPoint(&prism, grid, r, sub.cmin, margin);
    for (int c = sub.cmin + 1; c <= sub.cmax; c++) {
      for (int row : {r + 1, r}) {
        PushGridPoint(&prism, grid, row, c, margin);

        // prisms whose top lies below the shape cannot touch it
        const double(*v)[3] = prism.v;
        if (v[3][2] < bounds.lo[2] && v[4][2] < bounds.lo[2] && v[5][2] < bounds.lo[2]) {
          continue;
        }
        if (PrismContact(m, prism, g1, shape, pos1, mat1, con + ncon) &&
            ++ncon >= kMaxContactPair) {
          return ncon;
        }
      }
    }
  }
  return ncon;
}

int CollideHFieldConvex(const Model& m, const Data& d, Contact* con, int g1, int g2,
                        double margin) {
  const double* pos1 = &d.geom_xpos[3 * g1];
  const double* mat1 = &d.geom_xmat[9 * g1];
  HFieldGrid grid = GridOf(m, g1);

  // the geom's centre in the field's frame; its bounding sphere must reach the field
  double dif[3], pos[3];
  math::Sub3(dif, &d.geom_xpos[3 * g2], pos1);
  math::MulMatTVec3(pos, mat1, dif);
  if (SphereMissesBox(grid, pos, m.geom_rbound[g2] + margin)) return 0;

  // the geom as a shape posed in the field's frame, its box from its support points
  // (without the margin, which inflates it for GJK only)
  ConvexShape geom = ccd::GeomShape(m, d, g2, 0);
  math::Copy3(geom.pos, pos);
  math::MulMatTMat3(geom.mat, mat1, &d.geom_xmat[9 * g2]);
  Bounds bounds = SupportBounds(&geom);
  geom.margin = margin;
  return CollideHFieldShape(m, d, con, g1, &geom, bounds.lo, bounds.hi, margin);
}

}  // namespace simlab
