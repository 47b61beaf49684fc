// Constraint islands (MuJoCo mj_island, engine_island.c): kinematic trees joined by
// constraint rows form islands, and each island is an independent constraint problem.
// A tree touched by no row belongs to no island: its dofs keep the smooth acceleration.
//
// Trees are linked when one constraint's Jacobian reaches into both; the islands are the
// connected components of that tree graph, numbered in order of their first tree.
#include <algorithm>
#include <vector>

#include "engine/island.h"

namespace simlab {

namespace {

// The trees one constraint (its first row `r`) acts on, as MuJoCo finds them: by the
// element for limits, dof friction and connect/weld, else by scanning the row.
std::vector<int> RowTrees(const Model& m, const Data& d, int r) {
  int id = d.efc_id[r];
  switch (d.efc_type[r]) {
    case kCnstrFrictionDof: return {m.dof_treeid[id]};
    case kCnstrLimitJoint: return {m.dof_treeid[m.jnt_dofadr[id]]};
    case kCnstrEquality:
      if (m.eq_type[id] == kEqConnect || m.eq_type[id] == kEqWeld) {
        int b1 = m.eq_obj1id[id], b2 = m.eq_obj2id[id];
        if (m.eq_objtype[id] == kObjSite) {
          b1 = m.site_bodyid[b1];
          b2 = m.site_bodyid[b2];
        }
        return {m.body_treeid[b1], m.body_treeid[b2]};
      }
      break;
    default: break;
  }
  std::vector<int> trees;
  const double* row = &d.efc_J[static_cast<size_t>(r) * m.nv];
  for (int v = 0; v < m.nv; v++) {
    if (row[v] != 0) trees.push_back(m.dof_treeid[v]);
  }
  return trees;
}

// Union-find root with path halving.
int Root(std::vector<int>& parent, int t) {
  while (parent[t] != t) t = parent[t] = parent[parent[t]];
  return t;
}

}  // namespace

void FindIslands(const Model& m, const Data& d, Islands* out) {
  int ntree = 0;
  for (int v = 0; v < m.nv; v++) ntree = std::max(ntree, m.dof_treeid[v] + 1);

  // Link the trees of every constraint; mark trees that carry any row.
  std::vector<int> parent(ntree);
  std::vector<char> used(ntree, 0);
  for (int t = 0; t < ntree; t++) parent[t] = t;
  for (int r = 0; r < d.nefc; r++) {
    bool same = r > 0 && d.efc_type[r] == d.efc_type[r - 1] && d.efc_id[r] == d.efc_id[r - 1];
    if (same) continue;
    int first = -1;
    for (int t : RowTrees(m, d, r)) {
      if (t < 0) continue;  // the world
      used[t] = 1;
      if (first < 0) first = t;
      parent[Root(parent, t)] = Root(parent, first);
    }
  }

  // Number islands by their lowest tree; map dofs and rows.
  std::vector<int> tree_island(ntree, -1), root_island(ntree, -1);
  out->nisland = 0;
  for (int t = 0; t < ntree; t++) {
    if (!used[t]) continue;
    int root = Root(parent, t);
    if (root_island[root] < 0) root_island[root] = out->nisland++;
    tree_island[t] = root_island[root];
  }
  out->dof_island.assign(m.nv, -1);
  for (int v = 0; v < m.nv; v++) out->dof_island[v] = tree_island[m.dof_treeid[v]];
  out->efc_island.assign(d.nefc, -1);
  for (int r = 0; r < d.nefc; r++) {
    for (int t : RowTrees(m, d, r)) {
      if (t >= 0) {
        out->efc_island[r] = tree_island[t];
        break;
      }
    }
  }
}

}  // namespace simlab
