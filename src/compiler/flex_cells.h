// Interpolated flexes made of cells at compile time (MuJoCo 3.12's mjCFlex::Compile for
// a flex with cellcount, a shell or strain equality; engine/flex_cells.h describes the
// lattice and the layouts of flex_stiffness and flex_bending).
#ifndef SIMLAB_COMPILER_FLEX_CELLS_H_
#define SIMLAB_COMPILER_FLEX_CELLS_H_

#include <array>
#include <string>
#include <vector>

#include "engine/flex_cells.h"

namespace simlab::compiler {

// Which of the cx cy cz cells of a box hold no element (MuJoCo's ComputeCellEmpty):
// each element marks the cells its bounding box overlaps; for triangles (a surface) the
// unmarked cells reachable from the box's boundary through unmarked cells are empty
// (those the surface encloses are not), otherwise every unmarked cell is. The box is
// `bbox` (min xyz, max xyz), or the points' when null. vpos holds 3 numbers per point,
// elem dim + 1 point ids per element.
std::vector<bool> EmptyFlexCells(const std::array<int, 3>& cells, const std::vector<double>& vpos,
                                 const std::vector<int>& elem, int dim, const double* bbox);

// The nodes' positions (3 each, the whole lattice) turned by R0, the rotation of the
// first cell that is not empty (its edges from its first node along x, y, z, each
// normalized, as R0's rows): MuJoCo's ComputeUnrotatedNodePositions. Returns "" or the
// error when R0 is not orthonormal.
std::string UnrotatedFlexNodes(const FlexLattice& g, const std::vector<bool>& cell_empty,
                               const std::vector<double>& nodexpos, std::vector<double>* local,
                               double r0[9]);

// flex_stiffness of a flex with cells from its nodes' unrotated positions: one matrix
// per element, zero for an empty cell; with `strain`, each holds the element's stiff
// eigenmodes instead (computed at Young's modulus 10 and Poisson's ratio 0.3; a shell's
// face also gets its warp mode). Returns "" or the error (a shell's flat face).
std::string FlexCellStiffness(const FlexLattice& g, const std::vector<bool>& cell_empty,
                       const std::vector<double>& nodes, double young, double poisson,
                       double thickness, bool strain, std::vector<double>* stiffness);

// flex_bending of a shell: its count of edges between face elements, then each edge's
// faces, midpoints on both, stiffness D l / h and rest normal jump (MuJoCo's
// ComputeInterpBending), from its nodes' unrotated positions.
void FlexShellBending(const FlexLattice& g, const std::vector<double>& nodes, double young,
                      double poisson, double thickness, std::vector<double>* bending);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_FLEX_CELLS_H_
