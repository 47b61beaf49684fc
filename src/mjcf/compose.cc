// Model composition.
//
// <include> is a paste: before reading, the elements under the root of the included
// file replace the <include> element, and remember their own file and line for error
// messages. <attach> is a copy: the named body subtree of a model declared with
// <asset><model> (read on its own, with its own defaults) is copied into this body
// with every name prefixed; the child's contact pairs, excludes, tendons, equalities,
// actuators and sensors follow when everything they reference came along, and its
// keyframes become keyframes of this model, completed by the compiler (see AttachedKey).
#include "mjcf/compose.h"

#include <algorithm>
#include <set>

#include "mjcf/error.h"
#include "mjcf/limits.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

// ---------------------------------------------------------------- origins of nodes

void NodeOrigins::Record(pugi::xml_node node, const std::string& file, int line) {
  map_[node.internal_object()] = {file, line};
}

const NodeOrigins::Origin* NodeOrigins::Find(pugi::xml_node node) const {
  auto it = map_.find(node.internal_object());
  return it == map_.end() ? nullptr : &it->second;
}

std::string DirectoryOf(const std::string& path) {
  size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}

namespace {

// The element with its place: from `origins` if it was pasted in, else the main file.
XmlElement ElementAt(pugi::xml_node node, const NodeOrigins* origins, const std::string& file,
                     const LineIndex& lines) {
  if (origins) {
    if (const NodeOrigins::Origin* o = origins->Find(node)) return XmlElement(node, o->file, o->line);
  }
  return XmlElement(node, file, lines);
}

bool IsAbsolute(const std::string& path) { return !path.empty() && path[0] == '/'; }

// ---------------------------------------------------------------- <include>

constexpr int kMaxIncludeDepth = 64;

class IncludeExpander {
 public:
  IncludeExpander(const std::string& file, const LineIndex& lines, NodeOrigins* origins,
                  const AssetFiles* assets)
      : main_file_(file), main_dir_(DirectoryOf(file)), main_lines_(lines), origins_(origins),
        assets_(assets) {
    included_.insert(file);
  }

  // Expands the includes among the descendants of `parent`, an element on `level` of
  // the composed document, in a file of `dir`.
  void Children(pugi::xml_node parent, const std::string& dir, int depth, int level) {
    pugi::xml_node child = parent.first_child();
    while (child) {
      pugi::xml_node next = child.next_sibling();
      if (child.type() == pugi::node_element) {
        if (std::string(child.name()) == "include") {
          Include(child, dir, depth, level + 1);
        } else {
          Enter(child, level + 1);
          Children(child, dir, depth, level + 1);
        }
      }
      child = next;
    }
  }

  // The deepest level of the composed document so far (the root is level 1).
  int max_level() const { return max_level_; }

 private:
  // Every element of the composed document is at most kMaxTreeDepth levels deep, so
  // that the recursive walks after this one are bounded (each file on its own was
  // held to kMaxXmlDepth by its parser).
  void Enter(pugi::xml_node node, int level) {
    if (level > kMaxTreeDepth) {
      ElementAt(node, origins_, main_file_, main_lines_)
          .Fail("element nesting is too deep: with its included files pasted in, the model "
                "nests elements more than " + std::to_string(kMaxTreeDepth) +
                " levels deep (simlab's limit)");
    }
    max_level_ = std::max(max_level_, level);
  }

