// MJCF reader: flexes. A <deformable><flex> is read as written; a <flexcomp> in a body
// is expanded here, as MuJoCo's parser expands it (mjCFlexcomp::Make): its shape's
// points, the bodies and slider joints that carry the points that move, the flex, and
// the edge equality it asks for.
#include <string>

#include "compiler/orientation.h"
#include "mjcf/flexcomp.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

namespace {

const std::initializer_list<Keyword> kFlexSelfModes = {
    {"none", kFlexSelfNone}, {"narrow", kFlexSelfNarrow}, {"bvh", kFlexSelfBvh},
    {"sap", kFlexSelfSap},   {"auto", kFlexSelfAuto}};
const std::initializer_list<Keyword> kElastic2DModes = {
    {"none", kElastic2DNone}, {"bend", kElastic2DBend}, {"stretch", kElastic2DStretch},
    {"both", kElastic2DBoth}};
const std::initializer_list<Keyword> kFlexcompTypes = {
    {"grid", kFcompGrid},     {"box", kFcompBox},       {"cylinder", kFcompCylinder},
    {"ellipsoid", kFcompEllipsoid}, {"square", kFcompSquare}, {"disc", kFcompDisc},
    {"circle", kFcompCircle}, {"mesh", kFcompMesh},     {"gmsh", kFcompGmsh},
    {"direct", kFcompDirect}};
const std::initializer_list<Keyword> kFlexcompDofs = {
    {"full", kFcompDofFull}, {"radial", kFcompDofRadial}, {"trilinear", kFcompDofTrilinear},
    {"quadratic", kFcompDofQuadratic}, {"2d", kFcompDof2D}};
const std::initializer_list<Keyword> kFlexEdgeEqualities = {
    {"false", 0}, {"true", 1}, {"vert", 2}, {"strain", 3}};

// <contact> of a flex or flexcomp: how the flex collides.
void ReadFlexContact(const XmlElement& c, FlexSpec* flex) {
  c.CheckAttributes({"contype", "conaffinity", "condim", "priority", "friction", "solmix",
                     "solref", "solimp", "margin", "gap", "internal", "selfcollide",
                     "activelayers", "vertcollide", "passive"});
  c.Int("contype", &flex->contype);
  c.Int("conaffinity", &flex->conaffinity);
  c.Int("condim", &flex->condim);
  c.Int("priority", &flex->priority);
  c.Numbers("friction", flex->friction.data(), 3, false);
  c.Number("solmix", &flex->solmix);
  c.Numbers("solref", flex->solref.data(), kNRef, false);
  c.Numbers("solimp", flex->solimp.data(), kNImp, false);
  c.Number("margin", &flex->margin);
  c.Number("gap", &flex->gap);
  c.Bool("internal", &flex->internal);
  c.Enum("selfcollide", &flex->selfcollide, kFlexSelfModes);
  c.Bool("vertcollide", &flex->vertcollide);
  c.Bool("passive", &flex->passive);
  c.Int("activelayers", &flex->activelayers);
}

// <elasticity> of a flex or flexcomp: its material.
void ReadFlexElasticity(const XmlElement& c, FlexSpec* flex) {
  c.CheckAttributes({"young", "poisson", "damping", "thickness", "elastic2d"});
  c.Number("young", &flex->young);
  c.Number("poisson", &flex->poisson);
  c.Number("damping", &flex->damping);
  c.Number("thickness", &flex->thickness);
  c.Enum("elastic2d", &flex->elastic2d, kElastic2DModes);
}

// The look shared by <flex> and <flexcomp>: dim, radius, group, material, rgba, flatskin.
void ReadFlexLook(const XmlElement& e, FlexSpec* flex) {
  e.Int("dim", &flex->dim);
  e.Number("radius", &flex->radius);
  e.Int("group", &flex->group);
  e.Text("material", &flex->material);
  std::array<double, 4> rgba;
  if (e.Numbers("rgba", rgba)) {
    for (int k = 0; k < 4; k++) flex->rgba[k] = static_cast<float>(rgba[k]);
  }
  e.Bool("flatskin", &flex->flatskin);
}

}  // namespace

