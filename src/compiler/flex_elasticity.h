// Elasticity of flexes, as MuJoCo's compiler computes it (user_mesh.cc, mjCFlex::Compile):
//
//   flex_stiffness  21 numbers per element: the upper triangle of the element's metric
//                   tensor over its edges (3 edges of a triangle, 6 of a tetrahedron),
//                   which the engine multiplies with the edges' squared elongations;
//                   for an interpolated flex, the dense stiffness of its nodes instead.
//   flex_bending    17 numbers per edge of a triangle flex: the 4x4 cotangent bending
//                   operator of the edge's flap (its two triangles) and the coefficient
//                   of the force from a curved reference shape.
//   flex_edgeflap   the flap's two vertices opposite the edge.
// (each flex's part at flex_stiffnessadr, flex_bendingadr; an interpolated flex made of
// cells, MuJoCo 3.12's, lays them out as engine/flex_cells.h says, flex_cells.cc)
//
// Every sum and product runs in MuJoCo's order, so the numbers agree to the last bit.
#ifndef SIMLAB_COMPILER_FLEX_ELASTICITY_H_
#define SIMLAB_COMPILER_FLEX_ELASTICITY_H_

#include <array>
#include <vector>

// (kFlexStiffnessSize, kFlexBendingSize, kFlexElemEdgeCount and kFlexElemEdges, shared
// with the engine)
#include "engine/flex_elasticity.h"

namespace simlab::compiler {

// The flap of each edge of a triangle flex (MuJoCo's CreateFlapStencil): [0], [1] the
// edge's vertices as the first triangle holding it lists them, [2] that triangle's
// other vertex, [3] the other vertex of the last other triangle holding it (-1 for a
// boundary edge). flex_edgeflap takes [2] and [3]. `elem` holds the flex's element
// vertices (dim + 1 per element, after the compiler's reordering), `elemedge` their edge
// ids (kFlexElemEdgeCount[dim - 1] per element, in kFlexElemEdges order). For dim other
// than 2 every flap is -1.
std::vector<std::array<int, 4>> FlexFlaps(int dim, const std::vector<int>& elem,
                                          const std::vector<int>& elemedge, int nedge);

// flex_stiffness of a flex without nodes: 21 numbers per element of `elem`, from the
// vertices' world positions at qpos0 (3 per vertex). Triangles get theirs when
// elastic2d >= 2 and thickness > 0, tetrahedra always (at MuJoCo's fixed thickness 4);
// everything else is zero. The caller checked young > 0 and poisson in [0, 0.5).
void FlexElementStiffness(int dim, int elastic2d, double young, double poisson,
                          double thickness, const std::vector<double>& vertxpos,
                          const std::vector<int>& elem, std::vector<double>* stiffness);

// flex_bending of a triangle flex with elastic2d 1 or 3: 17 numbers per flap (zero for a
// boundary edge), from the vertices' world positions at qpos0.
void FlexBending(double young, double poisson, double thickness,
                 const std::vector<double>& vertxpos,
                 const std::vector<std::array<int, 4>>& flaps, std::vector<double>* bending);

// The stiffness of an interpolated flex (MuJoCo's ComputeLinearStiffness): the dense
// (3n x 3n) matrix of its n = (order + 1)^3 nodes (order 1 trilinear, 2 quadratic), from
// the nodes' world positions at qpos0 (their box spans the first to the last node),
// subtracted into the first (3n)^2 entries of *stiffness (grown to that size if shorter,
// never shrunk). MuJoCo computes it into the flex's zeroed 21 * nelem numbers and keeps
// only those: the caller passes them zeroed and copies back 21 * nelem.
void FlexInterpolatedStiffness(double young, double poisson, int order,
                               const std::vector<double>& nodexpos,
                               std::vector<double>* stiffness);

// The membrane stiffness of one face element of a shell (MuJoCo's
// ComputeLinearStiffness2D): the dense (3 npe x 3 npe) matrix, stored negated as
// FlexInterpolatedStiffness stores it, of its npe = (order + 1)^2 nodes at `pos` (world,
// 3 each, its first in-plane axis (normal + 1) % 3 slowest) in plane stress with the
// given thickness; only in-plane displacements couple. *stiffness is replaced. Returns
// false (stiffness unset) when the face is flat along an in-plane axis.
bool FlexFaceStiffness(double young, double poisson, double thickness, int order,
                       int normal_axis, const double* pos, std::vector<double>* stiffness);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_FLEX_ELASTICITY_H_
