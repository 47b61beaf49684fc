// Sleeping trees (see sleep.h): the derived arrays, waking, and falling asleep.
#include "engine/sleep.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

bool SleepEnabled(const Model& m) { return m.opt.enableflags & kEnableSleep; }

// True when every number is +0 (bit for bit, as MuJoCo compares bytes: -0 is not zero).
bool AllPositiveZero(const double* x, int n) {
  for (int i = 0; i < n; i++) {
    if (x[i] != 0 || std::signbit(x[i])) return false;
  }
  return true;
}

// True when max_i weight_i |x_i| stays below tol.
bool WeightedBelow(const double* x, const double* weight, int n, double tol) {
  double largest = 0;
  for (int i = 0; i < n; i++) {
    largest = std::max(largest, weight[i] * std::abs(x[i]));
    if (largest >= tol) return false;
  }
  return true;
}

// Whether tree t may sleep now: its policy allows it, nothing pushes it, and its dofs
// are slower than `tol` (dof_length scales the rotating ones); exactly still for tol 0.
bool TreeCanSleep(const Model& m, const Data& d, int t, double tol) {
  int policy = m.tree_sleep_policy[t];
  if (policy == kSleepNever || policy == kSleepAutoNever) return false;
  int body = m.tree_bodyadr[t], nbody = m.tree_bodynum[t];
  if (!AllPositiveZero(&d.xfrc_applied[6 * body], 6 * nbody)) return false;
  int dof = m.tree_dofadr[t], ndof = m.tree_dofnum[t];
  if (!AllPositiveZero(&d.qfrc_applied[dof], ndof)) return false;
  if (tol) return WeightedBelow(&d.qvel[dof], &m.dof_length[dof], ndof, tol);
  return AllPositiveZero(&d.qvel[dof], ndof);
}

// The lowest tree of the sleeping cycle through tree t, or -1 if t is in none.
int CycleId(const Data& d, int ntree, int t) {
  int lowest = t, current = t;
  for (int count = 0;; count++) {
    if (count > ntree) return -1;
    int next = d.tree_asleep[current];
    if (next < 0 || next >= ntree) return -1;
    lowest = std::min(lowest, next);
    current = next;
    if (current == t) return lowest;
  }
}

// Wakes tree t and the whole cycle it sleeps in, each to `value`; an awake tree only
// takes `value` if that is further from sleep. Returns how many trees woke.
int WakeTree(Data& d, int ntree, int t, int value) {
  if (d.tree_asleep[t] < 0) {
    d.tree_asleep[t] = std::min(value, d.tree_asleep[t]);
    return 0;
  }
  int woke = 0, current = t;
  do {
    int next = d.tree_asleep[current];
    if (next < 0 || next >= ntree) throw std::logic_error("sleep: broken cycle at tree " + std::to_string(t));
    d.tree_asleep[current] = value;
    woke++;
    current = next;
  } while (current != t && woke < ntree);
  return woke;
}

// Wakes whichever of trees a and b sleeps when the other is awake, to the awake one's
// count. Returns how many woke.
int WakeFromAwakePartner(Data& d, int ntree, int a, int b) {
  bool awake_a = d.tree_awake[a], awake_b = d.tree_awake[b];
  if (awake_a == awake_b) return 0;
  int sleeper = awake_a ? b : a;
  return WakeTree(d, ntree, sleeper, d.tree_asleep[awake_a ? a : b]);
}

// The bodies that move flex f, n of them: its nodes' (interpolated) or its vertices'.
const int* FlexMovers(const Model& m, int f, int* n) {
  if (m.flex_interp[f]) {
    *n = m.flex_nodenum[f];
    return &m.flex_nodebodyid[m.flex_nodeadr[f]];
  }
  *n = m.flex_vertnum[f];
  return &m.flex_vertbodyid[m.flex_vertadr[f]];
}

// A flex's sleep state: its first moving body's (the flex's trees share one island, so
// they sleep and wake together), or static when none moves (MuJoCo 3.12's mjOBJ_FLEX).
SleepState FlexSleepState(const Model& m, const Data& d, int f) {
  int n;
  const int* body = FlexMovers(m, f, &n);
  for (int j = 0; j < n; j++) {
    if (m.body_treeid[body[j]] >= 0) return static_cast<SleepState>(d.body_awake[body[j]]);
  }
  return kStatic;
}