// ---------------------------------------------------------------- <flex>

namespace {

// Is this element, as written, one that only MuJoCo 3.12 defines?
bool IsNewerConstruct(pugi::xml_node n) {
  std::string tag = n.name();
  if (tag == "flexstrain") return true;
  if (tag == "flex") return n.attribute("dof") || n.attribute("cellcount");
  if (tag != "flexcomp") return false;
  std::string dof = n.attribute("dof").as_string("full");
  std::string equality = n.child("edge").attribute("equality").as_string("false");
  if (n.attribute("cellcount") || dof == "2d" || equality == "strain") return true;
  std::string elastic2d = n.child("elasticity").attribute("elastic2d").as_string("none");
  return (dof == "trilinear" || dof == "quadratic") && elastic2d != "none";
}

}  // namespace

void Reader::FindNewerConstruct(pugi::xml_node root) {
  for (pugi::xml_node n : root.children()) {
    if (n.type() != pugi::node_element || !spec_->newer_construct.tag.empty()) continue;
    if (IsNewerConstruct(n)) {
      spec_->newer_construct = Element(n).src();
    } else {
      FindNewerConstruct(n);
    }
  }
}

void Reader::ReadFlex(const XmlElement& e, FlexSpec* flex) {
  e.CheckAttributes({"name", "group", "dim", "radius", "material", "rgba", "flatskin", "body",
                     "vertex", "element", "texcoord", "elemtexcoord", "node", "dof", "cellcount"});
  flex->src = e.src();
  ReadFlexLook(e, flex);
  if (!e.Has("body")) e.Fail("missing required attribute 'body'");
  if (!e.Has("element")) e.Fail("missing required attribute 'element'");
  flex->vertbody = e.Tokens("body");
  flex->nodebody = e.Tokens("node");
  flex->vert = ReadList(e, "vertex", ParseDouble);
  flex->elem = ReadList(e, "element", ParseInt);
  flex->texcoord = ReadList(e, "texcoord", ParseFloat);
  flex->elemtexcoord = ReadList(e, "elemtexcoord", ParseInt);
  // (MuJoCo 3.12: the nodes' interpolation order, and the cells of their lattice)
  int dof = kFcompDofFull;
  if (e.Enum("dof", &dof, kFlexcompDofs)) {
    flex->order = dof == kFcompDofTrilinear ? 1 : dof == kFcompDofQuadratic ? 2 : 0;
  }
  e.Ints("cellcount", flex->cellcount.data(), 3);

  // Children: contact, edge (stiffness and damping only), elasticity.
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() == "contact") {
      ReadFlexContact(c, flex);
    } else if (c.tag() == "edge") {
      c.CheckAttributes({"stiffness", "damping"});
      c.Number("stiffness", &flex->edgestiffness);
      c.Number("damping", &flex->edgedamping);
    } else if (c.tag() == "elasticity") {
      ReadFlexElasticity(c, flex);
    } else {
      Unknown(c);
    }
  }
}

// ---------------------------------------------------------------- <flexcomp>

