// MJCF reader: the document root, default classes and the body tree.
#include "mjcf/reader.h"

#include <cstring>
#include <utility>

#include "mjcf/error.h"

namespace simlab::mjcf {

// ---------------------------------------------------------------- entry point

ModelSpec ReadMjcf(const std::string& text, const std::string& file,
                   const AssetFilesPtr& assets) {
  ParsedModel model;
  ReadModel(text, file, &model, assets);
  return std::move(model.spec);
}

ModelSpec ReadMjcfFile(const std::string& path) {
  std::string text, problem;
  if (!ReadFileOrAsset(path, nullptr, &text, &problem)) {
    throw Error(path + ": " +
                (problem.empty() ? "cannot open file" : "cannot read file: " + problem));
  }
  return ReadMjcf(text, path);
}

void ReadModel(const std::string& text, const std::string& file, ParsedModel* out,
               const AssetFilesPtr& assets) {
  // Parse the XML (its syntax and depth checked).
  LineIndex lines(text);
  pugi::xml_document doc;
  pugi::xml_node root = ParseXml(text, file, lines, &doc);
  if (root.empty()) throw Error(file + ":1: malformed XML: no root element");
  if (std::strcmp(root.name(), "mujoco") != 0) {
    XmlElement e(root, file, lines);
    e.Fail("the root element must be <mujoco>");
  }

  // Paste in included files, then walk the document into a spec (which keeps the
  // assets for the models it attaches and for the compiler).
  NodeOrigins origins;
  int depth = ExpandIncludes(root, file, lines, &origins, assets.get());
  out->spec.file = file;
  out->spec.assets = assets;
  Reader reader(file, lines, &out->spec, &origins);
  reader.depth_ = depth;
  reader.Root(root);
  out->classes = std::move(reader.classes_);
  out->own_keys = reader.own_keys_;
  out->depth = reader.depth_;
}

Reader::Reader(const std::string& file, const LineIndex& lines, ModelSpec* spec,
               const NodeOrigins* origins)
    : file_(file), lines_(lines), spec_(spec), origins_(origins) {
  auto main = std::make_unique<DefaultClass>();
  main->name = "main";
  classes_["main"] = std::move(main);
  spec_->world.src = {file, 0, "worldbody", "world"};
}

void Reader::NotSupported(const XmlElement& e, const std::string& what) const {
  e.Fail((what.empty() ? "<" + e.tag() + ">" : what) + " is not supported yet");
}

void Reader::ChildPlugin(const XmlElement& e, PluginUse* use) {
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() != "plugin") Unknown(c);
    ReadOwnPlugin(c, e.tag(), use);
  }
}

void Reader::Unknown(const XmlElement& e) const {
  XmlElement parent = Element(e.node().parent());
  e.Fail("unknown element <" + e.tag() + "> in <" + parent.tag() + ">");
}

// ---------------------------------------------------------------- document root

void Reader::Root(pugi::xml_node root) {
  XmlElement top = Element(root);
  top.CheckAttributes({"model"});
  FindNewerConstruct(root);
  top.Text("model", &spec_->model_name);

  // Check every section name before reading any.
  static const char* kSections[] = {"compiler", "option",  "size",     "visual",
                                    "statistic", "default", "custom",   "asset",
                                    "contact",  "tendon",  "actuator", "keyframe",
                                    "worldbody", "sensor", "equality", "extension",
                                    "deformable"};
  for (pugi::xml_node child : root.children()) {
    if (child.type() != pugi::node_element) continue;
    XmlElement e = Element(child);
    bool known = false;
    for (const char* name : kSections) known = known || e.tag() == name;
    if (!known) Unknown(e);
  }

  // Read the sections in MuJoCo's order, whatever their order in the file.
  auto each = [&](const char* name, auto&& read) {
    for (pugi::xml_node n = root.child(name); n; n = n.next_sibling(name)) read(Element(n));
  };
  each("compiler", [&](const XmlElement& e) { Compiler(e); });
  each("option", [&](const XmlElement& e) { Option(e); });
  each("size", [&](const XmlElement& e) { Size(e); });
  each("visual", [&](const XmlElement& e) { Visual(e); });
  each("statistic", [&](const XmlElement& e) { Statistic(e); });
  each("default", [&](const XmlElement& e) { Default(e, nullptr); });
  each("extension", [&](const XmlElement& e) { Extension(e); });
  each("custom", [&](const XmlElement& e) { Custom(e); });
  each("asset", [&](const XmlElement& e) { Asset(e); });
  each("contact", [&](const XmlElement& e) { Contact(e); });
  each("deformable", [&](const XmlElement& e) { Deformable(e); });
  each("equality", [&](const XmlElement& e) { Equality(e); });
  each("tendon", [&](const XmlElement& e) { Tendon(e); });
  each("actuator", [&](const XmlElement& e) { Actuator(e); });
  each("sensor", [&](const XmlElement& e) { Sensor(e); });
  each("keyframe", [&](const XmlElement& e) { Keyframe(e); });
  each("worldbody", [&](const XmlElement& e) {
    if (e.node().first_attribute()) e.Fail("the world body cannot have attributes");
    Body(e, &spec_->world, nullptr, classes_.at("main").get());
  });

  FinishKeys();
  NoteUnusedClasses();
}

