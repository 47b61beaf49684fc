// MJCF reader: the sections outside the body tree (compiler, option, visual, asset,
// contact, tendon, actuator, keyframe), cameras, and lights, which are accepted and
// ignored because they do not change the simulation.
#include <cstdint>
#include <string>

#include "mjcf/error.h"
#include "mjcf/limits.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

// ---------------------------------------------------------------- compiler

void Reader::Compiler(const XmlElement& e) {
  e.CheckAttributes({"autolimits", "boundmass", "boundinertia", "settotalmass",
                     "balanceinertia", "strippath", "coordinate", "angle", "fitaabb",
                     "eulerseq", "meshdir", "texturedir", "discardvisual", "usethread",
                     "fusestatic", "inertiafromgeom", "inertiagrouprange", "saveinertial",
                     "assetdir", "alignfree"});
  CompilerSpec& c = spec_->compiler;
  bool flag = false;
  e.Bool("autolimits", &c.autolimits);
  e.Number("boundmass", &c.boundmass);
  e.Number("boundinertia", &c.boundinertia);
  e.Number("settotalmass", &c.settotalmass);
  e.Bool("balanceinertia", &c.balanceinertia);
  e.Bool("strippath", &c.strippath);
  e.Text("meshdir", &c.meshdir);
  e.Text("texturedir", &c.texturedir);
  e.Text("assetdir", &c.assetdir);
  e.Bool("fitaabb", &c.fitaabb);
  int global = 0;
  if (e.Enum("coordinate", &global, {{"local", 0}, {"global", 1}}) && global) {
    e.Fail("global coordinates are no longer supported (as in MuJoCo)");
  }
  int degree = 1;
  if (e.Enum("angle", &degree, {{"radian", 0}, {"degree", 1}})) c.degree = (degree == 1);
  if (e.Text("eulerseq", &c.eulerseq)) {
    if (c.eulerseq.size() != 3) e.Fail("eulerseq must have 3 characters");
    for (char ch : c.eulerseq) {
      if (std::string("xyzXYZ").find(ch) == std::string::npos) {
        e.Fail("eulerseq can only contain x, y, z, X, Y, Z");
      }
    }
  }
  e.Bool("discardvisual", &flag);
  e.Bool("usethread", &flag);
  e.Bool("fusestatic", &c.fusestatic);
  e.Tri("inertiafromgeom", &c.inertiafromgeom);
  e.Ints("inertiagrouprange", c.inertiagrouprange.data(), 2);
  e.Bool("saveinertial", &flag);
  e.Bool("alignfree", &c.alignfree);

  // <lengthrange>: options of the actuator lengthrange computation.
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c2 = Element(n);
    if (c2.tag() != "lengthrange") Unknown(c2);
    c2.CheckAttributes({"mode", "useexisting", "uselimit", "accel", "maxforce", "timeconst",
                        "timestep", "inttotal", "interval", "tolrange"});
    LengthRangeSpec& lr = c.lengthrange;
    c2.Enum("mode", &lr.mode, {{"none", 0}, {"muscle", 1}, {"muscleuser", 2}, {"all", 3}});
    c2.Bool("useexisting", &lr.useexisting);
    c2.Bool("uselimit", &lr.uselimit);
    c2.Number("accel", &lr.accel);
    c2.Number("maxforce", &lr.maxforce);
    c2.Number("timeconst", &lr.timeconst);
    c2.Number("timestep", &lr.timestep);
    c2.Number("inttotal", &lr.inttotal);
    c2.Number("interval", &lr.interval);
    c2.Number("tolrange", &lr.tolrange);
  }
}

// ---------------------------------------------------------------- option

