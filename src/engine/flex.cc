// Flexes in the pipeline (MuJoCo's mj_flex and the flex parts of the velocity and
// passive stages): the vertices' world positions, the elements' boxes, the edges'
// lengths and sparse Jacobians (on the dofs that move either end), the edges'
// velocities, and the edges' own springs and dampers.
#include <algorithm>
#include <cmath>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/flex_elasticity.h"
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
  for (int j = 0; j < nnode && j < 27; j++) {
    int b = m.flex_nodebodyid[nbegin + j];
    double* x = nodexpos + 3 * j;
    if (m.flex_centered[f]) {
      math::Copy3(x, &d.xpos[3 * b]);
      continue;
    }
    math::MulMatVec3(x, &d.xmat[9 * b], &m.flex_node[3 * (nbegin + j)]);
    math::Add3(x, x, &d.xpos[3 * b]);
  }
  int begin = m.flex_vertadr[f], end = begin + m.flex_vertnum[f];
  for (int i = begin; i < end; i++) {
    const double* p = &m.flex_vert0[3 * i];
    double* x = &d.flexvert_xpos[3 * i];
    math::Zero3(x);
    for (int j = 0; j < nnode; j++) {
      // (node j: x slowest; order 1 tests the bits of j, order 2 its base-3 digits)
      double w = order == 1
                     ? FlexShape(p[2], j & 1, 1) * FlexShape(p[1], j & 2, 1) * FlexShape(p[0], j & 4, 1)
                     : FlexShape(p[2], j % 3, 2) * FlexShape(p[1], (j / 3) % 3, 2) *
                           FlexShape(p[0], j / 9, 2);
      for (int k = 0; k < 3; k++) x[k] += nodexpos[3 * j + k] * w;
    }
  }
}