// The body that stands for side k of contact c (MuJoCo 3.12's mj_flexBody): a geom's; a
// vertex's; else an element's first vertex's, or an interpolated flex's first node's.
int ContactSideBody(const Model& m, const Contact& c, int k) {
  if (c.geom[k] >= 0) return m.geom_bodyid[c.geom[k]];
  int f = c.flex[k];
  if (m.flex_interp[f]) return m.flex_nodebodyid[m.flex_nodeadr[f]];
  int vert = c.vert[k];
  if (vert < 0) vert = m.flex_elem[m.flex_elemdataadr[f] + c.elem[k] * (m.flex_dim[f] + 1)];
  return m.flex_vertbodyid[m.flex_vertadr[f] + vert];
}

// Flex equality on flex f: once any of the flex's trees is awake, the island of its
// first sleeping tree wakes, to that awake tree's count (MuJoCo 3.12). Returns how many
// trees woke.
int WakeFlexEquality(const Model& m, Data& d, int f) {
  int n;
  const int* body = FlexMovers(m, f, &n);
  auto tree_of = [&](int j) { return m.body_treeid[body[j]]; };
  int awake = -1;
  for (int j = 0; j < n && awake < 0; j++) {
    if (tree_of(j) >= 0 && d.tree_awake[tree_of(j)]) awake = tree_of(j);
  }
  if (awake < 0) return 0;
  for (int j = 0; j < n; j++) {
    int t = tree_of(j);
    if (t >= 0 && !d.tree_awake[t]) return WakeTree(d, m.ntree, t, d.tree_asleep[awake]);
  }
  return 0;
}

// The trees of equality e's two sides (-1: the world), for the types that can wake.
bool EqualityTrees(const Model& m, int e, int* a, int* b) {
  int id1 = m.eq_obj1id[e], id2 = m.eq_obj2id[e];
  switch (m.eq_type[e]) {
    case kEqConnect:
    case kEqWeld:
      *a = m.body_treeid[EqualityBody(m, e, 0)];
      *b = m.body_treeid[EqualityBody(m, e, 1)];
      return true;
    case kEqJoint:
      *a = id1 >= 0 ? m.body_treeid[m.jnt_bodyid[id1]] : -1;
      *b = id2 >= 0 ? m.body_treeid[m.jnt_bodyid[id2]] : -1;
      return true;
    case kEqTendon:
      throw std::runtime_error("tendon equality does not yet support sleeping");
    default:
      // (flex, flexvert, flexstrain: WakeFlexEquality)
      return false;
  }
}

// True when tendon t is limited and within its margin of either end (MuJoCo tendonLimit).
bool TendonLimitActive(const Model& m, const Data& d, int t) {
  if (!m.tendon_limited[t]) return false;
  for (int side = -1; side <= 1; side += 2) {
    if (LimitDistance(&m.tendon_range[2 * t], d.ten_length[t], side) < m.tendon_margin[t]) return true;
  }
  return false;
}

// Puts the n trees in `trees` to sleep as one cycle; zeroes their qvel and qacc.
void SleepTrees(const Model& m, Data& d, const int* trees, int n) {
  for (int i = 0; i < n; i++) {
    int t = trees[i];
    if (d.tree_asleep[t] != -1) throw std::logic_error("sleep: tree " + std::to_string(t) + " is not ready");
    d.tree_asleep[t] = trees[i + 1 < n ? i + 1 : 0];
    std::fill_n(&d.qvel[m.tree_dofadr[t]], m.tree_dofnum[t], 0.0);
    std::fill_n(&d.qacc[m.tree_dofadr[t]], m.tree_dofnum[t], 0.0);
  }
}

// Counts up the slow steps of the awake trees (back to the start for a fast one).
void CountSlowSteps(const Model& m, Data& d) {
  for (int t = 0; t < m.ntree; t++) {
    int& asleep = d.tree_asleep[t];
    if (asleep >= 0) continue;
    if (TreeCanSleep(m, d, t, m.opt.sleep_tolerance)) {
      asleep += asleep < -1;
    } else {
      asleep = kTreeAwake;
    }
  }
}

SleepState TendonSleepState(const Model& m, const Data& d, int t) {
  int n = m.tendon_treenum[t];
  if (n == 0) return kStatic;
  const int* tree = &m.tendon_treeid[2 * t];
  if (n == 1) return d.tree_awake[tree[0]] ? kAwake : kAsleep;
  if (n == 2) return d.tree_awake[tree[0]] || d.tree_awake[tree[1]] ? kAwake : kAsleep;
  return kAwake;
}