void Reader::Option(const XmlElement& e) {
  e.CheckAttributes({"timestep", "impratio", "tolerance", "ls_tolerance", "noslip_tolerance",
                     "ccd_tolerance", "sleep_tolerance", "gravity", "wind", "magnetic",
                     "density", "viscosity", "o_margin", "o_solref", "o_solimp", "o_friction",
                     "integrator", "cone", "jacobian", "solver", "iterations", "ls_iterations",
                     "noslip_iterations", "ccd_iterations", "sdf_iterations",
                     "sdf_initpoints", "actuatorgroupdisable"});
  simlab::Option& o = spec_->option;
  e.Number("timestep", &o.timestep);
  e.Number("impratio", &o.impratio);
  e.Number("tolerance", &o.tolerance);
  e.Number("ls_tolerance", &o.ls_tolerance);
  e.Number("noslip_tolerance", &o.noslip_tolerance);
  e.Number("ccd_tolerance", &o.ccd_tolerance);
  e.Number("sleep_tolerance", &o.sleep_tolerance);
  e.Numbers("gravity", o.gravity);
  e.Numbers("wind", o.wind);
  e.Numbers("magnetic", o.magnetic);
  e.Number("density", &o.density);
  e.Number("viscosity", &o.viscosity);
  e.Number("o_margin", &o.o_margin);
  e.Numbers("o_solref", o.o_solref, false);
  e.Numbers("o_solimp", o.o_solimp, false);
  e.Numbers("o_friction", o.o_friction, false);
  e.Enum("integrator", &o.integrator,
         {{"Euler", kIntegratorEuler}, {"RK4", kIntegratorRK4}, {"implicit", kIntegratorImplicit},
          {"implicitfast", kIntegratorImplicitFast}});
  e.Enum("cone", &o.cone, {{"pyramidal", kConePyramidal}, {"elliptic", kConeElliptic}});
  e.Enum("jacobian", &o.jacobian,
         {{"dense", kJacobianDense}, {"sparse", kJacobianSparse}, {"auto", kJacobianAuto}});
  e.Enum("solver", &o.solver, {{"PGS", kSolverPGS}, {"CG", kSolverCG}, {"Newton", kSolverNewton}});
  e.Int("iterations", &o.iterations);
  e.Int("ls_iterations", &o.ls_iterations);
  e.Int("noslip_iterations", &o.noslip_iterations);
  e.Int("ccd_iterations", &o.ccd_iterations);
  e.Int("sdf_iterations", &o.sdf_iterations);
  e.Int("sdf_initpoints", &o.sdf_initpoints);

  // Disabled actuator groups become bits.
  int groups[31];
  int ngroup = e.Ints("actuatorgroupdisable", groups, 31, false);
  for (int i = 0; i < ngroup; i++) {
    if (groups[i] < 0 || groups[i] > 30) e.Fail("actuatorgroupdisable values must be in 0..30");
    o.disableactuator |= (1 << groups[i]);
  }

  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() != "flag") Unknown(c);
    Flags(c);
  }
}

void Reader::Flags(const XmlElement& e) {
  struct Flag {
    const char* name;
    int bit;
    bool enable;  // an enable bit (else a disable bit)
  };
  static const Flag kFlags[] = {
      {"constraint", kDisableConstraint, false}, {"equality", kDisableEquality, false},
      {"frictionloss", kDisableFrictionloss, false}, {"limit", kDisableLimit, false},
      {"contact", kDisableContact, false},       {"spring", kDisableSpring, false},
      {"damper", kDisableDamper, false},         {"gravity", kDisableGravity, false},
      {"clampctrl", kDisableClampctrl, false},   {"warmstart", kDisableWarmstart, false},
      {"filterparent", kDisableFilterparent, false}, {"actuation", kDisableActuation, false},
      {"refsafe", kDisableRefsafe, false},       {"sensor", kDisableSensor, false},
      {"midphase", kDisableMidphase, false},     {"eulerdamp", kDisableEulerdamp, false},
      {"autoreset", kDisableAutoreset, false},   {"nativeccd", kDisableNativeccd, false},
      {"island", kDisableIsland, false},         {"override", kEnableOverride, true},
      {"energy", kEnableEnergy, true},           {"fwdinv", kEnableFwdinv, true},
      {"invdiscrete", kEnableInvdiscrete, true}, {"multiccd", kEnableMulticcd, true},
      {"sleep", kEnableSleep, true}};
  std::vector<const char*> names;
  for (const Flag& f : kFlags) names.push_back(f.name);
  e.CheckAttributes(names);

  // "enable" sets an enable bit or clears a disable bit; "disable" the opposite.
  simlab::Option& o = spec_->option;
  for (const Flag& f : kFlags) {
    int on = 0;
    if (!e.Enum(f.name, &on, {{"disable", 0}, {"enable", 1}})) continue;
    int& bits = f.enable ? o.enableflags : o.disableflags;
    bits &= ~f.bit;
    if (on == (f.enable ? 1 : 0)) bits |= f.bit;
  }
}

