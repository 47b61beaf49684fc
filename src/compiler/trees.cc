// Kinematic trees and their sleep policies (MuJoCo's setConst tree part and the
// compiler's sleep rules): where each tree's bodies and dofs start, which trees a tendon
// runs through, and whether a tree may sleep.
#include <algorithm>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "mjcf/error.h"

namespace simlab::compiler {

namespace {

// The tree of the body a tendon path element is attached to, or -1 (pulleys, the world).
int WrapTree(const Model& m, int w) {
  int id = m.wrap_objid[w], body = -1;
  switch (m.wrap_type[w]) {
    case kWrapJoint: body = m.jnt_bodyid[id]; break;
    case kWrapSite: body = m.site_bodyid[id]; break;
    case kWrapSphere:
    case kWrapCylinder: body = m.geom_bodyid[id]; break;
    default: break;
  }
  return body >= 0 ? m.body_treeid[body] : -1;
}

// The distinct trees along tendon t's path, in path order.
std::vector<int> TendonTrees(const Model& m, int t) {
  std::vector<int> trees;
  for (int w = m.tendon_adr[t]; w < m.tendon_adr[t] + m.tendon_num[t]; w++) {
    int tree = WrapTree(m, w);
    if (tree >= 0 && std::find(trees.begin(), trees.end(), tree) == trees.end()) trees.push_back(tree);
  }
  return trees;
}

// tree_bodyadr/bodynum and tree_dofadr/dofnum: trees are numbered by their first dof, and
// their bodies and dofs are contiguous.
void TreeRanges(Model* m) {
  std::fill(m->tree_bodynum.begin(), m->tree_bodynum.end(), 0);
  std::fill(m->tree_dofnum.begin(), m->tree_dofnum.end(), 0);
  int current = -1;
  for (int b = 1; b < m->nbody; b++) {
    int tree = m->body_treeid[b];
    if (tree < 0) continue;
    if (tree > current) m->tree_bodyadr[current = tree] = b;
    m->tree_bodynum[current]++;
  }
  current = -1;
  for (int v = 0; v < m->nv; v++) {
    if (m->dof_treeid[v] > current) m->tree_dofadr[current = m->dof_treeid[v]] = v;
    m->tree_dofnum[current]++;
  }
}

// tendon_treenum and the first two tendon_treeid.
void TendonTreeIds(Model* m) {
  for (int t = 0; t < m->ntendon; t++) {
    std::vector<int> trees = TendonTrees(*m, t);
    m->tendon_treenum[t] = static_cast<int>(trees.size());
    m->tendon_treeid[2 * t] = trees.size() > 0 ? trees[0] : -1;
    m->tendon_treeid[2 * t + 1] = trees.size() > 1 ? trees[1] : -1;
  }
}

// A policy the model gives on a body: only a moving root body (the first of its tree).
void ExplicitPolicies(const CompileState& state, Model* m) {
  for (int b = 1; b < m->nbody; b++) {
    const mjcf::BodySpec& spec = *state.bodies[b].spec;
    if (spec.sleep == kSleepAuto) continue;
    int tree = m->body_treeid[b];
    if (tree < 0 || tree == m->body_treeid[b - 1]) {
      mjcf::ThrowAt(spec.src, "sleep policy only allowed for movable root bodies");
    }
    m->tree_sleep_policy[tree] = spec.sleep;
  }
}

// The tree an actuator moves through its joint, site or body (tendons: see below).
int ActuatorTree(const Model& m, int a) {
  int id = m.actuator_trnid[2 * a], body = -1;
  switch (m.actuator_trntype[a]) {
    case kTrnJoint:
    case kTrnJointInParent:
    case kTrnSo3: body = m.jnt_bodyid[id]; break;
    case kTrnSite:
    case kTrnSliderCrank: body = m.site_bodyid[id]; break;
    case kTrnBody: body = id; break;
    default: break;
  }
  return body >= 0 ? m.body_treeid[body] : -1;
}

// May the trees of flex f sleep? MuJoCo 3.12 lets a flex whose edges an equality holds
// sleep (its trees then share an island), and no other. MuJoCo 3.5.1 let no flex sleep
// and refused to step a flex equality with sleep enabled: its choice is kept where it
// could run the model, with sleep disabled in a model that follows 3.5.1 (Model::release).
bool FlexMaySleep(const Model& m, int f) {
  bool sleep = (m.opt.enableflags & kEnableSleep) != 0;
  return m.flex_edgeequality[f] != 0 && (sleep || m.release == Release::k3_12);
}

// Automatic policies: actuated trees never sleep, nor do trees a tendon couples with
// stiffness or damping or across more than two trees (an error when the model asked
// that such a tree sleep), nor do trees of flexes that may not (FlexMaySleep); every
// other automatic tree may.
void AutomaticPolicies(const CompileState& state, Model* m) {
  auto never = [m](int tree) {
    if (tree >= 0 && m->tree_sleep_policy[tree] == kSleepAuto) m->tree_sleep_policy[tree] = kSleepAutoNever;
  };
  for (int a = 0; a < m->nactuator; a++) {
    if (m->actuator_trntype[a] == kTrnTendon) {
      for (int tree : TendonTrees(*m, m->actuator_trnid[2 * a])) never(tree);
    } else {
      never(ActuatorTree(*m, a));
    }
  }
  for (int t = 0; t < m->ntendon; t++) {
    int n = m->tendon_treenum[t];
    bool springy = m->tendon_stiffness[t] != 0 || m->tendon_damping[t] != 0;
    if (n < 2 || (n == 2 && !springy)) continue;
    for (int tree : TendonTrees(*m, t)) {
      int policy = m->tree_sleep_policy[tree];
      if (policy == kSleepAllowed || policy == kSleepInit) {
        std::string why = n > 2 ? "which spans more than 2 trees" : "with non-zero stiffness or damping";
        mjcf::ThrowAt(state.spec->tendons[t].src, "tree " + std::to_string(tree) + " connected to tendon " +
                                                      std::to_string(t) + " " + why + ", sleeping not allowed");
      }
      never(tree);
    }
  }
  // Trees that carry the vertices (or nodes) of a flex that may not sleep.
  for (int f = 0; f < m->nflex; f++) {
    if (FlexMaySleep(*m, f)) continue;
    bool nodes = m->flex_interp[f] != 0;
    int begin = nodes ? m->flex_nodeadr[f] : m->flex_vertadr[f];
    int count = nodes ? m->flex_nodenum[f] : m->flex_vertnum[f];
    for (int j = begin; j < begin + count; j++) {
      int body = nodes ? m->flex_nodebodyid[j] : m->flex_vertbodyid[j];
      if (body >= 0) never(m->body_treeid[body]);
    }
  }
  for (int& policy : m->tree_sleep_policy) {
    if (policy == kSleepAuto) policy = kSleepAutoAllowed;
  }
}

}  // namespace

void CompileTrees(const CompileState& state, Model* m) {
  TreeRanges(m);
  TendonTreeIds(m);
  std::fill(m->tree_sleep_policy.begin(), m->tree_sleep_policy.end(), static_cast<int>(kSleepAuto));
  ExplicitPolicies(state, m);
  AutomaticPolicies(state, m);
}

}  // namespace simlab::compiler
