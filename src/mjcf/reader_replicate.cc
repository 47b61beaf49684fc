// MJCF reader: the <replicate> meta-element (MuJoCo's self-attachment).
//
// The children of <replicate> are read once into a scratch body that sits in the
// parent's place, inside a template frame. Each replica then gets its own frame
// (the accumulated offset and rotation) and copies of every element with the suffix
// `sep` + zero-padded index appended to its name. Elements outside the tree that
// name replicated objects (pairs, excludes, tendons, equalities, actuators, sensors)
// are copied with the suffix too whenever the suffixed names exist, as MuJoCo's
// attach does. Finally the scratch body goes away, and with it every element that
// still names one of its objects.
#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <string>

#include "compiler/orientation.h"
#include "math/math.h"
#include "mjcf/limits.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

namespace {

// ---------------------------------------------------------------- names in the model

// The names of the objects that references can point at, by object type.
struct NameTable {
  std::map<int, std::set<std::string>> by_type;

  bool Has(int type, const std::string& name) const {
    if (type == kObjXBody) type = kObjBody;
    auto it = by_type.find(type);
    return it != by_type.end() && it->second.count(name) > 0;
  }
  void Add(int type, const std::string& name) {
    if (!name.empty()) by_type[type].insert(name);
  }
};

// Every named object of a body subtree.
void CollectTree(const BodySpec& body, NameTable* names) {
  names->Add(kObjBody, body.src.name);
  for (const JointSpec& j : body.joints) names->Add(kObjJoint, j.src.name);
  for (const GeomSpec& g : body.geoms) names->Add(kObjGeom, g.src.name);
  for (const SiteSpec& s : body.sites) names->Add(kObjSite, s.src.name);
  for (const CameraSpec& c : body.cameras) names->Add(kObjCamera, c.src.name);
  for (const LightSpec& l : body.lights) names->Add(kObjLight, l.src.name);
  for (const auto& child : body.bodies) CollectTree(*child, names);
}

// The whole model's names as they stand now.
NameTable CollectNames(const ModelSpec& spec) {
  NameTable names;
  names.Add(kObjBody, "world");
  CollectTree(spec.world, &names);
  for (const TendonSpec& t : spec.tendons) names.Add(kObjTendon, t.src.name);
  for (const ActuatorSpec& a : spec.actuators) names.Add(kObjActuator, a.src.name);
  for (const MeshSpec& m : spec.meshes) names.Add(kObjMesh, m.src.name);
  return names;
}

// name + suffix, leaving empty names empty (MuJoCo namespaces named elements only).
std::string Suffixed(const std::string& name, const std::string& suffix) {
  return name.empty() ? name : name + suffix;
}

// ---------------------------------------------------------------- referencing elements
//
// Each Resolve* tries the element's references with the suffix (as MuJoCo's
// ResolveReferences after a namespace change) and, on success, rewrites them to the
// names found. An empty suffix checks the element as it is.

// Two references where either may stay outside the replicated part: both suffixed,
// else the one that failed without the suffix (pairs, excludes, two-object sensors).
bool ResolveTwo(const NameTable& names, int type1, std::string* name1, int type2,
                std::string* name2, const std::string& suffix) {
  std::string a = *name1 + suffix, b = *name2 + suffix;
  bool found1 = names.Has(type1, a), found2 = names.Has(type2, b);
  if (!found1 && found2) found1 = names.Has(type1, a = *name1);
  if (found1 && !found2) found2 = names.Has(type2, b = *name2);
  if (!found1 || !found2) return false;
  *name1 = a;
  *name2 = b;
  return true;
}

bool ResolveSensor(const NameTable& names, SensorSpec* s, const std::string& suffix) {
  bool has_obj = s->objtype != kObjUnknown, has_ref = s->reftype != kObjUnknown;
  if (has_obj && has_ref) {
    return ResolveTwo(names, s->objtype, &s->objname, s->reftype, &s->refname, suffix);
  }
  // One object or none: a sensor without objects (clock, energy, ...) always resolves.
  std::string* name = has_obj ? &s->objname : has_ref ? &s->refname : nullptr;
  if (!name) return true;
  std::string full = *name + suffix;
  if (!names.Has(has_obj ? s->objtype : s->reftype, full)) return false;
  *name = full;
  return true;
}

bool ResolveActuator(const NameTable& names, ActuatorSpec* a, const std::string& suffix) {
  std::string target = Suffixed(a->target, suffix);
  std::string slider = Suffixed(a->slidersite, suffix);
  std::string ref = Suffixed(a->refsite, suffix);
  bool ok = false;
  switch (a->trntype) {
    case kTrnJoint:
    case kTrnJointInParent: ok = names.Has(kObjJoint, target); break;
    case kTrnSliderCrank:
      ok = !slider.empty() && names.Has(kObjSite, slider) && names.Has(kObjSite, target);
      break;
    case kTrnTendon: ok = names.Has(kObjTendon, target); break;
    case kTrnSite: ok = (ref.empty() || names.Has(kObjSite, ref)) && names.Has(kObjSite, target); break;
    case kTrnBody: ok = names.Has(kObjBody, target); break;
    default: break;
  }
  if (!ok) return false;
  a->target = target;
  a->slidersite = slider;
  a->refsite = ref;
  return true;
}

// One tendon path element, found with the given names.
bool WrapFound(const NameTable& names, const WrapSpec& w, const std::string& target,
               const std::string& sidesite) {
  switch (w.type) {
    case kWrapJoint: return names.Has(kObjJoint, target);
    case kWrapSite: return names.Has(kObjSite, target);
    case kWrapSphere:
    case kWrapCylinder:
      return names.Has(kObjGeom, target) && (sidesite.empty() || names.Has(kObjSite, sidesite));
    default: return true;  // pulleys name nothing
  }
}

// Each path element tries the suffix and falls back to its own names; the tendon
// resolves only if at least one element (pulleys aside) took the suffix.
bool ResolveTendon(const NameTable& names, TendonSpec* t, const std::string& suffix) {
  int suffixed = 0;
  for (WrapSpec& w : t->wraps) {
    if (w.type == kWrapPulley) continue;
    // MuJoCo suffixes the side site even when there is none.
    std::string target = w.target + suffix, side = w.sidesite + suffix;
    if (WrapFound(names, w, target, side)) {
      w.target = target;
      if (w.type == kWrapSphere || w.type == kWrapCylinder) w.sidesite = side;
      suffixed++;
    } else if (!WrapFound(names, w, w.target, w.sidesite)) {
      return false;
    }
  }
  return suffixed > 0;
}

bool ResolveEquality(const NameTable& names, EqualitySpec* q, const std::string& suffix) {
  int type = q->type == kEqJoint    ? kObjJoint
             : q->type == kEqTendon ? kObjTendon
                                    : q->objtype;
  std::string name1 = Suffixed(q->name1, suffix), name2 = Suffixed(q->name2, suffix);
  if (!names.Has(type, name1)) return false;
  if (!name2.empty() && !names.Has(type, name2)) return false;
  q->name1 = name1;
  q->name2 = name2;
  return true;
}

bool Resolve(const NameTable& names, PairSpec* p, const std::string& suffix) {
  return ResolveTwo(names, kObjGeom, &p->geom1, kObjGeom, &p->geom2, suffix);
}
bool Resolve(const NameTable& names, ExcludeSpec* x, const std::string& suffix) {
  return ResolveTwo(names, kObjBody, &x->body1, kObjBody, &x->body2, suffix);
}
bool Resolve(const NameTable& names, TendonSpec* t, const std::string& suffix) {
  return ResolveTendon(names, t, suffix);
}
bool Resolve(const NameTable& names, EqualitySpec* q, const std::string& suffix) {
  return ResolveEquality(names, q, suffix);
}
bool Resolve(const NameTable& names, ActuatorSpec* a, const std::string& suffix) {
  return ResolveActuator(names, a, suffix);
}
bool Resolve(const NameTable& names, SensorSpec* s, const std::string& suffix) {
  return ResolveSensor(names, s, suffix);
}

// Whether an element names no object at all (a clock or energy sensor): it resolves
// under any suffix.
template <typename T>
bool NamesNothing(const T&) {
  return false;
}
bool NamesNothing(const SensorSpec& s) {
  return s.objtype == kObjUnknown && s.reftype == kObjUnknown;
}

// Appends a suffixed copy of every element of `list` present when the call starts
// whose suffixed references exist, as MuJoCo does (copies made for earlier replicas
// included); the copies' names join `names` as `type` (kObjUnknown: not referenced by
// name). Elements from index `first_copy` on were copied by this replicate: unless
// `retry_copies`, only those that name nothing (listed in `unnamed_copies`, which the
// new ones join) are tried again, since the others' names already carry an earlier
// replica's suffix and cannot take another one (see NameTakesTwoSuffixes). This keeps
// replicate linear in its count.
template <typename T>
void CopyReferencing(NameTable* names, const std::string& suffix, size_t first_copy,
                     bool retry_copies, int type, std::vector<T>* list,
                     std::vector<size_t>* unnamed_copies) {
  auto copy_one = [&](size_t k) {
    T copy = (*list)[k];
    if (!Resolve(*names, &copy, suffix)) return;
    copy.src.name = Suffixed(copy.src.name, suffix);
    if (type != kObjUnknown) names->Add(type, copy.src.name);
    if (NamesNothing(copy)) unnamed_copies->push_back(list->size());
    list->push_back(std::move(copy));
  };
  // (indices in increasing order either way: the copies keep MuJoCo's order)
  size_t n = list->size();
  if (retry_copies) {
    for (size_t k = 0; k < n; k++) copy_one(k);
    return;
  }
  std::vector<size_t> again = *unnamed_copies;
  for (size_t k = 0; k < first_copy; k++) copy_one(k);
  for (size_t k : again) copy_one(k);
}

// Whether some name ends like a replica suffix (`sep` and the count's digits, below
// `count`). Only then can a copy made for replica j, whose references end with j's
// suffix, find them again with replica i's suffix appended: that needs an object
// named "x<j's suffix><i's suffix>", i.e. one copied from an object "x<j's suffix>".
bool NameTakesTwoSuffixes(const NameTable& names, const std::string& sep, int count) {
  size_t width = std::to_string(count - 1).size();
  for (const auto& [type, set] : names.by_type) {
    for (const std::string& name : set) {
      if (name.size() < sep.size() + width) continue;
      size_t digits_at = name.size() - width;
      if (name.compare(digits_at - sep.size(), sep.size(), sep) != 0) continue;
      std::string digits = name.substr(digits_at);
      if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        continue;
      if (std::stoll(digits) < count) return true;
    }
  }
  return false;
}

// Drops the elements that named something that is gone (they resolved before).
template <typename T>
bool IsDangling(const NameTable& before, const NameTable& after, const T& element) {
  T probe = element;
  if (!Resolve(before, &probe, "")) return false;  // a user error: kept for the compiler
  probe = element;
  return !Resolve(after, &probe, "");
}

template <typename T>
void DropDangling(const NameTable& before, const NameTable& after, std::vector<T>* list) {
  auto dangling = [&](const T& element) { return IsDangling(before, after, element); };
  list->erase(std::remove_if(list->begin(), list->end(), dangling), list->end());
}

// Erases the elements of `list` whose mask entry is set.
template <typename T>
void EraseMasked(const std::vector<bool>& mask, std::vector<T>* list) {
  size_t kept = 0;
  for (size_t i = 0; i < list->size(); i++) {
    if (!mask[i] && kept++ != i) (*list)[kept - 1] = std::move((*list)[i]);
  }
  list->resize(kept);
}

// Which elements of `list` DropDangling would drop.
template <typename T>
std::vector<bool> DanglingMask(const NameTable& before, const NameTable& after, const std::vector<T>& list) {
  std::vector<bool> mask(list.size());
  for (size_t i = 0; i < list.size(); i++) mask[i] = IsDangling(before, after, list[i]);
  return mask;
}

// ---------------------------------------------------------------- tree copies

// The frame chain of an element of the scratch body, with the template frame replaced
// by one replica's frame (frames in between are copied once per replica).
class FrameRebase {
 public:
  FrameRebase(const FrameSpec* from, FramePtr to) : from_(from), to_(std::move(to)) {}

