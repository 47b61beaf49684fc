// Elastic forces of flexes (the flex part of MuJoCo's mj_springdamper, engine_passive.c):
// thin-plate bending of triangle flexes, the edge-metric elasticity of triangle and
// tetrahedron elements with its Rayleigh damping, and the linear elasticity of flexes
// interpolated from nodes in their corotated frame.
#ifndef SIMLAB_ENGINE_FLEX_ELASTICITY_H_
#define SIMLAB_ENGINE_FLEX_ELASTICITY_H_

#include "math/math.h"
#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// Numbers per element in flex_stiffness, per edge in flex_bending.
inline constexpr int kFlexStiffnessSize = 21;
inline constexpr int kFlexBendingSize = 17;

// Edges of an element of dimension dim, at [dim - 1]: a segment 1, a triangle 3, a
// tetrahedron 6 (MuJoCo's kNumEdges).
inline constexpr int kFlexElemEdgeCount[3] = {1, 3, 6};

// Each edge of an element as its two local vertices, at [dim - 1][edge] (MuJoCo's
// eledge; -1 past the element's edges). flex_elemedge lists an element's edges in this
// order, and the compiler numbers new edges as they first appear in it.
inline constexpr int kFlexElemEdges[3][6][2] = {
    {{0, 1}, {-1, -1}, {-1, -1}, {-1, -1}, {-1, -1}, {-1, -1}},
    {{1, 2}, {2, 0}, {0, 1}, {-1, -1}, {-1, -1}, {-1, -1}},
    {{0, 1}, {1, 2}, {2, 0}, {2, 3}, {0, 3}, {1, 3}}};

// Adds every flex's elastic forces into qfrc_spring and its damping into qfrc_damper, as
// MuJoCo does after the joint springs and dof dampers and before the flex edges' own
// spring-dampers (spring, damper: those forces are enabled). As in MuJoCo the element
// forces, damping included, go to qfrc_spring whatever the flags. Reads flexvert_xpos,
// flexedge_length, flexedge_velocity (and for interpolated flexes xpos, xmat, cvel,
// subtree_com, cdof); takes up to 15 * flex_nodenum or 3 * flex_vertnum + flex_edgenum
// doubles of the Data stack, plus what ApplyForceTorque takes, for vertices of bodies
// that are not simple point masses.
void FlexElasticForces(const Model& m, Data& d, bool spring, bool damper);

// The world position x of node `node` (a global node id) of interpolated flex f: its
// body's origin if the flex is centered, else its offset carried by its body.
inline void FlexNodeXpos(const Model& m, const Data& d, int f, int node, double x[3]) {
  int b = m.flex_nodebodyid[node];
  if (m.flex_centered[f]) return math::Copy3(x, &d.xpos[3 * b]);
  math::MulMatVec3(x, &d.xmat[9 * b], &m.flex_node[3 * node]);
  math::Add3(x, x, &d.xpos[3 * b]);
}

// The nodes of interpolated flex f in its corotated frame (MuJoCo's mj_flexInterpState):
// their world positions (and, if vel is not null, velocities) rotated by quat, the
// inverse of the rotation nearest the deformation gradient at the box's centre (found by
// iterating from the quat given, normally the identity), positions shifted by (.5 .5 .5).
// xpos and vel hold 3 * flex_nodenum numbers.
void FlexInterpState(const Model& m, const Data& d, int f, double* xpos, double* vel,
                     double quat[4]);

// r = q v q*, computed for a zero v too (MuJoCo's inline mji_rotVecQuat, which keeps
// the signs of zero that math::RotVecQuat's shortcut would not).
void FlexRotateAlways(double* r, const double* v, const double* q);

// The deformation gradient (row-major 3x3) at p of (order + 1)^3 nodes' positions, x
// slowest (MuJoCo's mju_defGradient).
void FlexDeformationGradient(double mat[9], const double p[3], const double* nodes, int order);

// Refines quat toward the rotation nearest `mat` (Mueller et al., "A robust method to
// extract the rotational part of deformations"; MuJoCo's mju_mat2Rot).
void FlexNearestRotation(double quat[4], const double mat[9]);

// Shape function i (0..order) of a flex interpolated with order 1 or 2 along one axis at
// s, and its derivative (MuJoCo's phi and dphi; the compiler's stiffness uses them too).
inline double FlexShape(double s, int i, int order) {
  if (order == 1) return i == 0 ? 1 - s : s;
  if (i == 0) return 2 * s * s - 3 * s + 1;
  if (i == 1) return 4 * (s - s * s);
  return 2 * s * s - s;
}
inline double FlexShapeSlope(double s, int i, int order) {
  if (order == 1) return i == 0 ? -1 : 1;
  if (i == 0) return 4 * s - 3;
  if (i == 1) return 4 * (1 - 2 * s);
  return 4 * s - 1;
}
// The weight of node j (x slowest: order 1 reads the bits of j, order 2 its base-3
// digits) at p in the flex's box: the product of the axes' shape functions (MuJoCo's
// mju_evalBasis, as mju_interpolate3D and mj_vertBodyWeight weight the nodes).
inline double FlexNodeWeight(const double p[3], int j, int order) {
  if (order == 1) {
    return FlexShape(p[2], j & 1, 1) * FlexShape(p[1], j & 2, 1) * FlexShape(p[0], j & 4, 1);
  }
  return FlexShape(p[2], j % 3, 2) * FlexShape(p[1], (j / 3) % 3, 2) * FlexShape(p[0], j / 9, 2);
}

// The gradient at p of the shape function of node (i, j, k) (x slowest): the product of
// the axes' shape functions differentiated along each axis in turn.
inline void FlexShapeGradient(double g[3], const double p[3], int i, int j, int k, int order) {
  g[0] = FlexShapeSlope(p[0], i, order) * FlexShape(p[1], j, order) * FlexShape(p[2], k, order);
  g[1] = FlexShape(p[0], i, order) * FlexShapeSlope(p[1], j, order) * FlexShape(p[2], k, order);
  g[2] = FlexShape(p[0], i, order) * FlexShape(p[1], j, order) * FlexShapeSlope(p[2], k, order);
}

}  // namespace simlab

#endif  // SIMLAB_ENGINE_FLEX_ELASTICITY_H_