SleepState ActuatorSleepState(const Model& m, const Data& d, int a) {
  int id = m.actuator_trnid[2 * a];
  switch (m.actuator_trntype[a]) {
    case kTrnJoint:
    case kTrnJointInParent:
    case kTrnSo3: return ElementSleepState(m, d, kObjJoint, id);
    case kTrnSliderCrank: {
      bool awake = ElementSleepState(m, d, kObjSite, id) == kAwake ||
                   ElementSleepState(m, d, kObjSite, m.actuator_trnid[2 * a + 1]) == kAwake;
      return awake ? kAwake : kAsleep;
    }
    case kTrnTendon: return TendonSleepState(m, d, id);
    case kTrnSite: return ElementSleepState(m, d, kObjSite, id);
    case kTrnBody: return ElementSleepState(m, d, kObjBody, id);
    default: return kAwake;
  }
}

SleepState EqualitySleepState(const Model& m, const Data& d, int e) {
  int type;
  switch (m.eq_type[e]) {
    case kEqConnect:
    case kEqWeld: type = m.eq_objtype[e]; break;
    case kEqJoint: type = kObjJoint; break;
    case kEqTendon: type = kObjTendon; break;
    case kEqFlex:
    case kEqFlexVert:
    case kEqFlexStrain: type = kObjFlex; break;
    default: return kAwake;
  }
  int id1 = m.eq_obj1id[e], id2 = m.eq_obj2id[e];
  SleepState s1 = id1 >= 0 ? ElementSleepState(m, d, type, id1) : kStatic;
  SleepState s2 = id2 >= 0 ? ElementSleepState(m, d, type, id2) : kStatic;
  return s1 != kAwake && s2 != kAwake ? kAsleep : kAwake;
}

// A sensor is awake when its object or its reference object is; user and plugin
// sensors, range finders and contact sensors over a site volume always are.
SleepState SensorSleepState(const Model& m, const Data& d, int s) {
  int type = m.sensor_type[s], objtype = m.sensor_objtype[s], reftype = m.sensor_reftype[s];
  if (type == kSensUser || type == kSensPlugin || type == kSensRangefinder) return kAwake;
  if (type == kSensContact && (objtype == kObjSite || reftype == kObjSite)) return kAwake;
  if (objtype == kObjUnknown && reftype == kObjUnknown) return kAwake;
  SleepState obj = ElementSleepState(m, d, objtype, m.sensor_objid[s]);
  SleepState ref = ElementSleepState(m, d, reftype, m.sensor_refid[s]);
  if (objtype == kObjUnknown) return ref == kAsleep ? kAsleep : kAwake;
  if (reftype == kObjUnknown) return obj == kAsleep ? kAsleep : kAwake;
  return obj == kAwake || ref == kAwake ? kAwake : kAsleep;
}

}  // namespace

// ---------------------------------------------------------------- kept values

SleepingDofValues::SleepingDofValues(const Model& m, Data& d, StackFrame& frame, Arrays arrays)
    : m_(m), d_(d), arrays_(arrays), active_(AnyAsleep(m, d)) {
  if (!active_) return;
  for (size_t k = 0; k < arrays_.size(); k++) {
    if (!arrays_[k]) continue;
    kept_[k] = frame.Alloc(m.nv);
    std::copy_n(arrays_[k], m.nv, kept_[k]);
  }
}

void SleepingDofValues::Restore() {
  if (!active_) return;
  for (int v = 0; v < m_.nv; v++) {
    if (d_.body_awake[m_.dof_bodyid[v]] == kAwake) continue;
    for (size_t k = 0; k < arrays_.size(); k++) {
      if (arrays_[k]) arrays_[k][v] = kept_[k][v];
    }
  }
}

// ---------------------------------------------------------------- derived arrays

