// Interpolated flexes made of cells (MuJoCo 3.12's flexcomp cellcount and shells).
//
// The nodes of such a flex form a lattice of (cx order + 1) x (cy order + 1) x
// (cz order + 1) points over the flex's box, x slowest, shared by its cx cy cz cells: a
// vertex moves with the (order + 1)^3 nodes of the cell that holds it (flex_vert0 is its
// place in the box). A volume flex is elastic in every cell that holds elements; a shell
// (an interpolated flex with 2D elasticity, flex_interp = -order) only on the lattice's
// boundary, its 2 (cy cz + cx cz + cx cy) face elements of (order + 1)^2 nodes, and its
// interior nodes follow the boundary by transfinite interpolation (they are pinned).
//
// flex_stiffness holds one (3 npe)^2 matrix per element (cell or face; npe its nodes),
// zero for an empty cell; with strain equality instead [neig, sqrt(lambda) v, ...] of
// the matrix's stiff eigenmodes. A shell's flex_bending holds [nedge, then per edge
// between two faces: face A, face B, A's and B's edge midpoints (2 each), stiffness,
// rest normal jump (3)].
//
// Flexes with one cell, no shell and no strain equality keep MuJoCo 3.5.1's layout
// (21 numbers per element, the node matrix in the first ones) and code paths.
#ifndef SIMLAB_ENGINE_FLEX_CELLS_H_
#define SIMLAB_ENGINE_FLEX_CELLS_H_

#include <array>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// Numbers per shell bending edge in flex_bending (after the leading edge count).
inline constexpr int kFlexShellBendSize = 10;
// The edge equality that keeps an interpolated flex's strain (flex_edgeequality 3).
inline constexpr int kFlexEdgeStrain = 3;

// The node lattice of a flex with cells.
struct FlexLattice {
  std::array<int, 3> cells = {1, 1, 1};
  int order = 1;
  bool shell = false;

  int Nodes(int axis) const { return cells[axis] * order + 1; }
  int Node(int i, int j, int k) const { return i * Nodes(1) * Nodes(2) + j * Nodes(2) + k; }
  int NodesPerCell() const { return (order + 1) * (order + 1) * (order + 1); }
  int NodesPerFace() const { return (order + 1) * (order + 1); }
  int NodesPerElement() const { return shell ? NodesPerFace() : NodesPerCell(); }
  int CellCount() const { return cells[0] * cells[1] * cells[2]; }
  int FaceCount() const {
    return 2 * (cells[1] * cells[2] + cells[0] * cells[2] + cells[0] * cells[1]);
  }
  int ElementCount() const { return shell ? FaceCount() : CellCount(); }
};

// The lattice of interpolated flex f.
FlexLattice FlexLatticeOf(const Model& m, int f);

// Does interpolated flex f follow MuJoCo 3.12's cells: more than one cell, a shell, or
// strain equality? (Other interpolated flexes follow MuJoCo 3.5.1.)
bool FlexHasCells(const Model& m, int f);

// The lattice ids of cell (ci, cj, ck)'s nodes, x slowest.
void FlexCellNodes(const FlexLattice& g, int ci, int cj, int ck, int* ids);

// Face element fe of a shell (sides x = 0, x = max, y = 0, y = max, z = 0, z = max in
// turn, each row by row): the lattice ids of its nodes, its first in-plane axis
// ((normal + 1) % 3) slowest; returns the side's normal axis.
int FlexFaceNodes(const FlexLattice& g, int fe, int* ids);

// The lattice ids of element fe's nodes: a cell's (fe = (ci cy + cj) cz + ck, its nodes
// as FlexCellNodes) or a shell's face's (as FlexFaceNodes); returns a face's normal axis,
// -1 for a cell.
int FlexElementNodes(const FlexLattice& g, int fe, int* ids);

// The cell holding parametric point coord (in [0, 1]^3 of the box), the point's place in
// that cell (local, clipped to [0, 1]) and, if ids is not null, the cell's node ids
// (MuJoCo's mju_cellLookup).
void FlexCellLookup(const double coord[3], const int cells[3], int order, double local[3],
                    int* ids);