  FramePtr operator()(const FramePtr& frame) {
    if (!frame) return frame;
    if (frame.get() == from_) return to_;
    auto it = done_.find(frame.get());
    if (it != done_.end()) return it->second;
    auto copy = std::make_shared<FrameSpec>(*frame);
    copy->parent = (*this)(frame->parent);
    done_[frame.get()] = copy;
    return copy;
  }

 private:
  const FrameSpec* from_;
  FramePtr to_;
  std::map<const FrameSpec*, FramePtr> done_;
};

// Appends the suffix to every name of a body subtree (camera and light targets
// included, as MuJoCo namespaces them).
void SuffixTree(BodySpec* body, const std::string& suffix) {
  body->src.name = Suffixed(body->src.name, suffix);
  for (JointSpec& j : body->joints) j.src.name = Suffixed(j.src.name, suffix);
  for (GeomSpec& g : body->geoms) g.src.name = Suffixed(g.src.name, suffix);
  for (SiteSpec& s : body->sites) s.src.name = Suffixed(s.src.name, suffix);
  for (CameraSpec& c : body->cameras) {
    c.src.name = Suffixed(c.src.name, suffix);
    c.target = Suffixed(c.target, suffix);
  }
  for (LightSpec& l : body->lights) {
    l.src.name = Suffixed(l.src.name, suffix);
    l.target = Suffixed(l.target, suffix);
  }
  for (auto& child : body->bodies) SuffixTree(child.get(), suffix);
}

// Appends one replica of the scratch body's elements to `body`, each list in order;
// their names join `names`.
void CopyReplica(const BodySpec& scratch, FrameRebase& rebase, const std::string& suffix,
                 BodySpec* body, NameTable* names) {
  BodySpec renamed;
  renamed.joints = scratch.joints;
  renamed.geoms = scratch.geoms;
  renamed.sites = scratch.sites;
  renamed.cameras = scratch.cameras;
  renamed.lights = scratch.lights;
  renamed.bodies = scratch.bodies;
  SuffixTree(&renamed, suffix);
  CollectTree(renamed, names);  // (`renamed` itself has no name)
  auto move_all = [&](auto& from, auto& to) {
    for (auto& element : from) {
      element.frame = rebase(element.frame);
      to.push_back(std::move(element));
    }
  };
  move_all(renamed.joints, body->joints);
  move_all(renamed.geoms, body->geoms);
  move_all(renamed.sites, body->sites);
  move_all(renamed.cameras, body->cameras);
  move_all(renamed.lights, body->lights);
  for (auto& child : renamed.bodies) {
    child->frame = rebase(child->frame);
    body->bodies.push_back(std::move(child));
  }
}

// Bytes of the elements one replica copies (its frame, the scratch body's elements and
// child subtrees), as the spec holds them.
uint64_t ReplicaBytes(const BodySpec& body) {
  uint64_t bytes = sizeof(FrameSpec);
  bytes += body.joints.size() * sizeof(JointSpec) + body.geoms.size() * sizeof(GeomSpec) +
           body.sites.size() * sizeof(SiteSpec) + body.cameras.size() * sizeof(CameraSpec) +
           body.lights.size() * sizeof(LightSpec);
  for (const auto& child : body.bodies) bytes += sizeof(BodySpec) + ReplicaBytes(*child);
  return bytes;
}

// The lengths of the lists of referencing elements before the first replica (the
// elements after them are this replicate's copies).
struct ReferenceCounts {
  size_t pairs, excludes, tendons, equalities, actuators, sensors;
};

// Replica i's frame: the template turned by i times `euler`, at `pos`, which then moves
// one offset further, in this replica's orientation.
FramePtr ReplicaFrame(const FrameSpec& templ, int i, const std::array<double, 3>& euler,
                      const std::array<double, 3>& offset, const CompilerSpec& compiler,
                      double pos[3]) {
  auto replica = std::make_shared<FrameSpec>(templ);
  Orientation turn;
  turn.kind = OrientKind::kEuler;
  for (int k = 0; k < 3; k++) turn.euler[k] = i * euler[k];
  compiler::ResolveOrientation(replica->quat.data(), compiler.degree, compiler.eulerseq, turn);
  std::copy(pos, pos + 3, replica->pos.begin());
  double mat[9], step[3];
  math::QuatToMat(mat, replica->quat.data());
  math::MulMatVec3(step, mat, offset.data());
  for (int k = 0; k < 3; k++) pos[k] += step[k];
  return replica;
}

// "sep" followed by the index, zero-padded to the digits of the count.
std::string ReplicaSuffix(const std::string& sep, int count, int index) {
  std::string digits = std::to_string(index);
  size_t width = std::to_string(count).size();
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return sep + digits;
}

// Copies, with one replica's suffix, the elements outside the tree that name its
// objects: in MuJoCo's order; tendons and actuators join the names before their users.
// `unnamed_copies`: the copies so far that name nothing, list by list (see
// CopyReferencing).
struct UnnamedCopies {
  std::vector<size_t> pairs, excludes, tendons, equalities, actuators, sensors;
};
void ReplicateReferences(const std::string& suffix, const ReferenceCounts& originals,
                         bool retry, NameTable* names, ModelSpec* spec, UnnamedCopies* unnamed) {
  CopyReferencing(names, suffix, originals.pairs, retry, kObjUnknown, &spec->pairs,
                  &unnamed->pairs);
  CopyReferencing(names, suffix, originals.excludes, retry, kObjUnknown, &spec->excludes,
                  &unnamed->excludes);
  CopyReferencing(names, suffix, originals.tendons, retry, kObjTendon, &spec->tendons,
                  &unnamed->tendons);
  CopyReferencing(names, suffix, originals.equalities, retry, kObjUnknown, &spec->equalities,
                  &unnamed->equalities);
  CopyReferencing(names, suffix, originals.actuators, retry, kObjActuator, &spec->actuators,
                  &unnamed->actuators);
  CopyReferencing(names, suffix, originals.sensors, retry, kObjUnknown, &spec->sensors,
                  &unnamed->sensors);
}

// An actuator or sensor computed by a plugin instance of its own, copied with a replica,
// would share that instance with its copies (MuJoCo copies the instance).
void CheckPluginCopies(const XmlElement& e, const ReferenceCounts& originals, const ModelSpec& spec) {
  for (size_t i = originals.actuators; i < spec.actuators.size(); i++) {
    if (spec.actuators[i].plugin.implicit_instance >= 0) {
      e.Fail("replicating an actuator that configures its own plugin instance is not supported yet");
    }
  }
  for (size_t i = originals.sensors; i < spec.sensors.size(); i++) {
    if (spec.sensors[i].plugin.implicit_instance >= 0) {
      e.Fail("replicating a sensor that configures its own plugin instance is not supported yet");
    }
  }
}

// Sensors that name no object are copied again with every replica, copies included
// (MuJoCo's rule: `count` replicas make 2^count of them). Past kMaxDoubledSensors the
// model is refused, before the next replica doubles them again.
constexpr size_t kMaxDoubledSensors = size_t{1} << 16;
void CheckSensorCopies(const XmlElement& e, int count, size_t doubling) {
  if (doubling <= kMaxDoubledSensors) return;
  e.Fail(AttrText("count", std::to_string(count)) + " copies the sensors without objects " +
         "(clock, energy...) with every replica, doubling them each time; " +
         std::to_string(doubling) + " already, over simlab's limit of " +
         std::to_string(kMaxDoubledSensors));
}

// The copies a replicate makes, multiplied by the replicates around it (`outer`), must
// fit the budget of one array; checked before the first copy.
void CheckReplicateBudget(const XmlElement& e, int count, uint64_t outer,
                          uint64_t replica_bytes) {
  uint64_t bytes = MulBytes(MulBytes(outer, static_cast<uint64_t>(count)), replica_bytes);
  if (bytes <= kMaxArrayBytes) return;
  std::string request = AttrText("count", std::to_string(count));
  if (outer > 1) {
    request += " (inside replicates that copy it " + std::to_string(outer) + " times)";
  }
  e.Fail(OverBudget(request, bytes, "replicated elements", kMaxArrayBytes));
}

}  // namespace