  // Replaces one <include> (on `level`) by the elements of its file, then expands those.
  void Include(pugi::xml_node node, const std::string& dir, int depth, int level) {
    XmlElement e = ElementAt(node, origins_, main_file_, main_lines_);
    e.CheckAttributes({"file"});
    if (node.find_child([](pugi::xml_node n) { return n.type() == pugi::node_element; })) {
      e.Fail("<include> cannot have child elements");
    }
    if (depth > kMaxIncludeDepth) e.Fail("includes are nested too deeply");
    std::string name, path, text, problem;
    e.RequiredText("file", &name);
    if (!Open(name, dir, &path, &text, &problem)) {
      if (!problem.empty()) e.Fail("cannot read included file " + problem);
      e.Fail("cannot open included file '" + name + "'" + NotAmongAssets(assets_));
    }
    if (included_.count(path)) {
      e.Fail("file '" + path + "' is already included (a file can be included only once, " +
             "so an include cannot be recursive)");
    }
    included_.insert(path);

    // Parse it; its root element is dropped and must hold at least one element.
    LineIndex lines(text);
    pugi::xml_document doc;
    pugi::xml_node root = ParseXml(text, path, lines, &doc);
    if (root.empty()) e.Fail("included file '" + path + "' has no root element");
    pugi::xml_node parent = node.parent();
    std::vector<pugi::xml_node> pasted;
    for (pugi::xml_node c : root.children()) {
      if (c.type() != pugi::node_element) continue;
      pugi::xml_node copy = parent.insert_copy_before(c, node);
      RecordTree(c, copy, path, lines);
      pasted.push_back(copy);
    }
    if (pasted.empty()) e.Fail("included file '" + path + "' is empty");
    origins_->Forget(node);
    parent.remove_child(node);

    // What was pasted may include further files, relative to this one.
    std::string next_dir = DirectoryOf(path);
    for (pugi::xml_node copy : pasted) {
      if (std::string(copy.name()) == "include") {
        Include(copy, next_dir, depth + 1, level);
      } else {
        Enter(copy, level);
        Children(copy, next_dir, depth + 1, level);
      }
    }
  }

  // MuJoCo looks next to the main file first, then next to the including file; each
  // place among the assets (matched by file name), then on disk.
  // `problem` says why the first file found could not be read (see ReadFileOrAsset).
  bool Open(const std::string& name, const std::string& dir, std::string* path,
            std::string* text, std::string* problem) const {
    std::vector<std::string> candidates = {name};
    if (!IsAbsolute(name)) candidates = {main_dir_ + name, dir + name};
    for (const std::string& candidate : candidates) {
      std::string why;
      if (ReadFileOrAsset(candidate, assets_, text, &why)) {
        *path = candidate;
        return true;
      }
      if (problem->empty() && !why.empty()) *problem = "'" + candidate + "': " + why;
    }
    return false;
  }

  // Every element of a pasted copy keeps the file and line of its original.
  void RecordTree(pugi::xml_node original, pugi::xml_node copy, const std::string& path,
                  const LineIndex& lines) {
    origins_->Record(copy, path, lines.Line(original.offset_debug()));
    pugi::xml_node a = original.first_child(), b = copy.first_child();
    for (; a && b; a = a.next_sibling(), b = b.next_sibling()) {
      if (a.type() == pugi::node_element) RecordTree(a, b, path, lines);
    }
  }

  std::string main_file_, main_dir_;
  const LineIndex& main_lines_;
  NodeOrigins* origins_;
  const AssetFiles* assets_;  // may be null
  std::set<std::string> included_;
  int max_level_ = 1;
};

}  // namespace

int ExpandIncludes(pugi::xml_node root, const std::string& file, const LineIndex& lines,
                   NodeOrigins* origins, const AssetFiles* assets) {
  IncludeExpander expander(file, lines, origins, assets);
  expander.Children(root, DirectoryOf(file), 0, 1);
  return expander.max_level();
}

XmlElement Reader::Element(pugi::xml_node node) const {
  return ElementAt(node, origins_, file_, lines_);
}

// ---------------------------------------------------------------- <asset><model>

namespace {

// Models that attach models: deeper than this is taken for a cycle.
constexpr int kMaxModelDepth = 32;
thread_local int model_depth = 0;

}  // namespace

