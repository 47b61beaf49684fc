// <compiler fusestatic="true">: bodies without joints merge into their parents after the
// bodies compile, as MuJoCo 3.5.1's compiler does (mjCModel::FuseStatic), quirks
// included, so that the compiled model is MuJoCo's to the bit:
//
//   - bodies are visited in depth-first order; a fused body's place is visited again
//     (its first child, or the next body, now sits there);
//   - a named body is kept when any section names it, and also when a section names a
//     body whose number, as MuJoCo's name table still holds it from before the earlier
//     fusions, lies past the end of the shrunken body list (the table is not renumbered
//     until the pass ends), or when a force or torque sensor reads a site on it;
//   - mass and inertia go into the parent unless the parent is the world, with the
//     fused body's inertial frame composed as MuJoCo composes it (inertial frame first);
//   - geoms and sites move into the parent's frame; cameras and lights move to the parent
//     with the pose they had in the fused body (MuJoCo compiles them again from their
//     specification after fusing).
#include <algorithm>
#include <array>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "mjcf/error.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

using mjcf::ThrowAt;

// The bodies the sections name (MuJoCo resolves them again for each named candidate).
std::vector<std::string> BodiesNamedBySections(const mjcf::ModelSpec& spec,
                                               const CompileState& state) {
  std::vector<std::string> names;
  auto add = [&](const std::string& name) {
    if (!name.empty()) names.push_back(name);
  };
  auto is_body = [](int objtype) { return objtype == kObjBody || objtype == kObjXBody; };
  for (const BodyState& b : state.bodies) {
    for (const mjcf::CameraSpec& c : b.spec->cameras) add(c.target);
    for (const mjcf::LightSpec& l : b.spec->lights) add(l.target);
  }
  for (const mjcf::SkinSpec& s : spec.skins) {
    for (const mjcf::SkinBoneSpec& bone : s.bones) add(bone.body);
  }
  for (const mjcf::ExcludeSpec& e : spec.excludes) add(e.body1), add(e.body2);
  for (const mjcf::EqualitySpec& e : spec.equalities) {
    if ((e.type == kEqConnect || e.type == kEqWeld) && e.objtype == kObjBody) add(e.name1), add(e.name2);
  }
  for (const mjcf::ActuatorSpec& a : spec.actuators) {
    if (a.trntype == kTrnBody) add(a.target);
  }
  for (const mjcf::SensorSpec& s : spec.sensors) {
    if (is_body(s.objtype)) add(s.objname);
    if (is_body(s.reftype)) add(s.refname);
  }
  return names;
}

// Sites read by force and torque sensors (their bodies cannot be fused).
std::set<std::string> ForceTorqueSites(const mjcf::ModelSpec& spec) {
  std::set<std::string> sites;
  for (const mjcf::SensorSpec& s : spec.sensors) {
    if ((s.type == kSensForce || s.type == kSensTorque) && s.objtype == kObjSite) sites.insert(s.objname);
  }
  return sites;
}

// The parent's mass and inertia with the fused body's added (mjCBody::AccumulateInertia,
// with its arithmetic: the fused body's inertial frame is composed with its body frame
// in that order, and sums run term by term).
void AccumulateInertia(const BodyState& other, BodyState* result) {
  double other_ipos[3], other_iquat[4], pos[3], quat[4];
  math::Copy3(other_ipos, other.ipos);
  math::CopyQuat(other_iquat, other.iquat);
  math::Copy3(pos, other.pos);
  math::CopyQuat(quat, other.quat);
  AccumulateChild(other_ipos, other_iquat, pos, quat);
  const double mass[2] = {result->mass, other.mass};
  double inertia[2][3], ipos[2][3], iquat[2][4];
  math::Copy3(inertia[0], result->inertia);
  math::Copy3(inertia[1], other.inertia);
  math::Copy3(ipos[0], result->ipos);
  math::Copy3(ipos[1], pos);
  math::CopyQuat(iquat[0], result->iquat);
  math::CopyQuat(iquat[1], quat);

  // The centre of mass.
  result->mass = 0;
  math::Zero3(result->ipos);
  for (int j = 0; j < 2; j++) {
    result->mass += mass[j];
    for (int k = 0; k < 3; k++) result->ipos[k] += mass[j] * ipos[j][k];
  }
  if (result->mass < kMinVal) {
    result->mass = 0;
    math::Zero3(result->inertia);
    math::Zero3(result->ipos);
    math::SetIdentityQuat(result->iquat);
    return;
  }
  for (int k = 0; k < 3; k++) result->ipos[k] /= result->mass;

  // Both inertias about it, then the principal axes.
  double total[6] = {0, 0, 0, 0, 0, 0};
  for (int j = 0; j < 2; j++) {
    double rotated[6], d[3];
    GlobalInertia(rotated, inertia[j], iquat[j]);
    for (int k = 0; k < 3; k++) d[k] = ipos[j][k] - result->ipos[k];
    double shift[6];
    OffCenter(shift, mass[j], d);
    for (int k = 0; k < 6; k++) total[k] += rotated[k] + shift[k];
  }
  if (const char* err = FullInertia(result->iquat, result->inertia, total)) {
    ThrowAt(other.spec->src, std::string("fusing static body inertias: ") + err);
  }
}

