// Elastic forces of interpolated flexes made of cells (MuJoCo 3.12's mj_flexPassiveInterp
// and mj_flexPassiveBendInterp, engine_passive.c).
//
// Stretch: each element (a cell, or a shell's face) with stiffness, in its own corotated
// frame: its nodes' displacement from their rest positions (flex_node0) times the
// element's stiffness (and its damping, the stiffness times the nodes' velocities),
// rotated back to the world and summed per node. A flex held by strain equality has its
// stiffness in the constraints instead.
//
// Shell bending: at the midpoint of each edge between two faces, the jump of the faces'
// unit normals n_A - n_B minus the rest jump (carried by the two faces' average
// rotation) is a residual r; energy D l / (2 h) |r|^2 pulls each face's nodes along the
// normal's derivative (the projection of r off the normal, crossed with the tangents).
#include <algorithm>
#include <cmath>

#include "engine/engine.h"
#include "engine/flex_cells.h"
#include "engine/flex_elasticity.h"
#include "engine/stack.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

namespace {

// The per-node forces of a flex onto its nodes' dofs: a node at its body's origin on a
// body with dofs directly (rotated into the body's frame), any other through its body's
// Jacobian at the node.
void ApplyNodeForces(const Model& m, Data& d, int f, const double* xpos, const double* frc,
                     const double* dmp, bool spring, bool damper) {
  const double no_torque[3] = {0, 0, 0};
  int nodeadr = m.flex_nodeadr[f];
  for (int i = 0; i < m.flex_nodenum[f]; i++) {
    int body = m.flex_nodebodyid[nodeadr + i];
    const double* node = &m.flex_node[3 * (nodeadr + i)];
    bool at_origin = m.flex_centered[f] || (node[0] == 0 && node[1] == 0 && node[2] == 0);
    if (m.body_dofnum[body] > 0 && at_origin) {
      const double* xmat = &d.xmat[9 * body];
      int dof = m.body_dofadr[body];
      double local[3];
      if (spring) {
        math::MulMatTVec3(local, xmat, frc + 3 * i);
        for (int k = 0; k < 3; k++) d.qfrc_spring[dof + k] += local[k];
      }
      if (damper) {
        math::MulMatTVec3(local, xmat, dmp + 3 * i);
        for (int k = 0; k < 3; k++) d.qfrc_damper[dof + k] += local[k];
      }
      continue;
    }
    const double* at = xpos + 3 * i;
    if (spring) ApplyForceTorque(m, d, frc + 3 * i, no_torque, at, body, d.qfrc_spring.data());
    if (damper) ApplyForceTorque(m, d, dmp + 3 * i, no_torque, at, body, d.qfrc_damper.data());
  }
}

// One element's nodes (ids), their positions, velocities and rest positions, and its
// corotated frame (world to corotated).
void GatherElement(const FlexLattice& g, int fe, const double* xpos, const double* vel,
                   const double* xpos0, int* ids, double* xe, double* ve, double* x0e,
                   double quat[4]) {
  int normal = FlexElementNodes(g, fe, ids);
  for (int n = 0; n < g.NodesPerElement(); n++) {
    math::Copy3(xe + 3 * n, xpos + 3 * ids[n]);
    if (ve) math::Copy3(ve + 3 * n, vel + 3 * ids[n]);
    if (x0e) math::Copy3(x0e + 3 * n, xpos0 + 3 * ids[n]);
  }
  if (g.shell) {
    FlexFaceRotation(g.order, normal, xe, quat);
  } else {
    FlexCellRotation(g.order, xe, quat);
  }
}

// Stretch of flex f's elements, summed per node into frc (spring) and dmp (damper).
void StretchForces(const Model& m, Data& d, int f, const double* xpos, const double* vel,
                   double* frc, double* dmp, bool spring, bool damper) {
  FlexLattice g = FlexLatticeOf(m, f);
  int npe = g.NodesPerElement(), ndof = 3 * npe;
  const double* stiffness = &m.flex_stiffness[m.flex_stiffnessadr[f]];
  const double* xpos0 = &m.flex_node0[3 * m.flex_nodeadr[f]];
  StackFrame frame(d);
  double* xe = frame.Alloc(ndof);
  double* ve = frame.Alloc(ndof);
  double* x0e = frame.Alloc(ndof);
  double* displacement = frame.Alloc(ndof);
  double* fe_frc = frame.Alloc(ndof);
  double* fe_dmp = frame.Alloc(ndof);
  int ids[27];
  for (int fe = 0; fe < g.ElementCount(); fe++) {
    const double* k = stiffness + static_cast<size_t>(fe) * ndof * ndof;
    if (k[0] == 0) continue;  // an empty cell

    // The element in its corotated frame, displaced from rest.
    double quat[4];
    GatherElement(g, fe, xpos, vel, xpos0, ids, xe, ve, x0e, quat);
    for (int n = 0; n < npe; n++) {
      math::RotVecQuat(xe + 3 * n, xe + 3 * n, quat);
      math::RotVecQuat(ve + 3 * n, ve + 3 * n, quat);
    }
    for (int i = 0; i < ndof; i++) displacement[i] = xe[i] - x0e[i];

    // Forces in the corotated frame (k holds minus the stiffness), back to the world.
    if (spring) math::MulMatVec(fe_frc, k, displacement, ndof, ndof);
    if (damper) math::MulMatVec(fe_dmp, k, ve, ndof, ndof);
    math::NegQuat(quat, quat);
    for (int n = 0; n < npe; n++) {
      double world[3];
      if (spring) {
        FlexRotateAlways(world, fe_frc + 3 * n, quat);
        math::Add3(frc + 3 * ids[n], frc + 3 * ids[n], world);
      }
      if (damper) {
        FlexRotateAlways(world, fe_dmp + 3 * n, quat);
        math::Add3(dmp + 3 * ids[n], dmp + 3 * ids[n], world);
      }
    }
  }
}

// The part of r off the unit normal n, over the normal's length before normalizing.
void OffNormal(double w[3], const double r[3], const double n[3], double inv_length) {
  double along = math::Dot3(n, r);
  for (int k = 0; k < 3; k++) w[k] = (r[k] - n[k] * along) * inv_length;
}

// A face's nodes pulled by one bending edge: stiffness (g0 (w x t2) - g1 (w x t1)) on
// each node, g0 and g1 its shape function's slopes at the edge's midpoint `local`,
// added with `sign`.
void PullFace(int order, const int* ids, const double local[2], const double w[3],
              const double t1[3], const double t2[3], double stiffness, double sign, double* frc) {
  double wt2[3], wt1[3];
  math::Cross3(wt2, w, t2);
  math::Cross3(wt1, w, t1);
  int n = 0;
  for (int l0 = 0; l0 <= order; l0++) {
    for (int l1 = 0; l1 <= order; l1++, n++) {
      double g0 = FlexShapeSlope(local[0], l0, order) * FlexShape(local[1], l1, order);
      double g1 = FlexShape(local[0], l0, order) * FlexShapeSlope(local[1], l1, order);
      double* f = frc + 3 * ids[n];
      for (int k = 0; k < 3; k++) {
        double pull = stiffness * (g0 * wt2[k] - g1 * wt1[k]);
        f[k] = sign > 0 ? f[k] + pull : f[k] - pull;
      }
    }
  }
}

// The bending of one edge between faces A and B (their nodes' positions xa, xb and ids,
// their corotated frames qa, qb), into frc.
void BendEdge(int order, const double* edge, const double* xa, const double* xb, const int* ida,
              const int* idb, const double qa_in[4], const double qb_in[4], double* frc) {
  const double local_a[2] = {edge[2], edge[3]}, local_b[2] = {edge[4], edge[5]};
  double stiffness = edge[6];

  // The faces' unit normals at the edge's midpoint.
  double na[3], ta1[3], ta2[3], nb[3], tb1[3], tb2[3];
  FlexFaceNormal(order, xa, local_a, na, ta1, ta2);
  FlexFaceNormal(order, xb, local_b, nb, tb1, tb2);
  double len_a = math::Norm3(na), len_b = math::Norm3(nb);
  if (len_a < kMinVal || len_b < kMinVal) return;
  double inv_a = 1.0 / len_a, inv_b = 1.0 / len_b;
  math::Scale3(na, na, inv_a);
  math::Scale3(nb, nb, inv_b);

  // The rest jump carried by the faces' average rotation (corotated to world).
  double qa[4], qb[4], avg[4];
  math::CopyQuat(qa, qa_in);
  math::CopyQuat(qb, qb_in);
  if (math::Dot(qa, qb, 4) < 0) {
    for (int k = 0; k < 4; k++) qb[k] = -qb[k];
  }
  for (int k = 0; k < 4; k++) avg[k] = qa[k] + qb[k];
  double norm = std::sqrt(math::Dot(avg, avg, 4));
  if (norm < kMinVal) {
    math::SetIdentityQuat(avg);
  } else {
    double inv = 1 / norm;
    for (int k = 0; k < 4; k++) avg[k] *= inv;
  }
  math::NegQuat(avg, avg);
  double rest[3];
  math::RotVecQuat(rest, edge + 7, avg);

  // The residual, and the pull on both faces' nodes.
  double r[3];
  math::Sub3(r, na, nb);
  for (int k = 0; k < 3; k++) r[k] -= rest[k];
  double wa[3], wb[3];
  OffNormal(wa, r, na, inv_a);
  OffNormal(wb, r, nb, inv_b);
  PullFace(order, ida, local_a, wa, ta1, ta2, stiffness, +1, frc);
  PullFace(order, idb, local_b, wb, tb1, tb2, stiffness, -1, frc);
}

// Bending of shell f's edges, into frc (its damping is not modelled, as in MuJoCo).
void ShellBendingForces(const Model& m, Data& d, int f, const double* xpos, double* frc) {
  FlexLattice g = FlexLatticeOf(m, f);
  const double* bending = &m.flex_bending[m.flex_bendingadr[f]];
  int nedge = static_cast<int>(bending[0]);
  int npe = g.NodesPerFace(), nface = g.FaceCount();

  // Every face's nodes and corotated frame, once (their node ids are looked up again per
  // edge, which is cheap and keeps the step free of allocations).
  StackFrame frame(d);
  double* face_xpos = frame.Alloc(3 * static_cast<size_t>(npe) * nface);
  double* face_quat = frame.Alloc(4 * static_cast<size_t>(nface));
  int ida[9], idb[9];
  for (int fe = 0; fe < nface; fe++) {
    GatherElement(g, fe, xpos, nullptr, nullptr, ida, face_xpos + 3 * npe * fe, nullptr, nullptr,
                  face_quat + 4 * fe);
  }
  for (int e = 0; e < nedge; e++) {
    const double* edge = bending + 1 + e * kFlexShellBendSize;
    if (edge[6] == 0) continue;
    int a = static_cast<int>(edge[0]), b = static_cast<int>(edge[1]);
    FlexFaceNodes(g, a, ida);
    FlexFaceNodes(g, b, idb);
    BendEdge(g.order, edge, face_xpos + 3 * npe * a, face_xpos + 3 * npe * b, ida, idb,
             face_quat + 4 * a, face_quat + 4 * b, frc);
  }
}

}  // namespace