// The template's elements and the first replica's copies of them (those in child bodies,
// which do not move), and the template's actuators' new places (-1: gone).
struct ReplicaMap {
  std::set<const void*> templ;                       // every joint and body of the template
  std::map<const void*, const void*> copies;         // template element -> first copy
  std::map<int, int> actuators;                      // index before -> index after
};

namespace {

void CollectTemplate(const BodySpec& b, std::set<const void*>* out) {
  out->insert(&b);
  for (const JointSpec& j : b.joints) out->insert(&j);
  for (const auto& child : b.bodies) CollectTemplate(*child, out);
}

// Pairs a template subtree with its copy (same shape), element by element.
void MapCopies(const BodySpec& from, const BodySpec& to, std::map<const void*, const void*>* out) {
  (*out)[&from] = &to;
  for (size_t k = 0; k < from.joints.size() && k < to.joints.size(); k++) (*out)[&from.joints[k]] = &to.joints[k];
  for (size_t k = 0; k < from.bodies.size() && k < to.bodies.size(); k++) {
    MapCopies(*from.bodies[k], *to.bodies[k], out);
  }
}

// Where each actuator goes when the template's are dropped: the k-th dropped one (in
// order) to the first replica's k-th copy (copies start at `first_copy`, `copied` of
// them); the others keep their order. Counts that do not pair up map nothing.
std::map<int, int> ActuatorMoves(const std::vector<bool>& dropped, size_t first_copy, size_t copied) {
  std::vector<int> after(dropped.size(), -1);
  int next = 0;
  for (size_t i = 0; i < dropped.size(); i++) {
    if (!dropped[i]) after[i] = next++;
  }
  std::map<int, int> moves;
  size_t k = 0;
  for (size_t i = 0; i < dropped.size(); i++) {
    if (i >= first_copy) break;
    if (!dropped[i]) {
      moves[static_cast<int>(i)] = after[i];
    } else {
      moves[static_cast<int>(i)] = k < copied ? after[first_copy + k] : -1;
      k++;
    }
  }
  if (k != copied) {
    for (auto& [before, now] : moves) {
      if (dropped[before]) now = -1;
    }
  }
  return moves;
}

}  // namespace