// Each element's box (centre, half sizes grown by the flex's radius).
void FlexElementBoxes(const Model& m, Data& d, int f) {
  int dim = m.flex_dim[f];
  const double* vert = &d.flexvert_xpos[3 * m.flex_vertadr[f]];
  for (int e = 0; e < m.flex_elemnum[f]; e++) {
    const int* el = &m.flex_elem[m.flex_elemdataadr[f] + e * (dim + 1)];
    double lo[3], hi[3];
    math::Copy3(lo, vert + 3 * el[0]);
    math::Copy3(hi, vert + 3 * el[0]);
    for (int i = 1; i <= dim; i++) {
      for (int k = 0; k < 3; k++) {
        lo[k] = std::min(lo[k], vert[3 * el[i] + k]);
        hi[k] = std::max(hi[k], vert[3 * el[i] + k]);
      }
    }
    double* box = &d.flexelem_aabb[6 * (m.flex_elemadr[f] + e)];
    for (int k = 0; k < 3; k++) {
      box[k] = 0.5 * (hi[k] + lo[k]);
      box[k + 3] = 0.5 * (hi[k] - lo[k]) + m.flex_radius[f];
    }
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
  SolverFrame frame(d.solver_scratch);
  const int* dofs = &m.flexedge_J_colind[m.flexedge_J_rowadr[e]];
  double* jac1 = frame.RealsToWrite(3 * static_cast<size_t>(n));
  double* jac2 = frame.RealsToWrite(3 * static_cast<size_t>(n));
  JacobianOnDofs(m, d, dofs, n, jac1, nullptr, pos1, m.flex_vertbodyid[v1]);
  JacobianOnDofs(m, d, dofs, n, jac2, nullptr, pos2, m.flex_vertbodyid[v2]);
  double* row = &d.flexedge_J[m.flexedge_J_rowadr[e]];
  for (int k = 0; k < n; k++) {
    double sum = 0;
    for (int r = 0; r < 3; r++) {
      if (dir[r] != 0) sum += (jac2[r * n + k] - jac1[r * n + k]) * dir[r];
    }
    row[k] = sum;
  }
}

// r (3 x 2) = a (3 x 2) b (2 x 2).
void MulMat322(double* r, const double* a, const double* b) {
  for (int i = 0; i < 3; i++) {
    r[2 * i] = a[2 * i] * b[0] + a[2 * i + 1] * b[2];
    r[2 * i + 1] = a[2 * i] * b[1] + a[2 * i + 1] * b[3];
  }
}

// Edge e of flex f seen from vertex v: its rest vector in the flex's plane (flex_vert0
// scaled by the box), its current vector, and the mass of its far end (at least
// mjMINVAL; 1 without a body).
double VertexEdge(const Model& m, const Data& d, int f, int e, int v, double dx[3], double dy[3]) {
  int vbase = m.flex_vertadr[f], ebase = m.flex_edgeadr[f];
  int v1 = m.flex_edge[2 * (ebase + e)], v2 = m.flex_edge[2 * (ebase + e) + 1];
  math::Sub3(dx, &m.flex_vert0[3 * (vbase + v2)], &m.flex_vert0[3 * (vbase + v1)]);
  for (int k = 0; k < 3; k++) dx[k] *= 2 * m.flex_size[3 * f + k];
  math::Sub3(dy, &d.flexvert_xpos[3 * (vbase + v2)], &d.flexvert_xpos[3 * (vbase + v1)]);
  int body = m.flex_vertbodyid[vbase + (v == v1 ? v2 : v1)];
  return body >= 0 ? std::max(m.body_mass[body], 1e-15) : 1.0;
}

// res (n) = jac (3 x n)^T vec, skipping zero entries of vec (MuJoCo's mju_mulMatTVec).
void MulJacT(const double* jac, const double* vec, int n, double* res) {
  std::fill(res, res + n, 0.0);
  for (int r = 0; r < 3; r++) {
    if (vec[r] == 0) continue;
    for (int k = 0; k < n; k++) res[k] += jac[r * n + k] * vec[r];
  }
}

// The derivative of one vertex invariant along one edge of vertex v, w.r.t. the edge's
// two ends (g1 at v1, -g1 at v2), added into the dense row `row`.
void AddEdgeEndsJacobian(const Model& m, Data& d, int f, int e, const double g1[3],
                         double* row, SolverFrame& frame) {
  int vbase = m.flex_vertadr[f], ebase = m.flex_edgeadr[f];
  int ends[2] = {vbase + m.flex_edge[2 * (ebase + e)], vbase + m.flex_edge[2 * (ebase + e) + 1]};
  int* chain = frame.IntsToWrite(m.nv);
  double* jac = frame.RealsToWrite(3 * static_cast<size_t>(m.nv));
  double* local = frame.RealsToWrite(m.nv);
  for (int side = 0; side < 2; side++) {
    int body = m.flex_vertbodyid[ends[side]];
    int n = MergedDofChain(m, body, body, chain);
    JacobianOnDofs(m, d, chain, n, jac, nullptr, &d.flexvert_xpos[3 * ends[side]], body);
    double g[3] = {side ? -g1[0] : g1[0], side ? -g1[1] : g1[1], side ? -g1[2] : g1[2]};
    MulJacT(jac, g, n, local);
    for (int j = 0; j < n; j++) row[chain[j]] += local[j];
  }
}

// Flex f's vertex invariants (Chen, Kry and Vouga's locking-free thin plates, as MuJoCo):
// per vertex, the trace and determinant of the Cauchy strain of its edges' deformation
// gradient, less their rest values, scaled by sqrt(mass); and their Jacobians.
void FlexVertexInvariants(const Model& m, Data& d, int f) {
  SolverFrame frame(d.solver_scratch);
  double* j0 = frame.Reals(m.nv);
  double* j1 = frame.Reals(m.nv);
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
      double g0[3], g1[3];
      for (int r = 0; r < 3; r++) {
        g0[r] = (fb[2 * r] * dx[0] + fb[2 * r + 1] * dx[1]) * (-2 * w);
        g1[r] = (fadjb[2 * r] * dx[0] + fadjb[2 * r + 1] * dx[1]) * (-2 * w);
      }
      AddEdgeEndsJacobian(m, d, f, e, g0, j0, frame);
      AddEdgeEndsJacobian(m, d, f, e, g1, j1, frame);
    }

    // Into the sparse rows, clearing the dense ones for the next vertex.
    for (int row = 0; row < 2; row++) {
      double* dense = row ? j1 : j0;
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

void FlexKinematics(const Model& m, Data& d) {
  if (m.nflex == 0) return;
  for (int f = 0; f < m.nflex; f++) {
    if (m.flex_interp[f] == 0) {
      FlexVertexPositions(m, d, f);
    } else {
      FlexInterpolatedPositions(m, d, f);
    }
  }
  for (int f = 0; f < m.nflex; f++) FlexElementBoxes(m, d, f);

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