// ---------------------------------------------------------------- size, visual, statistic

void Reader::Size(const XmlElement& e) {
  e.CheckAttributes({"memory", "njmax", "nconmax", "nstack", "nuserdata", "nkey",
                     "nuser_body", "nuser_jnt", "nuser_geom", "nuser_site", "nuser_cam",
                     "nuser_tendon", "nuser_actuator", "nuser_sensor"});
  int value = 0;
  for (const char* name : {"njmax", "nconmax", "nstack", "nuserdata", "nuser_body",
                           "nuser_jnt", "nuser_geom", "nuser_site", "nuser_cam",
                           "nuser_tendon", "nuser_actuator"}) {
    e.Int(name, &value);
  }
  if (e.Int("nuser_sensor", &spec_->nuser_sensor) && spec_->nuser_sensor < -1) {
    e.Fail("nuser_sensor must be -1 (automatic) or more");
  }
  spec_->size_src = e.src();

  // Keyframes: the reader makes nkey of them (blank ones up to nkey), so their number
  // is held to the budget before any is made.
  if (e.Int("nkey", &spec_->nkey) && spec_->nkey < 0) e.Fail("nkey cannot be negative");
  uint64_t bytes = MulBytes(static_cast<uint64_t>(spec_->nkey), sizeof(KeySpec));
  if (bytes > kMaxArrayBytes) {
    e.Fail(OverBudget(AttrText("nkey", std::to_string(spec_->nkey)), bytes, "keyframes",
                      kMaxArrayBytes));
  }
}

void Reader::Visual(const XmlElement& e) {
  e.CheckAttributes({});
  struct Child {
    const char* tag;
    std::vector<const char*> attrs;
  };
  static const Child kChildren[] = {
      {"global", {"cameraid", "orthographic", "fovy", "ipd", "azimuth", "elevation",
                  "linewidth", "glow", "offwidth", "offheight", "realtime",
                  "ellipsoidinertia", "bvactive"}},
      {"quality", {"shadowsize", "offsamples", "numslices", "numstacks", "numquads"}},
      {"headlight", {"ambient", "diffuse", "specular", "active"}},
      {"map", {"stiffness", "stiffnessrot", "force", "torque", "alpha", "fogstart", "fogend",
               "znear", "zfar", "haze", "shadowclip", "shadowscale", "actuatortendon"}},
      {"scale", {"forcewidth", "contactwidth", "contactheight", "connect", "com", "camera",
                 "light", "selectpoint", "jointlength", "jointwidth", "actuatorlength",
                 "actuatorwidth", "framelength", "framewidth", "constraint", "slidercrank",
                 "frustum"}},
      {"rgba", {"fog", "haze", "force", "inertia", "joint", "actuator", "actuatornegative",
                "actuatorpositive", "com", "camera", "light", "selectpoint", "connect",
                "contactpoint", "contactforce", "contactfriction", "contacttorque",
                "contactgap", "rangefinder", "constraint", "slidercrank", "crankbroken",
                "frustum", "bv", "bvactive"}}};
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    const Child* match = nullptr;
    for (const Child& k : kChildren) {
      if (c.tag() == k.tag) match = &k;
    }
    if (!match) Unknown(c);
    c.CheckAttributes(match->attrs);
    // The near clipping plane is the default focal length of cameras; the free camera
    // and the perturbation springs are kept for viewers.
    if (c.tag() == "map") {
      c.Number("znear", &spec_->znear);
      c.Number("znear", &spec_->vis.map.znear);
      c.Number("zfar", &spec_->vis.map.zfar);
      c.Number("stiffness", &spec_->vis.map.stiffness);
      c.Number("stiffnessrot", &spec_->vis.map.stiffnessrot);
    }
    if (c.tag() == "global") {
      c.Number("fovy", &spec_->vis.global.fovy);
      c.Number("azimuth", &spec_->vis.global.azimuth);
      c.Number("elevation", &spec_->vis.global.elevation);
    }
    if (c.tag() == "headlight") {
      Visual::Headlight& h = spec_->vis.headlight;
      c.Numbers("ambient", h.ambient);
      c.Numbers("diffuse", h.diffuse);
      c.Numbers("specular", h.specular);
      c.Int("active", &h.active);
    }
    if (c.tag() == "rgba") c.Numbers("haze", spec_->vis.rgba.haze);
  }
}