void Reader::MoveCarriedKeys(const ReplicaMap& first) {
  // Each entry's element becomes its first copy; one of the template's without a copy
  // is dropped (nullptr, or -1 for an actuator), as nothing may point at a removed one.
  auto to_copy = [&](const void* element) -> const void* {
    if (!first.templ.count(element)) return element;
    auto it = first.copies.find(element);
    return it == first.copies.end() ? nullptr : it->second;
  };
  auto to_index = [&](int a) {
    auto it = first.actuators.find(a);
    return it == first.actuators.end() ? a : it->second;
  };
  auto retarget = [](auto& list, auto where, auto gone) {
    for (auto& entry : list) entry.first = static_cast<decltype(gone)>(where(entry.first));
    list.erase(std::remove_if(list.begin(), list.end(), [&](const auto& e) { return e.first == gone; }),
               list.end());
  };
  for (auto& [name, key] : carried_) {
    retarget(key.qpos, to_copy, static_cast<const JointSpec*>(nullptr));
    retarget(key.qvel, to_copy, static_cast<const JointSpec*>(nullptr));
    retarget(key.mpos, to_copy, static_cast<const BodySpec*>(nullptr));
    retarget(key.mquat, to_copy, static_cast<const BodySpec*>(nullptr));
    retarget(key.act, to_index, -1);
    retarget(key.ctrl, to_index, -1);
  }
}

