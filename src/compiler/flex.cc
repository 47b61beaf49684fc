// Flexes (MuJoCo's mjCFlex::Compile and the flex part of mjCModel::CopyObjects): the
// checks, the vertices' world positions at qpos0, tetrahedra turned outward, edges
// numbered as they first appear, flaps and elasticity (flex_elasticity.cc), shells and
// element-vertex collision pairs, element layers, and the box that flex_vert0 is
// relative to. The constants at qpos0 (edge Jacobian sparsity, rest lengths, inverse
// weights) are set by ComputeConstants (constants.cc, FlexConstants).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/flex_cells.h"
#include "compiler/flex_elasticity.h"
#include "compiler/orientation.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

namespace {

constexpr double kMinVal = 1e-15;  // MuJoCo's mjMINVAL

// Sizes and flags MuJoCo checks before anything else.
void CheckFlexSpec(const mjcf::FlexSpec& f, bool interpolated) {
  const mjcf::Source& at = f.src;
  if (f.dim < 1 || f.dim > 3) ThrowAt(at, "dim must be 1, 2 or 3");
  if (f.elem.empty()) ThrowAt(at, "elem is empty");
  if (f.elem.size() % (f.dim + 1)) ThrowAt(at, "elem size must be multiple of (dim+1)");
  if (f.vertbody.empty() && !interpolated) ThrowAt(at, "vertbody and nodebody are both empty");
  if (f.vert.size() % 3) ThrowAt(at, "vert size must be a multiple of 3");
  if (f.edgestiffness > 0 && f.dim > 1) {
    ThrowAt(at, "edge stiffness only available for dim=1, please use elasticity plugins");
  }
  if (interpolated && f.selfcollide != kFlexSelfNone) {
    ThrowAt(at, "trilinear interpolation cannot do self-collision");
  }
  if (interpolated && f.internal) ThrowAt(at, "trilinear interpolation cannot do internal collisions");
}

// The cells of cellcount c (which may be anything written), in 64 bits.
int64_t CellProduct(const std::array<int, 3>& c) {
  return static_cast<int64_t>(c[0]) * c[1] * c[2];
}

// A flex with an interpolation order (dof; MuJoCo 3.12): its lattice from its cellcount
// and order, and as many nodes.
void CheckLattice(const mjcf::FlexSpec& f, FlexState* flex) {
  const std::array<int, 3>& c = f.cellcount;
  if (c[0] == 0 || c[1] == 0 || c[2] == 0) {
    ThrowAt(f.src, "cellcount cannot be 0 in any dimension when interpolation order > 0");
  }
  if (c[0] < 0 || c[1] < 0 || c[2] < 0) ThrowAt(f.src, "cellcount must be positive");
  FlexLattice& g = flex->lattice;
  g.cells = c;
  g.order = flex->order;
  g.shell = f.elastic2d != mjcf::kElastic2DNone;
  // The lattice's nodes (saturated: cellcount may be anything written).
  constexpr int64_t kMost = std::numeric_limits<int64_t>::max();
  int64_t expected = 1;
  for (int k = 0; k < 3; k++) {
    int64_t along = static_cast<int64_t>(c[k]) * g.order + 1;
    expected = expected > kMost / along ? kMost : expected * along;
  }
  if (flex->nnode != expected) {
    std::string count = expected == kMost ? "at least 2^63" : std::to_string(expected);
    ThrowAt(f.src, "number of nodes (" + std::to_string(flex->nnode) +
                       ") does not match cellcount and dof expected (" + count + ")");
  }
}

// The number of vertices, whether they all sit at their bodies' origins (no vertex
// data) or all in one body, and the interpolation order from the node count.
void CountVertices(const mjcf::FlexSpec& f, FlexState* flex) {
  if (f.vert.empty()) {
    flex->centered = true;
    flex->nvert = static_cast<int>(f.vertbody.size());
  } else {
    flex->nvert = static_cast<int>(f.vert.size() / 3);
    if (f.vertbody.size() == 1) {
      flex->rigid = true;
    } else if (static_cast<int>(f.vertbody.size()) != flex->nvert) {
      ThrowAt(f.src, "vertbody size must be 1 or nvert");
    }
  }
  if (flex->nvert < f.dim + 1) ThrowAt(f.src, "not enough vertices");
  flex->nnode = static_cast<int>(f.nodebody.size());
  flex->order = f.order;
  if (flex->nnode && !flex->order && flex->cells) {
    ThrowAt(f.src, "Interpolation order must be explicitly specified (dof is missing)");
  }
  if (flex->nnode && !flex->order) {
    flex->order = static_cast<int>(std::pow(flex->nnode, 1.0 / 3) - 1);
    if (flex->nnode != static_cast<int>(std::pow(flex->order + 1, 3))) {
      ThrowAt(f.src, "number of nodes must be " + std::to_string(flex->order) + "^3 but it is " +
                         std::to_string(flex->nnode));
    }
  }
  // (MuJoCo's engine holds at most mjMAXFLEXNODES = 27 nodes per cell: order 2)
  if (flex->order > 2) ThrowAt(f.src, "a flex interpolates from at most 27 nodes (order 2)");
  // (an order written as dof, MuJoCo 3.12's, asks for the lattice's nodes even of one cell)
  if (flex->cells || f.order > 0) CheckLattice(f, flex);
  for (int v : f.elem) {
    if (v < 0 || v >= flex->nvert) ThrowAt(f.src, "elem vertex id out of range");
  }
}

// Texture coordinates: two per vertex, and per element corner (the elements' own
// vertices when not given).
void FlexTexcoords(const mjcf::FlexSpec& f, FlexState* flex) {
  if (!f.texcoord.empty() && f.texcoord.size() != 2 * static_cast<size_t>(flex->nvert) &&
      f.elemtexcoord.empty()) {
    ThrowAt(f.src, "two texture coordinates per vertex expected");
  }
  flex->elemtexcoord = f.elemtexcoord;
  if (f.elemtexcoord.empty() && !f.texcoord.empty()) {
    size_t n = std::min(3 * static_cast<size_t>(flex->nelem), f.elem.size());
    flex->elemtexcoord.assign(3 * static_cast<size_t>(flex->nelem), 0);
    std::copy(f.elem.begin(), f.elem.begin() + n, flex->elemtexcoord.begin());
  }
}

// Does flex f bend its triangles between vertices of its own (not an interpolated flex's,
// which ride on its nodes)?
bool BendsVertices(const mjcf::FlexSpec& f) {
  bool bending = f.elastic2d == mjcf::kElastic2DBend || f.elastic2d == mjcf::kElastic2DBoth;
  return f.dim == 2 && bending && f.nodebody.empty();
}

// The body of each vertex and node, by name. A bending flex's vertices each need three
// slide joints, or (MuJoCo 3.12) none: pinned to a static body.
void FindFlexBodies(const mjcf::FlexSpec& f, const CompileState& state, const NameIndex& bodies,
                    FlexState* flex) {
  for (const std::string& name : f.vertbody) {
    int id = bodies.Find(name);
    if (id < 0) ThrowAt(f.src, "unknown body '" + name + "' in flex");
    int njoint = state.bodies[id].joint_num;
    if (njoint != 3 && BendsVertices(f)) {
      if (state.release == Release::k3_5_1) ThrowAt(f.src, "pins are not supported for bending");
      if (njoint != 0) {
        ThrowAt(f.src, "pinned flex vertices with bending require a static (jointless) pin body, body '" +
                           name + "' has joints");
      }
    }
    flex->vertbodyid.push_back(id);
  }
  for (const std::string& name : f.nodebody) {
    int id = bodies.Find(name);
    if (id < 0) ThrowAt(f.src, "unknown body '" + name + "' in flex");
    flex->nodebodyid.push_back(id);
  }
}

// res = a b, normalized (MuJoCo's compiler composes poses with mjuu_mulquat).
void UserMulQuat(double* res, const double* a, const double* b) {
  double q[4] = {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                 a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                 a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                 a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
  NormalizeVec(q, 4);
  for (int k = 0; k < 4; k++) res[k] = q[k];
}

// Every body's frame in the world at qpos0 (MuJoCo's xpos0, xquat0).
void BodyFramesAtQpos0(const CompileState& state, std::vector<double>* xpos,
                       std::vector<double>* xquat) {
  size_t n = state.bodies.size();
  xpos->assign(3 * n, 0);
  xquat->assign(4 * n, 0);
  (*xquat)[0] = 1;
  for (size_t b = 1; b < n; b++) {
    const BodyState& body = state.bodies[b];
    const double* ppos = xpos->data() + 3 * body.parent;
    const double* pquat = xquat->data() + 4 * body.parent;
    double* pos = xpos->data() + 3 * b;
    math::RotVecQuat(pos, body.pos, pquat);
    for (int k = 0; k < 3; k++) pos[k] += ppos[k];
    UserMulQuat(xquat->data() + 4 * b, pquat, body.quat);
  }
}

// World positions at qpos0 of `count` points with offsets `local` (none: the body
// origins) in bodies `bodyid` (or all in bodyid[0] when `one_body`).
std::vector<double> WorldPoints(int count, const std::vector<int>& bodyid, bool one_body,
                                const std::vector<double>& local, bool use_local,
                                const std::vector<double>& xpos, const std::vector<double>& xquat) {
  std::vector<double> out(3 * static_cast<size_t>(count));
  for (int i = 0; i < count; i++) {
    int b = one_body ? bodyid[0] : bodyid[i];
    double* p = out.data() + 3 * i;
    for (int k = 0; k < 3; k++) p[k] = xpos[3 * b + k];
    if (use_local) {
      double offset[3];
      math::RotVecQuat(offset, local.data() + 3 * i, xquat.data() + 4 * b);
      for (int k = 0; k < 3; k++) p[k] += offset[k];
    }
  }
  return out;
}

// Tetrahedra with faces (0,1,2), (0,2,3), (0,3,1), (1,3,2) turned outward: vertices 1
// and 2 swap where the third vertex lies on the positive side of the first face.
void OrientTetrahedra(FlexState* flex) {
  for (int e = 0; e < flex->nelem; e++) {
    int* t = flex->elem.data() + 4 * e;
    const double* v0 = flex->vertxpos.data() + 3 * t[0];
    double a[3], b[3], c[3], normal[3];
    for (int k = 0; k < 3; k++) {
      a[k] = flex->vertxpos[3 * t[1] + k] - v0[k];
      b[k] = flex->vertxpos[3 * t[2] + k] - v0[k];
      c[k] = flex->vertxpos[3 * t[3] + k] - v0[k];
    }
    math::Cross3(normal, a, b);
    if (normal[0] * c[0] + normal[1] * c[1] + normal[2] * c[2] > 0) std::swap(t[1], t[2]);
  }
}

// The edges, numbered as they first appear going through the elements' local edges,
// and each element's edge ids.
void MakeEdges(int dim, FlexState* flex) {
  int per_elem = kFlexElemEdgeCount[dim - 1];
  std::map<std::array<int, 2>, int> ids;
  flex->elemedge.assign(static_cast<size_t>(flex->nelem) * per_elem, 0);
  for (int e = 0; e < flex->nelem; e++) {
    const int* v = flex->elem.data() + (dim + 1) * e;
    for (int k = 0; k < per_elem; k++) {
      int a = v[kFlexElemEdges[dim - 1][k][0]], b = v[kFlexElemEdges[dim - 1][k][1]];
      std::array<int, 2> key = {std::min(a, b), std::max(a, b)};
      auto [it, inserted] = ids.emplace(key, static_cast<int>(flex->edge.size()));
      if (inserted) flex->edge.push_back(key);
      flex->elemedge[static_cast<size_t>(e) * per_elem + k] = it->second;
    }
  }
}

// A flex made of cells: the stiffness of its cells or faces (with a Young's modulus, or
// their stiff modes for strain equality), and a shell's bending between its faces.
void MakeCellElasticity(const mjcf::FlexSpec& f, bool strain, FlexState* flex) {
  if (f.young > 0 && (f.poisson < 0 || f.poisson >= 0.5)) {
    ThrowAt(f.src, "Poisson ratio must be in [0, 0.5)");
  }
  if (f.young > 0 || strain) {
    std::string error = FlexCellStiffness(flex->lattice, flex->cell_empty, flex->nodelocal,
                                          f.young, f.poisson, f.thickness, strain, &flex->stiffness);
    if (!error.empty()) ThrowAt(f.src, error);
  }
  bool bending = f.elastic2d == mjcf::kElastic2DBend || f.elastic2d == mjcf::kElastic2DBoth;
  if (flex->lattice.shell && bending && f.thickness > 0 && f.young > 0) {
    FlexShellBending(flex->lattice, flex->nodelocal, f.young, f.poisson, f.thickness,
                     &flex->bending);
  }
}

// Stiffness of the elements and bending of the edges (only with a Young's modulus).
void MakeElasticity(const mjcf::FlexSpec& f, bool strain, FlexState* flex) {
  int nedge = static_cast<int>(flex->edge.size());
  if (f.dim == 2) flex->flaps = FlexFlaps(f.dim, flex->elem, flex->elemedge, nedge);
  if (flex->cells) return MakeCellElasticity(f, strain, flex);
  if (f.young <= 0) return;
  if (f.poisson < 0 || f.poisson >= 0.5) ThrowAt(f.src, "Poisson ratio must be in [0, 0.5)");
  if (flex->interpolated) {
    size_t n = flex->nodexpos.size();
    int min_size = static_cast<int>(std::ceil(static_cast<double>(n * n / 21)));
    if (min_size > flex->nelem) {
      ThrowAt(f.src, "Trilinear dofs are require at least " + std::to_string(min_size) + " elements");
    }
    // (zeroed for FlexInterpolatedStiffness, which subtracts into them)
    flex->stiffness.assign(kFlexStiffnessSize * static_cast<size_t>(flex->nelem), 0);
  } else {
    FlexElementStiffness(f.dim, f.elastic2d, f.young, f.poisson, f.thickness, flex->vertxpos,
                         flex->elem, &flex->stiffness);
  }
  if (f.dim == 2 && (f.elastic2d == mjcf::kElastic2DBend || f.elastic2d == mjcf::kElastic2DBoth)) {
    if (f.thickness < 0) ThrowAt(f.src, "thickness must be positive for bending stiffness");
    FlexBending(f.young, f.poisson, f.thickness, flex->vertxpos, flex->flaps, &flex->bending);
  }
}

// A fragment of an element's boundary (a vertex of a segment, an edge of a triangle, a
// face of a tetrahedron): its vertices sorted, its element, its vertices as the
// element lists them.
struct Fragment {
  std::vector<int> sorted;
  int elem = 0;
  std::vector<int> original;
  bool operator<(const Fragment& o) const {
    if (sorted != o.sorted) return sorted < o.sorted;
    if (elem != o.elem) return elem < o.elem;
    return original < o.original;
  }
};

// The boundary fragments of every element, in MuJoCo's order per element.
std::vector<Fragment> ElementFragments(int dim, const FlexState& flex) {
  static const int kSegment[2][1] = {{0}, {1}};
  static const int kTriangle[3][2] = {{0, 1}, {2, 0}, {1, 2}};
  static const int kTetrahedron[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  std::vector<Fragment> frags;
  for (int e = 0; e < flex.nelem; e++) {
    const int* el = flex.elem.data() + (dim + 1) * e;
    for (int k = 0; k <= dim; k++) {
      Fragment f;
      f.elem = e;
      for (int j = 0; j < dim; j++) {
        int local = dim == 1 ? kSegment[k][j] : dim == 2 ? kTriangle[k][j] : kTetrahedron[k][j];
        f.original.push_back(el[local]);
      }
      f.sorted = f.original;
      std::sort(f.sorted.begin(), f.sorted.end());
      frags.push_back(std::move(f));
    }
  }
  return frags;
}

// Shells (the fragments no other element shares), element layers (distance from the
// boundary, 3D), and element-vertex collision pairs of neighbouring elements at the
// boundary (1D and 2D): MuJoCo's CreateShellPair.
void MakeShellsAndPairs(int dim, FlexState* flex) {
  std::vector<Fragment> frags = ElementFragments(dim, *flex);
  std::sort(frags.begin(), frags.end());
  std::vector<bool> border(flex->nelem, false), border_frag(frags.size(), false);
  std::vector<std::array<int, 2>> connect;  // element pairs sharing a fragment
  std::vector<std::vector<int>> shared;     // and the fragment
  int run = 1;
  for (size_t n = 1; n <= frags.size(); n++) {
    if (n < frags.size() && frags[n].sorted == frags[n - 1].sorted) {
      connect.push_back({frags[n - 1].elem, frags[n].elem});
      shared.push_back(frags[n].sorted);
      run++;
      continue;
    }
    if (run == 1) {
      border[frags[n - 1].elem] = true;
      border_frag[n - 1] = true;
    }
    run = 1;
  }
  for (size_t i = 0; i < frags.size(); i++) {
    if (border_frag[i]) flex->shell.insert(flex->shell.end(), frags[i].original.begin(), frags[i].original.end());
  }

  // Layers: 0 at the border, then the fewest steps to it through shared faces.
  flex->elemlayer.assign(flex->nelem, dim < 3 ? 0 : flex->nelem + 1);
  if (dim == 3) {
    for (int e = 0; e < flex->nelem; e++) {
      if (border[e]) flex->elemlayer[e] = 0;
    }
    for (bool change = true; change;) {
      change = false;
      for (const auto& c : connect) {
        int& l1 = flex->elemlayer[c[0]];
        int& l2 = flex->elemlayer[c[1]];
        if (l1 > l2 + 1) {
          l1 = l2 + 1;
          change = true;
        } else if (l2 > l1 + 1) {
          l2 = l1 + 1;
          change = true;
        }
      }
    }
    return;
  }

  // Element-vertex pairs: each element of a bordering pair with the other's far vertex.
  for (size_t i = 0; i < connect.size(); i++) {
    if (!border[connect[i][0]] && !border[connect[i][1]]) continue;
    for (int side = 0; side < 2; side++) {
      const int* el = flex->elem.data() + (dim + 1) * connect[i][side];
      for (int k = 0; k <= dim; k++) {
        if (std::find(shared[i].begin(), shared[i].end(), el[k]) != shared[i].end()) continue;
        flex->evpair.push_back(connect[i][1 - side]);
        flex->evpair.push_back(el[k]);
        break;
      }
    }
  }
}

// The box of the active elements (each grown by the radius), as the root of MuJoCo's
// flex BVH holds it; the vertices' places in it on [0, 1]^3 (flex_vert0) and its half
// sizes without the radius (flex_size).
void VertexBox(const mjcf::FlexSpec& f, FlexState* flex) {
  constexpr double kMax = std::numeric_limits<double>::max();
  double aamm[6] = {kMax, kMax, kMax, -kMax, -kMax, -kMax};
  for (const FlexElementBox& e : ActiveFlexElements(*flex)) {
    for (int k = 0; k < 3; k++) {
      aamm[k] = std::min(aamm[k], e.aabb[k] - e.aabb[k + 3]);
      aamm[k + 3] = std::max(aamm[k + 3], e.aabb[k] + e.aabb[k + 3]);
    }
  }
  InflateFlatBox(aamm);
  double center[3];
  for (int k = 0; k < 3; k++) {
    center[k] = (aamm[k + 3] + aamm[k]) / 2;
    flex->size[k] = (aamm[k + 3] - aamm[k]) / 2 - f.radius;
  }
  flex->vert0.assign(3 * static_cast<size_t>(flex->nvert), 0);
  for (int j = 0; j < flex->nvert; j++) {
    for (int k = 0; k < 3; k++) {
      flex->vert0[3 * j + k] = flex->size[k] > kMinVal
                                   ? (flex->vertxpos[3 * j + k] - center[k]) / (2 * flex->size[k]) + 0.5
                                   : 0.5;
    }
  }
}

// A flex made of cells: its empty cells (from a flexcomp, else from its elements; none
// for a shell), its nodes turned by the lattice's rotation R0 (flex_node0), and its
// vertices' places in the box of the turned nodes (flex_vert0, flex_size).
void PrepareCells(const mjcf::FlexSpec& f, FlexState* flex) {
  FlexLattice& g = flex->lattice;
  flex->cell_empty = f.cell_empty;
  if (flex->cell_empty.empty() && !g.shell && g.CellCount() > 1) {
    flex->cell_empty = EmptyFlexCells(g.cells, flex->vertxpos, f.elem, f.dim, nullptr);
  }
  double r0[9];
  std::string error = UnrotatedFlexNodes(g, flex->cell_empty, flex->nodexpos, &flex->nodelocal, r0);
  if (!error.empty()) ThrowAt(f.src, error);

  // The turned nodes' box, and each turned vertex's place in it.
  double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
  for (size_t i = 0; i + 2 < flex->nodelocal.size(); i += 3) {
    for (int k = 0; k < 3; k++) {
      lo[k] = std::min(lo[k], flex->nodelocal[i + k]);
      hi[k] = std::max(hi[k], flex->nodelocal[i + k]);
    }
  }
  for (int k = 0; k < 3; k++) flex->size[k] = (hi[k] - lo[k]) / 2;
  flex->vert0.assign(3 * static_cast<size_t>(flex->nvert), 0);
  for (int j = 0; j < flex->nvert; j++) {
    double local[3];
    math::MulMatVec3(local, r0, flex->vertxpos.data() + 3 * j);
    for (int k = 0; k < 3; k++) {
      double extent = hi[k] - lo[k];
      flex->vert0[3 * j + k] = extent > kMinVal ? (local[k] - lo[k]) / extent : 0.5;
    }
  }
}

// One flex, compiled.
FlexState CompileFlex(const mjcf::FlexSpec& f, bool strain, const CompileState& state,
                      const NameIndex& bodies, const NameIndex& materials,
                      const std::vector<double>& xpos, const std::vector<double>& xquat) {
  FlexState flex;
  flex.spec = &f;
  flex.interpolated = !f.nodebody.empty();
  CheckFlexSpec(f, flex.interpolated);
  flex.cells = flex.interpolated && (CellProduct(f.cellcount) != 1 ||
                                     f.elastic2d != mjcf::kElastic2DNone || strain);
  if (flex.cells && f.elastic2d != mjcf::kElastic2DNone) {
    if (f.thickness <= 0) ThrowAt(f.src, "2d elasticity requires positive thickness");
    if (f.poisson < 0 || f.poisson >= 0.5) ThrowAt(f.src, "Poisson ratio must be in [0, 0.5)");
  }
  flex.nelem = static_cast<int>(f.elem.size() / (f.dim + 1));
  CountVertices(f, &flex);
  FlexTexcoords(f, &flex);
  flex.matid = f.material.empty() ? -1 : materials.Find(f.material);
  if (!f.material.empty() && flex.matid < 0) ThrowAt(f.src, "unknown material '" + f.material + "' in flex");
  FindFlexBodies(f, state, bodies, &flex);

  // Repeated vertices in an element.
  for (int e = 0; e < flex.nelem; e++) {
    std::vector<int> el(f.elem.begin() + (f.dim + 1) * e, f.elem.begin() + (f.dim + 1) * (e + 1));
    std::sort(el.begin(), el.end());
    if (std::adjacent_find(el.begin(), el.end()) != el.end()) ThrowAt(f.src, "repeated vertex in element");
  }

  // Rigid: every vertex in one body. Centered: every vertex at its body's origin.
  if (!flex.rigid && !flex.interpolated) {
    flex.rigid = std::all_of(flex.vertbodyid.begin(), flex.vertbodyid.end(),
                             [&](int b) { return b == flex.vertbodyid[0]; });
  }
  const std::vector<double>& local = flex.interpolated ? f.node : f.vert;
  if (!flex.centered) flex.centered = std::all_of(local.begin(), local.end(), [](double v) { return v == 0; });

  // World positions at qpos0; an interpolated flex's vertices are in its parent body.
  flex.vertxpos = WorldPoints(flex.nvert, flex.vertbodyid, flex.rigid, f.vert,
                              !flex.centered || flex.interpolated, xpos, xquat);
  if (flex.interpolated) flex.vertbodyid.assign(flex.nvert, -1);
  flex.nodexpos = WorldPoints(flex.nnode, flex.nodebodyid, false, f.node, !flex.centered, xpos, xquat);

  flex.elem = f.elem;
  if (f.dim == 3) OrientTetrahedra(&flex);
  if (flex.cells) PrepareCells(f, &flex);
  MakeEdges(f.dim, &flex);
  MakeElasticity(f, strain, &flex);
  MakeShellsAndPairs(f.dim, &flex);
  if (flex.cells) return flex;
  if (f.young > 0 && flex.interpolated) {
    FlexInterpolatedStiffness(f.young, f.poisson, flex.order, flex.nodexpos, &flex.stiffness);
  }
  VertexBox(f, &flex);

  // (MuJoCo 3.5.1's layout: 21 stiffness numbers per element, 17 bending per edge)
  flex.stiffness.resize(kFlexStiffnessSize * static_cast<size_t>(flex.nelem), 0);
  flex.bending.resize(kFlexBendingSize * flex.edge.size(), 0);
  return flex;
}

// The release the model follows: MuJoCo 3.12 when it uses a construct only 3.12 defines
// (the reader found it), or one 3.5.1 refuses and 3.12 accepts: a bending flex's vertex
// pinned to a static body.
Release ModelRelease(const mjcf::ModelSpec& spec, const CompileState& state, const NameIndex& bodies) {
  auto joints = [&](const std::string& name) {
    int id = bodies.Find(name);
    return id < 0 ? -1 : state.bodies[id].joint_num;
  };
  bool newer = !spec.newer_construct.tag.empty() || FlexBendingOnStaticPin(spec, joints);
  return newer ? Release::k3_12 : Release::k3_5_1;
}

}  // namespace

const mjcf::FlexSpec* FlexBendingOnStaticPin(const mjcf::ModelSpec& spec,
                                             const std::function<int(const std::string&)>& joints) {
  for (const mjcf::FlexSpec& f : spec.flexes) {
    if (!BendsVertices(f)) continue;
    for (const std::string& name : f.vertbody) {
      if (joints(name) == 0) return &f;
    }
  }
  return nullptr;
}

void CompileFlexes(const mjcf::ModelSpec& spec, CompileState* state) {
  NameIndex bodies = BodyNames(*state);
  state->release = ModelRelease(spec, *state, bodies);
  NameIndex materials = MaterialNames(spec);
  std::vector<double> xpos, xquat;
  BodyFramesAtQpos0(*state, &xpos, &xquat);
  state->flexes.clear();
  for (const mjcf::FlexSpec& f : spec.flexes) {
    bool strain = std::any_of(spec.equalities.begin(), spec.equalities.end(), [&](const auto& eq) {
      return eq.type == kEqFlexStrain && eq.name1 == f.src.name;
    });
    state->flexes.push_back(CompileFlex(f, strain, *state, bodies, materials, xpos, xquat));
  }
}

}  // namespace simlab::compiler

namespace simlab::compiler {

namespace {

// The dofs of the bodies on the paths from `bodies` to the world, each body once.
size_t PathDofs(const CompileState& state, const std::vector<int>& bodies) {
  std::vector<int> seen;
  size_t dofs = 0;
  for (int b : bodies) {
    for (; b >= 0; b = state.bodies[b].parent) {
      if (std::find(seen.begin(), seen.end(), b) != seen.end()) continue;
      seen.push_back(b);
      dofs += state.bodies[b].dofnum;
    }
  }
  return dofs;
}

}  // namespace

void FlexSizes(const CompileState& state, Model* m) {
  m->nflex = static_cast<int>(state.flexes.size());
  m->nflexnode = m->nflexvert = m->nflexedge = m->nflexelem = m->nflexelemdata = 0;
  m->nflexelemedge = m->nflexshelldata = m->nflexevpair = m->nflextexcoord = 0;
  m->nflexstiffness = m->nflexbending = 0;
  m->nJfe = m->nJfv = 0;
  for (const FlexState& f : state.flexes) {
    int dim = f.spec->dim;
    m->nflexnode += f.nnode;
    m->nflexvert += f.nvert;
    m->nflexedge += static_cast<int>(f.edge.size());
    m->nflexelem += f.nelem;
    m->nflexelemdata += f.nelem * (dim + 1);
    m->nflexelemedge += f.nelem * kFlexElemEdgeCount[dim - 1];
    m->nflexshelldata += static_cast<int>(f.shell.size());
    m->nflexevpair += static_cast<int>(f.evpair.size() / 2);
    m->nflextexcoord += static_cast<int>(f.spec->texcoord.size() / 2);
    m->nflexstiffness += static_cast<int>(f.stiffness.size());
    m->nflexbending += static_cast<int>(f.bending.size());
    if (f.interpolated || f.rigid) continue;

    // Nonzeros of the edge Jacobian: the dofs of the bodies on both vertices' paths to
    // the world; of the vertex Jacobian, those of a vertex's and its neighbours' paths.
    for (const auto& e : f.edge) {
      m->nJfe += static_cast<int>(
          PathDofs(state, {f.vertbodyid[e[0]], f.vertbodyid[e[1]]}));
    }
    std::vector<std::vector<int>> neighbours(f.nvert);
    for (const auto& e : f.edge) {
      neighbours[e[0]].push_back(e[1]);
      neighbours[e[1]].push_back(e[0]);
    }
    for (int v = 0; v < f.nvert; v++) {
      std::vector<int> bodies = {f.vertbodyid[v]};
      for (int n : neighbours[v]) bodies.push_back(f.vertbodyid[n]);
      m->nJfv += static_cast<int>(PathDofs(state, bodies));
    }
  }
}

namespace {

// Where each flex's vertices, nodes, edges, elements, shells, pairs and texture
// coordinates start in the shared arrays, and how many it has (-1: none, for shells,
// pairs and texture coordinates).
void FlexAddresses(const CompileState& state, Model* m) {
  int vert = 0, node = 0, edge = 0, elem = 0, elemdata = 0, elemedge = 0, shelldata = 0;
  int evpair = 0, texcoord = 0, stiffness = 0, bending = 0;
  for (int i = 0; i < m->nflex; i++) {
    const FlexState& f = state.flexes[i];
    int dim = f.spec->dim, ntexcoord = static_cast<int>(f.spec->texcoord.size() / 2);
    m->flex_vertadr[i] = vert;
    m->flex_vertnum[i] = f.nvert;
    m->flex_nodeadr[i] = node;
    m->flex_nodenum[i] = f.nnode;
    m->flex_edgeadr[i] = edge;
    m->flex_edgenum[i] = static_cast<int>(f.edge.size());
    m->flex_elemadr[i] = elem;
    m->flex_elemnum[i] = f.nelem;
    m->flex_elemdataadr[i] = elemdata;
    m->flex_elemedgeadr[i] = elemedge;
    m->flex_shellnum[i] = static_cast<int>(f.shell.size()) / dim;
    m->flex_shelldataadr[i] = m->flex_shellnum[i] ? shelldata : -1;
    m->flex_evpairnum[i] = static_cast<int>(f.evpair.size() / 2);
    m->flex_evpairadr[i] = f.evpair.empty() ? -1 : evpair;
    m->flex_texcoordadr[i] = ntexcoord ? texcoord : -1;
    m->flex_stiffnessadr[i] = f.stiffness.empty() ? -1 : stiffness;
    m->flex_bendingadr[i] = f.bending.empty() ? -1 : bending;
    vert += f.nvert;
    node += f.nnode;
    edge += m->flex_edgenum[i];
    elem += f.nelem;
    elemdata += (dim + 1) * f.nelem;
    elemedge += kFlexElemEdgeCount[dim - 1] * f.nelem;
    shelldata += static_cast<int>(f.shell.size());
    evpair += m->flex_evpairnum[i];
    texcoord += ntexcoord;
    stiffness += static_cast<int>(f.stiffness.size());
    bending += static_cast<int>(f.bending.size());
  }
}

// Flex i's contact, look, elasticity and kind, and which of its lengths the first
// equality on it keeps.
void FlexProperties(const mjcf::ModelSpec& spec, const FlexState& f, int i, Model* m) {
  const mjcf::FlexSpec& s = *f.spec;
  m->flex_names[i] = s.src.name;
  m->flex_contype[i] = s.contype;
  m->flex_conaffinity[i] = s.conaffinity;
  m->flex_condim[i] = s.condim;
  m->flex_priority[i] = s.priority;
  m->flex_solmix[i] = s.solmix;
  std::copy(s.solref.begin(), s.solref.end(), &m->flex_solref[kNRef * i]);
  std::copy(s.solimp.begin(), s.solimp.end(), &m->flex_solimp[kNImp * i]);
  std::copy(s.friction.begin(), s.friction.end(), &m->flex_friction[3 * i]);
  m->flex_margin[i] = s.margin;
  m->flex_gap[i] = s.gap;
  m->flex_internal[i] = s.internal;
  m->flex_selfcollide[i] = s.selfcollide;
  m->flex_activelayers[i] = s.activelayers;
  m->flex_passive[i] = s.passive;
  m->flex_dim[i] = s.dim;
  m->flex_matid[i] = f.matid;
  m->flex_group[i] = s.group;
  m->flex_radius[i] = s.radius;
  std::copy(f.size, f.size + 3, &m->flex_size[3 * i]);
  for (int k = 0; k < 4; k++) m->flex_rgba[4 * i + k] = s.rgba[k];
  m->flex_flatskin[i] = s.flatskin;
  m->flex_damping[i] = s.damping;
  m->flex_edgestiffness[i] = s.edgestiffness;
  m->flex_edgedamping[i] = s.edgedamping;
  m->flex_rigid[i] = f.rigid;
  m->flex_centered[i] = f.centered;
  m->flex_interp[i] = f.cells && f.lattice.shell ? -f.order : f.order;
  std::copy(s.cellcount.begin(), s.cellcount.end(), &m->flex_cellnum[3 * i]);
  m->flex_edgeequality[i] = 0;
  // (1 edges, 2 vertices, 3 strain: the first equality on the flex says which)
  for (const mjcf::EqualitySpec& eq : spec.equalities) {
    bool on_flex = eq.type == kEqFlex || eq.type == kEqFlexVert || eq.type == kEqFlexStrain;
    if (eq.name1 != s.src.name || !on_flex) continue;
    m->flex_edgeequality[i] = eq.type == kEqFlex ? 1 : eq.type == kEqFlexVert ? 2 : 3;
    break;
  }
}

// Flex i's elements (vertices, edges, texture corners, layers, stiffness), shells,
// element-vertex pairs and texture coordinates.
void FlexElements(const FlexState& f, int i, Model* m) {
  const mjcf::FlexSpec& s = *f.spec;
  int data = m->flex_elemdataadr[i];
  std::copy(f.elem.begin(), f.elem.end(), &m->flex_elem[data]);
  const std::vector<int>& corners = s.texcoord.empty() ? f.elem : f.elemtexcoord;
  std::copy(corners.begin(), corners.begin() + std::min(corners.size(), f.elem.size()),
            &m->flex_elemtexcoord[data]);
  std::copy(f.elemedge.begin(), f.elemedge.end(), &m->flex_elemedge[m->flex_elemedgeadr[i]]);
  std::copy(f.elemlayer.begin(), f.elemlayer.end(), &m->flex_elemlayer[m->flex_elemadr[i]]);
  if (!f.stiffness.empty()) {
    std::copy(f.stiffness.begin(), f.stiffness.end(),
              m->flex_stiffness.begin() + m->flex_stiffnessadr[i]);
  }
  if (!f.shell.empty()) std::copy(f.shell.begin(), f.shell.end(), &m->flex_shell[m->flex_shelldataadr[i]]);
  if (!f.evpair.empty()) std::copy(f.evpair.begin(), f.evpair.end(), &m->flex_evpair[2 * m->flex_evpairadr[i]]);
  if (!s.texcoord.empty()) {
    std::copy(s.texcoord.begin(), s.texcoord.end(), &m->flex_texcoord[2 * m->flex_texcoordadr[i]]);
  }
}

// Flex i's vertices and nodes: local positions (zero when centered), places in the box,
// bodies.
void FlexVertices(const FlexState& f, int i, Model* m) {
  const mjcf::FlexSpec& s = *f.spec;
  int vert = m->flex_vertadr[i], node = m->flex_nodeadr[i];
  if (!f.centered || f.interpolated) std::copy(s.vert.begin(), s.vert.end(), m->flex_vert.begin() + 3 * vert);
  if (!f.centered) std::copy(s.node.begin(), s.node.end(), m->flex_node.begin() + 3 * node);
  std::copy(f.vert0.begin(), f.vert0.end(), m->flex_vert0.begin() + 3 * vert);
  const std::vector<double>& node0 = f.cells ? f.nodelocal : f.nodexpos;
  std::copy(node0.begin(), node0.end(), m->flex_node0.begin() + 3 * node);
  for (int k = 0; k < f.nvert; k++) {
    m->flex_vertbodyid[vert + k] = f.rigid ? f.vertbodyid[0] : f.vertbodyid[k];
  }
  std::copy(f.nodebodyid.begin(), f.nodebodyid.end(), m->flex_nodebodyid.begin() + node);
}

// Flex i's edges: vertices, flaps (bending triangles), bending, whether both ends move
// together.
void FlexEdges(const FlexState& f, int i, Model* m) {
  const mjcf::FlexSpec& s = *f.spec;
  int edge = m->flex_edgeadr[i];
  bool flap = s.dim == 2 && (s.elastic2d == mjcf::kElastic2DBend || s.elastic2d == mjcf::kElastic2DBoth);
  if (!f.bending.empty()) {
    std::copy(f.bending.begin(), f.bending.end(), m->flex_bending.begin() + m->flex_bendingadr[i]);
  }
  for (int k = 0; k < m->flex_edgenum[i]; k++) {
    m->flex_edge[2 * (edge + k)] = f.edge[k][0];
    m->flex_edge[2 * (edge + k) + 1] = f.edge[k][1];
    m->flex_edgeflap[2 * (edge + k)] = flap ? f.flaps[k][2] : -1;
    m->flex_edgeflap[2 * (edge + k) + 1] = flap ? f.flaps[k][3] : -1;
    if (f.rigid) {
      m->flexedge_rigid[edge + k] = 1;
    } else if (!f.interpolated) {
      int b1 = f.vertbodyid[f.edge[k][0]], b2 = f.vertbodyid[f.edge[k][1]];
      m->flexedge_rigid[edge + k] = m->body_weldid[b1] == m->body_weldid[b2];
    }
  }
}

}  // namespace

void LayoutFlexes(const mjcf::ModelSpec& spec, const CompileState& state, Model* m) {
  FlexAddresses(state, m);
  for (int i = 0; i < m->nflex; i++) {
    const FlexState& f = state.flexes[i];
    FlexProperties(spec, f, i, m);
    FlexElements(f, i, m);
    FlexVertices(f, i, m);
    FlexEdges(f, i, m);
  }
}

}  // namespace simlab::compiler