void Reader::AssetModel(const XmlElement& e) {
  e.CheckAttributes({"name", "file", "content_type"});
  std::string file, name, type;
  e.RequiredText("file", &file);
  if (e.Text("content_type", &type) && type != "text/xml") {
    e.Fail("content_type must be \"text/xml\"");
  }

  // The file is relative to the main file's folder (among the assets first); it is
  // read on its own, with this model's assets.
  std::string path = IsAbsolute(file) ? file : DirectoryOf(file_) + file;
  std::string text, problem;
  if (!ReadFileOrAsset(path, spec_->assets.get(), &text, &problem)) {
    if (!problem.empty()) e.Fail("cannot read model file '" + path + "': " + problem);
    e.Fail("cannot open model file '" + path + "'" + NotAmongAssets(spec_->assets.get()));
  }
  if (model_depth >= kMaxModelDepth) e.Fail("models are nested too deeply (a cycle of models?)");
  auto model = std::make_shared<ParsedModel>();
  model_depth++;
  try {
    ReadModel(text, path, model.get(), spec_->assets);
  } catch (...) {
    model_depth--;
    throw;
  }
  model_depth--;

  // Its name, unless given, is the model's own.
  if (!e.Text("name", &name)) name = model->spec.model_name;
  if (models_.count(name)) e.Fail("repeated model name '" + name + "'");
  models_[name] = model;
}

// ---------------------------------------------------------------- <attach>

// The copied elements: names (prefixed) by kind, and child element -> copy.
struct Attachment {
  std::string prefix;
  std::map<int, std::set<std::string>> names;  // by ObjType
  std::map<const JointSpec*, const JointSpec*> joints;
  std::map<const BodySpec*, const BodySpec*> bodies;
  std::vector<std::pair<const ActuatorSpec*, int>> actuators;  // index here, or -1
  // The child's <compiler> settings, which its elements keep (those of a model the child
  // itself attached keep theirs), and the child's frames copied under them.
  CompilerPtr settings;
  std::map<const FrameSpec*, FramePtr> frames;

  void Keep(CompilerPtr* own) const {
    if (!*own) *own = settings;
  }
  // A frame chain of the child, copied with the child's settings, ending at `base` (null:
  // where the child's chain ends).
  FramePtr Frame(const FramePtr& frame, const FramePtr& base = nullptr) {
    if (!frame) return base;
    if (!base) {
      auto done = frames.find(frame.get());
      if (done != frames.end()) return done->second;
    }
    auto copy = std::make_shared<FrameSpec>(*frame);
    Keep(&copy->compiler);
    copy->parent = Frame(frame->parent, base);
    if (!base) frames[frame.get()] = copy;
    return copy;
  }

  // Prefixes a name (a reference when `kind` is kObjUnknown, else an element's own).
  void Rename(std::string* name, int kind = kObjUnknown) {
    if (name->empty()) return;
    *name = prefix + *name;
    if (kind != kObjUnknown) names[kind].insert(*name);
  }
  bool Has(int kind, const std::string& name) const {
    auto it = names.find(kind);
    return it != names.end() && it->second.count(name) > 0;
  }
};

