// The flex constants that need the model at qpos0 (MuJoCo's makeFlexSparse and the flex
// parts of set0 and setStat): the sparsity of the edge Jacobian, the edges' inverse
// weights, and the body sizes the edges lengthen.
#include <algorithm>
#include <vector>

#include "compiler/compiler.h"
#include "engine/engine.h"
#include "math/dot.h"
#include "math/math.h"
#include "simlab/simlab.h"

namespace simlab::compiler {

namespace {

constexpr double kMinVal = 1e-15;  // MuJoCo's mjMINVAL

// The edges at each vertex of flex f (flex_vertedgeadr, flex_vertedgenum, and the
// flex's edge ids from *offset in flex_vertedge), in edge order.
void VertexEdges(Model* m, int f, int* offset) {
  int vbase = m->flex_vertadr[f], ebase = m->flex_edgeadr[f], nvert = m->flex_vertnum[f];
  int* count = &m->flex_vertedgenum[vbase];
  int* adr = &m->flex_vertedgeadr[vbase];
  for (int e = 0; e < m->flex_edgenum[f]; e++) {
    count[m->flex_edge[2 * (ebase + e)]]++;
    count[m->flex_edge[2 * (ebase + e) + 1]]++;
  }
  int total = 0;
  for (int v = 0; v < nvert; v++) {
    adr[v] = *offset + total;
    total += count[v];
  }
  std::vector<int> filled(nvert, 0);
  for (int e = 0; e < m->flex_edgenum[f]; e++) {
    for (int side = 0; side < 2; side++) {
      int v = m->flex_edge[2 * (ebase + e) + side];
      m->flex_vertedge[adr[v] + filled[v]++] = e;
    }
  }
  *offset += total;
}

// Each vertex's metric, the inverse of its mass-weighted rest edge outer products (2 x 2,
// in the flex's plane; zero when singular). The flex must lie in the xy plane.
void VertexMetrics(Model* m, int f) {
  int vbase = m->flex_vertadr[f];
  for (int v = 0; v < m->flex_vertnum[f]; v++) {
    double b[4] = {0, 0, 0, 0};
    int adr = m->flex_vertedgeadr[vbase + v];
    for (int k = 0; k < m->flex_vertedgenum[vbase + v]; k++) {
      double dx[3];
      double weight = FlexRestEdge(*m, f, m->flex_vertedge[adr + k], v, dx);
      if (std::abs(dx[2]) > kMinVal) throw Error("flex vertices are not in the same plane");
      for (int r = 0; r < 2; r++) {
        for (int c = 0; c < 2; c++) b[2 * r + c] += weight * dx[r] * dx[c];
      }
    }
    double* metric = &m->flex_vertmetric[4 * (vbase + v)];
    double det = b[0] * b[3] - b[1] * b[2];
    if (std::abs(det) < kMinVal) continue;
    double inv = 1.0 / det;
    metric[0] = b[3] * inv;
    metric[1] = -b[1] * inv;
    metric[2] = -b[2] * inv;
    metric[3] = b[0] * inv;
  }
}

// The two rows per vertex of the vertex Jacobian: on the dofs of the bodies of the
// vertex's edges' ends, ascending; rows follow the previous flex's.
void VertexJacobianSparsity(Model* m, int f) {
  int vbase = m->flex_vertadr[f], ebase = m->flex_edgeadr[f];
  int* rowadr = m->flexvert_J_rowadr.data();
  int* rownnz = m->flexvert_J_rownnz.data();
  int first = 2 * vbase;
  rowadr[first] = first > 0 ? rowadr[first - 1] + rownnz[first - 1] : 0;
  std::vector<int> chain(m->nv);
  std::vector<char> used(m->nv);
  for (int v = 0; v < m->flex_vertnum[f]; v++) {
    std::fill(used.begin(), used.end(), 0);
    int adr = m->flex_vertedgeadr[vbase + v], nnz = 0;
    for (int k = 0; k < m->flex_vertedgenum[vbase + v]; k++) {
      int e = ebase + m->flex_vertedge[adr + k];
      for (int side = 0; side < 2; side++) {
        int body = m->flex_vertbodyid[vbase + m->flex_edge[2 * e + side]];
        int n = MergedDofChain(*m, body, body, chain.data());
        for (int j = 0; j < n; j++) nnz += used[chain[j]] ? 0 : (used[chain[j]] = 1);
      }
    }
    int row0 = 2 * (vbase + v), row1 = row0 + 1;
    rownnz[row0] = rownnz[row1] = nnz;
    rowadr[row1] = rowadr[row0] + nnz;
    if (row1 + 1 < 2 * m->nflexvert) rowadr[row1 + 1] = rowadr[row1] + nnz;
    for (int j = 0, c = 0; j < m->nv; j++) {
      if (!used[j]) continue;
      m->flexvert_J_colind[rowadr[row0] + c] = j;
      m->flexvert_J_colind[rowadr[row1] + c] = j;
      c++;
    }
  }
}

}  // namespace

void FlexAlignToPlane(Model* m) {
  for (int f = 0; f < m->nflex; f++) {
    if (m->flex_dim[f] != 2 || m->flex_edgeequality[f] != 2) continue;
    // The first triangle's normal turned to z, every vertex with it.
    int vbase = m->flex_vertadr[f];
    const int* t = &m->flex_elem[m->flex_elemdataadr[f]];
    double* v0 = &m->flex_vert0[3 * vbase];
    double e1[3], e2[3], normal[3], quat[4], mat[9];
    math::Sub3(e1, v0 + 3 * t[1], v0 + 3 * t[0]);
    math::Sub3(e2, v0 + 3 * t[2], v0 + 3 * t[0]);
    math::Cross3(normal, e1, e2);
    math::Normalize3(normal);
    math::QuatZToVec(quat, normal);
    math::QuatToMat(mat, quat);
    for (int v = 0; v < m->flex_vertnum[f]; v++) {
      double turned[3];
      math::MulMatTVec3(turned, mat, v0 + 3 * v);
      math::Copy3(v0 + 3 * v, turned);
    }
  }
}

void FlexJacobianSparsity(Model* m) {
  std::fill(m->flexedge_J_rowadr.begin(), m->flexedge_J_rowadr.end(), 0);
  std::fill(m->flexedge_J_rownnz.begin(), m->flexedge_J_rownnz.end(), 0);
  std::fill(m->flexvert_J_rowadr.begin(), m->flexvert_J_rowadr.end(), 0);
  std::fill(m->flexvert_J_rownnz.begin(), m->flexvert_J_rownnz.end(), 0);
  std::fill(m->flex_vertedgeadr.begin(), m->flex_vertedgeadr.end(), 0);
  std::fill(m->flex_vertedgenum.begin(), m->flex_vertedgenum.end(), 0);
  std::fill(m->flex_vertedge.begin(), m->flex_vertedge.end(), 0);
  std::fill(m->flex_vertmetric.begin(), m->flex_vertmetric.end(), 0.0);
  std::vector<int> chain(m->nv);
  int vertedge_offset = 0;
  for (int f = 0; f < m->nflex; f++) {
    if (m->flex_rigid[f] || m->flex_interp[f]) continue;
    // (no edge equality, spring or damper: no rows, as MuJoCo)
    bool none = !m->flex_edgeequality[f] && !m->flex_edgedamping[f] &&
                !m->flex_edgestiffness[f] && !m->flex_damping[f];

    // Each edge's row: after the previous edge's (MuJoCo's rule, which restarts at 0
    // after a flex without rows), on the dofs that move either vertex's body.
    int vbase = m->flex_vertadr[f], ebase = m->flex_edgeadr[f];
    for (int e = ebase; e < ebase + m->flex_edgenum[f] && !none; e++) {
      if (e > 0) m->flexedge_J_rowadr[e] = m->flexedge_J_rowadr[e - 1] + m->flexedge_J_rownnz[e - 1];
      int b1 = m->flex_vertbodyid[vbase + m->flex_edge[2 * e]];
      int b2 = m->flex_vertbodyid[vbase + m->flex_edge[2 * e + 1]];
      int n = MergedDofChain(*m, b1, b2, chain.data());
      m->flexedge_J_rownnz[e] = n;
      std::copy(chain.begin(), chain.begin() + n, m->flexedge_J_colind.begin() + m->flexedge_J_rowadr[e]);
    }

    // A cloth kept by its vertices' metric: adjacency, metrics, vertex rows.
    if (m->flex_dim[f] == 2 && m->flex_edgeequality[f] == 2) {
      VertexEdges(m, f, &vertedge_offset);
      VertexMetrics(m, f);
      VertexJacobianSparsity(m, f);
    }
  }
}

void FlexEdgeInvWeights(Model* m, const Data& d) {
  if (m->nv == 0) return;
  std::vector<double> row(m->nv), solved(m->nv);
  for (int f = 0; f < m->nflex; f++) {
    if (m->flex_interp[f]) continue;
    int vbase = m->flex_vertadr[f];
    for (int e = m->flex_edgeadr[f]; e < m->flex_edgeadr[f] + m->flex_edgenum[f]; e++) {
      int b1 = m->flex_vertbodyid[vbase + m->flex_edge[2 * e]];
      int b2 = m->flex_vertbodyid[vbase + m->flex_edge[2 * e + 1]];
      // Rigid edges weigh nothing; edges between point masses, their mean inverse mass;
      // others J M^-1 J'.
      if (m->flexedge_rigid[e]) {
        m->flexedge_invweight0[e] = 0;
      } else if (m->body_simple[b1] == 2 && m->body_simple[b2] == 2) {
        m->flexedge_invweight0[e] = (1 / m->body_mass[b1] + 1 / m->body_mass[b2]) / 2;
      } else {
        std::fill(row.begin(), row.end(), 0.0);
        int adr = m->flexedge_J_rowadr[e];
        for (int j = adr; j < adr + m->flexedge_J_rownnz[e]; j++) {
          row[m->flexedge_J_colind[j]] = d.flexedge_J[j];
        }
        solved = row;
        SolveSparse(*m, d.qLD.data(), d.qLDiagInv.data(), solved.data());
        m->flexedge_invweight0[e] = math::Dot(row.data(), solved.data(), m->nv);
      }
    }
  }
}

void FlexBodySizes(const Model& m, const Data& d, std::vector<double>* size) {
  auto& s = *size;
  for (int f = 0; f < m.nflex; f++) {
    // An interpolated flex: each node body reaches as far as the farthest other node.
    if (m.flex_interp[f]) {
      int begin = m.flex_nodeadr[f], end = begin + m.flex_nodenum[f];
      for (int v1 = begin; v1 < end; v1++) {
        for (int v2 = begin; v2 < end; v2++) {
          int b1 = m.flex_nodebodyid[v1], b2 = m.flex_nodebodyid[v2];
          double dif[3];
          math::Sub3(dif, &d.xpos[3 * b1], &d.xpos[3 * b2]);
          s[b1] = std::max(s[b1], math::Norm3(dif));
        }
      }
      continue;
    }
    // Otherwise each vertex body as far as its longest edge.
    int vbase = m.flex_vertadr[f];
    for (int e = m.flex_edgeadr[f]; e < m.flex_edgeadr[f] + m.flex_edgenum[f]; e++) {
      int b1 = m.flex_vertbodyid[vbase + m.flex_edge[2 * e]];
      int b2 = m.flex_vertbodyid[vbase + m.flex_edge[2 * e + 1]];
      s[b1] = std::max(s[b1], m.flexedge_length0[e]);
      s[b2] = std::max(s[b2], m.flexedge_length0[e]);
    }
  }
}

}  // namespace simlab::compiler
