// Height fields: <asset><hfield> elevation grids and the geoms that use them, laid out
// as MuJoCo's compiler does (hfield_* arrays, elevations normalized to [0, 1]).
#include <algorithm>
#include <string>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "compiler/texture_png.h"
#include "mjcf/error.h"

namespace simlab::compiler {

namespace {

// Elevations shifted and scaled to [0, 1] (a flat field becomes all zero), in single
// precision as MuJoCo's compiler computes them.
std::vector<float> NormalizedElevation(const mjcf::HFieldSpec& s, std::vector<float> data) {
  float lo = 1e10f, hi = -1e10f;
  for (float v : data) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (lo > hi) ThrowAt(s.src, "invalid data range in hfield");
  for (float& v : data) {
    v -= lo;
    if (hi - lo > kEps) v /= hi - lo;
  }
  return data;
}

void CheckHFieldSpec(const mjcf::HFieldSpec& s) {
  if (s.src.name.empty()) ThrowAt(s.src, "empty name in height field");
  for (double v : s.size) {
    if (!(v > 0)) ThrowAt(s.src, "size parameter is not positive in hfield");
  }
}

// The hfield each geom names (-1 for none); hfield geoms must name one, others none.
std::vector<int> GeomHFieldIds(const std::vector<std::string>& names, const CompileState& state) {
  std::vector<int> ids;
  for (const GeomState& g : state.geoms) {
    const mjcf::GeomSpec& s = *g.spec;
    if ((s.type == kGeomHfield) != !s.hfield.empty()) {
      ThrowAt(s.src, "hfield geom needs an hfield, and only hfield geoms can have one");
    }
    ids.push_back(s.hfield.empty() ? -1 : FindNamed(s.src, names, s.hfield, "hfield"));
  }
  return ids;
}

// True if geoms a and b pass MuJoCo's contype/conaffinity test.
bool CanTouch(const mjcf::GeomSpec& a, const mjcf::GeomSpec& b) {
  return (a.contype & b.conaffinity) || (b.contype & a.conaffinity);
}

bool NamedInPair(const mjcf::ModelSpec& spec, const std::string& geom) {
  for (const mjcf::PairSpec& p : spec.pairs) {
    if (!geom.empty() && (p.geom1 == geom || p.geom2 == geom)) return true;
  }
  return false;
}

}  // namespace

void CompileHFields(const mjcf::ModelSpec& spec, CompileState* state) {
  // Names are required and unique; data normalized once per field.
  std::vector<std::string> names;
  state->hfields.resize(spec.hfields.size());
  for (size_t i = 0; i < spec.hfields.size(); i++) {
    const mjcf::HFieldSpec& s = spec.hfields[i];
    CheckHFieldSpec(s);
    if (FindName(names, s.src.name) >= 0) ThrowAt(s.src, "repeated hfield name '" + s.src.name + "'");
    names.push_back(s.src.name);
    HFieldState& h = state->hfields[i];
    h.spec = &s;
    std::vector<float> elevation;
    if (s.file.empty()) {
      h.nrow = s.nrow;
      h.ncol = s.ncol;
      elevation = s.elevation;
    } else {
      LoadHFieldFile(spec, s, &h.nrow, &h.ncol, &elevation);
    }
    h.data = NormalizedElevation(s, std::move(elevation));
  }

  // Geoms: geom_dataid is the hfield's id.
  std::vector<int> ids = GeomHFieldIds(names, *state);
  for (size_t i = 0; i < state->geoms.size(); i++) {
    if (ids[i] < 0) continue;
    state->geoms[i].hfield = &state->hfields[ids[i]];
    state->geoms[i].meshid = ids[i];
  }
}

void HFieldGeomSize(GeomState* g) {
  const std::array<double, 4>& size = g->hfield->spec->size;
  g->size[0] = size[0];
  g->size[1] = size[1];
  g->size[2] = 0.25 * size[2] + 0.5 * size[3];
}

void CheckHFieldCollisions(const mjcf::ModelSpec& spec, const CompileState& state) {
  // Height fields collide through MuJoCo's native CCD; with the nativeccd flag disabled
  // MuJoCo switches to libccd's MPR, which is not supported yet. A pair is skipped when
  // both geoms are welded to the same body (static geoms included); any other pair that
  // passes the type/affinity test, or is a <pair>, could collide, and so could any flex
  // that passes it.
  if (!(spec.option.disableflags & kDisableNativeccd)) return;
  const std::string refusal =
      "hfield collisions with the nativeccd flag disabled are not supported yet";
  for (const GeomState& h : state.geoms) {
    if (!h.hfield) continue;
    if (NamedInPair(spec, h.spec->src.name)) {
      ThrowAt(h.spec->src, refusal + " (the geom is in a <pair>)");
    }
    int hweld = state.bodies[h.body].weldid;
    for (const GeomState& g : state.geoms) {
      if (&g == &h || state.bodies[g.body].weldid == hweld || !CanTouch(*h.spec, *g.spec)) {
        continue;
      }
      std::string other = g.spec->src.name.empty()
                              ? "at line " + std::to_string(g.spec->src.line)
                              : "'" + g.spec->src.name + "'";
      ThrowAt(h.spec->src, refusal + " (the hfield can touch geom " + other +
                               "; set contype and conaffinity to 0)");
    }
    // Flex elements meet height fields through the same prisms (mjc_HFieldElem).
    for (const mjcf::FlexSpec& f : spec.flexes) {
      if (!(h.spec->contype & f.conaffinity) && !(f.contype & h.spec->conaffinity)) continue;
      std::string other = f.src.name.empty() ? "at line " + std::to_string(f.src.line)
                                             : "'" + f.src.name + "'";
      ThrowAt(h.spec->src, refusal + " (the hfield can touch flex " + other +
                               "; set contype and conaffinity to 0)");
    }
  }
}

void CheckSdfCollisions(const mjcf::ModelSpec& spec, const CompileState& state) {
  // A height field and an sdf geom: MuJoCo's reference build warns and makes no contacts,
  // its 3.5.1 release has its own collider, simlab has neither yet: such a pair that
  // could collide (not welded together and passing contype/conaffinity, or a <pair>) is
  // refused.
  for (const GeomState& s : state.geoms) {
    if (s.spec->type != kGeomSdf) continue;
    int sweld = state.bodies[s.body].weldid;
    for (const GeomState& g : state.geoms) {
      if (g.spec->type != kGeomHfield) continue;
      bool paired = false;
      for (const mjcf::PairSpec& p : spec.pairs) {
        const std::string &a = s.spec->src.name, &b = g.spec->src.name;
        paired = paired || (!a.empty() && !b.empty() &&
                            ((p.geom1 == a && p.geom2 == b) || (p.geom1 == b && p.geom2 == a)));
      }
      bool can_touch = state.bodies[g.body].weldid != sweld && CanTouch(*s.spec, *g.spec);
      if (!paired && !can_touch) continue;
      std::string other = g.spec->src.name.empty()
                              ? "at line " + std::to_string(g.spec->src.line)
                              : "'" + g.spec->src.name + "'";
      ThrowAt(s.spec->src, "collisions between sdf geoms and hfield geoms are not supported "
                           "yet (the sdf geom can touch geom " + other +
                           "; set contype and conaffinity to 0)");
    }
  }
}

void HFieldSizes(const CompileState& state, Model* m) {
  m->nhfield = static_cast<int>(state.hfields.size());
  m->nhfielddata = 0;
  for (const HFieldState& h : state.hfields) m->nhfielddata += static_cast<int>(h.data.size());
}

void LayoutHFields(const CompileState& state, Model* m) {
  int adr = 0;
  for (int i = 0; i < m->nhfield; i++) {
    const HFieldState& h = state.hfields[i];
    std::copy(h.spec->size.begin(), h.spec->size.end(), &m->hfield_size[4 * i]);
    m->hfield_nrow[i] = h.nrow;
    m->hfield_ncol[i] = h.ncol;
    m->hfield_adr[i] = adr;
    std::copy(h.data.begin(), h.data.end(), m->hfield_data.begin() + adr);
    adr += static_cast<int>(h.data.size());
    m->hfield_names[i] = h.spec->src.name;
  }
}

}  // namespace simlab::compiler