void UpdateSleep(const Model& m, Data& d, bool static_awake) {
  // Trees.
  d.ntree_awake = 0;
  for (int t = 0; t < m.ntree; t++) {
    d.tree_awake[t] = d.tree_asleep[t] < 0;
    d.ntree_awake += d.tree_awake[t];
  }

  // Bodies: mocap bodies (and, at reset, every body of no tree) awake, the rest of the
  // world static; listed when not asleep, and by their parent's state.
  d.nbody_awake = d.nparent_awake = 0;
  for (int b = 0; b < m.nbody; b++) {
    int tree = m.body_treeid[b];
    if (tree < 0) {
      bool mocap = m.body_mocapid[m.body_rootid[b]] >= 0;
      d.body_awake[b] = mocap || static_awake ? kAwake : kStatic;
    } else {
      d.body_awake[b] = d.tree_awake[tree] ? kAwake : kAsleep;
    }
    if (d.body_awake[b] != kAsleep) d.body_awake_ind[d.nbody_awake++] = b;
    if (b > 0 && d.body_awake[m.body_parentid[b]] != kAsleep) d.parent_awake_ind[d.nparent_awake++] = b;
  }

  // Dofs of awake trees.
  d.nv_awake = 0;
  for (int v = 0; v < m.nv; v++) {
    int b = m.dof_bodyid[v];
    if (m.body_treeid[b] >= 0 && d.body_awake[b] == kAwake) d.dof_awake_ind[d.nv_awake++] = v;
  }
}

// ---------------------------------------------------------------- waking

int WakeChanged(const Model& m, Data& d) {
  if (!SleepEnabled(m)) {
    if (d.ntree_awake < m.ntree) std::fill(d.tree_asleep.begin(), d.tree_asleep.end(), kTreeAwake);
    return m.ntree - d.ntree_awake;
  }
  int woke = 0;
  for (int t = 0; t < m.ntree; t++) {
    if (d.tree_asleep[t] < 0) continue;
    if (d.tree_awake[t] || !TreeCanSleep(m, d, t, 0)) woke += WakeTree(d, m.ntree, t, kTreeAwake);
  }
  return woke;
}

int WakeOnContact(const Model& m, Data& d) {
  if (!SleepEnabled(m)) return 0;
  int woke = 0;
  for (int c = 0; c < d.ncon; c++) {
    // (a flex side by the body that stands for it)
    const Contact& con = d.contact[c];
    int a = m.body_treeid[ContactSideBody(m, con, 0)], b = m.body_treeid[ContactSideBody(m, con, 1)];
    if (a < 0 || b < 0) continue;
    if (!d.tree_awake[a] && !d.tree_awake[b]) {
      throw std::logic_error("sleep: contact between sleeping trees " + std::to_string(a) + " and " +
                             std::to_string(b));
    }
    woke += WakeFromAwakePartner(d, m.ntree, a, b);
  }
  return woke;
}

int WakeOnTendonLimit(const Model& m, Data& d) {
  if (!SleepEnabled(m)) return 0;
  int woke = 0;
  for (int t = 0; t < m.ntendon; t++) {
    if (m.tendon_treenum[t] != 2 || !TendonLimitActive(m, d, t)) continue;
    woke += WakeFromAwakePartner(d, m.ntree, m.tendon_treeid[2 * t], m.tendon_treeid[2 * t + 1]);
  }
  return woke;
}

int WakeOnEquality(const Model& m, Data& d) {
  if (!SleepEnabled(m)) return 0;
  int woke = 0;
  for (int e = 0; e < m.neq; e++) {
    if (!d.eq_active[e]) continue;
    int type = m.eq_type[e];
    if (type == kEqFlex || type == kEqFlexVert || type == kEqFlexStrain) {
      woke += WakeFlexEquality(m, d, m.eq_obj1id[e]);
      continue;
    }
    int a, b;
    if (!EqualityTrees(m, e, &a, &b)) continue;
    SleepState sa = a >= 0 ? static_cast<SleepState>(d.tree_awake[a]) : kStatic;
    SleepState sb = b >= 0 ? static_cast<SleepState>(d.tree_awake[b]) : kStatic;
    if (sa != kAsleep && sb != kAsleep) continue;
    if (sa == kStatic || sb == kStatic || a == b) continue;
    if (sa == kAsleep && sb == kAsleep) {
      // Two sleeping islands an equality joins: both wake.
      if (CycleId(d, m.ntree, a) != CycleId(d, m.ntree, b)) {
        woke += WakeTree(d, m.ntree, a, kTreeAwake);
        woke += WakeTree(d, m.ntree, b, kTreeAwake);
      }
      continue;
    }
    woke += WakeTree(d, m.ntree, sa == kAsleep ? a : b, kTreeAwake);
  }
  return woke;
}