namespace {

void RenameLight(LightSpec* light, Attachment* att) {
  att->Rename(&light->src.name, kObjLight);
  att->Rename(&light->target);
  att->Rename(&light->texture);
}

// Renames a copied subtree, maps the child's elements to their copies, and gives them
// the child's settings (the body's own frame is the caller's to set).
void RenameTree(const BodySpec& original, BodySpec* copy, Attachment* att) {
  att->bodies[&original] = copy;
  att->Rename(&copy->src.name, kObjBody);
  att->Keep(&copy->compiler);
  for (size_t i = 0; i < copy->joints.size(); i++) {
    JointSpec& j = copy->joints[i];
    att->joints[&original.joints[i]] = &j;
    att->Rename(&j.src.name, kObjJoint);
    att->Keep(&j.compiler);
    j.frame = att->Frame(j.frame);
  }
  for (GeomSpec& g : copy->geoms) {
    att->Rename(&g.src.name, kObjGeom);
    att->Rename(&g.material);
    att->Keep(&g.compiler);
    g.frame = att->Frame(g.frame);
  }
  for (SiteSpec& s : copy->sites) {
    att->Rename(&s.src.name, kObjSite);
    att->Rename(&s.material);
    att->Keep(&s.compiler);
    s.frame = att->Frame(s.frame);
  }
  for (CameraSpec& c : copy->cameras) {
    att->Rename(&c.src.name, kObjCamera);
    att->Rename(&c.target);
    att->Keep(&c.compiler);
    c.frame = att->Frame(c.frame);
  }
  for (LightSpec& l : copy->lights) {
    RenameLight(&l, att);
    att->Keep(&l.compiler);
    l.frame = att->Frame(l.frame);
  }
  for (size_t i = 0; i < copy->bodies.size(); i++) {
    copy->bodies[i]->frame = att->Frame(copy->bodies[i]->frame);
  }
  for (size_t i = 0; i < copy->bodies.size(); i++) {
    RenameTree(*original.bodies[i], copy->bodies[i].get(), att);
  }
}

// A body of the child by name, anywhere in its tree.
const BodySpec* FindBody(const BodySpec& body, const std::string& name) {
  if (body.src.name == name) return &body;
  for (const auto& child : body.bodies) {
    if (const BodySpec* found = FindBody(*child, name)) return found;
  }
  return nullptr;
}

// A tendon follows when every joint, site and geom on its path came along.
bool AttachTendon(TendonSpec* t, Attachment* att) {
  bool found = true;
  for (WrapSpec& w : t->wraps) {
    att->Rename(&w.target);
    att->Rename(&w.sidesite);
    if (w.type == kWrapJoint) found = found && att->Has(kObjJoint, w.target);
    if (w.type == kWrapSite) found = found && att->Has(kObjSite, w.target);
    if (w.type == kWrapSphere || w.type == kWrapCylinder) {
      found = found && att->Has(kObjGeom, w.target);
    }
    if (!w.sidesite.empty()) found = found && att->Has(kObjSite, w.sidesite);
  }
  return found;
}

// A contact pair follows when both its geoms came along; an exclude when both its bodies
// did (MuJoCo copies the child's pairs and excludes and drops those that name others).
bool AttachPair(PairSpec* pair, Attachment* att) {
  att->Rename(&pair->geom1);
  att->Rename(&pair->geom2);
  return att->Has(kObjGeom, pair->geom1) && att->Has(kObjGeom, pair->geom2);
}

bool AttachExclude(ExcludeSpec* exclude, Attachment* att) {
  att->Rename(&exclude->body1);
  att->Rename(&exclude->body2);
  return att->Has(kObjBody, exclude->body1) && att->Has(kObjBody, exclude->body2);
}

// An equality follows when its objects came along (no second body: the world).
bool AttachEquality(EqualitySpec* eq, Attachment* att) {
  att->Rename(&eq->name1);
  att->Rename(&eq->name2);
  int kind = kObjUnknown;
  switch (eq->type) {
    case kEqConnect:
    case kEqWeld: kind = eq->objtype; break;
    case kEqJoint: kind = kObjJoint; break;
    case kEqTendon: kind = kObjTendon; break;
    default: return false;
  }
  bool second = eq->name2.empty() || att->Has(kind, eq->name2);
  return att->Has(kind, eq->name1) && second;
}

// An actuator follows when its transmission target (and slider or reference site) did.
bool AttachActuator(ActuatorSpec* a, Attachment* att) {
  att->Rename(&a->target);
  att->Rename(&a->slidersite);
  att->Rename(&a->refsite);
  switch (a->trntype) {
    case kTrnJoint:
    case kTrnJointInParent: return att->Has(kObjJoint, a->target);
    case kTrnTendon: return att->Has(kObjTendon, a->target);
    case kTrnSliderCrank:
      return att->Has(kObjSite, a->target) && att->Has(kObjSite, a->slidersite);
    case kTrnSite:
      return att->Has(kObjSite, a->target) &&
             (a->refsite.empty() || att->Has(kObjSite, a->refsite));
    case kTrnBody: return att->Has(kObjBody, a->target);
    default: return false;
  }
}

// A sensor follows when every object it names (sensorized and reference) was copied;
// sensors that name none (clock, energy) always follow.
bool AttachSensor(SensorSpec* s, Attachment* att) {
  auto copied = [&](int type, std::string* name) {
    if (type == kObjUnknown) return true;
    att->Rename(name);
    return att->Has(type == kObjXBody ? kObjBody : type, *name);
  };
  bool object = copied(s->objtype, &s->objname);
  bool reference = copied(s->reftype, &s->refname);
  return object && reference;
}

// The child's joints and mocap bodies in its own compiled order (depth first).
void ChildOrder(const BodySpec& body, std::vector<const JointSpec*>* joints,
                std::vector<const BodySpec*>* mocap) {
  if (body.mocap) mocap->push_back(&body);
  for (const JointSpec& j : body.joints) joints->push_back(&j);
  for (const auto& child : body.bodies) ChildOrder(*child, joints, mocap);
}

// One element's share of a keyframe row: the element and its number of values.
struct Slot {
  const void* element;
  int width;
};

// Checks a child keyframe's row against the child's size (MuJoCo does it on attach).
void CheckRowSize(const KeySpec& key, const char* what, const std::vector<double>& given,
                  const std::vector<Slot>& slots) {
  size_t total = 0;
  for (const Slot& s : slots) total += s.width;
  if (!given.empty() && given.size() != total) {
    ThrowAt(key.src, std::string("invalid ") + what + " size, expected " +
                         std::to_string(total) + ", got " + std::to_string(given.size()));
  }
}

}  // namespace