void Reader::Statistic(const XmlElement& e) {
  e.CheckAttributes({"meaninertia", "meanmass", "meansize", "extent", "center"});
  double v = 0;
  if (e.Number("meaninertia", &v)) spec_->meaninertia = v;
  if (e.Number("meanmass", &v)) spec_->meanmass = v;
  if (e.Number("meansize", &v)) spec_->meansize = v;
  if (e.Number("extent", &v)) {
    if (v <= 0) e.Fail("extent must be strictly positive");
    spec_->extent = v;
  }
  e.Numbers("center", spec_->center);
}

// ---------------------------------------------------------------- custom, asset, contact

void Reader::Custom(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() == "numeric") {
      c.CheckAttributes({"name", "size", "data"});
      c.Vector("data");
    } else if (c.tag() == "text") {
      c.CheckAttributes({"name", "data"});
    } else if (c.tag() == "tuple") {
      c.CheckAttributes({"name"});
      for (pugi::xml_node t : n.children()) {
        if (t.type() != pugi::node_element) continue;
        XmlElement te = Element(t);
        if (te.tag() != "element") Unknown(te);
        te.CheckAttributes({"objtype", "objname", "prm"});
      }
    } else {
      Unknown(c);
    }
  }
}

void Reader::Asset(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() == "texture") {
      spec_->textures.emplace_back();
      ReadTexture(c, &spec_->textures.back());
    } else if (c.tag() == "material") {
      const DefaultClass* cls = FindClass(c, "class");
      MaterialSpec mat = cls ? cls->material : classes_.at("main")->material;
      ReadMaterial(c, &mat, false);
      spec_->materials.push_back(std::move(mat));
    } else if (c.tag() == "model") {
      AssetModel(c);
    } else if (c.tag() == "mesh") {
      const DefaultClass* cls = FindClass(c, "class");
      MeshSpec mesh = cls ? cls->mesh : classes_.at("main")->mesh;
      ReadMesh(c, &mesh, false);
      ChildPlugin(c, &mesh.plugin);
      spec_->meshes.push_back(std::move(mesh));
    } else if (c.tag() == "hfield") {
      spec_->hfields.emplace_back();
      ReadHField(c, &spec_->hfields.back());
    } else if (c.tag() == "skin") {
      ReadSkin(c, &spec_->skins.emplace_back());
    } else {
      Unknown(c);
    }
  }
}

void Reader::Deformable(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() == "skin") {
      ReadSkin(c, &spec_->skins.emplace_back());
    } else if (c.tag() == "flex") {
      ReadFlex(c, &spec_->flexes.emplace_back());
    } else {
      Unknown(c);
    }
  }
}