// ---------------------------------------------------------------- default classes

void Reader::Default(const XmlElement& e, const DefaultClass* parent) {
  e.CheckAttributes({"class"});
  std::string name;
  e.Text("class", &name);

  // The top level is class "main"; nested classes copy their parent.
  DefaultClass* def = nullptr;
  if (!parent) {
    if (!name.empty() && name != "main") e.Fail("the top-level default class cannot be renamed");
    def = classes_.at("main").get();
  } else {
    if (name.empty()) e.Fail("a nested default needs a class name");
    if (classes_.count(name)) e.Fail("repeated default class name '" + name + "'");
    auto made = std::make_unique<DefaultClass>(*parent);
    made->name = name;
    made->parent = parent->name;
    made->src = e.src();
    made->src.name = name;
    own_classes_.insert(name);
    def = made.get();
    classes_[name] = std::move(made);
  }

  // The class's own elements first, then nested classes (which copy the result).
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    const std::string& tag = c.tag();
    if (tag == "default") continue;
    if (tag == "joint") {
      ReadJoint(c, &def->joint, true);
    } else if (tag == "geom") {
      ReadGeom(c, &def->geom, true);
    } else if (tag == "site") {
      ReadSite(c, &def->site, true);
    } else if (tag == "tendon") {
      ReadTendon(c, &def->tendon, true);
    } else if (tag == "camera") {
      ReadCamera(c, &def->camera, true);
    } else if (tag == "light") {
      ReadLight(c, &def->light, true);
    } else if (tag == "equality") {
      ReadEquality(c, &def->equality, true);
    } else if (tag == "pair") {
      ReadPair(c, &def->pair, true);
    } else if (tag == "mesh") {
      ReadMesh(c, &def->mesh, true);
    } else if (tag == "material") {
      ReadMaterial(c, &def->material, true);
    } else if (IsActuatorElement(tag)) {
      ReadActuator(c, &def->actuator, true);
    } else {
      Unknown(c);
    }
  }
  for (pugi::xml_node n = e.node().child("default"); n; n = n.next_sibling("default")) {
    Default(Element(n), def);
  }
}

const DefaultClass* Reader::FindClass(const XmlElement& e, const char* attr) const {
  std::string name;
  if (!e.Text(attr, &name)) return nullptr;
  auto it = classes_.find(name);
  if (it == classes_.end()) e.Fail("unknown default class '" + name + "'");
  used_classes_.insert(name);
  return it->second.get();
}

void Reader::NoteUnusedClasses() {
  // A class is used when it, or a class nested in it, is named by an element.
  std::set<std::string> used;
  for (const std::string& name : used_classes_) {
    for (auto it = classes_.find(name); it != classes_.end(); it = classes_.find(it->second->parent)) {
      if (!used.insert(it->first).second) break;
    }
  }
  // (classes an attached model brought along are its own document's business)
  for (const std::string& name : own_classes_) {
    if (!used.count(name)) spec_->unused_classes.push_back(classes_.at(name)->src);
  }
}

// ---------------------------------------------------------------- the body tree

void Reader::Body(const XmlElement& e, BodySpec* body, const FramePtr& frame,
                  const DefaultClass* def) {
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    BodyChild(Element(n), body, frame, def);
  }
}

