// MJCF reader: joint, geom, site, tendon and actuator elements. The same readers fill
// a default class (in_default) and an element in the model, as in MuJoCo.
#include <string>

#include "mjcf/error.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

namespace {

const std::initializer_list<Keyword> kJointTypes = {
    {"free", kJointFree}, {"ball", kJointBall}, {"slide", kJointSlide}, {"hinge", kJointHinge}};

const std::initializer_list<Keyword> kGeomTypes = {
    {"plane", kGeomPlane},       {"hfield", kGeomHfield},     {"sphere", kGeomSphere},
    {"capsule", kGeomCapsule},   {"ellipsoid", kGeomEllipsoid}, {"cylinder", kGeomCylinder},
    {"box", kGeomBox},           {"mesh", kGeomMesh},         {"sdf", kGeomSdf}};

}  // namespace

// ---------------------------------------------------------------- joint

void Reader::ReadJoint(const XmlElement& e, JointSpec* j, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"type", "group", "pos", "axis", "springdamper", "limited",
                       "actuatorfrclimited", "solreflimit", "solimplimit", "solreffriction",
                       "solimpfriction", "stiffness", "range", "actuatorfrcrange",
                       "actuatorgravcomp", "margin", "ref", "springref", "armature", "damping",
                       "frictionloss", "user"});
  } else {
    e.CheckAttributes({"name", "class", "type", "group", "pos", "axis", "springdamper",
                       "limited", "actuatorfrclimited", "solreflimit", "solimplimit",
                       "solreffriction", "solimpfriction", "stiffness", "range",
                       "actuatorfrcrange", "actuatorgravcomp", "margin", "ref", "springref",
                       "armature", "damping", "frictionloss", "user"});
    j->src = e.src();
  }
  e.Enum("type", &j->type, kJointTypes);
  e.Tri("limited", &j->limited);
  e.Tri("actuatorfrclimited", &j->actfrclimited);
  e.Int("group", &j->group);
  e.Numbers("solreflimit", j->solref_limit, false);
  e.Numbers("solimplimit", j->solimp_limit, false);
  e.Numbers("solreffriction", j->solref_friction, false);
  e.Numbers("solimpfriction", j->solimp_friction, false);
  e.Numbers("pos", j->pos);
  e.Numbers("axis", j->axis);
  e.Numbers("springdamper", j->springdamper);
  e.Number("stiffness", &j->stiffness);
  e.Numbers("range", j->range);
  e.Numbers("actuatorfrcrange", j->actfrcrange);
  e.Number("margin", &j->margin);
  e.Number("ref", &j->ref);
  e.Number("springref", &j->springref);
  e.Number("armature", &j->armature);
  e.Number("damping", &j->damping);
  e.Number("frictionloss", &j->frictionloss);
  e.Bool("actuatorgravcomp", &j->actgravcomp);
  e.Vector("user");
  if ((j->springdamper[0] != 0 || j->springdamper[1] != 0) &&
      (j->springdamper[0] <= 0 || j->springdamper[1] <= 0)) {
    e.Fail("springdamper values must both be positive when given");
  }
}

// ---------------------------------------------------------------- geom