// The tree as the pass edits it: each body's children, geoms and sites by index into
// the state's lists as flattened.
struct FuseTree {
  std::vector<std::vector<int>> children, geoms, sites;
  // Each body's node geom pointers as MuJoCo's tree keeps them (see
  // BodyState::stale_bvh_nodeid), by geom index; empty until a body takes a fused one.
  std::vector<std::vector<int>> node_geoms;
};

FuseTree TreeOf(const CompileState& state) {
  size_t n = state.bodies.size();
  FuseTree t{std::vector<std::vector<int>>(n), std::vector<std::vector<int>>(n),
             std::vector<std::vector<int>>(n), std::vector<std::vector<int>>(n)};
  for (const BodyState& b : state.bodies) {
    if (b.parent >= 0) t.children[b.parent].push_back(b.id);
    for (int k = 0; k < b.geom_num; k++) t.geoms[b.id].push_back(b.geom_begin + k);
    for (int k = 0; k < b.site_num; k++) t.sites[b.id].push_back(b.site_begin + k);
  }
  return t;
}

// Does the geom collide (and so sit in its body's bounding-volume tree)?
bool Collides(const GeomState& g) { return g.spec->contype || g.spec->conaffinity; }

// The tree MuJoCo builds over body b's colliding geoms as they stand, written over its
// node pointers: the new tree's leaves overwrite the first places, inner nodes leave
// what was there, and the list grows by the new tree's size.
void RebuildNodeGeoms(int b, const CompileState& state, FuseTree* t) {
  std::vector<std::array<double, 6>> boxes;
  boxes.reserve(t->geoms[b].size());  // (the geoms below point into it)
  std::vector<BvhGeom> geoms;
  for (int g : t->geoms[b]) {
    const GeomState& geom = state.geoms[g];
    if (!Collides(geom)) continue;
    GeomAabb(geom, boxes.emplace_back().data());
    geoms.push_back({g, boxes.back().data(), geom.pos, geom.quat});
  }
  const BodyState& body = state.bodies[b];
  std::vector<int> nodes = BvhNodeGeoms(geoms, body.ipos, body.iquat);
  std::vector<int>& slots = t->node_geoms[b];
  slots.resize(slots.size() + nodes.size(), -1);
  for (size_t k = 0; k < nodes.size(); k++) {
    if (nodes[k] >= 0) slots[k] = nodes[k];
  }
}

// Moves body `id` into its parent: its mass, children, geoms, sites, cameras and lights.
void FuseIntoParent(int id, CompileState* state, FuseTree* t) {
  BodyState& body = state->bodies[id];
  BodyState& parent = state->bodies[body.parent];
  auto colliding = [&](int b) {
    return std::count_if(t->geoms[b].begin(), t->geoms[b].end(),
                         [&](int g) { return Collides(state->geoms[g]); });
  };
  if (colliding(id) > 0 && colliding(body.parent) > 0) state->fused_bvh_padding++;
  if (t->node_geoms[body.parent].empty()) RebuildNodeGeoms(body.parent, *state, t);
  if (body.parent != 0 && body.mass >= kMinVal) AccumulateInertia(body, &parent);

  // Children take the body's place among the parent's, in the parent's frame.
  for (int c : t->children[id]) {
    AccumulateChild(body.pos, body.quat, state->bodies[c].pos, state->bodies[c].quat);
    state->bodies[c].parent = body.parent;
  }
  std::vector<int>& siblings = t->children[body.parent];
  auto at = std::find(siblings.begin(), siblings.end(), id);
  at = siblings.insert(at, t->children[id].begin(), t->children[id].end());
  siblings.erase(at + static_cast<long>(t->children[id].size()));

  // Geoms and sites after the parent's own, in its frame.
  for (int g : t->geoms[id]) {
    AccumulateChild(body.pos, body.quat, state->geoms[g].pos, state->geoms[g].quat);
    t->geoms[body.parent].push_back(g);
  }
  for (int s : t->sites[id]) {
    AccumulateChild(body.pos, body.quat, state->sites[s].pos, state->sites[s].quat);
    t->sites[body.parent].push_back(s);
  }
  parent.fused.push_back(body.spec);
  parent.fused.insert(parent.fused.end(), body.fused.begin(), body.fused.end());
  RebuildNodeGeoms(body.parent, *state, t);
}

