// Tendons. Fixed: a linear combination of joint positions, L = sum coef_i q_i.
// Spatial: a path through sites, wrapping around sphere and cylinder geoms, split by
// pulleys (MuJoCo mjCTendon/mjCWrap): ids and the validity rules of the path.
#include <string>

#include "compiler/compiler.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::kAuto;
using mjcf::kTrue;
using mjcf::ThrowAt;

namespace {

bool Limited(const mjcf::CompilerSpec& c, const mjcf::Source& src, int limited,
             const std::array<double, 2>& range, const char* attr) {
  bool hasrange = !(range[0] == 0 && range[1] == 0);
  if (limited == kAuto && !c.autolimits && hasrange) {
    ThrowAt(src, std::string("has ") + attr + "range but not " + attr +
                     "limited; set autolimits=\"true\" in <compiler> or set " + attr + "limited");
  }
  return limited == kTrue || (limited == kAuto && range[0] < range[1]);
}

// Checks and copies one tendon's scalar fields.
void TendonFields(const mjcf::CompilerSpec& model, const mjcf::TendonSpec& t, int i, Model* m) {
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(t.compiler, model);  // (its own model's)
  m->tendon_limited[i] = Limited(c, t.src, t.limited, t.range, "");
  if (m->tendon_limited[i] && t.range[0] >= t.range[1]) ThrowAt(t.src, "invalid tendon range");
  m->tendon_actfrclimited[i] = Limited(c, t.src, t.actfrclimited, t.actfrcrange, "actuatorfrc");
  if (m->tendon_actfrclimited[i] &&
      (t.actfrcrange[0] >= t.actfrcrange[1] || t.actfrcrange[0] > 0 || t.actfrcrange[1] < 0)) {
    ThrowAt(t.src, "invalid actuatorfrcrange");
  }
  if (t.springlength[0] > t.springlength[1]) ThrowAt(t.src, "invalid springlength");
  for (int k = 0; k < 2; k++) {
    m->tendon_range[2 * i + k] = t.range[k];
    m->tendon_actfrcrange[2 * i + k] = t.actfrcrange[k];
    m->tendon_lengthspring[2 * i + k] = t.springlength[k];
  }
  for (int k = 0; k < kNRef; k++) {
    m->tendon_solref_lim[kNRef * i + k] = t.solref_limit[k];
    m->tendon_solref_fri[kNRef * i + k] = t.solref_friction[k];
  }
  for (int k = 0; k < kNImp; k++) {
    m->tendon_solimp_lim[kNImp * i + k] = t.solimp_limit[k];
    m->tendon_solimp_fri[kNImp * i + k] = t.solimp_friction[k];
  }
  m->tendon_margin[i] = t.margin;
  m->tendon_stiffness[i] = t.stiffness;
  m->tendon_damping[i] = t.damping;
  m->tendon_armature[i] = t.armature;
  m->tendon_frictionloss[i] = t.frictionloss;
  m->tendon_names[i] = t.src.name;
}

// The tree objects a path can refer to, indexed by name.
struct PathNames {
  NameIndex joints, sites, geoms;
};

// Model ids of one path element (MuJoCo's wrap_type, wrap_objid, wrap_prm).
void ResolveWrap(const mjcf::WrapSpec& w, const PathNames& names, const CompileState& state,
                 int adr, Model* m) {
  int type = w.type, objid = -1;
  double prm = w.prm;
  switch (w.type) {
    case kWrapJoint:
      objid = FindNamed(w.src, names.joints, w.target, "joint");
      break;
    case kWrapSite:
      objid = FindNamed(w.src, names.sites, w.target, "site");
      break;
    case kWrapPulley:
      if (w.prm < 0) ThrowAt(w.src, "pulley has a negative divisor");
      break;
    default: {
      // A geom: its type decides sphere or cylinder wrapping; prm holds the side site.
      objid = FindNamed(w.src, names.geoms, w.target, "geom");
      int geom_type = state.geoms[objid].spec->type;
      if (geom_type != kGeomSphere && geom_type != kGeomCylinder) {
        ThrowAt(w.src, "geom '" + w.target + "' is not a sphere or cylinder");
      }
      type = geom_type == kGeomCylinder ? kWrapCylinder : kWrapSphere;
      prm = -1;
      if (!w.sidesite.empty()) {
        prm = FindNamed(w.src, names.sites, w.sidesite, "side site");
      }
    }
  }
  m->wrap_type[adr] = type;
  m->wrap_objid[adr] = objid;
  m->wrap_prm[adr] = prm;
}

// MuJoCo's rules for a spatial path (types already resolved at [adr, adr + n)).
void CheckSpatialPath(const mjcf::TendonSpec& t, int adr, int n, const Model& m) {
  if (t.armature < 0) ThrowAt(t.src, "tendon armature cannot be negative");
  auto type = [&](int k) { return m.wrap_type[adr + k]; };
  for (int k = 0; k < n; k++) {
    const mjcf::Source& src = t.wraps[k].src;
    bool pulley_before = k == 0 || type(k - 1) == kWrapPulley;
    bool pulley_after = k == n - 1 || type(k + 1) == kWrapPulley;
    switch (type(k)) {
      case kWrapPulley:
        if (k > 0 && type(k - 1) == kWrapPulley) ThrowAt(src, "consecutive pulleys");
        if (k == n - 1) ThrowAt(src, "the tendon path ends with a pulley");
        break;
      case kWrapSite:
        if (pulley_before && pulley_after) ThrowAt(src, "a site needs a neighbor that is not a pulley");
        if (k < n - 1 && type(k + 1) == kWrapSite &&
            m.wrap_objid[adr + k] == m.wrap_objid[adr + k + 1]) {
          ThrowAt(src, "site is repeated");
        }
        break;
      case kWrapSphere:
      case kWrapCylinder:
        if (k == 0 || k == n - 1 || type(k - 1) != kWrapSite || type(k + 1) != kWrapSite) {
          ThrowAt(src, "a wrapping geom must be between two sites");
        }
        if (t.armature > 0) ThrowAt(src, "geom wrapping is not supported with tendon armature");
        break;
      default: ThrowAt(src, "a joint cannot be part of a spatial tendon");
    }
  }
}

}  // namespace