void Reader::Contact(const XmlElement& e) {
  // Explicit geom pairs (with class defaults) and excluded body pairs.
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() == "pair") {
      const DefaultClass* cls = FindClass(c, "class");
      PairSpec pair = cls ? cls->pair : classes_.at("main")->pair;
      ReadPair(c, &pair, false);
      spec_->pairs.push_back(std::move(pair));
    } else if (c.tag() == "exclude") {
      c.CheckAttributes({"name", "body1", "body2"});
      ExcludeSpec ex;
      ex.src = c.src();
      c.RequiredText("body1", &ex.body1);
      c.RequiredText("body2", &ex.body2);
      spec_->excludes.push_back(std::move(ex));
    } else {
      Unknown(c);
    }
  }
}

// One <pair>, or the pair defaults of a class.
void Reader::ReadPair(const XmlElement& e, PairSpec* pair, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"condim", "friction", "solref", "solreffriction", "solimp", "gap",
                       "margin"});
  } else {
    e.CheckAttributes({"name", "class", "geom1", "geom2", "condim", "friction", "solref",
                       "solreffriction", "solimp", "gap", "margin"});
    pair->src = e.src();
    e.RequiredText("geom1", &pair->geom1);
    e.RequiredText("geom2", &pair->geom2);
  }
  e.Int("condim", &pair->condim);
  e.Numbers("friction", pair->friction, false);
  e.Numbers("solref", pair->solref, false);
  e.Numbers("solreffriction", pair->solreffriction, false);
  e.Numbers("solimp", pair->solimp, false);
  e.Number("margin", &pair->margin);
  e.Number("gap", &pair->gap);
}

// ---------------------------------------------------------------- tendon, actuator, keyframe

void Reader::Tendon(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() != "fixed" && c.tag() != "spatial") Unknown(c);
    const DefaultClass* cls = FindClass(c, "class");
    TendonSpec tendon = cls ? cls->tendon : classes_.at("main")->tendon;
    tendon.spatial = c.tag() == "spatial";
    ReadTendon(c, &tendon, false);

    // The path, in order.
    for (pugi::xml_node w : n.children()) {
      if (w.type() != pugi::node_element) continue;
      tendon.wraps.push_back(ReadWrap(Element(w), tendon.spatial));
    }
    spec_->tendons.push_back(std::move(tendon));
  }
}

// One path element: <joint> in a fixed tendon; <site>, <geom>, <pulley> in a spatial one.
WrapSpec Reader::ReadWrap(const XmlElement& we, bool spatial) const {
  // Per element: where it may appear, its type, and its target, number and side-site
  // attributes (null where it has none).
  struct WrapKind {
    const char* tag;
    bool spatial;
    int type;
    const char* target;
    const char* number;
    const char* side;
  };
  static const WrapKind kKinds[] = {{"joint", false, kWrapJoint, "joint", "coef", nullptr},
                                    {"site", true, kWrapSite, "site", nullptr, nullptr},
                                    {"geom", true, kWrapSphere, "geom", nullptr, "sidesite"},
                                    {"pulley", true, kWrapPulley, nullptr, "divisor", nullptr}};
  for (const WrapKind& k : kKinds) {
    if (we.tag() != k.tag || spatial != k.spatial) continue;
    std::vector<const char*> allowed;
    for (const char* attr : {k.target, k.number, k.side}) {
      if (attr) allowed.push_back(attr);
    }
    we.CheckAttributes(allowed);
    WrapSpec wrap;
    wrap.src = we.src();
    wrap.type = k.type;
    if (k.target) we.RequiredText(k.target, &wrap.target);
    if (k.number) we.RequiredNumber(k.number, &wrap.prm);
    if (k.side) we.Text(k.side, &wrap.sidesite);
    return wrap;
  }
  Unknown(we);
}

