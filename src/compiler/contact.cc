// Contact settings of the model: explicit geom pairs, excluded body pairs, and the
// per-body union of geom contype/conaffinity that the broad phase filters with.
//
// Pairs and exclusions are ordered by body signature (body1 << 16) + body2, with
// body1 <= body2, as MuJoCo sorts them; the collision driver merges them with the
// broad phase's body pairs in that order.
#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

int Signature(int body1, int body2) { return (body1 << 16) + body2; }

// The order of elements sorted by signature; ties keep their written order.
std::vector<int> SortedBySignature(const std::vector<int>& signatures) {
  std::vector<int> order(signatures.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return signatures[a] < signatures[b]; });
  return order;
}

// One pair's fields: geoms ordered so that body1 <= body2, and its own parameters.
void LayoutPair(const mjcf::PairSpec& p, int g1, int g2, int i, Model* m) {
  if (p.condim != 1 && p.condim != 3 && p.condim != 4 && p.condim != 6) {
    ThrowAt(p.src, "condim must be 1, 3, 4 or 6");
  }
  if (m->geom_bodyid[g1] > m->geom_bodyid[g2]) std::swap(g1, g2);
  m->pair_dim[i] = p.condim;
  m->pair_geom1[i] = g1;
  m->pair_geom2[i] = g2;
  m->pair_signature[i] = Signature(m->geom_bodyid[g1], m->geom_bodyid[g2]);
  for (int k = 0; k < kNRef; k++) {
    m->pair_solref[kNRef * i + k] = p.solref[k];
    m->pair_solreffriction[kNRef * i + k] = p.solreffriction[k];
  }
  for (int k = 0; k < kNImp; k++) m->pair_solimp[kNImp * i + k] = p.solimp[k];
  for (int k = 0; k < 5; k++) m->pair_friction[5 * i + k] = p.friction[k];
  m->pair_margin[i] = p.margin;
  m->pair_gap[i] = p.gap;
  m->pair_names[i] = p.src.name;
}

void CompilePairs(const mjcf::ModelSpec& spec, Model* m) {
  // Resolve the geoms, then lay the pairs out in signature order.
  std::vector<int> g1(m->npair), g2(m->npair), signatures(m->npair);
  NameIndex geoms(m->geom_names);
  for (int i = 0; i < m->npair; i++) {
    const mjcf::PairSpec& p = spec.pairs[i];
    g1[i] = FindNamed(p.src, geoms, p.geom1, "geom");
    g2[i] = FindNamed(p.src, geoms, p.geom2, "geom");
    int b1 = m->geom_bodyid[g1[i]], b2 = m->geom_bodyid[g2[i]];
    signatures[i] = Signature(std::min(b1, b2), std::max(b1, b2));
  }
  std::vector<int> order = SortedBySignature(signatures);
  for (int i = 0; i < m->npair; i++) {
    int k = order[i];
    LayoutPair(spec.pairs[k], g1[k], g2[k], i, m);
  }
}

void CompileExcludes(const mjcf::ModelSpec& spec, Model* m) {
  std::vector<int> signatures(m->nexclude);
  NameIndex bodies(m->body_names);
  for (int i = 0; i < m->nexclude; i++) {
    const mjcf::ExcludeSpec& ex = spec.excludes[i];
    int b1 = FindNamed(ex.src, bodies, ex.body1, "body");
    int b2 = FindNamed(ex.src, bodies, ex.body2, "body");
    signatures[i] = Signature(std::min(b1, b2), std::max(b1, b2));
  }
  std::vector<int> order = SortedBySignature(signatures);
  for (int i = 0; i < m->nexclude; i++) {
    m->exclude_signature[i] = signatures[order[i]];
    m->exclude_names[i] = spec.excludes[order[i]].src.name;
  }
}

// body_contype/conaffinity: the union of the body's geoms' bits.
void BodyContactBits(Model* m) {
  for (int b = 0; b < m->nbody; b++) {
    m->body_contype[b] = m->body_conaffinity[b] = 0;
    for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; g++) {
      m->body_contype[b] |= m->geom_contype[g];
      m->body_conaffinity[b] |= m->geom_conaffinity[g];
    }
  }
}

}  // namespace

void CompileContacts(const mjcf::ModelSpec& spec, Model* m) {
  CompilePairs(spec, m);
  CompileExcludes(spec, m);
  BodyContactBits(m);
}

}  // namespace simlab::compiler