void FlexCellElasticForces(const Model& m, Data& d, int f, bool spring, bool damper) {
  int nnode = m.flex_nodenum[f];
  int adr = m.flex_stiffnessadr[f];
  int bendadr = m.flex_bendingadr[f];
  // (MuJoCo 3.12 asks its first element's first number: the count of modes with strain
  // equality, else K(0, 0) of cell 0, zero when that cell is empty, and always zero for
  // a shell, whose face 0 lies across x so that its dof 0 is out of plane: a shell
  // without strain equality gets no membrane force, here as in 3.12)
  bool stretch = adr >= 0 && m.flex_stiffness[adr] != 0 &&
                 m.flex_edgeequality[f] != kFlexEdgeStrain;
  bool bend = m.flex_interp[f] < 0 && bendadr >= 0 && m.flex_bending[bendadr] != 0;
  if (!stretch && !bend) return;
  StackFrame frame(d);
  double* xpos = frame.Alloc(3 * static_cast<size_t>(nnode));
  double* vel = frame.Alloc(3 * static_cast<size_t>(nnode));
  double* frc = frame.Alloc(3 * static_cast<size_t>(nnode));
  double* dmp = frame.Alloc(3 * static_cast<size_t>(nnode));

  // Stretch, its damping scaled by the flex's.
  if (stretch) {
    FlexCellNodeState(m, d, f, xpos, vel);
    std::fill(frc, frc + 3 * nnode, 0.0);
    std::fill(dmp, dmp + 3 * nnode, 0.0);
    StretchForces(m, d, f, xpos, vel, frc, dmp, spring, damper);
    for (int i = 0; i < 3 * nnode; i++) dmp[i] *= m.flex_damping[f];
    ApplyNodeForces(m, d, f, xpos, frc, dmp, spring, damper);
  }

  // A shell's bending (no damping).
  if (bend) {
    FlexCellNodeState(m, d, f, xpos, vel);
    std::fill(frc, frc + 3 * nnode, 0.0);
    std::fill(dmp, dmp + 3 * nnode, 0.0);
    if (spring) ShellBendingForces(m, d, f, xpos, frc);
    ApplyNodeForces(m, d, f, xpos, frc, dmp, spring, damper);
  }
}

}  // namespace simlab
