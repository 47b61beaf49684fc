// Flexes in the pipeline (MuJoCo's mj_flex and the flex parts of the velocity and
// passive stages): the vertices' world positions, the elements' boxes, the edges'
// lengths and sparse Jacobians (on the dofs that move either end), the edges'
// velocities, and the edges' own springs and dampers.
#include <algorithm>
#include <cmath>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/flex_cells.h"
#include "engine/flex_elasticity.h"
#include "engine/stack.h"
#include "math/dot.h"
#include "math/math.h"
#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

namespace {

// World positions of flex f's vertices: their bodies' origins (centered), or their
// offsets carried by their bodies.
void FlexVertexPositions(const Model& m, Data& d, int f) {
  int begin = m.flex_vertadr[f], end = begin + m.flex_vertnum[f];
  for (int i = begin; i < end; i++) {
    int b = m.flex_vertbodyid[i];
    double* x = &d.flexvert_xpos[3 * i];
    if (m.flex_centered[f]) {
      math::Copy3(x, &d.xpos[3 * b]);
      continue;
    }
    math::MulMatVec3(x, &d.xmat[9 * b], &m.flex_vert[3 * i]);
    math::Add3(x, x, &d.xpos[3 * b]);
  }
}

// World positions of an interpolated flex's vertices: its nodes (bodies' origins, or
// offsets carried by their bodies) weighted by the shape functions of each vertex's
// place in the box, flex_vert0 (MuJoCo's mju_interpolate3D).
void FlexInterpolatedPositions(const Model& m, Data& d, int f) {
  int order = m.flex_interp[f];
  int nnode = m.flex_nodenum[f], nbegin = m.flex_nodeadr[f];
  double nodexpos[3 * 27];
  for (int j = 0; j < nnode && j < 27; j++) FlexNodeXpos(m, d, f, nbegin + j, nodexpos + 3 * j);
  int begin = m.flex_vertadr[f], end = begin + m.flex_vertnum[f];
  for (int i = begin; i < end; i++) {
    const double* p = &m.flex_vert0[3 * i];
    double* x = &d.flexvert_xpos[3 * i];
    math::Zero3(x);
    for (int j = 0; j < nnode; j++) {
      double w = FlexNodeWeight(p, j, order);
      for (int k = 0; k < 3; k++) x[k] += nodexpos[3 * j + k] * w;
    }
  }
}

// World positions of the vertices of a flex made of cells: each from the nodes of the
// cell holding it (a shell's interior nodes following its boundary), weighted by the
// shape functions of its place in that cell (MuJoCo 3.12's mj_flex).
void FlexCellPositions(const Model& m, Data& d, int f) {
  FlexLattice g = FlexLatticeOf(m, f);
  StackFrame frame(d);
  double* nodexpos = frame.Alloc(3 * static_cast<size_t>(m.flex_nodenum[f]));
  FlexCellNodeState(m, d, f, nodexpos, nullptr);
  int begin = m.flex_vertadr[f], end = begin + m.flex_vertnum[f];
  for (int i = begin; i < end; i++) {
    double local[3], weight[27];
    int ids[27];
    FlexCellLookup(&m.flex_vert0[3 * i], g.cells.data(), g.order, local, ids);
    FlexCellWeights(local, g.order, weight);
    double* x = &d.flexvert_xpos[3 * i];
    math::Zero3(x);
    for (int j = 0; j < g.NodesPerCell(); j++) {
      for (int k = 0; k < 3; k++) x[k] += nodexpos[3 * ids[j] + k] * weight[j];
    }
  }
}

// Each element's box (centre, half sizes grown by the flex's radius).
void FlexElementBoxes(const Model& m, Data& d, int f) {
  int dim = m.flex_dim[f];
  const double* vert = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  for (int e = 0; e < m.flex_elemnum[f]; e++) {
    const int* el = &m.flex_elem[m.flex_elemdataadr[f] + e * (dim + 1)];
    FlexElementAabb(vert, el, dim, m.flex_radius[f], &d.flexelem_aabb[6 * (m.flex_elemadr[f] + e)]);
  }
}

// Does flex f need its edges' Jacobians: an edge equality, edge springs or dampers, or
// element damping?
bool FlexNeedsEdgeJacobian(const Model& m, int f) {
  return m.flex_edgeequality[f] == 1 || m.flex_edgedamping[f] != 0 ||
         m.flex_edgestiffness[f] != 0 || m.flex_damping[f] != 0;
}

// Edge e's length, and (when asked) its Jacobian: the direction from its first vertex
// to its second times the difference of the two vertices' point Jacobians, on the dofs
// of the edge's row (flexedge_J_colind).
void FlexEdge(const Model& m, Data& d, int f, int e, bool jacobian) {
  int vbase = m.flex_vertadr[f];
  int v1 = vbase + m.flex_edge[2 * e], v2 = vbase + m.flex_edge[2 * e + 1];
  const double* pos1 = &d.flexvert_xpos[3 * v1];
  const double* pos2 = &d.flexvert_xpos[3 * v2];
  double dir[3];
  math::Sub3(dir, pos2, pos1);
  d.flexedge_length[e] = math::Normalize3(dir);
  int n = m.flexedge_J_rownnz[e];
  if (!jacobian || n == 0) return;
  int adr = m.flexedge_J_rowadr[e];
  JacobianDifferenceAlong(m, d, &m.flexedge_J_colind[adr], n, pos1, m.flex_vertbodyid[v1], pos2,
                          m.flex_vertbodyid[v2], dir, &d.flexedge_J[adr]);
}

// r (3 x 2) = a (3 x 2) b (2 x 2).
void MulMat322(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    r[2 * i] = a[2 * i] * b[0] + a[2 * i + 1] * b[2];
    r[2 * i + 1] = a[2 * i] * b[1] + a[2 * i + 1] * b[3];
  }
}