void Reader::Actuator(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    const std::string& tag = c.tag();
    if (!IsActuatorElement(tag) && tag != "plugin") Unknown(c);
    const DefaultClass* cls = FindClass(c, "class");
    ActuatorSpec act = cls ? cls->actuator : classes_.at("main")->actuator;
    if (tag == "plugin") {
      ReadPluginActuator(c, &act);
    } else {
      ReadActuator(c, &act, false);
    }
    spec_->actuators.push_back(std::move(act));
  }
}

void Reader::Keyframe(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() != "key") Unknown(c);
    c.CheckAttributes({"name", "time", "qpos", "qvel", "act", "mpos", "mquat", "ctrl"});
    KeySpec key;
    key.src = c.src();
    c.Number("time", &key.time);
    auto read = [&](const char* name, std::vector<double>* out) {
      if (auto v = c.Vector(name)) *out = *v;
    };
    read("qpos", &key.qpos);
    read("qvel", &key.qvel);
    read("act", &key.act);
    read("mpos", &key.mpos);
    read("mquat", &key.mquat);
    read("ctrl", &key.ctrl);
    spec_->keys.push_back(std::move(key));
  }
}

// ---------------------------------------------------------------- cameras and lights

const std::initializer_list<Keyword> kCamLightModes = {
    {"fixed", 0}, {"track", 1}, {"trackcom", 2}, {"targetbody", 3}, {"targetbodycom", 4}};

namespace {

const std::initializer_list<Keyword> kProjections = {{"perspective", 0}, {"orthographic", 1}};
const std::initializer_list<Keyword> kCameraOutputs = {
    {"rgb", 1}, {"depth", 2}, {"distance", 4}, {"normal", 8}, {"segmentation", 16}};

// The output attribute: a list of flags, or-ed together.
void ReadCameraOutput(const XmlElement& e, int* output) {
  std::vector<std::string> tokens = e.Tokens("output");
  if (tokens.empty()) return;
  *output = 0;
  for (const std::string& t : tokens) {
    int bit = -1;
    for (const Keyword& k : kCameraOutputs) {
      if (t == k.first) bit = k.second;
    }
    if (bit < 0) e.Fail("unknown camera output '" + t + "'");
    *output |= bit;
  }
}

}  // namespace

void Reader::ReadCamera(const XmlElement& e, CameraSpec* cam, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"projection", "fovy", "ipd", "resolution", "output", "pos", "quat",
                       "axisangle", "xyaxes", "zaxis", "euler", "mode", "focal", "focalpixel",
                       "principal", "principalpixel", "sensorsize", "user"});
  } else {
    e.CheckAttributes({"name", "class", "projection", "fovy", "ipd", "resolution", "output",
                       "pos", "quat", "axisangle", "xyaxes", "zaxis", "euler", "mode",
                       "target", "focal", "focalpixel", "principal", "principalpixel",
                       "sensorsize", "user"});
    cam->src = e.src();
    e.Text("target", &cam->target);
  }
  e.Enum("mode", &cam->mode, kCamLightModes);
  e.Numbers("pos", cam->pos);
  e.Quat("quat", cam->quat);
  e.Orient(&cam->alt);
  e.Number("ipd", &cam->ipd);
  e.Enum("projection", &cam->projection, kProjections);
  e.Numbers("principalpixel", cam->principalpixel);
  e.Numbers("principal", cam->principal);
  e.Numbers("focalpixel", cam->focalpixel);
  e.Numbers("focal", cam->focal);
  e.Ints("resolution", cam->resolution.data(), 2);
  ReadCameraOutput(e, &cam->output);
  // The field of view comes from fovy or from the sensor size, not both.
  bool sensorsize = e.Numbers("sensorsize", cam->sensorsize) > 0;
  bool fovy = e.Number("fovy", &cam->fovy);
  if (fovy && sensorsize) e.Fail("either 'fovy' or 'sensorsize' can be given, not both");
  e.Vector("user");
}


}  // namespace simlab::mjcf
