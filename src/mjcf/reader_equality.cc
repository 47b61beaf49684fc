// MJCF reader: the <equality> section (connect, weld, joint, tendon and flex constraints;
// a flexstrain keeps the cell it holds in data[0-2]) and the <equality> element of
// default classes, which sets active, solref and solimp.
//
// Connect and weld name their objects in one of two ways: a body (with an anchor, and
// optionally a second body, which is the world otherwise) or two sites. The reader
// decides which, records it in `objtype`, and leaves the lookups to the compiler.
#include <string>

#include "mjcf/error.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

namespace {

const std::initializer_list<Keyword> kEqualityTypes = {
    {"connect", kEqConnect}, {"weld", kEqWeld},   {"joint", kEqJoint},
    {"tendon", kEqTendon},   {"flex", kEqFlex},   {"flexvert", kEqFlexVert},
    {"flexstrain", kEqFlexStrain}};

// The attributes every equality element accepts, and those of each kind.
std::vector<const char*> EqualityAttributes(int type) {
  std::vector<const char*> attrs = {"name", "class", "active", "solref", "solimp"};
  std::vector<const char*> own;
  switch (type) {
    case kEqConnect: own = {"body1", "body2", "anchor", "site1", "site2"}; break;
    case kEqWeld: own = {"body1", "body2", "relpose", "anchor", "site1", "site2", "torquescale"}; break;
    case kEqJoint: own = {"joint1", "joint2", "polycoef"}; break;
    case kEqFlex:
    case kEqFlexVert: own = {"flex"}; break;
    case kEqFlexStrain: own = {"flex", "cell"}; break;
    default: own = {"tendon1", "tendon2", "polycoef"}; break;
  }
  attrs.insert(attrs.end(), own.begin(), own.end());
  return attrs;
}

// Connect or weld: body semantics (body1, optional body2, anchor, relpose) or site
// semantics (site1 and site2), never both.
void ReadBodyOrSites(const XmlElement& e, EqualitySpec* eq) {
  bool weld = eq->type == kEqWeld;
  bool has_anchor = e.Numbers("anchor", eq->data.data(), 3) > 0;
  bool has_relpose = weld && e.Numbers("relpose", eq->data.data() + 3, 7) > 0;
  bool any_site = e.Has("site1") || e.Has("site2");
  bool any_body = e.Has("body1") || e.Has("body2") || has_anchor || has_relpose;
  if (any_site && any_body) e.Fail("body and site attributes cannot be mixed");

  // Which form: both sites, or body1 (with an anchor, for connect).
  bool by_sites = e.Has("site1") && e.Has("site2");
  bool by_body = e.Has("body1") && (weld || has_anchor);
  if (by_sites == by_body) {
    e.Fail(weld ? "a weld needs body1 (optionally body2, anchor, relpose), or site1 and site2"
                : "a connect needs body1 and anchor (optionally body2), or site1 and site2");
  }
  if (by_body) {
    eq->objtype = kObjBody;
    e.Text("body1", &eq->name1);
    e.Text("body2", &eq->name2);
    // A weld without anchor welds at body2's origin.
    if (weld && !has_anchor) eq->data[0] = eq->data[1] = eq->data[2] = 0;
  } else {
    eq->objtype = kObjSite;
    e.Text("site1", &eq->name1);
    e.Text("site2", &eq->name2);
  }
  if (weld) e.Number("torquescale", &eq->data[10]);
}

// Joint or tendon: the first object is required, the second optional; polycoef fills
// as many of the 5 coefficients as are written.
void ReadCoupling(const XmlElement& e, EqualitySpec* eq) {
  bool joint = eq->type == kEqJoint;
  e.RequiredText(joint ? "joint1" : "tendon1", &eq->name1);
  e.Text(joint ? "joint2" : "tendon2", &eq->name2);
  e.Numbers("polycoef", eq->data.data(), 5, false);
}

}  // namespace

// ---------------------------------------------------------------- the section

void Reader::Equality(const XmlElement& e) {
  e.CheckAttributes({});
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement c = Element(n);
    const std::string& tag = c.tag();
    if (tag == "distance") c.Fail("distance equality constraints were removed in MuJoCo 2.2.2");
    int type = -1;
    for (const Keyword& k : kEqualityTypes) {
      if (tag == k.first) type = k.second;
    }
    if (type < 0) Unknown(c);

    // Class defaults first, then the element's own attributes.
    const DefaultClass* cls = FindClass(c, "class");
    EqualitySpec eq = cls ? cls->equality : classes_.at("main")->equality;
    eq.type = type;
    ReadEquality(c, &eq, false);
    spec_->equalities.push_back(std::move(eq));
  }
}

// ---------------------------------------------------------------- one element

void Reader::ReadEquality(const XmlElement& e, EqualitySpec* eq, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"active", "solref", "solimp"});
  } else {
    e.CheckAttributes(EqualityAttributes(eq->type));
    eq->src = e.src();
    if (eq->type == kEqConnect || eq->type == kEqWeld) {
      ReadBodyOrSites(e, eq);
    } else if (eq->type == kEqFlex || eq->type == kEqFlexVert) {
      e.RequiredText("flex", &eq->name1);
    } else if (eq->type == kEqFlexStrain) {
      // (the compiler checks the cell against the flex's cells; MuJoCo reads past them
      // when cell is left out)
      e.RequiredText("flex", &eq->name1);
      if (e.Numbers("cell", eq->data.data(), 3) == 0) {
        e.Fail("missing cell: the cell's x, y, z indices (or 'f -1 -1' for face f of a shell)");
      }
    } else {
      ReadCoupling(e, eq);
    }
  }
  e.Bool("active", &eq->active);
  e.Numbers("solref", eq->solref, false);
  e.Numbers("solimp", eq->solimp, false);
}

}  // namespace simlab::mjcf