// The weights of a cell's nodes at local (x slowest), each the product of the axes'
// shape functions taken x first (MuJoCo's mju_evalBasisArray).
void FlexCellWeights(const double local[3], int order, double* weight);

// Moves a shell's interior nodes (3 numbers each in xpos, the whole lattice) to the
// transfinite interpolation of its boundary (MuJoCo's mju_shellTrackInterior).
void FlexShellInterior(const FlexLattice& g, double* xpos);

// The boundary nodes an interior node (i, j, k) of a shell follows, with their weights
// times w, each passed to add(node, weight) in MuJoCo's order (mju_shellTFIWeights).
template <typename Add>
void FlexShellInteriorWeights(const FlexLattice& g, int i, int j, int k, double w, Add add) {
  int nx = g.Nodes(0), ny = g.Nodes(1), nz = g.Nodes(2);
  double s = static_cast<double>(i) / (nx - 1);
  double t = static_cast<double>(j) / (ny - 1);
  double u = static_cast<double>(k) / (nz - 1);
  // The six faces.
  add(g.Node(0, j, k), w * (1 - s));
  add(g.Node(nx - 1, j, k), w * s);
  add(g.Node(i, 0, k), w * (1 - t));
  add(g.Node(i, ny - 1, k), w * t);
  add(g.Node(i, j, 0), w * (1 - u));
  add(g.Node(i, j, nz - 1), w * u);
  // The twelve edges, taken off.
  add(g.Node(i, 0, 0), -w * (1 - t) * (1 - u));
  add(g.Node(i, 0, nz - 1), -w * (1 - t) * u);
  add(g.Node(i, ny - 1, 0), -w * t * (1 - u));
  add(g.Node(i, ny - 1, nz - 1), -w * t * u);
  add(g.Node(0, j, 0), -w * (1 - s) * (1 - u));
  add(g.Node(0, j, nz - 1), -w * (1 - s) * u);
  add(g.Node(nx - 1, j, 0), -w * s * (1 - u));
  add(g.Node(nx - 1, j, nz - 1), -w * s * u);
  add(g.Node(0, 0, k), -w * (1 - s) * (1 - t));
  add(g.Node(0, ny - 1, k), -w * (1 - s) * t);
  add(g.Node(nx - 1, 0, k), -w * s * (1 - t));
  add(g.Node(nx - 1, ny - 1, k), -w * s * t);
  // The eight corners, put back.
  for (int a = 0; a < 2; a++) {
    for (int b = 0; b < 2; b++) {
      for (int c = 0; c < 2; c++) {
        double ws = a ? s : 1 - s, wt = b ? t : 1 - t, wu = c ? u : 1 - u;
        add(g.Node(a * (nx - 1), b * (ny - 1), c * (nz - 1)), w * ws * wt * wu);
      }
    }
  }
}

// World positions of flex f's nodes (3 each): their bodies' origins, or offsets carried
// by their bodies; a shell's interior nodes then follow its boundary. If vel is not
// null, also their velocities (MuJoCo's mju_flexGatherState).
void FlexCellNodeState(const Model& m, const Data& d, int f, double* xpos, double* vel);

// The corotated frame of one element from its nodes' positions (a cell's, x slowest, or
// a face's, with its normal axis): the inverse of the rotation nearest the deformation
// gradient at the element's centre, found from the identity.
void FlexCellRotation(int order, const double* xpos, double quat[4]);
void FlexFaceRotation(int order, int normal_axis, const double* xpos, double quat[4]);

// The tangents of a face element along its two parametric axes at local, and their
// cross product (unnormalized), from its nodes' positions (mju_flexFaceNormal2D).
void FlexFaceNormal(int order, const double* xpos, const double local[2], double normal[3],
                    double t1[3], double t2[3]);

// Adds flex f's elasticity (a flex with cells) into qfrc_spring and qfrc_damper:
// each element's stretch in its corotated frame unless strain equality holds it, then a
// shell's bending between faces (flex_cell_elasticity.cc).
void FlexCellElasticForces(const Model& m, Data& d, int f, bool spring, bool damper);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_FLEX_CELLS_H_