void Reader::Attach(const XmlElement& e, BodySpec* body, const FramePtr& frame) {
  e.CheckAttributes({"model", "body", "prefix"});
  std::string model_name, body_name;
  Attachment att;
  e.RequiredText("model", &model_name);
  e.RequiredText("prefix", &att.prefix);
  e.Text("body", &body_name);
  auto found = models_.find(model_name);
  if (found == models_.end()) {
    e.Fail("unknown model '" + model_name + "' (declare it with <asset><model>)");
  }
  std::shared_ptr<const ParsedModel> child = found->second;
  const ModelSpec& cs = child->spec;
  CheckAttachDepth(e, *child);
  att.settings = std::make_shared<const CompilerSpec>(cs.compiler);
  if (!cs.active_plugins.empty() || !cs.plugin_instances.empty() || !cs.implicit_instances.empty()) {
    NotSupported(e, "attaching a model that uses plugins");
  }

  // The child's keyframes go onto its elements first (as MuJoCo stores them).
  HoldKeys(e, *child, att.prefix);

  // The attachment frame: the enclosing <frame>, else a new identity frame.
  FramePtr base = frame;
  if (!base) {
    auto made = std::make_shared<FrameSpec>();
    made->src = e.src();
    base = made;
  }

  // The tree: one body subtree, or the whole child world (its bodies, geoms, sites).
  std::vector<const BodySpec*> originals;
  if (!body_name.empty()) {
    const BodySpec* original = FindBody(cs.world, body_name);
    if (!original) e.Fail("model '" + model_name + "' has no body '" + body_name + "'");
    originals.push_back(original);
  } else {
    att.names[kObjBody].insert("world");
    for (const auto& b : cs.world.bodies) originals.push_back(b.get());
    for (GeomSpec g : cs.world.geoms) {
      g.frame = att.Frame(g.frame, base);
      att.Keep(&g.compiler);
      att.Rename(&g.src.name, kObjGeom);
      body->geoms.push_back(std::move(g));
    }
    for (SiteSpec s : cs.world.sites) {
      s.frame = att.Frame(s.frame, base);
      att.Keep(&s.compiler);
      att.Rename(&s.src.name, kObjSite);
      body->sites.push_back(std::move(s));
    }
    for (CameraSpec c : cs.world.cameras) {
      c.frame = att.Frame(c.frame, base);
      att.Keep(&c.compiler);
      att.Rename(&c.src.name, kObjCamera);
      att.Rename(&c.target);
      body->cameras.push_back(std::move(c));
    }
    for (LightSpec l : cs.world.lights) {
      l.frame = att.Frame(l.frame, base);
      att.Keep(&l.compiler);
      RenameLight(&l, &att);
      body->lights.push_back(std::move(l));
    }
  }
  for (const BodySpec* original : originals) {
    auto copy = std::make_unique<BodySpec>(*original);
    RenameTree(*original, copy.get(), &att);
    copy->frame = body_name.empty() ? att.Frame(original->frame, base) : base;
    body->bodies.push_back(std::move(copy));
  }

  // The child's textures and materials come along, prefixed as its geoms' references are.
  for (TextureSpec t : cs.textures) {
    att.Rename(&t.src.name, kObjTexture);
    spec_->textures.push_back(std::move(t));
  }
  for (MaterialSpec mat : cs.materials) {
    att.Rename(&mat.src.name, kObjMaterial);
    for (std::string& tex : mat.textures) att.Rename(&tex);
    spec_->materials.push_back(std::move(mat));
  }

  // Elements outside the tree that reference only what was copied, in MuJoCo's order.
  for (PairSpec pair : cs.pairs) {
    if (!AttachPair(&pair, &att)) continue;
    att.Rename(&pair.src.name, kObjPair);
    spec_->pairs.push_back(std::move(pair));
  }
  for (ExcludeSpec exclude : cs.excludes) {
    if (!AttachExclude(&exclude, &att)) continue;
    att.Rename(&exclude.src.name, kObjExclude);
    spec_->excludes.push_back(std::move(exclude));
  }
  for (TendonSpec t : cs.tendons) {
    if (!AttachTendon(&t, &att)) continue;
    att.Keep(&t.compiler);
    att.Rename(&t.src.name, kObjTendon);
    spec_->tendons.push_back(std::move(t));
  }
  for (EqualitySpec eq : cs.equalities) {
    if (!AttachEquality(&eq, &att)) continue;
    att.Rename(&eq.src.name, kObjEquality);
    spec_->equalities.push_back(std::move(eq));
  }
  for (const ActuatorSpec& original : cs.actuators) {
    ActuatorSpec a = original;
    bool keep = AttachActuator(&a, &att);
    att.actuators.emplace_back(&original, keep ? static_cast<int>(spec_->actuators.size()) : -1);
    if (!keep) continue;
    att.Keep(&a.compiler);
    att.Rename(&a.src.name, kObjActuator);
    spec_->actuators.push_back(std::move(a));
  }
  for (SensorSpec s : cs.sensors) {
    if (!AttachSensor(&s, &att)) continue;
    att.Rename(&s.src.name, kObjSensor);
    spec_->sensors.push_back(std::move(s));
  }
  AttachClasses(*child, att.prefix);
  CarryKeys(att);
}

