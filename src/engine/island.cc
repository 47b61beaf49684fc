// Constraint islands (MuJoCo mj_island, engine_island.c): kinematic trees joined by
// constraint rows form islands, and each island is an independent constraint problem.
// A tree touched by no row belongs to no island: its dofs keep the smooth acceleration.
//
// Trees are linked when one constraint's Jacobian reaches into both; the islands are the
// connected components of that tree graph, numbered in order of their first tree.
#include <algorithm>
#include <vector>

#include "engine/constraint.h"
#include "engine/island.h"

namespace simlab {

namespace {

// The trees row `r` acts on, as MuJoCo finds them: by the element for limits, dof
// friction, contacts (their geoms' bodies) and connect/weld, else by scanning the row. `trees` is reused between rows.
void RowTrees(const Model& m, const Data& d, int r, std::vector<int>* trees) {
  trees->clear();
  int id = d.efc_id[r];
  int type = d.efc_type[r];
  if (type == kCnstrFrictionDof) {
    trees->push_back(m.dof_treeid[id]);
  } else if (type == kCnstrLimitJoint) {
    trees->push_back(m.dof_treeid[m.jnt_dofadr[id]]);
  } else if (type >= kCnstrContactFrictionless) {
    // The moving side first (the world's tree is -1).
    int t1 = m.body_treeid[m.geom_bodyid[d.contact[id].geom[0]]];
    int t2 = m.body_treeid[m.geom_bodyid[d.contact[id].geom[1]]];
    if (t1 < 0) std::swap(t1, t2);
    trees->push_back(t1);
    trees->push_back(t2);
  } else if (type == kCnstrEquality && (m.eq_type[id] == kEqConnect || m.eq_type[id] == kEqWeld)) {
    trees->push_back(m.body_treeid[EqualityBody(m, id, 0)]);
    trees->push_back(m.body_treeid[EqualityBody(m, id, 1)]);
  } else {
    const double* row = &d.efc_J[static_cast<size_t>(r) * m.nv];
    for (int v = 0; v < m.nv; v++) {
      int tree = m.dof_treeid[v];
      if (row[v] != 0 && (trees->empty() || trees->back() != tree)) trees->push_back(tree);
    }
  }
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

  // Link the trees of every constraint; mark trees that carry any row. Rows of one
  // constraint share its trees; each row keeps its first moving tree.
  std::vector<int> parent(ntree), first_tree(d.nefc, -1), trees;
  std::vector<char> used(ntree, 0);
  for (int t = 0; t < ntree; t++) parent[t] = t;
  for (int r = 0; r < d.nefc; r++) {
    bool same = r > 0 && d.efc_type[r] == d.efc_type[r - 1] && d.efc_id[r] == d.efc_id[r - 1];
    if (same) {
      first_tree[r] = first_tree[r - 1];
      continue;
    }
    RowTrees(m, d, r, &trees);
    for (int t : trees) {
      if (t < 0) continue;  // the world
      used[t] = 1;
      if (first_tree[r] < 0) first_tree[r] = t;
      parent[Root(parent, t)] = Root(parent, first_tree[r]);
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
  for (int r = 0; r < d.nefc; r++) out->efc_island[r] = tree_island[first_tree[r]];
}

}  // namespace simlab
