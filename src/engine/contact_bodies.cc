// The bodies of a contact's two sides (contact_bodies.h).
#include "engine/contact_bodies.h"

#include <algorithm>
#include <cmath>

#include "engine/flex_cells.h"
#include "engine/flex_elasticity.h"

namespace simlab {

namespace {

bool ValidFlex(const Model& m, int f) { return f >= 0 && f < m.nflex; }

// The bodies of element e of flex f weighted by inverse distance to `point`, without
// vertex `skip` (flex numbering) when the element holds it (mj_elemBodyWeight).
bool ElementBodies(const Model& m, const Data& d, int f, int e, int skip, const double* point,
                   ContactSide* side) {
  int dim = m.flex_dim[f];
  if (e < 0 || e >= m.flex_elemnum[f] || dim < 1 || dim > 3) return false;
  const int* vert = &m.flex_elem[m.flex_elemdataadr[f] + e * (dim + 1)];
  int found = -1;
  for (int i = 0; i <= dim; i++) {
    const double* x = &d.flexvert_xpos[3 * static_cast<size_t>(m.flex_vertadr[f] + vert[i])];
    double dif[3] = {point[0] - x[0], point[1] - x[1], point[2] - x[2]};
    double dist = std::sqrt(dif[0] * dif[0] + dif[1] * dif[1] + dif[2] * dif[2]);
    side->weight[i] = 1.0 / std::max(kMinVal, dist);
    side->body[i] = m.flex_vertadr[f] + vert[i];  // (the vertex; its body comes later)
    if (vert[i] == skip) found = i;
  }
  int n = dim + 1;
  if (found >= 0) {
    for (int i = found; i < dim; i++) {
      side->weight[i] = side->weight[i + 1];
      side->body[i] = side->body[i + 1];
    }
    n--;
  }
  double sum = 0;
  for (int i = 0; i < n; i++) sum += side->weight[i];
  if (!(sum >= kMinVal)) return false;
  double scale = 1.0 / sum;
  for (int i = 0; i < n; i++) side->weight[i] = side->weight[i] * scale;
  side->n = n;
  return true;
}

// The nodes of interpolated flex f moving the vertices `vert` (global ids, weights
// `weight`, n of them): the shape functions of their weighted place in the box, the
// nodes whose function is below 1e-5 left out (mj_vertBodyWeight, mju_evalBasis).
void NodeBodies(const Model& m, int f, const int* vert, const double* weight, int n,
                ContactSide* side) {
  double x[3] = {0, 0, 0};
  for (int i = 0; i < n; i++) {
    const double* p = &m.flex_vert0[3 * static_cast<size_t>(vert[i])];
    for (int j = 0; j < 3; j++) x[j] = x[j] + p[j] * weight[i];
  }
  int order = m.flex_interp[f];
  side->n = 0;
  for (int i = 0; i < m.flex_nodenum[f] && side->n < ContactSide::kMax; i++) {
    double w = FlexNodeWeight(x, i, order);
    if (w < 1e-5) continue;
    side->weight[side->n] = w;
    side->body[side->n++] = m.flex_nodebodyid[m.flex_nodeadr[f] + i];
  }
}

// Adds weight w to `body` on the side, or the body with w if it is not there yet.
void AddBodyWeight(ContactSide* side, int body, double w) {
  for (int i = 0; i < side->n; i++) {
    if (side->body[i] != body) continue;
    side->weight[i] += w;
    return;
  }
  if (side->n == ContactSide::kMax) return;
  side->body[side->n] = body;
  side->weight[side->n++] = w;
}

// The nodes of flex f (made of cells) moving the vertices `vert` (global ids, weights
// `weight`, n of them): the cell holding their place weighted by the weights' sizes, its
// nodes' shape functions with the weights' sign (those below 1e-5 left out), a shell's
// interior node passed on to the boundary nodes it follows, each body once (MuJoCo
// 3.12's mj_vertBodyWeight).
void CellNodeBodies(const Model& m, int f, const int* vert, const double* weight, int n,
                    ContactSide* side) {
  double sign = n > 0 && weight[0] < 0 ? -1 : 1;
  double coord[3] = {0, 0, 0};
  for (int i = 0; i < n; i++) {
    const double* p = &m.flex_vert0[3 * static_cast<size_t>(vert[i])];
    for (int k = 0; k < 3; k++) coord[k] += p[k] * std::abs(weight[i]);
  }
  FlexLattice g = FlexLatticeOf(m, f);
  double local[3], basis[27];
  int ids[27];
  FlexCellLookup(coord, g.cells.data(), g.order, local, ids);
  FlexCellWeights(local, g.order, basis);
  const int* bodyid = &m.flex_nodebodyid[m.flex_nodeadr[f]];
  int ny = g.Nodes(1), nz = g.Nodes(2);
  side->n = 0;
  for (int j = 0; j < g.NodesPerCell(); j++) {
    double w = basis[j];
    if (w < 1e-5) continue;
    int node = ids[j];
    int i = node / (ny * nz), jj = (node / nz) % ny, k = node % nz;
    bool interior = i > 0 && i < g.Nodes(0) - 1 && jj > 0 && jj < ny - 1 && k > 0 && k < nz - 1;
    if (g.shell && interior) {
      FlexShellInteriorWeights(g, i, jj, k, sign * w, [&](int boundary, double bw) {
        AddBodyWeight(side, bodyid[boundary], bw);
      });
      continue;
    }
    AddBodyWeight(side, bodyid[node], sign * w);
  }
}

}  // namespace

bool ContactSideBodies(const Model& m, const Data& d, const Contact& c, int k,
                       bool signed_weights, ContactSide* side) {
  side->n = 0;
  double sign = signed_weights && k == 0 ? -1 : 1;
  if (c.geom[k] >= 0) {
    if (c.geom[k] >= m.ngeom) return false;
    side->n = 1;
    side->body[0] = m.geom_bodyid[c.geom[k]];
    side->weight[0] = sign;
    return true;
  }
  int f = c.flex[k];
  if (!ValidFlex(m, f)) return false;
  int interp = m.flex_interp[f];
  if (interp < -2 || interp > 2) return false;
  // The vertex (global id), or the element's vertices, with their weights.
  if (c.vert[k] >= 0) {
    if (c.vert[k] >= m.flex_vertnum[f]) return false;
    side->n = 1;
    side->body[0] = m.flex_vertadr[f] + c.vert[k];
    side->weight[0] = sign;
  } else {
    if (!ElementBodies(m, d, f, c.elem[k], c.vert[1 - k], c.pos, side)) return false;
    for (int i = 0; i < side->n && sign < 0; i++) side->weight[i] = side->weight[i] * -1;
  }
  // Vertices to bodies: their own, or an interpolated flex's nodes.
  if (interp != 0) {
    int vert[4];
    double weight[4];
    int n = std::min(side->n, 4);
    std::copy_n(side->body, n, vert);
    std::copy_n(side->weight, n, weight);
    if (FlexHasCells(m, f)) {
      CellNodeBodies(m, f, vert, weight, n, side);
    } else {
      NodeBodies(m, f, vert, weight, n, side);
    }
    return true;
  }
  for (int i = 0; i < side->n; i++) {
    side->body[i] = m.flex_vertbodyid[side->body[i]];
    if (side->body[i] < 0) return false;
  }
  return true;
}

bool ContactOnTwoBodies(const Model& m, const Contact& c) {
  for (int k = 0; k < 2; k++) {
    if (c.geom[k] >= 0) continue;
    bool vertex = c.vert[k] >= 0 && ValidFlex(m, c.flex[k]) && m.flex_interp[c.flex[k]] == 0;
    if (!vertex) return false;
  }
  return true;
}

bool ContactOnPassiveFlex(const Model& m, const Contact& c) {
  for (int k = 0; k < 2; k++) {
    if (ValidFlex(m, c.flex[k]) && m.flex_passive[c.flex[k]]) return true;
  }
  return false;
}

}  // namespace simlab