// ---------------------------------------------------------------- <replicate>

void Reader::Replicate(const XmlElement& e, BodySpec* body, const FramePtr& frame,
                       const DefaultClass* def) {
  // (MuJoCo 3.5 accepts a prefix attribute and leaves the replicas' names as they are)
  e.CheckAttributes({"count", "offset", "euler", "sep", "childclass", "prefix"});
  int count = 0;
  if (!e.Int("count", &count)) e.Fail("required attribute missing: 'count'");
  if (count < 1) e.Fail("replicate count must be positive");
  std::array<double, 3> offset = {0, 0, 0}, euler = {0, 0, 0};
  e.Numbers("offset", offset);
  e.Numbers("euler", euler);
  std::string sep;
  e.Text("sep", &sep);
  const DefaultClass* childclass = FindClass(e, "childclass");
  // MuJoCo resizes and copies keyframes around each replica in ways not followed yet.
  if (!spec_->keys.empty() || spec_->nkey > 0) {
    NotSupported(e, "<replicate> in a model with keyframes");
  }

  // Read the children once, into a scratch body in the replicate's place (replicates
  // inside are multiplied by this count).
  auto scratch_owner = std::make_unique<BodySpec>();
  BodySpec* scratch = scratch_owner.get();
  scratch->src = e.src();
  body->bodies.push_back(std::move(scratch_owner));
  auto templ = std::make_shared<FrameSpec>();
  templ->src = e.src();
  templ->parent = frame;
  if (IsWorld(body)) world_standins_.push_back(scratch);
  uint64_t outer = replicate_factor_;
  replicate_factor_ = MulBytes(outer, static_cast<uint64_t>(count));
  size_t implicit_instances = spec_->implicit_instances.size();
  Body(e, scratch, templ, childclass ? childclass : def);
  replicate_factor_ = outer;
  // (MuJoCo gives each replica its own copy of a plugin instance; simlab does not yet)
  if (spec_->implicit_instances.size() != implicit_instances || scratch->plugin.active) {
    NotSupported(e, "a plugin inside <replicate>");
  }
  CheckReplicateBudget(e, count, outer, ReplicaBytes(*scratch));

  // One replica per index: its frame, its tree elements, then the references to them.
  NameTable names = CollectNames(*spec_);
  ReferenceCounts originals = {spec_->pairs.size(),     spec_->excludes.size(),
                               spec_->tendons.size(),   spec_->equalities.size(),
                               spec_->actuators.size(), spec_->sensors.size()};
  bool retry_copies = NameTakesTwoSuffixes(names, sep, count);
  UnnamedCopies unnamed;
  ReplicaMap first;
  CollectTemplate(*scratch, &first.templ);
  size_t first_copies = 0;
  double pos[3] = {0, 0, 0};
  for (int i = 0; i < count; i++) {
    FramePtr replica = ReplicaFrame(*templ, i, euler, offset, spec_->compiler, pos);
    std::string suffix = ReplicaSuffix(sep, count, i);
    FrameRebase rebase(templ.get(), replica);
    const size_t child_at = body->bodies.size();
    CopyReplica(*scratch, rebase, suffix, body, &names);
    ReplicateReferences(suffix, originals, retry_copies, &names, spec_, &unnamed);
    if (i == 0) {
      for (size_t k = 0; k < scratch->bodies.size(); k++) {
        MapCopies(*scratch->bodies[k], *body->bodies[child_at + k], &first.copies);
      }
      first_copies = spec_->actuators.size() - originals.actuators;
    }
    CheckPluginCopies(e, originals, *spec_);
    CheckSensorCopies(e, count, unnamed.sensors.size());
  }

  // Remove the scratch body, and whatever still names its elements.
  NameTable before = CollectNames(*spec_);
  auto& siblings = body->bodies;
  siblings.erase(std::find_if(siblings.begin(), siblings.end(),
                              [&](const auto& b) { return b.get() == scratch; }));
  world_standins_.erase(std::remove(world_standins_.begin(), world_standins_.end(), scratch),
                        world_standins_.end());
  // (each list against the names left after the lists before it)
  DropDangling(before, CollectNames(*spec_), &spec_->pairs);
  DropDangling(before, CollectNames(*spec_), &spec_->excludes);
  DropDangling(before, CollectNames(*spec_), &spec_->tendons);
  DropDangling(before, CollectNames(*spec_), &spec_->equalities);
  // (the actuators dropped decide where the carried keyframes' actuators go)
  std::vector<bool> dropped = DanglingMask(before, CollectNames(*spec_), spec_->actuators);
  first.actuators = ActuatorMoves(dropped, originals.actuators, first_copies);
  MoveCarriedKeys(first);
  EraseMasked(dropped, &spec_->actuators);
  DropDangling(before, CollectNames(*spec_), &spec_->sensors);
}

bool Reader::IsWorld(const BodySpec* body) const {
  return body == &spec_->world ||
         std::find(world_standins_.begin(), world_standins_.end(), body) !=
             world_standins_.end();
}

}  // namespace simlab::mjcf
