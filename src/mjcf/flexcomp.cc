// The generated shapes of <flexcomp>: grid, circle, square, disc, box, cylinder and
// ellipsoid, with MuJoCo's point order, element order and texture coordinates
// (mjCFlexcomp::MakeGrid, MakeSquare, MakeBox).
#include <algorithm>
#include <cmath>

#include "compiler/orientation.h"
#include "math/elementary.h"
#include "mjcf/flexcomp.h"

namespace simlab::mjcf {

namespace {

constexpr double kPi = 3.14159265358979323846;

void AddPoint(FlexcompPoints* out, double x, double y, double z) {
  out->point.push_back(x);
  out->point.push_back(y);
  out->point.push_back(z);
}

// Texture coordinate (i / (n - 1)) in the precision each shape computes it in.
template <typename Real>
void AddTexcoord(FlexcompPoints* out, int i, int ni, int j, int nj) {
  out->texcoord.push_back(static_cast<float>(i / static_cast<Real>(std::max(ni - 1, 1))));
  out->texcoord.push_back(static_cast<float>(j / static_cast<Real>(std::max(nj - 1, 1))));
}

// A line of count[0] points (or a closed circle of count[0]-1 points; its sines and
// cosines are musl's, as MuJoCo's reference build computes them).
void MakeLine(const FlexcompShapeInput& in, FlexcompPoints* out) {
  const auto& count = in.count;
  for (int ix = 0; ix < count[0]; ix++) {
    if (in.type == kFcompCircle) {
      if (ix >= count[0] - 1) continue;
      double theta = 2 * kPi / (count[0] - 1);
      double radius = in.spacing[0] / math::Sin(theta / 2) / 2;
      AddPoint(out, radius * math::Cos(theta * ix), radius * math::Sin(theta * ix), 0);
      out->element.push_back(ix);
      out->element.push_back(ix == count[0] - 2 ? 0 : ix + 1);
    } else {
      AddPoint(out, in.spacing[0] * (ix - 0.5 * (count[0] - 1)), 0, 0);
      if (ix < count[0] - 1) {
        out->element.push_back(ix);
        out->element.push_back(ix + 1);
      }
    }
  }
}

// A count[0] x count[1] sheet of points, two triangles per cell (flipped in two
// quadrants for a disc, so the radial projection keeps them well shaped).
void MakeSheet(const FlexcompShapeInput& in, bool needtex, FlexcompPoints* out) {
  const auto& count = in.count;
  for (int ix = 0; ix < count[0]; ix++) {
    for (int iy = 0; iy < count[1]; iy++) {
      int quad2tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
      double pos[2] = {in.spacing[0] * (ix - 0.5 * (count[0] - 1)),
                       in.spacing[1] * (iy - 0.5 * (count[1] - 1))};
      AddPoint(out, pos[0], pos[1], 0);
      if (needtex) AddTexcoord<double>(out, ix, count[0], iy, count[1]);

      // The disc's flipped quadrants.
      bool flip = (pos[0] < -compiler::kEps && pos[1] > -compiler::kEps) ||
                  (pos[0] > -compiler::kEps && pos[1] < -compiler::kEps);
      if (flip && in.type == kFcompDisc) {
        quad2tri[0][2] = 3;
        quad2tri[1][0] = 1;
      }

      // The cell's two triangles (numbered as a block's bottom layer, as MuJoCo does).
      if (ix < count[0] - 1 && iy < count[1] - 1) {
        int vert[4] = {GridId(count, ix, iy, 0), GridId(count, ix + 1, iy, 0),
                       GridId(count, ix + 1, iy + 1, 0), GridId(count, ix, iy + 1, 0)};
        for (const auto& tri : quad2tri) {
          for (int v : tri) out->element.push_back(vert[v]);
        }
      }
    }
  }
}

// A count[0] x count[1] x count[2] block of points, six tetrahedra per cell.
void MakeBlock(const FlexcompShapeInput& in, bool needtex, FlexcompPoints* out) {
  const auto& count = in.count;
  static const int kCubeToTets[6][4] = {{0, 3, 1, 7}, {0, 1, 4, 7}, {1, 3, 2, 7},
                                        {1, 2, 6, 7}, {1, 5, 4, 7}, {1, 6, 5, 7}};
  auto id = [&](int ix, int iy, int iz) { return GridId(count, ix, iy, iz); };
  for (int ix = 0; ix < count[0]; ix++) {
    for (int iy = 0; iy < count[1]; iy++) {
      for (int iz = 0; iz < count[2]; iz++) {
        AddPoint(out, in.spacing[0] * (ix - 0.5 * (count[0] - 1)),
                 in.spacing[1] * (iy - 0.5 * (count[1] - 1)),
                 in.spacing[2] * (iz - 0.5 * (count[2] - 1)));
        if (needtex) AddTexcoord<float>(out, ix, count[0], iy, count[1]);
        if (ix == count[0] - 1 || iy == count[1] - 1 || iz == count[2] - 1) continue;

        // The cell's corners, bottom face then top face, and its tetrahedra.
        int vert[8] = {id(ix, iy, iz),         id(ix + 1, iy, iz),
                       id(ix + 1, iy + 1, iz), id(ix, iy + 1, iz),
                       id(ix, iy, iz + 1),     id(ix + 1, iy, iz + 1),
                       id(ix + 1, iy + 1, iz + 1), id(ix, iy + 1, iz + 1)};
        for (const auto& tet : kCubeToTets) {
          for (int v : tet) out->element.push_back(vert[v]);
        }
      }
    }
  }
}

// The point id of a surface grid point of a closed box, side by side (MuJoCo's BoxID;
// id 0 is the centre point of a 3D box).
int BoxId(const std::array<int, 3>& count, int ix, int iy, int iz) {
  int top = count[0] * count[1];
  int side_y = count[0] * (count[2] - 2);
  int side_x = (count[1] - 2) * (count[2] - 2);
  if (iz == 0) return ix * count[1] + iy + 1;
  if (iz == count[2] - 1) return top + ix * count[1] + iy + 1;
  if (iy == 0) return 2 * top + ix * (count[2] - 2) + iz;
  if (iy == count[1] - 1) return 2 * top + side_y + ix * (count[2] - 2) + iz;
  if (ix == 0) return 2 * top + 2 * side_y + (iy - 1) * (count[2] - 2) + iz;
  return 2 * top + 2 * side_y + side_x + (iy - 1) * (count[2] - 2) + iz;
}

// A surface grid point projected onto the box, cylinder or ellipsoid (BoxProject).
void BoxProject(const FlexcompShapeInput& in, int ix, int iy, int iz, double pos[3]) {
  const auto& count = in.count;
  pos[0] = 2.0 * ix / (count[0] - 1) - 1;
  pos[1] = 2.0 * iy / (count[1] - 1) - 1;
  pos[2] = 2.0 * iz / (count[2] - 1) - 1;
  double size[3] = {0.5 * in.spacing[0] * (count[0] - 1), 0.5 * in.spacing[1] * (count[1] - 1),
                    0.5 * in.spacing[2] * (count[2] - 1)};
  if (in.type == kFcompCylinder) {
    double l0 = std::max(std::abs(pos[0]), std::abs(pos[1]));
    compiler::NormalizeVec(pos, 2);
    pos[0] *= size[0] * l0;
    pos[1] *= size[1] * l0;
    pos[2] *= size[2];
    return;
  }
  if (in.type == kFcompEllipsoid) compiler::NormalizeVec(pos, 3);
  for (int k = 0; k < 3; k++) pos[k] *= size[k];
}

// The surface points of a box-like shape, side by side: the two z faces, then the
// two y faces without their z edges, then the two x faces without their y and z edges.
// idx maps grid coordinates to point ids (2D shapes have no centre point).
void BoxSurfacePoints(const FlexcompShapeInput& in, bool needtex, std::vector<int>* idx,
                      FlexcompPoints* out) {
  const auto& count = in.count;
  int n = 0;
  auto add = [&](int ix, int iy, int iz, int tu, int nu, int tv, int nv) {
    double pos[3];
    BoxProject(in, ix, iy, iz, pos);
    AddPoint(out, pos[0], pos[1], pos[2]);
    (*idx)[GridId(count, ix, iy, iz)] = n++;
    if (needtex) AddTexcoord<float>(out, tu, nu, tv, nv);
  };
  // (a surface is open at the top: no top side, and the other sides reach its edge)
  bool open = in.dim == 2;
  int zend = open ? count[2] : count[2] - 1;
  for (int iz = 0; iz < count[2]; iz += count[2] - 1) {
    if (open && iz != 0) continue;
    for (int ix = 0; ix < count[0]; ix++) {
      for (int iy = 0; iy < count[1]; iy++) add(ix, iy, iz, ix, count[0], iy, count[1]);
    }
  }
  for (int iy = 0; iy < count[1]; iy += count[1] - 1) {
    for (int ix = 0; ix < count[0]; ix++) {
      for (int iz = 1; iz < zend; iz++) add(ix, iy, iz, ix, count[0], iz, count[2]);
    }
  }
  for (int ix = 0; ix < count[0]; ix += count[0] - 1) {
    for (int iy = 1; iy < count[1] - 1; iy++) {
      for (int iz = 1; iz < zend; iz++) add(ix, iy, iz, iy, count[1], iz, count[2]);
    }
  }
}

// Two elements per surface cell with corners a, b, c, d (in the side's order): for a
// 3D shape tetrahedra from the centre point 0, else the triangles t1, t2.
void AddCell(bool solid, const int tet[4], const int tri[6], FlexcompPoints* out) {
  if (solid) {
    const int order[8] = {0, tet[0], tet[1], tet[2], 0, tet[0], tet[3], tet[2]};
    out->element.insert(out->element.end(), order, order + 8);
  } else {
    out->element.insert(out->element.end(), tri, tri + 6);
  }
}

// The elements of a box-like shape, side by side in the order of its points.
void BoxSurfaceElements(const FlexcompShapeInput& in, const std::vector<int>& idx,
                        FlexcompPoints* out) {
  const auto& count = in.count;
  bool solid = in.dim == 3;
  auto lin = [&](int ix, int iy, int iz) { return idx[GridId(count, ix, iy, iz)]; };
  auto box = [&](int ix, int iy, int iz) { return BoxId(count, ix, iy, iz); };
  // z sides
  for (int iz = 0; iz < count[2]; iz += count[2] - 1) {
    if (!solid && iz != 0) continue;  // (open at the top)
    int s1 = iz == 0 ? 1 : 0, s2 = iz == 0 ? 0 : 1;
    for (int ix = 0; ix < count[0] - 1; ix++) {
      for (int iy = 0; iy < count[1] - 1; iy++) {
        int tet[4] = {box(ix, iy, iz), box(ix + 1, iy, iz), box(ix + 1, iy + 1, iz),
                      box(ix, iy + 1, iz)};
        int tri[6] = {lin(ix, iy, iz), lin(ix + 1, iy + s1, iz), lin(ix + 1, iy + s2, iz),
                      lin(ix, iy, iz), lin(ix + s2, iy + 1, iz), lin(ix + s1, iy + 1, iz)};
        AddCell(solid, tet, tri, out);
      }
    }
  }
  // y sides
  for (int iy = 0; iy < count[1]; iy += count[1] - 1) {
    for (int ix = 0; ix < count[0] - 1; ix++) {
      for (int iz = 0; iz < count[2] - 1; iz++) {
        int ix0 = iy == 0 ? ix : ix + 1, dx = iy == 0 ? 1 : -1;
        int tet[4] = {box(ix, iy, iz), box(ix + 1, iy, iz), box(ix + 1, iy, iz + 1),
                      box(ix, iy, iz + 1)};
        int tri[6] = {lin(ix0, iy, iz), lin(ix0 + dx, iy, iz), lin(ix0 + dx, iy, iz + 1),
                      lin(ix0, iy, iz), lin(ix0 + dx, iy, iz + 1), lin(ix0, iy, iz + 1)};
        AddCell(solid, tet, tri, out);
      }
    }
  }
  // x sides
  for (int ix = 0; ix < count[0]; ix += count[0] - 1) {
    for (int iy = 0; iy < count[1] - 1; iy++) {
      for (int iz = 0; iz < count[2] - 1; iz++) {
        int iy0 = ix != 0 ? iy : iy + 1, dy = ix != 0 ? 1 : -1;
        int tet[4] = {box(ix, iy, iz), box(ix, iy + 1, iz), box(ix, iy + 1, iz + 1),
                      box(ix, iy, iz + 1)};
        int tri[6] = {lin(ix, iy0, iz), lin(ix, iy0 + dy, iz), lin(ix, iy0 + dy, iz + 1),
                      lin(ix, iy0, iz), lin(ix, iy0 + dy, iz + 1), lin(ix, iy0, iz + 1)};
        AddCell(solid, tet, tri, out);
      }
    }
  }
}

// A box, cylinder or ellipsoid: its surface open at the top (dim 2, MuJoCo's default of
// MakeBox), or tetrahedra from a centre point to the closed surface's cells (dim 3).
void MakeBoxShape(const FlexcompShapeInput& in, bool needtex, FlexcompPoints* out) {
  if (in.dim == 3) AddPoint(out, 0, 0, 0);
  if (needtex) {
    out->texcoord.push_back(0);
    out->texcoord.push_back(0);
  }
  std::vector<int> idx(static_cast<size_t>(in.count[0]) * in.count[1] * in.count[2]);
  BoxSurfacePoints(in, needtex, &idx, out);
  BoxSurfaceElements(in, idx, out);
}

// The square's points pulled onto a disc: each point keeps its direction and moves to
// its square "radius" (the larger coordinate) times the disc's half sizes.
void ProjectToDisc(const FlexcompShapeInput& in, FlexcompPoints* out) {
  double size[2] = {0.5 * in.spacing[0] * (in.count[0] - 1), 0.5 * in.spacing[1] * (in.count[1] - 1)};
  for (size_t i = 0; i + 2 < out->point.size(); i += 3) {
    double* pos = out->point.data() + i;
    double l0 = std::max(std::abs(pos[0]), std::abs(pos[1]));
    compiler::NormalizeVec(pos, 2);
    pos[0] *= size[0] * l0;
    pos[1] *= size[1] * l0;
  }
}

}  // namespace

std::string MakeFlexcompShape(const FlexcompShapeInput& in, FlexcompPoints* out) {
  out->dim = in.dim;
  bool needtex = in.texcoord_given ? false : in.has_material;
  switch (in.type) {
    case kFcompGrid:
    case kFcompCircle:
      if (in.dim == 1) MakeLine(in, out);
      else if (in.dim == 2) MakeSheet(in, needtex, out);
      else MakeBlock(in, needtex, out);
      if (out->element.empty()) return "No elements were created in grid";
      return "";
    case kFcompSquare:
    case kFcompDisc:
      out->dim = 2;
      MakeSheet(in, needtex, out);
      if (out->element.empty()) return "No elements were created in grid";
      if (in.type == kFcompDisc) ProjectToDisc(in, out);
      return "";
    case kFcompBox:
    case kFcompCylinder:
    case kFcompEllipsoid:
      MakeBoxShape(in, needtex, out);
      return "";
    default:
      return "Unknown flexcomp type";
  }
}

}  // namespace simlab::mjcf
