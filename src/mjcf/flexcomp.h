// <flexcomp>: MuJoCo's generator of flexes. The reader expands one into a flex, the
// bodies and joints that carry its vertices, and (optionally) an edge equality, as
// MuJoCo's parser does (mjCFlexcomp::Make).
//
// This header holds the shapes' points and elements (flexcomp.cc for the generated
// shapes, flexcomp_file.cc for the mesh and GMSH files).
#ifndef SIMLAB_MJCF_FLEXCOMP_H_
#define SIMLAB_MJCF_FLEXCOMP_H_

#include <array>
#include <string>
#include <vector>

#include "mjcf/assets.h"
#include "mjcf/spec.h"

namespace simlab::mjcf {

// The flexcomp types (mjtFcompType) and dof types (mjtDof), in MuJoCo's order.
enum FlexcompType : int {
  kFcompGrid = 0, kFcompBox, kFcompCylinder, kFcompEllipsoid, kFcompSquare, kFcompDisc,
  kFcompCircle, kFcompMesh, kFcompGmsh, kFcompDirect
};
enum FlexcompDof : int {
  kFcompDofFull = 0, kFcompDofRadial, kFcompDofTrilinear, kFcompDofQuadratic, kFcompDof2D
};

// The points (3 per point) and elements (dim+1 point ids each) of a flexcomp, with
// optional texture coordinates (2 per point) and per-element texture ids. `dim` is the
// flex's dimension; a shape may set it (square and disc are 2D, a GMSH file says).
struct FlexcompPoints {
  int dim = 2;
  std::vector<double> point;
  std::vector<int> element;
  std::vector<float> texcoord;
  std::vector<int> elemtexcoord;
};

// The point id of grid coordinates in a count[0] x count[1] sheet or count[0] x count[1]
// x count[2] block of points, x slowest (MuJoCo's GridID).
inline int GridId(const std::array<int, 3>& count, int ix, int iy) { return ix * count[1] + iy; }
inline int GridId(const std::array<int, 3>& count, int ix, int iy, int iz) {
  return ix * count[1] * count[2] + iy * count[2] + iz;
}

// What a generated shape needs: its type, dimension, grid counts and spacing, and
// whether it makes texture coordinates (a material is named and none were written).
struct FlexcompShapeInput {
  int type = kFcompGrid;
  int dim = 2;
  std::array<int, 3> count = {10, 10, 10};
  std::array<double, 3> spacing = {0.02, 0.02, 0.02};
  bool has_material = false;
  bool texcoord_given = false;
};

// The points and elements of a grid, circle, square, disc, box, cylinder or ellipsoid
// (MuJoCo's MakeGrid, MakeSquare, MakeBox). Returns "" or MuJoCo's error message.
std::string MakeFlexcompShape(const FlexcompShapeInput& in, FlexcompPoints* out);

// A flexcomp as written: MuJoCo's mjCFlexcomp before Make.
struct FlexcompSpec {
  Source src;
  std::string name;
  int type = kFcompGrid;
  int dof = kFcompDofFull;
  std::array<int, 3> count = {10, 10, 10};
  std::array<int, 3> cellcount = {-1, -1, -1};  // cells of the node lattice (-1: not given)
  std::array<double, 3> spacing = {0.02, 0.02, 0.02};
  std::array<double, 3> scale = {1, 1, 1};
  std::array<double, 3> origin = {0, 0, 0};
  double mass = 1, inertiabox = 0.005;
  bool rigid = false;
  std::string file;  // resolved path
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 4> quat = {1, 0, 0, 0};
  int equality = 0;  // 0 none, 1 edges (kEqFlex), 2 vertices (kEqFlexVert), 3 strain
  EqualitySpec eq;   // its solref and solimp
  std::vector<int> pinid, pinrange, pingrid, pingridrange;
  FlexSpec flex;
  FlexcompPoints shape;
  std::vector<bool> pinned;
};

// The mesh or GMSH file of a flexcomp, read from `path` (already resolved against the
// model's folder and meshdir; `assets` holds files given in memory, or is null).
// type="mesh": a surface mesh (STL or OBJ, as simlab's <mesh> reads them). dim 2 takes its
// faces as triangles; dim 3 makes a tetrahedron from `origin` to each face of positive
// volume, the origin becoming point 0 (MuJoCo's MakeMesh). texcoord and elemtexcoord
// come from the mesh when it has texture coordinates.
// type="gmsh": a GMSH 4.1 or 2.2 file, ascii or binary, of lines (4.1), triangles or
// tetrahedra; sets out->dim from the file's elements and appends its nodes and elements
// to any points and elements written (MuJoCo's LoadGMSH). A mesh file's texture
// coordinates replace any written; without them the written ones stay.
// Return "" on success, else the error message (MuJoCo's wording where it has one); a
// mesh file the mesh reader refuses throws simlab::Error at `src`, the flexcomp.
std::string LoadFlexcompMesh(const Source& src, const std::string& path, const AssetFiles* assets,
                             int dim, const std::array<double, 3>& origin, FlexcompPoints* out);
std::string LoadFlexcompGmsh(const std::string& path, const AssetFiles* assets,
                             FlexcompPoints* out);

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_FLEXCOMP_H_