// The copied tree nests below the <attach> element as deep as in its own model: the
// two together stay within kMaxTreeDepth (each was read within it).
void Reader::CheckAttachDepth(const XmlElement& e, const ParsedModel& child) {
  int level = 0;
  for (pugi::xml_node n = e.node(); n.type() == pugi::node_element; n = n.parent()) level++;
  int depth = level + child.depth;
  if (depth > kMaxTreeDepth) {
    std::string name;
    e.Text("model", &name);
    e.Fail("element nesting is too deep: with model '" + name + "' attached here, the " +
           "model nests elements " + std::to_string(depth) + " levels deep, more than " +
           std::to_string(kMaxTreeDepth) + " (simlab's limit)");
  }
  depth_ = std::max(depth_, depth);
}

// The child's default classes become classes of this model, prefixed ("main" too).
void Reader::AttachClasses(const ParsedModel& child, const std::string& prefix) {
  for (const auto& [name, cls] : child.classes) {
    std::string renamed = prefix + name;
    if (classes_.count(renamed)) continue;
    auto copy = std::make_unique<DefaultClass>(*cls);
    copy->name = renamed;
    if (!copy->parent.empty()) copy->parent = prefix + copy->parent;
    classes_[renamed] = std::move(copy);
  }
}

// Each keyframe of the child becomes a keyframe of this model, named with the prefix
// (an unnamed one is named by the prefix alone); its values go onto the child's
// elements, which carry them into this model when they are copied.
void Reader::HoldKeys(const XmlElement& e, const ParsedModel& child, const std::string& prefix) {
  const ModelSpec& cs = child.spec;
  for (const KeySpec& k : cs.keys) {
    if (k.attached) NotSupported(e, "keyframes of a model that attaches models itself");
  }

  // The child's rows, element by element.
  std::vector<const JointSpec*> joints;
  std::vector<const BodySpec*> mocap;
  ChildOrder(cs.world, &joints, &mocap);
  std::vector<Slot> qpos, qvel, act, ctrl, mpos, mquat;
  for (const JointSpec* j : joints) {
    qpos.push_back({j, j->type == kJointFree ? 7 : j->type == kJointBall ? 4 : 1});
    qvel.push_back({j, j->type == kJointFree ? 6 : j->type == kJointBall ? 3 : 1});
  }
  for (const ActuatorSpec& a : cs.actuators) {
    act.push_back({&a, a.actdim > 0 ? a.actdim : a.dyntype != kDynNone ? 1 : 0});
    ctrl.push_back({&a, 1});
  }
  for (const BodySpec* b : mocap) {
    mpos.push_back({b, 3});
    mquat.push_back({b, 4});
  }

  // Split each keyframe among the elements.
  auto hold = [&](const KeySpec& k, const char* what, const std::vector<double>& given,
                  const std::vector<Slot>& slots, KeyValues HeldValues::*field) {
    CheckRowSize(k, what, given, slots);
    size_t offset = 0;
    for (const Slot& s : slots) {
      if (given.empty() || s.width == 0) continue;
      auto begin = given.begin() + static_cast<ptrdiff_t>(offset);
      (held_[s.element].*field)[prefix + k.src.name].assign(begin, begin + s.width);
      offset += s.width;
    }
  };
  for (int i = 0; i < child.own_keys; i++) {
    const KeySpec& k = cs.keys[i];
    hold(k, "qpos", k.qpos, qpos, &HeldValues::qpos);
    hold(k, "qvel", k.qvel, qvel, &HeldValues::qvel);
    hold(k, "act", k.act, act, &HeldValues::act);
    hold(k, "ctrl", k.ctrl, ctrl, &HeldValues::ctrl);
    hold(k, "mpos", k.mpos, mpos, &HeldValues::mpos);
    hold(k, "mquat", k.mquat, mquat, &HeldValues::mquat);
    KeySpec key;
    key.src = k.src;
    key.src.name = prefix + k.src.name;
    key.time = k.time;
    attached_keys_.push_back(std::move(key));
  }
}