// Edge e of flex f seen from vertex v: its rest vector (FlexRestEdge) and its current
// vector; returns the mass of its far end.
double VertexEdge(const Model& m, const Data& d, int f, int e, int v, double dx[3], double dy[3]) {
  int vbase = m.flex_vertadr[f], ebase = m.flex_edgeadr[f];
  int v1 = m.flex_edge[2 * (ebase + e)], v2 = m.flex_edge[2 * (ebase + e) + 1];
  math::Sub3(dy, &d.flexvert_xpos[3 * (vbase + v2)], &d.flexvert_xpos[3 * (vbase + v1)]);
  return FlexRestEdge(m, f, e, v, dx);
}

// res (n) = jac (3 x n)^T vec, skipping zero entries of vec (MuJoCo's mju_mulMatTVec).
void MulJacT(const double* jac, const double* vec, int n, double* res) {
  std::fill(res, res + n, 0.0);
  for (int r = 0; r < 3; r++) {
    if (vec[r] == 0) continue;
    for (int k = 0; k < n; k++) res[k] += jac[r * n + k] * vec[r];
  }
}

// Scratch for the vertex invariants' Jacobians, taken once per flex: the dense rows of
// the two invariants, and for each end of an edge its dof chain and point Jacobian.
struct VertexScratch {
  double* rows[2];
  int* chain[2];
  double* jac[2];
  double* local;
};

// The derivatives g[0], g[1] of the two invariants along edge e (at its first end; the
// second end takes their negatives), added into the dense rows through both ends' point
// Jacobians, in MuJoCo's order for each row: first end, then second.
void AddEdgeEndsJacobian(const Model& m, Data& d, int f, int e, const double g[2][3],
                         VertexScratch& s) {
  int vbase = m.flex_vertadr[f], ebase = m.flex_edgeadr[f];
  int ends[2] = {vbase + m.flex_edge[2 * (ebase + e)], vbase + m.flex_edge[2 * (ebase + e) + 1]};
  int n[2];
  for (int side = 0; side < 2; side++) {
    int body = m.flex_vertbodyid[ends[side]];
    n[side] = MergedDofChain(m, body, body, s.chain[side]);
    JacobianOnDofs(m, d, s.chain[side], n[side], s.jac[side], nullptr,
                   &d.flexvert_xpos[3 * ends[side]], body);
  }
  for (int row = 0; row < 2; row++) {
    for (int side = 0; side < 2; side++) {
      double sign = side ? -1 : 1;
      double gs[3] = {sign * g[row][0], sign * g[row][1], sign * g[row][2]};
      MulJacT(s.jac[side], gs, n[side], s.local);
      for (int j = 0; j < n[side]; j++) s.rows[row][s.chain[side][j]] += s.local[j];
    }
  }
}

