// Bounding volume hierarchies of the bodies' colliding geoms, for the collision
// midphase (MuJoCo's mjCBoundingVolumeHierarchy for bodies).
//
// Each body with colliding geoms (contype or conaffinity nonzero) gets a binary tree: the
// root box holds all of them, and each node splits its geoms at the median of their
// centres along the box's longest side, down to one geom per leaf. Boxes are centre and
// half sizes in the body's inertial frame (body_ipos, body_iquat), as the engine tests
// them against d.xipos and d.ximat; a plane's box is kMaxVal wide, as MuJoCo's.
//
// The tree only prunes geom pairs that cannot touch; the contacts of a body pair are
// sorted by geom afterwards, so its shape never changes the result. The median split
// sorts by a strict order (centre, then geom id) so that the tree is the same whatever
// the standard library.
#include <algorithm>
#include <cmath>
#include <vector>

#include "compiler/compiler.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

constexpr double kFlatBox = 1e-14;  // flat boxes are inflated by this much (mjEPS)

// A colliding geom of the body: its id, its centre in the body's inertial frame, and
// the corners of its box there (min x y z, max x y z).
struct Element {
  int geom = -1;
  double centre[3] = {0, 0, 0};
  double aamm[6] = {0, 0, 0, 0, 0, 0};
};

// The geom's box (aabb, in its frame at pos, quat in the body frame), turned into the
// body's inertial frame (ipos, iquat).
Element MakeElement(const BvhGeom& g, const double* ipos, const double* iquat) {
  Element e;
  e.geom = g.id;
  const double* aabb = g.aabb;
  double inverse[4], offset[3];
  math::NegQuat(inverse, iquat);
  math::Sub3(offset, g.pos, ipos);
  math::RotVecQuat(e.centre, offset, inverse);
  for (int k = 0; k < 3; k++) {
    e.aamm[k] = kMaxVal;
    e.aamm[3 + k] = -kMaxVal;
  }
  // The eight corners: geom frame -> body frame -> inertial frame.
  for (int v = 0; v < 8; v++) {
    double corner[3], body[3], inertial[3];
    for (int k = 0; k < 3; k++) {
      double sign = (v >> k) & 1 ? 1 : -1;
      corner[k] = aabb[k] + sign * aabb[3 + k];
    }
    math::RotVecQuat(body, corner, g.quat);
    math::Add3(body, body, offset);
    math::RotVecQuat(inertial, body, inverse);
    for (int k = 0; k < 3; k++) {
      e.aamm[k] = std::min(e.aamm[k], inertial[k]);
      e.aamm[3 + k] = std::max(e.aamm[3 + k], inertial[k]);
    }
  }
  return e;
}

// Builds the tree below a new node over elements [begin, end); returns the node's
// index within the body's tree.
class TreeBuilder {
 public:
  TreeBuilder(std::vector<int>& child, std::vector<int>& nodeid, std::vector<int>& depth,
              std::vector<double>& aabb)
      : child_(child), nodeid_(nodeid), depth_(depth), aabb_(aabb) {}

  int Build(std::vector<Element>::iterator begin, std::vector<Element>::iterator end, int level) {
    int index = static_cast<int>(nodeid_.size());
    double aamm[6];
    Bounds(begin, end, aamm);
    child_.insert(child_.end(), {-1, -1});
    nodeid_.push_back(-1);
    depth_.push_back(level);
    for (int k = 0; k < 3; k++) {
      aabb_.push_back(0.5 * (aamm[3 + k] + aamm[k]));
    }
    for (int k = 0; k < 3; k++) {
      aabb_.push_back(0.5 * (aamm[3 + k] - aamm[k]));
    }
    if (end - begin == 1) {
      nodeid_[index] = begin->geom;
      return index;
    }
    int axis = LongestBoxSide(aamm);
    std::sort(begin, end, [axis](const Element& a, const Element& b) {
      if (a.centre[axis] != b.centre[axis]) return a.centre[axis] < b.centre[axis];
      return a.geom < b.geom;
    });
    auto middle = begin + (end - begin) / 2;
    int left = Build(begin, middle, level + 1);
    int right = Build(middle, end, level + 1);
    child_[2 * index] = left;
    child_[2 * index + 1] = right;
    return index;
  }

