// Bounding volume hierarchies of the flexes, for the collision midphase (MuJoCo's
// mjCFlex::CreateBVH with its mjCBoundingVolumeHierarchy).
//
// Each flex gets a binary tree over its active elements (all of them for lines and
// triangles; tetrahedra of the first activelayers layers), built from the elements'
// world boxes at qpos0 (grown by the flex radius): each node splits its elements at the
// median of their box centres along its longest side, down to one element per leaf.
// Only the tree's shape is kept in the model (bvh_child, bvh_depth, bvh_nodeid = the
// element of a leaf); the boxes move with the flex and are recomputed every step in
// Data::bvh_aabb_dyn. The trees follow the bodies' trees in bvh_*.
//
// The shape matters: a flex's self-collision walks its tree and keeps the contacts in the
// order it finds them. MuJoCo splits with std::nth_element under an order that takes
// centres within mjEPS as equal and then orders by element; the same split comes from a
// full sort under that order, done here by a merge sort (well defined whatever the data).
#include <algorithm>
#include <cmath>
#include <vector>

#include "compiler/compiler.h"
#include "engine/engine.h"

namespace simlab::compiler {

namespace {

constexpr double kFlatBox = 1e-14;  // flat boxes are inflated, centres compared, to mjEPS

using FlexElement = FlexElementBox;

// MuJoCo's median order along an axis: centres farther apart than mjEPS by centre,
// otherwise by element.
bool Before(const FlexElement& a, const FlexElement& b, int axis) {
  if (std::abs(a.aabb[axis] - b.aabb[axis]) > kFlatBox) return a.aabb[axis] < b.aabb[axis];
  return a.id < b.id;
}

// Stable merge sort of [begin, end) under Before (scratch: as long as the range).
void MergeSort(FlexElement* begin, FlexElement* end, int axis, FlexElement* scratch) {
  long n = end - begin;
  if (n < 2) return;
  FlexElement* middle = begin + n / 2;
  MergeSort(begin, middle, axis, scratch);
  MergeSort(middle, end, axis, scratch);
  FlexElement *left = begin, *right = middle, *out = scratch;
  while (left < middle && right < end) {
    *out++ = Before(*right, *left, axis) ? *right++ : *left++;
  }
  out = std::copy(left, middle, out);
  out = std::copy(right, end, out);
  std::copy(scratch, out, begin);
}

// Builds the tree below a new node over [begin, end); returns the node's index within
// the flex's tree (nodes in preorder, the left child first).
class FlexTreeBuilder {
 public:
  FlexTreeBuilder(std::vector<int>& child, std::vector<int>& nodeid, std::vector<int>& depth,
                  std::vector<FlexElement>& scratch)
      : child_(child), nodeid_(nodeid), depth_(depth), scratch_(scratch) {}

  int Build(FlexElement* begin, FlexElement* end, int level, int base) {
    int index = static_cast<int>(nodeid_.size()) - base;
    double aamm[6];
    Bounds(begin, end, aamm);
    child_.insert(child_.end(), {-1, -1});
    nodeid_.push_back(-1);
    depth_.push_back(level);
    if (end - begin == 1) {
      nodeid_.back() = begin->id;
      return index;
    }
    int axis = LongestBoxSide(aamm);
    MergeSort(begin, end, axis, scratch_.data());
    FlexElement* middle = begin + (end - begin) / 2;
    int left = Build(begin, middle, level + 1, base);
    int right = Build(middle, end, level + 1, base);
    child_[2 * static_cast<size_t>(base + index)] = left;
    child_[2 * static_cast<size_t>(base + index) + 1] = right;
    return index;
  }

 private:
  // The box around the elements' boxes, flat sides inflated.
  static void Bounds(const FlexElement* begin, const FlexElement* end, double* aamm) {
    for (int k = 0; k < 3; k++) {
      aamm[k] = begin->aabb[k] - begin->aabb[3 + k];
      aamm[3 + k] = begin->aabb[k] + begin->aabb[3 + k];
    }
    for (const FlexElement* e = begin; e != end; ++e) {
      for (int k = 0; k < 3; k++) {
        aamm[k] = std::min(aamm[k], e->aabb[k] - e->aabb[3 + k]);
        aamm[3 + k] = std::max(aamm[3 + k], e->aabb[k] + e->aabb[3 + k]);
      }
    }
    InflateFlatBox(aamm);
  }

  std::vector<int>& child_;
  std::vector<int>& nodeid_;
  std::vector<int>& depth_;
  std::vector<FlexElement>& scratch_;
};

}  // namespace

std::vector<FlexElementBox> ActiveFlexElements(const FlexState& flex) {
  const mjcf::FlexSpec& spec = *flex.spec;
  int dim = spec.dim;
  std::vector<FlexElementBox> elements;
  for (int e = 0; e < flex.nelem; e++) {
    if (dim == 3 && flex.elemlayer[e] >= spec.activelayers) continue;
    FlexElementBox element;
    element.id = e;
    FlexElementAabb(flex.vertxpos.data(), flex.elem.data() + static_cast<size_t>(dim + 1) * e, dim,
                    spec.radius, element.aabb);
    elements.push_back(element);
  }
  return elements;
}

void CompileFlexBvh(Model* m, const CompileState& state) {
  std::vector<int> child = std::move(m->bvh_child);
  std::vector<int> nodeid = std::move(m->bvh_nodeid);
  std::vector<int> depth = std::move(m->bvh_depth);
  for (int f = 0; f < m->nflex && f < static_cast<int>(state.flexes.size()); f++) {
    std::vector<FlexElement> elements = ActiveFlexElements(state.flexes[f]);
    int base = static_cast<int>(nodeid.size());
    m->flex_bvhadr[f] = elements.empty() ? -1 : base;
    if (!elements.empty()) {
      std::vector<FlexElement> scratch(elements.size());
      FlexTreeBuilder builder(child, nodeid, depth, scratch);
      builder.Build(elements.data(), elements.data() + elements.size(), 0, base);
    }
    m->flex_bvhnum[f] = static_cast<int>(nodeid.size()) - base;
  }
  m->nbvh = static_cast<int>(nodeid.size());
  m->nbvhdynamic = m->nbvh - m->nbvhstatic;
  m->bvh_child = std::move(child);
  m->bvh_nodeid = std::move(nodeid);
  m->bvh_depth = std::move(depth);
}

}  // namespace simlab::compiler
