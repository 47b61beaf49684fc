// Constraint islands (MuJoCo mj_island, engine_island.c): kinematic trees joined by
// constraint rows form islands, and each island is an independent constraint problem.
// A tree touched by no row belongs to no island: its dofs keep the smooth acceleration.
//
// Trees are linked when one constraint's Jacobian reaches into both; the islands are the
// connected components of that tree graph, numbered in order of their first tree.
#include <algorithm>

#include "engine/constraint.h"
#include "engine/flex_cells.h"
#include "engine/island.h"
#include "engine/rows.h"

namespace simlab {

namespace {

// The trees row `r` acts on, as MuJoCo finds them: by the element for limits, dof
// friction, contacts (their geoms' bodies) and connect/weld, else by scanning the row.
// Writes them to `trees` (room for nv + 1) and returns how many.
int RowTrees(const Model& m, const Data& d, int r, int* trees) {
  int id = d.efc_id[r];
  int type = d.efc_type[r];
  if (type == kCnstrFrictionDof) {
    trees[0] = m.dof_treeid[id];
    return 1;
  }
  if (type == kCnstrLimitJoint) {
    trees[0] = m.dof_treeid[m.jnt_dofadr[id]];
    return 1;
  }
  if (type >= kCnstrContactFrictionless && d.contact[id].geom[0] >= 0 &&
      d.contact[id].geom[1] >= 0) {
    // The moving side first (the world's tree is -1).
    trees[0] = m.body_treeid[m.geom_bodyid[d.contact[id].geom[0]]];
    trees[1] = m.body_treeid[m.geom_bodyid[d.contact[id].geom[1]]];
    if (trees[0] < 0) std::swap(trees[0], trees[1]);
    return 2;
  }
  if (type >= kCnstrContactFrictionless) {
    // A flex contact: the trees of the row's columns, every stored one with a sparse
    // Jacobian, the nonzero ones with a dense one (as MuJoCo's treeNext).
    bool sparse = SparseJacobian(m);
    int n = 0;
    for (int k = d.efc_J_rowadr[r]; k < d.efc_J_rowadr[r] + d.efc_J_rownnz[r]; k++) {
      int tree = m.dof_treeid[d.efc_J_colind[k]];
      if ((sparse || d.efc_J[k] != 0) && (n == 0 || trees[n - 1] != tree)) trees[n++] = tree;
    }
    return n;
  }
  if (type == kCnstrEquality && (m.eq_type[id] == kEqConnect || m.eq_type[id] == kEqWeld)) {
    trees[0] = m.body_treeid[EqualityBody(m, id, 0)];
    trees[1] = m.body_treeid[EqualityBody(m, id, 1)];
    return 2;
  }
  int n = 0;
  for (int k = d.efc_J_rowadr[r]; k < d.efc_J_rowadr[r] + d.efc_J_rownnz[r]; k++) {
    int tree = m.dof_treeid[d.efc_J_colind[k]];
    if (d.efc_J[k] != 0 && (n == 0 || trees[n - 1] != tree)) trees[n++] = tree;
  }
  return n;
}

// Union-find root with path halving.
int Root(int* parent, int t) {
  while (parent[t] != t) t = parent[t] = parent[parent[t]];
  return t;
}

// island_ntree, island_itreeadr and map_itree2tree from d.tree_island: each island's
// trees in increasing order, islands in order, then the trees of no island. `placed` is
// scratch for d.nisland counts.
void ListTreesByIsland(const Model& m, Data& d, int* placed) {
  const int* tree_island = d.tree_island.data();
  std::fill(d.island_ntree.begin(), d.island_ntree.begin() + d.nisland, 0);
  for (int t = 0; t < m.ntree; t++) {
    if (tree_island[t] >= 0) d.island_ntree[tree_island[t]]++;
  }
  int adr = 0;
  for (int i = 0; i < d.nisland; i++) {
    d.island_itreeadr[i] = adr;
    adr += d.island_ntree[i];
  }
  for (int t = 0; t < m.ntree; t++) {
    int island = tree_island[t];
    if (island >= 0) {
      d.map_itree2tree[d.island_itreeadr[island] + placed[island]++] = t;
    } else {
      d.map_itree2tree[adr++] = t;
    }
  }
}

// Joins the trees of each flex made of cells (flex_cells.h) whose elasticity couples
// its nodes without rows (its cells' or faces' stiffness, a shell's bending): MuJoCo
// 3.12's islands hold such a flex whole, its trees counted as constrained. (Other
// flexes keep MuJoCo 3.5.1's islands, made of rows only.)
void JoinElasticFlexTrees(const Model& m, const Data& d, int* parent, int* used) {
  for (int f = 0; f < m.nflex; f++) {
    if (!FlexHasCells(m, f) || m.flex_rigid[f] || m.flex_dim[f] < 2) continue;
    int adr = m.flex_stiffnessadr[f];
    if (m.flex_bendingadr[f] < 0 && (adr < 0 || m.flex_stiffness[adr] == 0)) continue;
    int first = -1;
    for (int j = m.flex_nodeadr[f]; j < m.flex_nodeadr[f] + m.flex_nodenum[f]; j++) {
      int t = m.body_treeid[m.flex_nodebodyid[j]];
      if (t < 0 || t == first || !d.tree_awake[t]) continue;
      if (first < 0) {
        first = t;
        continue;
      }
      used[first] = used[t] = 1;
      parent[Root(parent, t)] = Root(parent, first);
    }
  }
}

}  // namespace

void FindIslands(const Model& m, Data& d) {
  int ntree = m.ntree;
  SolverFrame frame(d.solver_scratch);
  int* parent = frame.Ints(ntree);
  int* used = frame.Ints(ntree);
  int* first_tree = frame.Ints(d.nefc);
  int* trees = frame.Ints(m.nv + 1);

  // Link the trees of every constraint; mark trees that carry any row. Rows of one
  // constraint share its trees; each row keeps its first moving tree.
  for (int t = 0; t < ntree; t++) parent[t] = t;
  for (int r = 0; r < d.nefc; r++) {
    // (except a flex equality's rows, one per edge, vertex invariant or strain mode, each
    // on the trees of its own columns)
    bool same = r > 0 && d.efc_type[r] == d.efc_type[r - 1] && d.efc_id[r] == d.efc_id[r - 1];
    int eq_type = d.efc_type[r] == kCnstrEquality ? m.eq_type[d.efc_id[r]] : -1;
    bool flex = eq_type == kEqFlex || eq_type == kEqFlexVert || eq_type == kEqFlexStrain;
    same = same && !flex;
    if (same) {
      first_tree[r] = first_tree[r - 1];
      continue;
    }
    first_tree[r] = -1;
    int n = RowTrees(m, d, r, trees);
    for (int k = 0; k < n; k++) {
      int t = trees[k];
      if (t < 0) continue;  // the world
      used[t] = 1;
      if (first_tree[r] < 0) first_tree[r] = t;
      parent[Root(parent, t)] = Root(parent, first_tree[r]);
    }
  }

  JoinElasticFlexTrees(m, d, parent, used);

  // Number islands by their lowest tree; map dofs and rows.
  int* tree_island = d.tree_island.data();
  int* root_island = frame.Ints(ntree);
  std::fill(tree_island, tree_island + ntree, -1);
  std::fill(root_island, root_island + ntree, -1);
  d.nisland = 0;
  for (int t = 0; t < ntree; t++) {
    if (!used[t]) continue;
    int root = Root(parent, t);
    if (root_island[root] < 0) root_island[root] = d.nisland++;
    tree_island[t] = root_island[root];
  }
  for (int v = 0; v < m.nv; v++) d.dof_island[v] = tree_island[m.dof_treeid[v]];
  ListTreesByIsland(m, d, frame.Ints(d.nisland));
  for (int r = 0; r < d.nefc; r++) {
    d.efc_island[r] = first_tree[r] < 0 ? -1 : tree_island[first_tree[r]];
  }
}

}  // namespace simlab