// ---------------------------------------------------------------- falling asleep

int PutToSleep(const Model& m, Data& d) {
  if (!SleepEnabled(m)) return 0;
  // (rows but no islands: nothing says which trees move together)
  if (d.nefc && !d.nisland) return 0;
  CountSlowSteps(m, d);

  // Islands whose trees have all been slow long enough.
  int slept = 0;
  for (int i = 0; i < d.nisland; i++) {
    const int* trees = &d.map_itree2tree[d.island_itreeadr[i]];
    int n = d.island_ntree[i];
    bool ready = std::all_of(trees, trees + n, [&d](int t) { return d.tree_asleep[t] >= -1; });
    if (!ready) continue;
    SleepTrees(m, d, trees, n);
    slept += n;
  }

  // Trees no constraint touches, each alone.
  int first = d.nisland ? d.island_itreeadr[d.nisland - 1] + d.island_ntree[d.nisland - 1] : 0;
  for (int j = first; j < m.ntree; j++) {
    int t = d.nisland ? d.map_itree2tree[j] : j;
    if (d.tree_asleep[t] != -1) continue;
    SleepTrees(m, d, &t, 1);
    slept++;
  }
  return slept;
}

// ---------------------------------------------------------------- reset

void ResetSleep(const Model& m, Data& d) {
  std::fill(d.tree_asleep.begin(), d.tree_asleep.end(), kTreeAwake);
  int ninit = static_cast<int>(std::count(m.tree_sleep_policy.begin(), m.tree_sleep_policy.end(),
                                          static_cast<int>(kSleepInit)));
  if (SleepEnabled(m) && ninit > 0) {
    // The whole pipeline at the reset pose, everything awake, to find the islands; then
    // the trees marked init fall asleep, each with its whole island.
    UpdateSleep(m, d, /*static_awake=*/true);
    ForwardSkip(m, d, kStageNone, Sensors::kCompute);
    for (int t = 0; t < m.ntree; t++) {
      d.tree_asleep[t] = m.tree_sleep_policy[t] == kSleepInit ? -1 : kTreeAwake;
    }
    int slept = PutToSleep(m, d);
    if (slept != ninit) {
      int t = 0;
      while (t < m.ntree && !(m.tree_sleep_policy[t] == kSleepInit && d.tree_asleep[t] < 0)) t++;
      int body = t < m.ntree ? m.tree_bodyadr[t] : 0;
      throw Error(std::to_string(ninit) + " trees were marked as sleep='init' but only " + std::to_string(slept) +
                  " could be slept; body '" + m.body_names[body] + "' (id " + std::to_string(body) +
                  ") is the root of the first tree that could not sleep (it is constrained to a tree that "
                  "may not)");
    }
    // (the reset keeps the poses and contacts but no constraint rows)
    std::fill(d.qacc_smooth.begin(), d.qacc_smooth.end(), 0.0);
    std::fill(d.qfrc_smooth.begin(), d.qfrc_smooth.end(), 0.0);
    d.nefc = d.ne = d.nf = d.nl = d.nisland = 0;
  }
  UpdateSleep(m, d);
}

// ---------------------------------------------------------------- element states

SleepState ElementSleepState(const Model& m, const Data& d, int type, int id) {
  switch (type) {
    case kObjBody:
    case kObjXBody: return static_cast<SleepState>(d.body_awake[id]);
    case kObjJoint: return static_cast<SleepState>(d.body_awake[m.jnt_bodyid[id]]);
    case kObjSite: return static_cast<SleepState>(d.body_awake[m.site_bodyid[id]]);
    case kObjDof: return static_cast<SleepState>(d.body_awake[m.dof_bodyid[id]]);
    case kObjGeom: return static_cast<SleepState>(d.body_awake[m.geom_bodyid[id]]);
    case kObjCamera: return static_cast<SleepState>(d.body_awake[m.cam_bodyid[id]]);
    case kObjLight: return static_cast<SleepState>(d.body_awake[m.light_bodyid[id]]);
    case kObjEquality: return EqualitySleepState(m, d, id);
    case kObjTendon: return TendonSleepState(m, d, id);
    case kObjActuator: return ActuatorSleepState(m, d, id);
    case kObjSensor: return SensorSleepState(m, d, id);
    case kObjFlex: return FlexSleepState(m, d, id);
    default: return kAwake;
  }
}

}  // namespace simlab