void CompileTendons(const mjcf::ModelSpec& spec, const CompileState& state, Model* m) {
  PathNames names;
  for (size_t i = 0; i < state.joints.size(); i++) {
    names.joints.Insert(state.joints[i].spec->src.name, static_cast<int>(i));
  }
  for (size_t i = 0; i < state.sites.size(); i++) {
    names.sites.Insert(state.sites[i].spec->src.name, static_cast<int>(i));
  }
  for (size_t i = 0; i < state.geoms.size(); i++) {
    names.geoms.Insert(state.geoms[i].spec->src.name, static_cast<int>(i));
  }
  NameIndex seen;
  int adr = 0;
  for (int i = 0; i < m->ntendon; i++) {
    const mjcf::TendonSpec& t = spec.tendons[i];
    if (t.wraps.empty()) ThrowAt(t.src, "a tendon path cannot be empty");
    if (t.spatial && t.wraps.size() < 2) {
      ThrowAt(t.src, "a spatial tendon path needs at least two objects");
    }
    if (t.spatial && t.width <= 0) ThrowAt(t.src, "a spatial tendon must have positive width");
    if (!seen.Insert(t.src.name, i)) ThrowAt(t.src, "repeated tendon name '" + t.src.name + "'");

    // Path: joints with coefficients, or sites, geoms and pulleys.
    m->tendon_adr[i] = adr;
    m->tendon_num[i] = static_cast<int>(t.wraps.size());
    for (const mjcf::WrapSpec& w : t.wraps) ResolveWrap(w, names, state, adr++, m);
    if (t.spatial) CheckSpatialPath(t, m->tendon_adr[i], m->tendon_num[i], *m);
    TendonFields(spec.compiler, t, i, m);
  }
}

}  // namespace simlab::compiler