 private:
  // The box around the elements (flat sides inflated).
  static void Bounds(std::vector<Element>::iterator begin, std::vector<Element>::iterator end,
                     double* aamm) {
    for (int k = 0; k < 3; k++) {
      aamm[k] = kMaxVal;
      aamm[3 + k] = -kMaxVal;
    }
    for (auto e = begin; e != end; ++e) {
      for (int k = 0; k < 3; k++) {
        aamm[k] = std::min(aamm[k], e->aamm[k]);
        aamm[3 + k] = std::max(aamm[3 + k], e->aamm[3 + k]);
      }
    }
    InflateFlatBox(aamm);
  }

  std::vector<int>& child_;
  std::vector<int>& nodeid_;
  std::vector<int>& depth_;
  std::vector<double>& aabb_;
};

}  // namespace

std::vector<int> BvhNodeGeoms(const std::vector<BvhGeom>& geoms, const double* ipos,
                              const double* iquat) {
  std::vector<int> child, nodeid, depth;
  std::vector<double> aabb;
  TreeBuilder builder(child, nodeid, depth, aabb);
  std::vector<Element> elements;
  for (const BvhGeom& g : geoms) elements.push_back(MakeElement(g, ipos, iquat));
  if (!elements.empty()) builder.Build(elements.begin(), elements.end(), 0);
  return nodeid;
}

void CompileBodyBvh(Model* m, const CompileState& state) {
  std::vector<int> child, nodeid, depth;
  std::vector<double> aabb;
  TreeBuilder builder(child, nodeid, depth, aabb);
  for (int b = 0; b < m->nbody; b++) {
    // body_margin: the widest margin among the body's geoms (MuJoCo 3.5.1; 3.12 adds the gap).
    m->body_margin[b] = 0;
    std::vector<Element> elements;
    for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; g++) {
      m->body_margin[b] = std::max(m->body_margin[b], m->geom_margin[g]);
      if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
      BvhGeom geom{g, &m->geom_aabb[6 * g], &m->geom_pos[3 * g], &m->geom_quat[4 * g]};
      elements.push_back(MakeElement(geom, &m->body_ipos[3 * b], &m->body_iquat[4 * b]));
    }
    int base = static_cast<int>(nodeid.size());
    m->body_bvhadr[b] = elements.empty() ? -1 : base;
    if (!elements.empty()) builder.Build(elements.begin(), elements.end(), 0);
    m->body_bvhnum[b] = static_cast<int>(nodeid.size()) - base;
    // Inner nodes keep what earlier trees of a body that took fused bodies left there.
    const std::vector<int>& stale = state.bodies[b].stale_bvh_nodeid;
    for (int k = 0; k < m->body_bvhnum[b] && k < static_cast<int>(stale.size()); k++) {
      int& id = nodeid[static_cast<size_t>(base + k)];
      if (child[2 * static_cast<size_t>(base + k)] >= 0 && id < 0) id = stale[static_cast<size_t>(k)];
    }
    // Children are numbered within the body's tree.
    for (size_t k = 2 * static_cast<size_t>(base); k < child.size(); k++) {
      if (child[k] >= 0) child[k] -= base;
    }
  }
  // Zero nodes past the trees (fusestatic's count, see CompileState::fused_bvh_padding).
  const int padding = state.fused_bvh_padding;
  child.resize(child.size() + 2 * static_cast<size_t>(padding), 0);
  nodeid.resize(nodeid.size() + static_cast<size_t>(padding), 0);
  depth.resize(depth.size() + static_cast<size_t>(padding), 0);
  aabb.resize(aabb.size() + 6 * static_cast<size_t>(padding), 0);
  m->nbvh = static_cast<int>(nodeid.size());
  m->nbvhstatic = m->nbvh;  // (the flexes' trees follow: CompileFlexBvh)
  m->nbvhdynamic = 0;
  m->bvh_child = std::move(child);
  m->bvh_nodeid = std::move(nodeid);
  m->bvh_depth = std::move(depth);
  m->bvh_aabb = std::move(aabb);
}

void InflateFlatBox(double aamm[6]) {
  for (int k = 0; k < 3; k++) {
    if (std::abs(aamm[3 + k] - aamm[k]) < kFlatBox) {
      aamm[k] -= kFlatBox;
      aamm[3 + k] += kFlatBox;
    }
  }
}

int LongestBoxSide(const double aamm[6]) {
  double edges[3] = {aamm[3] - aamm[0], aamm[4] - aamm[1], aamm[5] - aamm[2]};
  int axis = 0;
  if (edges[1] >= edges[0] + kFlatBox) axis = 1;
  if (edges[2] >= edges[axis] + kFlatBox) axis = 2;
  return axis;
}

}  // namespace simlab::compiler