void Reader::ReadGeom(const XmlElement& e, GeomSpec* g, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"type", "pos", "quat", "contype", "conaffinity", "condim", "group",
                       "priority", "size", "material", "friction", "mass", "density",
                       "shellinertia", "solmix", "solref", "solimp", "margin", "gap",
                       "fromto", "axisangle", "xyaxes", "zaxis", "euler", "hfield", "mesh",
                       "fitscale", "rgba", "fluidshape", "fluidcoef", "user"});
  } else {
    e.CheckAttributes({"name", "class", "type", "contype", "conaffinity", "condim", "group",
                       "priority", "size", "material", "friction", "mass", "density",
                       "shellinertia", "solmix", "solref", "solimp", "margin", "gap",
                       "fromto", "pos", "quat", "axisangle", "xyaxes", "zaxis", "euler",
                       "hfield", "mesh", "fitscale", "rgba", "fluidshape", "fluidcoef", "user"});
    g->src = e.src();
  }
  e.Enum("type", &g->type, kGeomTypes);
  e.Numbers("size", g->size, false);
  e.Int("contype", &g->contype);
  e.Int("conaffinity", &g->conaffinity);
  e.Int("condim", &g->condim);
  e.Int("group", &g->group);
  e.Int("priority", &g->priority);
  e.Numbers("friction", g->friction, false);
  e.Number("solmix", &g->solmix);
  e.Numbers("solref", g->solref, false);
  e.Numbers("solimp", g->solimp, false);
  e.Number("margin", &g->margin);
  e.Number("gap", &g->gap);
  e.Text("hfield", &g->hfield);
  e.Text("mesh", &g->mesh);
  e.Number("fitscale", &g->fitscale);
  e.Numbers("rgba", g->rgba);
  e.Text("material", &g->material);
  int fluidshape = g->fluid_ellipsoid ? 1 : 0;
  e.Enum("fluidshape", &fluidshape, {{"none", 0}, {"ellipsoid", 1}});
  g->fluid_ellipsoid = fluidshape == 1;
  e.Numbers("fluidcoef", g->fluidcoef, false);
  e.Vector("user");
  e.Number("mass", &g->mass);
  e.Number("density", &g->density);
  e.Numbers("fromto", g->fromto);
  e.Numbers("pos", g->pos);
  e.Quat("quat", g->quat);
  e.Orient(&g->alt);
  e.Bool("shellinertia", &g->shellinertia);
}

// ---------------------------------------------------------------- site

void Reader::ReadSite(const XmlElement& e, SiteSpec* s, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"type", "group", "pos", "quat", "material", "size", "fromto",
                       "axisangle", "xyaxes", "zaxis", "euler", "rgba", "user"});
  } else {
    e.CheckAttributes({"name", "class", "type", "group", "pos", "quat", "material", "size",
                       "fromto", "axisangle", "xyaxes", "zaxis", "euler", "rgba", "user"});
    s->src = e.src();
  }
  e.Enum("type", &s->type, kGeomTypes);
  e.Numbers("size", s->size, false);
  e.Int("group", &s->group);
  e.Numbers("pos", s->pos);
  e.Quat("quat", s->quat);
  e.Numbers("rgba", s->rgba);
  e.Text("material", &s->material);
  e.Numbers("fromto", s->fromto);
  e.Orient(&s->alt);
  e.Vector("user");
}

// ---------------------------------------------------------------- tendon

void Reader::ReadTendon(const XmlElement& e, TendonSpec* t, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"group", "limited", "range", "solreflimit", "solimplimit",
                       "solreffriction", "solimpfriction", "frictionloss", "springlength",
                       "width", "material", "margin", "stiffness", "damping", "rgba", "user"});
  } else if (t->spatial) {
    e.CheckAttributes({"name", "class", "group", "limited", "actuatorfrclimited", "range",
                       "actuatorfrcrange", "solreflimit", "solimplimit", "solreffriction",
                       "solimpfriction", "frictionloss", "springlength", "width", "material",
                       "margin", "stiffness", "damping", "armature", "rgba", "user"});
    t->src = e.src();
  } else {
    e.CheckAttributes({"name", "class", "group", "limited", "actuatorfrclimited", "range",
                       "actuatorfrcrange", "solreflimit", "solimplimit", "solreffriction",
                       "solimpfriction", "frictionloss", "springlength", "margin",
                       "stiffness", "damping", "armature", "user"});
    t->src = e.src();
  }
  e.Int("group", &t->group);
  e.Tri("limited", &t->limited);
  e.Tri("actuatorfrclimited", &t->actfrclimited);
  e.Number("width", &t->width);
  e.Numbers("solreflimit", t->solref_limit, false);
  e.Numbers("solimplimit", t->solimp_limit, false);
  e.Numbers("solreffriction", t->solref_friction, false);
  e.Numbers("solimpfriction", t->solimp_friction, false);
  e.Numbers("range", t->range);
  e.Numbers("actuatorfrcrange", t->actfrcrange);
  e.Number("margin", &t->margin);
  e.Number("stiffness", &t->stiffness);
  e.Number("damping", &t->damping);
  e.Number("armature", &t->armature);
  e.Number("frictionloss", &t->frictionloss);
  // One spring length means the same value for both ends of the dead band.
  if (e.Numbers("springlength", t->springlength, false) == 1) {
    t->springlength[1] = t->springlength[0];
  }
  std::array<double, 4> rgba;
  e.Numbers("rgba", rgba);
  e.Vector("user");
}

}  // namespace simlab::mjcf