void Reader::Flexcomp(const XmlElement& e, BodySpec* body, const DefaultClass* def) {
  e.CheckAttributes({"name", "type", "group", "dim", "dof", "count", "cellcount", "spacing", "radius",
                     "rigid", "mass", "inertiabox", "scale", "file", "point", "element",
                     "texcoord", "material", "rgba", "flatskin", "pos", "quat", "axisangle",
                     "xyaxes", "zaxis", "euler", "origin"});
  FlexcompSpec fc;
  fc.src = e.src();
  e.RequiredText("name", &fc.name);
  e.Enum("type", &fc.type, kFlexcompTypes);
  e.Ints("count", fc.count.data(), 3);
  e.Ints("cellcount", fc.cellcount.data(), 3);
  e.Numbers("spacing", fc.spacing);
  e.Numbers("scale", fc.scale);
  e.Number("mass", &fc.mass);
  e.Number("inertiabox", &fc.inertiabox);
  std::string file;
  if (e.Text("file", &file)) fc.file = AssetPath(file, spec_->compiler.meshdir, e);
  ReadFlexLook(e, &fc.flex);
  if (!e.Numbers("origin", fc.origin) && fc.type == kFcompMesh && fc.flex.dim == 3) {
    e.Fail("origin must be specified for mesh flexcomps if dim=3");
  }
  e.Numbers("pos", fc.pos);
  e.Quat("quat", fc.quat);
  Orientation alt;
  e.Orient(&alt);
  e.Bool("rigid", &fc.rigid);
  fc.shape.point = ReadList(e, "point", ParseDouble);
  fc.shape.element = ReadList(e, "element", ParseInt);
  fc.shape.texcoord = ReadList(e, "texcoord", ParseFloat);
  e.Enum("dof", &fc.dof, kFlexcompDofs);
  FlexcompChildren(e, &fc);

  // The pose of the points.
  const char* error = compiler::ResolveOrientation(fc.quat.data(), spec_->compiler.degree,
                                                   spec_->compiler.eulerseq, alt);
  if (error) e.Fail(error);
  MakeFlexcomp(e, &fc, body, def);
}

// <edge>, <elasticity>, <contact>, <pin> of a flexcomp.
void Reader::FlexcompChildren(const XmlElement& e, FlexcompSpec* fc) {
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    if (c.tag() == "edge") {
      c.CheckAttributes({"equality", "solref", "solimp", "stiffness", "damping"});
      c.Enum("equality", &fc->equality, kFlexEdgeEqualities);
      c.Numbers("solref", fc->eq.solref.data(), kNRef, false);
      c.Numbers("solimp", fc->eq.solimp.data(), kNImp, false);
      c.Number("stiffness", &fc->flex.edgestiffness);
      c.Number("damping", &fc->flex.edgedamping);
    } else if (c.tag() == "elasticity") {
      ReadFlexElasticity(c, &fc->flex);
    } else if (c.tag() == "contact") {
      ReadFlexContact(c, &fc->flex);
    } else if (c.tag() == "pin") {
      c.CheckAttributes({"id", "range", "grid", "gridrange"});
      auto append = [&](const char* attr, std::vector<int>* to) {
        std::vector<int> v = ReadList(c, attr, ParseInt);
        to->insert(to->end(), v.begin(), v.end());
      };
      append("id", &fc->pinid);
      append("range", &fc->pinrange);
      append("grid", &fc->pingrid);
      append("gridrange", &fc->pingridrange);
    } else if (c.tag() == "plugin") {
      NotSupported(c, "a flexcomp's <plugin>");
    } else {
      Unknown(c);
    }
  }
  // An equality and elasticity together: MuJoCo 3.5.1 refuses stretching elasticity with
  // any equality; 3.12 (a model that follows it) refuses a Young's modulus unless the
  // elasticity only bends, and keeps strain (the stiff modes of an interpolated flex's
  // elements) to interpolated flexcomps.
  if (spec_->newer_construct.tag.empty()) {
    if (fc->flex.elastic2d >= 2 && fc->equality) {
      e.Fail("elasticity and edge constraints cannot both be present");
    }
    return;
  }
  if (fc->equality && fc->flex.elastic2d != kElastic2DBend && fc->flex.young > 0) {
    e.Fail("flex constraints and elasticity (young) cannot both be present");
  }
  if (fc->equality == 3 && fc->dof != kFcompDofTrilinear && fc->dof != kFcompDofQuadratic) {
    e.Fail("strain equality needs an interpolated flexcomp (dof trilinear or quadratic)");
  }
}

}  // namespace simlab::mjcf