// Flex f's vertex invariants (Chen, Kry and Vouga's locking-free thin plates, as MuJoCo):
// per vertex, the trace and determinant of the Cauchy strain of its edges' deformation
// gradient, less their rest values, scaled by sqrt(mass); and their Jacobians.
void FlexVertexInvariants(const Model& m, Data& d, int f) {
  SolverFrame frame(d.solver_scratch);
  VertexScratch scratch;
  for (int k = 0; k < 2; k++) {
    scratch.rows[k] = frame.Reals(m.nv);
    scratch.chain[k] = frame.IntsToWrite(m.nv);
    scratch.jac[k] = frame.RealsToWrite(3 * static_cast<size_t>(m.nv));
  }
  scratch.local = frame.RealsToWrite(m.nv);
  int vbase = m.flex_vertadr[f];
  for (int v = 0; v < m.flex_vertnum[f]; v++) {
    int vadr = vbase + v, adr = m.flex_vertedgeadr[vadr], count = m.flex_vertedgenum[vadr];
    const double* metric = &m.flex_vertmetric[4 * vadr];

    // The deformation gradient F = (sum w dy dx') metric, its Cauchy strain F'F.
    double a[6] = {0, 0, 0, 0, 0, 0};
    for (int k = 0; k < count; k++) {
      double dx[3], dy[3];
      double w = VertexEdge(m, d, f, m.flex_vertedge[adr + k], v, dx, dy);
      for (int r = 0; r < 3; r++) {
        a[2 * r] += w * dy[r] * dx[0];
        a[2 * r + 1] += w * dy[r] * dx[1];
      }
    }
    double F[6];
    MulMat322(F, a, metric);
    double c[4] = {F[0] * F[0] + F[2] * F[2] + F[4] * F[4], F[0] * F[1] + F[2] * F[3] + F[4] * F[5],
                   F[1] * F[0] + F[3] * F[2] + F[5] * F[4], F[1] * F[1] + F[3] * F[3] + F[5] * F[5]};
    double scale = 1.0;
    int body = m.flex_vertbodyid[vadr];
    if (body >= 0 && m.body_mass[body] > 1e-15) scale = std::sqrt(m.body_mass[body]);
    d.flexvert_length[2 * vadr] = (c[0] + c[3] - 2) * scale;
    d.flexvert_length[2 * vadr + 1] = (c[0] * c[3] - c[1] * c[2] - 1) * scale;

    // Derivatives along each edge: F metric for the trace, F adj(C) metric for the
    // determinant, times the rest edge, weighted.
    double fb[6], adj[4] = {c[3], -c[1], -c[2], c[0]}, fadj[6], fadjb[6];
    MulMat322(fb, F, metric);
    MulMat322(fadj, F, adj);
    MulMat322(fadjb, fadj, metric);
    for (int k = 0; k < count; k++) {
      int e = m.flex_vertedge[adr + k];
      double dx[3], dy[3];
      double w = VertexEdge(m, d, f, e, v, dx, dy);
      double g[2][3];
      for (int r = 0; r < 3; r++) {
        g[0][r] = (fb[2 * r] * dx[0] + fb[2 * r + 1] * dx[1]) * (-2 * w);
        g[1][r] = (fadjb[2 * r] * dx[0] + fadjb[2 * r + 1] * dx[1]) * (-2 * w);
      }
      AddEdgeEndsJacobian(m, d, f, e, g, scratch);
    }

    // Into the sparse rows, clearing the dense ones for the next vertex.
    for (int row = 0; row < 2; row++) {
      double* dense = scratch.rows[row];
      int r = 2 * vadr + row, radr = m.flexvert_J_rowadr[r];
      for (int j = 0; j < m.flexvert_J_rownnz[r]; j++) {
        int col = m.flexvert_J_colind[radr + j];
        d.flexvert_J[radr + j] += dense[col] * scale;
        dense[col] = 0;
      }
    }
  }
}

}  // namespace

