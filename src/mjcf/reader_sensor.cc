// MJCF reader: the <sensor> section. Each element names a sensor type and the object
// it is attached to (by an attribute such as site= or joint=, or by objtype/objname);
// the compiler resolves the names and sizes the output.
#include <string>
#include <tuple>
#include <vector>

#include "mjcf/reader.h"
#include "simlab/simlab.h"

namespace simlab::mjcf {

namespace {

// How a sensor element names its object.
enum class Target {
  kSite,       // site="..."
  kJoint,      // joint="..."
  kTendon,     // tendon="..."
  kActuator,   // actuator="..."
  kBody,       // body="..." (subtree sensors)
  kFrame,      // objtype/objname, optional reftype/refname
  kFrameAcc,   // objtype/objname only
  kNone,       // global sensors
  kSpecial     // read by its own function
};

// A sensor type (its element tag is SensorTypeName(type)) and how it names its object.
struct SensorKind {
  int type;
  Target target;
};

constexpr SensorKind kKinds[] = {
    {kSensTouch, Target::kSite},
    {kSensAccelerometer, Target::kSite},
    {kSensVelocimeter, Target::kSite},
    {kSensGyro, Target::kSite},
    {kSensForce, Target::kSite},
    {kSensTorque, Target::kSite},
    {kSensMagnetometer, Target::kSite},
    {kSensCamProjection, Target::kSpecial},
    {kSensRangefinder, Target::kSpecial},
    {kSensJointPos, Target::kJoint},
    {kSensJointVel, Target::kJoint},
    {kSensTendonPos, Target::kTendon},
    {kSensTendonVel, Target::kTendon},
    {kSensActuatorPos, Target::kActuator},
    {kSensActuatorVel, Target::kActuator},
    {kSensActuatorFrc, Target::kActuator},
    {kSensJointActFrc, Target::kJoint},
    {kSensTendonActFrc, Target::kTendon},
    {kSensBallQuat, Target::kJoint},
    {kSensBallAngVel, Target::kJoint},
    {kSensJointLimitPos, Target::kJoint},
    {kSensJointLimitVel, Target::kJoint},
    {kSensJointLimitFrc, Target::kJoint},
    {kSensTendonLimitPos, Target::kTendon},
    {kSensTendonLimitVel, Target::kTendon},
    {kSensTendonLimitFrc, Target::kTendon},
    {kSensFramePos, Target::kFrame},
    {kSensFrameQuat, Target::kFrame},
    {kSensFrameXAxis, Target::kFrame},
    {kSensFrameYAxis, Target::kFrame},
    {kSensFrameZAxis, Target::kFrame},
    {kSensFrameLinVel, Target::kFrame},
    {kSensFrameAngVel, Target::kFrame},
    {kSensFrameLinAcc, Target::kFrameAcc},
    {kSensFrameAngAcc, Target::kFrameAcc},
    {kSensSubtreeCom, Target::kBody},
    {kSensSubtreeLinVel, Target::kBody},
    {kSensSubtreeAngMom, Target::kBody},
    {kSensInsideSite, Target::kSpecial},
    {kSensGeomDist, Target::kSpecial},
    {kSensGeomNormal, Target::kSpecial},
    {kSensGeomFromTo, Target::kSpecial},
    {kSensContact, Target::kSpecial},
    {kSensEPotential, Target::kNone},
    {kSensEKinetic, Target::kNone},
    {kSensClock, Target::kNone},
    {kSensTactile, Target::kSpecial},
    {kSensUser, Target::kSpecial},
};

// The attributes every sensor but user, tactile and plugin accepts.
const std::vector<const char*> kCommon = {"name", "nsample", "interp", "delay", "interval",
                                          "cutoff", "noise", "user"};

// Object type keywords (MuJoCo's mju_str2Type); anything else is unknown.
int ObjTypeFromName(const std::string& s) {
  for (int type = kObjBody; type <= kObjPlugin; type++) {
    if (s == ObjTypeName(type)) return type;
  }
  return kObjUnknown;
}

// Allowed attributes: the common ones plus the given extras.
std::vector<const char*> With(std::initializer_list<const char*> extra) {
  std::vector<const char*> all = kCommon;
  all.insert(all.end(), extra.begin(), extra.end());
  return all;
}

// An ordered keyword list (data="dist point normal") as a bit mask; keywords must
// come in the list's order, and none given means only the first.
int DataMask(const XmlElement& e, const std::vector<const char*>& keywords) {
  std::vector<std::string> tokens = e.Tokens("data");
  if (tokens.empty()) return 1;
  std::string order;
  for (size_t k = 0; k < keywords.size(); k++) order += (k ? ", " : "") + std::string(keywords[k]);
  int mask = 0;
  int last = -1;
  for (const std::string& t : tokens) {
    int index = -1;
    for (size_t k = 0; k < keywords.size(); k++) {
      if (t == keywords[k]) index = static_cast<int>(k);
    }
    if (index < 0) e.Fail("unknown data keyword '" + t + "' (allowed: " + order + ")");
    if (index <= last) e.Fail("data attributes must be in order: " + order);
    mask |= 1 << index;
    last = index;
  }
  return mask;
}

// objtype/objname (both required), for frame sensors.
void ReadObject(const XmlElement& e, SensorSpec* s) {
  std::string type;
  e.RequiredText("objtype", &type);
  s->objtype = ObjTypeFromName(type);
  e.RequiredText("objname", &s->objname);
}

// reftype/refname: optional, but a refname needs its reftype.
void ReadReference(const XmlElement& e, SensorSpec* s) {
  std::string type;
  if (e.Text("reftype", &type)) {
    s->reftype = ObjTypeFromName(type);
    e.RequiredText("refname", &s->refname);
  } else if (e.Text("refname", &type)) {
    e.Fail("refname '" + type + "' given but reftype is missing");
  }
}

// A pair of alternatives such as geom1/body1: exactly one must be given.
void ReadOneOf(const XmlElement& e, const char* geom, const char* body, int* type,
               std::string* name) {
  bool has_body = e.Text(body, name);
  bool has_geom = e.Text(geom, name);
  if (has_body == has_geom) {
    e.Fail(std::string("exactly one of (") + geom + ", " + body + ") must be specified");
  }
  *type = has_body ? kObjBody : kObjGeom;
}

void ReadRangefinder(const XmlElement& e, SensorSpec* s) {
  e.CheckAttributes(With({"site", "camera", "data"}));
  bool site = e.Text("site", &s->objname);
  bool camera = e.Text("camera", &s->objname);
  if (site == camera) e.Fail("rangefinder requires exactly one of 'site' or 'camera'");
  s->objtype = site ? kObjSite : kObjCamera;
  s->intprm[0] = DataMask(e, {"dist", "dir", "origin", "point", "normal", "depth"});
}

// contact: optional first criterion (site, geom1, body1 or subtree1) and second
// (geom2, body2 or subtree2), the data fields, the reduction and the count.
void ReadContact(const XmlElement& e, SensorSpec* s) {
  e.CheckAttributes(With({"geom1", "geom2", "body1", "body2", "subtree1", "subtree2", "site",
                          "num", "data", "reduce"}));
  int given1 = 0;
  s->objtype = kObjUnknown;
  for (auto [attr, type] : {std::pair{"site", kObjSite}, {"body1", kObjBody},
                            {"subtree1", kObjXBody}, {"geom1", kObjGeom}}) {
    if (e.Text(attr, &s->objname)) given1++, s->objtype = type;
  }
  if (given1 > 1) e.Fail("at most one of (geom1, body1, subtree1, site) can be specified");
  int given2 = 0;
  s->reftype = kObjUnknown;
  for (auto [attr, type] : {std::pair{"body2", kObjBody}, {"subtree2", kObjXBody},
                            {"geom2", kObjGeom}}) {
    if (e.Text(attr, &s->refname)) given2++, s->reftype = type;
  }
  if (given2 > 1) e.Fail("at most one of (geom2, body2, subtree2) can be specified");
  s->intprm[0] = DataMask(e, {"found", "force", "torque", "dist", "pos", "normal", "tangent"});
  e.Enum("reduce", &s->intprm[1],
         {{"none", 0}, {"mindist", 1}, {"maxforce", 2}, {"netforce", 3}});
  s->intprm[2] = 1;
  e.Int("num", &s->intprm[2]);
  if (s->intprm[2] <= 0) e.Fail("'num' must be positive in sensor");
}

// user: optional object, a required dim, and the stage and data type it declares.
void ReadUser(const XmlElement& e, SensorSpec* s) {
  e.CheckAttributes({"name", "objtype", "objname", "datatype", "needstage", "dim", "cutoff",
                     "noise", "user"});
  std::string type;
  bool named = e.Text("objname", &s->objname);
  if (e.Text("objtype", &type)) {
    if (!named) e.Fail("objtype '" + type + "' given but objname is missing");
    s->objtype = ObjTypeFromName(type);
  } else if (named) {
    e.Fail("objname '" + s->objname + "' given but objtype is missing");
  }
  if (!e.Int("dim", &s->dim)) e.Fail("required attribute missing: 'dim'");
  e.Enum("needstage", &s->needstage,
         {{"none", kStageNone}, {"pos", kStagePos}, {"vel", kStageVel}, {"acc", kStageAcc}});
  e.Enum("datatype", &s->datatype,
         {{"real", kDataReal}, {"positive", kDataPositive}, {"axis", kDataAxis},
          {"quaternion", kDataQuaternion}});
}

// The sensors read by their own rules (Target::kSpecial).
void ReadSpecial(const XmlElement& e, SensorSpec* s) {
  switch (s->type) {
    case kSensCamProjection:
      e.CheckAttributes(With({"site", "camera"}));
      s->objtype = kObjSite;
      e.RequiredText("site", &s->objname);
      s->reftype = kObjCamera;
      e.RequiredText("camera", &s->refname);
      return;
    case kSensRangefinder: return ReadRangefinder(e, s);
    case kSensInsideSite:
      e.CheckAttributes(With({"site", "objtype", "objname"}));
      s->reftype = kObjSite;
      e.RequiredText("site", &s->refname);
      ReadObject(e, s);
      return;
    case kSensGeomDist:
    case kSensGeomNormal:
    case kSensGeomFromTo:
      e.CheckAttributes(With({"geom1", "geom2", "body1", "body2"}));
      ReadOneOf(e, "geom1", "body1", &s->objtype, &s->objname);
      ReadOneOf(e, "geom2", "body2", &s->reftype, &s->refname);
      return;
    case kSensContact: return ReadContact(e, s);
    case kSensTactile:
      e.CheckAttributes({"name", "geom", "mesh", "nsample", "interp", "delay", "interval",
                         "user"});
      s->reftype = kObjGeom;
      e.RequiredText("geom", &s->refname);
      s->objtype = kObjMesh;
      e.RequiredText("mesh", &s->objname);
      return;
    default: return ReadUser(e, s);
  }
}

// The object attribute of the simple kinds.
void ReadTarget(const XmlElement& e, Target target, SensorSpec* s) {
  auto one = [&](const char* attr, int type) {
    e.CheckAttributes(With({attr}));
    s->objtype = type;
    e.RequiredText(attr, &s->objname);
  };
  switch (target) {
    case Target::kSite: return one("site", kObjSite);
    case Target::kJoint: return one("joint", kObjJoint);
    case Target::kTendon: return one("tendon", kObjTendon);
    case Target::kActuator: return one("actuator", kObjActuator);
    case Target::kBody: return one("body", kObjBody);
    case Target::kFrame:
      e.CheckAttributes(With({"objtype", "objname", "reftype", "refname"}));
      ReadObject(e, s);
      return ReadReference(e, s);
    case Target::kFrameAcc:
      e.CheckAttributes(With({"objtype", "objname"}));
      return ReadObject(e, s);
    case Target::kNone: return e.CheckAttributes(kCommon);
    case Target::kSpecial: return ReadSpecial(e, s);
  }
}

// The filtering, delay and sampling attributes every sensor has.
void ReadCommon(const XmlElement& e, SensorSpec* s) {
  e.Number("cutoff", &s->cutoff);
  e.Number("noise", &s->noise);
  e.Int("nsample", &s->nsample);
  e.Enum("interp", &s->interp, {{"zoh", 0}, {"linear", 1}, {"cubic", 2}});
  e.Number("delay", &s->delay);
  e.Numbers("interval", s->interval, false);
  if (auto user = e.Vector("user")) s->user = *user;
}

}  // namespace

void Reader::ReadPluginSensor(const XmlElement& e, SensorSpec* s) {
  e.CheckAttributes({"name", "plugin", "instance", "cutoff", "objtype", "objname", "reftype",
                     "refname", "user"});
  ReadPluginUse(e, "sensor", &s->plugin);
  // objtype/objname and reftype/refname: optional, each name with its type
  for (auto [type_attr, name_attr, type, name] :
       {std::tuple{"objtype", "objname", &s->objtype, &s->objname},
        std::tuple{"reftype", "refname", &s->reftype, &s->refname}}) {
    std::string keyword;
    bool typed = e.Text(type_attr, &keyword);
    bool named = e.Text(name_attr, name);
    if (typed != named) {
      e.Fail(std::string(typed ? type_attr : name_attr) + " is specified but " +
             (typed ? name_attr : type_attr) + " is not");
    }
    if (typed) {
      *type = ObjTypeFromName(keyword);
      if (*type == kObjUnknown) e.Fail("unknown object type '" + keyword + "'");
    }
  }
}

void Reader::Sensor(const XmlElement& section) {
  section.CheckAttributes({});
  for (pugi::xml_node n : section.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement e = Element(n);
    if (e.tag() == "plugin") {
      SensorSpec s;
      s.src = e.src();
      s.type = kSensPlugin;
      ReadPluginSensor(e, &s);
      e.Number("cutoff", &s.cutoff);
      if (auto user = e.Vector("user")) s.user = *user;
      spec_->sensors.push_back(std::move(s));
      continue;
    }
    const SensorKind* kind = nullptr;
    for (const SensorKind& k : kKinds) {
      if (e.tag() == SensorTypeName(k.type)) kind = &k;
    }
    if (!kind) Unknown(e);

    // Type and object first (they check the attributes), then the common ones.
    SensorSpec s;
    s.src = e.src();
    s.type = kind->type;
    ReadTarget(e, kind->target, &s);
    ReadCommon(e, &s);
    spec_->sensors.push_back(std::move(s));
  }
}

}  // namespace simlab::mjcf