// The copied elements take their held keyframe values into this model; the child's
// originals forget them.
void Reader::CarryKeys(const Attachment& att) {
  auto carry = [&](const void* original, auto copy, KeyValues HeldValues::*field,
                   auto AttachedKey::*list) {
    auto it = held_.find(original);
    if (it == held_.end()) return;
    for (auto& [name, values] : it->second.*field) {
      (carried_[name].*list).emplace_back(copy, std::move(values));
    }
    (it->second.*field).clear();
  };
  for (const auto& [original, copy] : att.joints) {
    carry(original, copy, &HeldValues::qpos, &AttachedKey::qpos);
    carry(original, copy, &HeldValues::qvel, &AttachedKey::qvel);
  }
  for (const auto& [original, index] : att.actuators) {
    if (index < 0) continue;
    carry(original, index, &HeldValues::act, &AttachedKey::act);
    carry(original, index, &HeldValues::ctrl, &AttachedKey::ctrl);
  }
  for (const auto& [original, copy] : att.bodies) {
    carry(original, copy, &HeldValues::mpos, &AttachedKey::mpos);
    carry(original, copy, &HeldValues::mquat, &AttachedKey::mquat);
  }
}

void Reader::FinishKeys() {
  own_keys_ = static_cast<int>(spec_->keys.size());
  while (static_cast<int>(spec_->keys.size()) < spec_->nkey) {
    KeySpec key;
    key.src = {file_, 0, "key", ""};
    spec_->keys.push_back(key);
  }
  for (KeySpec& key : attached_keys_) {
    key.attached = std::make_shared<AttachedKey>(carried_[key.src.name]);
    spec_->keys.push_back(std::move(key));
  }
  attached_keys_.clear();
}

}  // namespace simlab::mjcf