void Reader::BodyChild(const XmlElement& c, BodySpec* body, const FramePtr& frame,
                       const DefaultClass* def) {
  // Elements take their class attribute, else the enclosing body's or frame's class.
  const DefaultClass* cls = nullptr;
  if (c.tag() != "body" && c.tag() != "frame") cls = FindClass(c, "class");
  if (!cls) cls = def;
  bool world = IsWorld(body);
  const std::string& tag = c.tag();
  if (tag == "inertial") {
    if (world) c.Fail("the world body cannot have an inertial");
    Inertial(c, body);
  } else if (tag == "joint") {
    if (world) c.Fail("the world body cannot have joints");
    JointSpec joint = cls->joint;
    ReadJoint(c, &joint, false);
    joint.frame = frame;
    body->joints.push_back(std::move(joint));
  } else if (tag == "freejoint") {
    if (world) c.Fail("the world body cannot have joints");
    FreeJoint(c, body, frame);
  } else if (tag == "geom") {
    GeomSpec geom = cls->geom;
    ReadGeom(c, &geom, false);
    ChildPlugin(c, &geom.plugin);
    geom.frame = frame;
    body->geoms.push_back(std::move(geom));
  } else if (tag == "site") {
    SiteSpec site = cls->site;
    ReadSite(c, &site, false);
    site.frame = frame;
    body->sites.push_back(std::move(site));
  } else if (tag == "camera") {
    CameraSpec cam = cls->camera;
    ReadCamera(c, &cam, false);
    cam.frame = frame;
    body->cameras.push_back(std::move(cam));
  } else if (tag == "light") {
    LightSpec light = cls->light;
    ReadLight(c, &light, false);
    light.frame = frame;
    body->lights.push_back(std::move(light));
  } else if (tag == "frame") {
    Frame(c, body, frame, def);
  } else if (tag == "body") {
    ChildBody(c, body, frame, def);
  } else if (tag == "attach") {
    Attach(c, body, frame);
  } else if (tag == "replicate") {
    Replicate(c, body, frame, def);
  } else if (tag == "plugin") {
    ReadOwnPlugin(c, "body", &body->plugin);
  } else if (tag == "flexcomp") {
    Flexcomp(c, body, def);
  } else if (tag == "composite") {
    NotSupported(c);
  } else {
    Unknown(c);
  }
}

void Reader::ChildBody(const XmlElement& e, BodySpec* parent, const FramePtr& frame,
                       const DefaultClass* def) {
  e.CheckAttributes({"name", "childclass", "pos", "quat", "mocap", "axisangle", "xyaxes",
                     "zaxis", "euler", "gravcomp", "sleep", "user"});
  const DefaultClass* childclass = FindClass(e, "childclass");
  auto body = std::make_unique<BodySpec>();
  body->src = e.src();
  body->frame = frame;

  // Pose, flags.
  e.Numbers("pos", body->pos);
  e.Quat("quat", body->quat);
  e.Orient(&body->alt);
  e.Bool("mocap", &body->mocap);
  e.Number("gravcomp", &body->gravcomp);
  e.Enum("sleep", &body->sleep,
         {{"auto", kSleepAuto}, {"never", kSleepNever}, {"allowed", kSleepAllowed}, {"init", kSleepInit}});
  e.Vector("user");

  // Contents, with the childclass (if any) as their default.
  BodySpec* raw = body.get();
  parent->bodies.push_back(std::move(body));
  Body(e, raw, nullptr, childclass ? childclass : def);
}

void Reader::Frame(const XmlElement& e, BodySpec* body, const FramePtr& frame,
                   const DefaultClass* def) {
  e.CheckAttributes({"name", "childclass", "pos", "quat", "axisangle", "xyaxes", "zaxis",
                     "euler"});
  const DefaultClass* childclass = FindClass(e, "childclass");
  auto spec = std::make_shared<FrameSpec>();
  spec->src = e.src();
  spec->parent = frame;
  e.Numbers("pos", spec->pos);
  e.Quat("quat", spec->quat);
  e.Orient(&spec->alt);
  Body(e, body, spec, childclass ? childclass : def);
}

void Reader::Inertial(const XmlElement& e, BodySpec* body) {
  e.CheckAttributes({"pos", "quat", "mass", "diaginertia", "axisangle", "xyaxes", "zaxis",
                     "euler", "fullinertia"});
  body->explicit_inertial = true;
  body->inertial_src = e.src();
  if (!e.Has("pos")) e.Fail("missing required attribute 'pos'");
  e.Numbers("pos", body->ipos);
  e.Quat("quat", body->iquat);
  e.RequiredNumber("mass", &body->mass);
  if (body->mass < 0) e.Fail("mass must not be negative");
  e.Numbers("diaginertia", body->inertia);
  Orientation alt;
  e.Orient(&alt);
  bool full = e.Numbers("fullinertia", body->fullinertia) > 0;
  if (full && (alt.kind != OrientKind::kQuat || e.Has("quat"))) {
    e.Fail("fullinertia and inertial orientation cannot both be specified");
  }
  if (full && e.Has("diaginertia")) {
    e.Fail("fullinertia and diaginertia cannot both be specified");
  }
  body->ialt = alt;
}

void Reader::FreeJoint(const XmlElement& e, BodySpec* body, const FramePtr& frame) {
  // A free joint ignores default classes, as in MuJoCo.
  e.CheckAttributes({"name", "group", "align"});
  JointSpec joint;
  joint.src = e.src();
  joint.type = kJointFree;
  joint.frame = frame;
  e.Int("group", &joint.group);
  e.Tri("align", &joint.align);
  body->joints.push_back(std::move(joint));
}

}  // namespace simlab::mjcf