// The state's lists again, depth first from the edited tree, with ids renumbered.
void Rebuild(const FuseTree& t, CompileState* state) {
  std::vector<int> order;
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    int b = stack.back();
    stack.pop_back();
    order.push_back(b);
    for (auto c = t.children[b].rbegin(); c != t.children[b].rend(); ++c) stack.push_back(*c);
  }
  std::vector<int> new_id(state->bodies.size(), -1);
  for (size_t i = 0; i < order.size(); i++) new_id[order[i]] = static_cast<int>(i);

  std::vector<int> new_geom(state->geoms.size(), -1);
  int next_geom = 0;
  for (int old : order) {
    for (int g : t.geoms[old]) new_geom[g] = next_geom++;
  }

  std::vector<BodyState> bodies;
  std::vector<JointState> joints;
  std::vector<GeomState> geoms;
  std::vector<SiteState> sites;
  for (int old : order) {
    BodyState b = state->bodies[old];
    b.id = new_id[old];
    b.parent = old == 0 ? -1 : new_id[b.parent];
    b.weldid = (b.id == 0 || b.joint_num > 0) ? b.id : bodies[b.parent].weldid;
    int joint_begin = b.joint_begin;
    b.joint_begin = static_cast<int>(joints.size());
    b.geom_begin = static_cast<int>(geoms.size());
    b.site_begin = static_cast<int>(sites.size());
    b.geom_num = static_cast<int>(t.geoms[old].size());
    b.site_num = static_cast<int>(t.sites[old].size());
    for (int g : t.node_geoms[old]) b.stale_bvh_nodeid.push_back(g < 0 ? -1 : new_geom[g]);
    for (int k = 0; k < b.joint_num; k++) {
      joints.emplace_back(state->joints[joint_begin + k]).body = b.id;
    }
    for (int g : t.geoms[old]) geoms.emplace_back(state->geoms[g]).body = b.id;
    for (int s : t.sites[old]) sites.emplace_back(state->sites[s]).body = b.id;
    bodies.push_back(b);
  }
  state->bodies = std::move(bodies);
  state->joints = std::move(joints);
  state->geoms = std::move(geoms);
  state->sites = std::move(sites);
}

}  // namespace

void FuseStaticBodies(const mjcf::ModelSpec& spec, CompileState* state) {
  if (!spec.compiler.fusestatic) return;
  const std::vector<std::string> named = BodiesNamedBySections(spec, *state);
  const std::set<std::string> ft_sites = ForceTorqueSites(spec);
  FuseTree tree = TreeOf(*state);

  // MuJoCo's name table: each body's number as last set (the flattened order, or the
  // place it was visited at).
  std::unordered_map<std::string, int> table;
  for (const BodyState& b : state->bodies) {
    if (b.id == 0) table["world"] = 0;
    else if (!b.spec->src.name.empty()) table[b.spec->src.name] = b.id;
  }

  // Visit the bodies in depth-first order as the list shrinks.
  std::vector<int> list(state->bodies.size());
  for (size_t i = 0; i < list.size(); i++) list[i] = static_cast<int>(i);
  for (size_t i = 1; i < list.size(); i++) {
    const BodyState& body = state->bodies[list[i]];
    const std::string& name = body.spec->src.name;
    if (!name.empty()) {
      table.erase(name);
      bool resolves = std::all_of(named.begin(), named.end(), [&](const std::string& n) {
        auto it = table.find(n);
        return it != table.end() && it->second < static_cast<int>(list.size());
      });
      for (int s : tree.sites[body.id]) {
        if (ft_sites.count(state->sites[s].spec->src.name)) resolves = false;
      }
      table[name] = static_cast<int>(i);
      if (!resolves) continue;
    }
    if (body.joint_num > 0 || body.spec->mocap) continue;
    FuseIntoParent(body.id, state, &tree);
    if (!name.empty()) table.erase(name);
    list.erase(list.begin() + static_cast<long>(i));
    i--;
  }
  Rebuild(tree, state);
}

}  // namespace simlab::compiler