void FlexElementAabb(const double* xpos, const int* elem, int dim, double radius, double box[6]) {
  double lo[3], hi[3];
  math::Copy3(lo, xpos + 3 * elem[0]);
  math::Copy3(hi, xpos + 3 * elem[0]);
  for (int i = 1; i <= dim; i++) {
    for (int k = 0; k < 3; k++) {
      lo[k] = std::min(lo[k], xpos[3 * elem[i] + k]);
      hi[k] = std::max(hi[k], xpos[3 * elem[i] + k]);
    }
  }
  for (int k = 0; k < 3; k++) {
    box[k] = 0.5 * (hi[k] + lo[k]);
    box[k + 3] = 0.5 * (hi[k] - lo[k]) + radius;
  }
}

double FlexRestEdge(const Model& m, int f, int e, int v, double dx[3]) {
  int vbase = m.flex_vertadr[f], ebase = m.flex_edgeadr[f];
  int v1 = m.flex_edge[2 * (ebase + e)], v2 = m.flex_edge[2 * (ebase + e) + 1];
  math::Sub3(dx, &m.flex_vert0[3 * (vbase + v2)], &m.flex_vert0[3 * (vbase + v1)]);
  for (int k = 0; k < 3; k++) dx[k] *= 2 * m.flex_size[3 * f + k];
  int body = m.flex_vertbodyid[vbase + (v == v1 ? v2 : v1)];
  return body >= 0 ? std::max(m.body_mass[body], 1e-15) : 1.0;
}

void FlexKinematics(const Model& m, Data& d) {
  if (m.nflex == 0) return;
  for (int f = 0; f < m.nflex; f++) {
    if (m.flex_interp[f] == 0) {
      FlexVertexPositions(m, d, f);
    } else if (FlexHasCells(m, f)) {
      FlexCellPositions(m, d, f);
    } else {
      FlexInterpolatedPositions(m, d, f);
    }
  }
  for (int f = 0; f < m.nflex; f++) FlexElementBoxes(m, d, f);
  // The flexes' tree boxes from them (where MuJoCo's mj_flex updates them).
  FlexBoundingVolumes(m, d);

  // Edges of flexes that can make forces: lengths, and Jacobians where needed.
  std::fill(d.flexedge_J.begin(), d.flexedge_J.end(), 0.0);
  std::fill(d.flexvert_J.begin(), d.flexvert_J.end(), 0.0);
  for (int f = 0; f < m.nflex; f++) {
    if (m.flex_rigid[f] || m.flex_interp[f]) continue;
    bool jacobian = FlexNeedsEdgeJacobian(m, f);
    int begin = m.flex_edgeadr[f], end = begin + m.flex_edgenum[f];
    for (int e = begin; e < end; e++) FlexEdge(m, d, f, e, jacobian);
    if (m.flex_dim[f] == 2 && m.flex_edgeequality[f] == 2) FlexVertexInvariants(m, d, f);
  }
}

void FlexEdgeVelocity(const Model& m, Data& d) {
  for (int e = 0; e < m.nflexedge; e++) {
    int adr = m.flexedge_J_rowadr[e];
    // (a flex without rows has none: its addresses may be the arrays' ends)
    d.flexedge_velocity[e] = math::DotSparse(d.flexedge_J.data() + adr, d.qvel.data(),
                                             m.flexedge_J_rownnz[e], m.flexedge_J_colind.data() + adr);
  }
}

void FlexEdgeSpringDamper(const Model& m, Data& d, bool spring, bool damper) {
  for (int f = 0; f < m.nflex; f++) {
    double stiffness = spring ? m.flex_edgestiffness[f] : 0;
    double damping = damper ? m.flex_edgedamping[f] : 0;
    if (m.flex_rigid[f] || (stiffness == 0 && damping == 0)) continue;
    int begin = m.flex_edgeadr[f], end = begin + m.flex_edgenum[f];
    for (int e = begin; e < end; e++) {
      if (m.flexedge_rigid[e]) continue;
      double frc_spring = stiffness * (m.flexedge_length0[e] - d.flexedge_length[e]);
      double frc_damper = -damping * d.flexedge_velocity[e];
      int adr = m.flexedge_J_rowadr[e];
      for (int j = adr; j < adr + m.flexedge_J_rownnz[e]; j++) {
        int dof = m.flexedge_J_colind[j];
        d.qfrc_spring[dof] += d.flexedge_J[j] * frc_spring;
        d.qfrc_damper[dof] += d.flexedge_J[j] * frc_damper;
      }
    }
  }
}

}  // namespace simlab
