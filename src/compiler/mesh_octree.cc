// The signed distance field of a mesh used by an sdf geom (MuJoCo 3.5's mesh octree,
// mjCOctree): an octree over the mesh's bounding box enlarged by 10%, each cell split
// into eight while any triangle touches it, to depth 6; then refined until neighbouring
// leaves differ by at most one level. The field's value at each cell corner is the
// signed distance to the mesh (negative inside); a corner that lies on the face or edge
// of a coarser neighbour ("hanging") takes the mean of that face's or edge's corners, so
// that the trilinear field is continuous. The engine interpolates it (collision_sdf.cc).
//
// Cells are numbered as MuJoCo numbers them (breadth first, children in slot order x,
// y, z bits), and corners are shared between cells when their coordinates are equal to
// the bit, as MuJoCo's table of corners shares them.
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <vector>

#include "compiler/compiler.h"
#include "math/elementary.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

constexpr int kMaxLevel = 6;           // cells of this level are not split
constexpr double kBoxScale = 1.1;      // the root cell: the mesh's box enlarged by this
constexpr double kHangingTol = 1e-9;   // a corner on a coarser cell's boundary plane

using Triangle = std::array<std::array<double, 3>, 3>;
using Point = std::array<double, 3>;

struct Cell {
  int level = 0;
  int parent = -1;
  int slot = -1;                 // its place among its parent's children
  std::array<int, 8> child;      // -1: a leaf
  std::array<int, 8> corner;     // corner ids, slot order
  std::array<double, 6> aamm;    // min x y z, max x y z
};

// Does triangle t touch box `aamm`? (Schwarz and Seidel's triangle/box overlap test:
// the boxes, the triangle's plane, then the three projections of its edges.)
bool TouchesBox(const Triangle& t, const double aamm[6]) {
  for (int i = 0; i < 3; i++) {
    if (t[0][i] < aamm[i] && t[1][i] < aamm[i] && t[2][i] < aamm[i]) return false;
    if (t[0][i] > aamm[i + 3] && t[1][i] > aamm[i + 3] && t[2][i] > aamm[i + 3]) return false;
  }
  double edge[3][3], normal[3];
  for (int i = 0; i < 3; i++) {
    for (int k = 0; k < 3; k++) edge[i][k] = t[(i + 1) % 3][k] - t[i][k];
  }
  math::Cross3(normal, edge[0], edge[1]);
  const double size[3] = {aamm[3] - aamm[0], aamm[4] - aamm[1], aamm[5] - aamm[2]};
  double crit[3], near[3], far[3];
  for (int k = 0; k < 3; k++) {
    crit[k] = normal[k] > 0 ? size[k] : 0;
    near[k] = crit[k] - t[0][k];
    far[k] = size[k] - crit[k] - t[0][k];
  }
  const double at_min = math::Dot3(normal, aamm);
  if ((at_min + math::Dot3(normal, near)) * (at_min + math::Dot3(normal, far)) > 0) return false;
  for (int a = 0; a < 3; a++) {
    int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int i = 0; i < 3; i++) {
      double sign = normal[a] >= 0 ? 1 : -1;
      double n[2] = {-edge[i][c] * sign, edge[i][b] * sign};
      double offset = -(n[0] * t[i][b] + n[1] * t[i][c]) + std::max(0.0, size[b] * n[0]) +
                      std::max(0.0, size[c] * n[1]);
      if (n[0] * aamm[b] + n[1] * aamm[c] + offset < 0) return false;
    }
  }
  return true;
}

// The signed distance from a point to a closed triangle mesh, computed as the distance
// routine behind MuJoCo 3.5.1's (WebAssembly) octree values computes it, to the bit: the
// nearest feature (vertex, edge or face) of each triangle, triangles visited through a
// tree of bounding spheres (nearer sphere first, pruned by the distance so far), and
// the sign from that feature's angle-weighted pseudonormal (Baerentzen and Aanaes).
class MeshDistance {
 public:
  explicit MeshDistance(const MeshState& mesh) {
    size_t nvert = mesh.vert.size() / 3;
    for (size_t v = 0; v < nvert; v++) {
      vert_.push_back({mesh.vert[3 * v], mesh.vert[3 * v + 1], mesh.vert[3 * v + 2]});
    }
    for (size_t f = 0; f + 2 < mesh.face.size(); f += 3) {
      tri_.push_back({mesh.face[f], mesh.face[f + 1], mesh.face[f + 2]});
    }
    std::vector<int> order(tri_.size());
    for (size_t i = 0; i < order.size(); i++) order[i] = static_cast<int>(i);
    nodes_.emplace_back();
    Sphere root;
    if (!tri_.empty()) BuildTree(0, &root, &order, 0, static_cast<int>(order.size()));
    MakePseudonormals();
  }

  double Signed(const Point& p) const {
    Nearest n;
    if (tri_.empty()) return 0;
    Query(0, p, &n);
    const std::array<int, 3>& t = tri_[n.triangle];
    const Point* normal = &face_normal_[n.triangle];
    switch (n.feature) {
      case kV0: normal = &vert_normal_[t[0]]; break;
      case kV1: normal = &vert_normal_[t[1]]; break;
      case kV2: normal = &vert_normal_[t[2]]; break;
      case kE01: normal = &edge_normal_[n.triangle][0]; break;
      case kE12: normal = &edge_normal_[n.triangle][1]; break;
      case kE02: normal = &edge_normal_[n.triangle][2]; break;
      case kFace: break;
    }
    Point away;
    for (int k = 0; k < 3; k++) {
      double at = n.bary[0] * vert_[t[0]][k] + n.bary[1] * vert_[t[1]][k] + n.bary[2] * vert_[t[2]][k];
      away[k] = p[k] - at;
    }
    return Dot(away, *normal) >= 0.0 ? n.dist : -n.dist;
  }

 private:
  enum Feature { kV0, kV1, kV2, kE01, kE12, kE02, kFace };
  struct Sphere {
    Point centre = {0, 0, 0};
    double radius = 0;
  };
  struct Node {
    Sphere left_sphere, right_sphere;
    int left = -1, right = -1;  // a leaf: left -1, right its triangle
  };
  struct Nearest {
    double dist = std::numeric_limits<double>::max();
    Feature feature = kFace;
    int triangle = -1;
    Point bary = {0, 0, 0};
  };

  static double Dot(const Point& a, const Point& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  static Point Sub(const Point& a, const Point& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
  static Point Cross(const Point& a, const Point& b) {
    Point r;
    math::Cross3(r.data(), a.data(), b.data());
    return r;
  }
  static double Length(const Point& a) { return std::sqrt(Dot(a, a)); }
  static Point Unit(const Point& a) {
    double n = Length(a);
    return {a[0] / n, a[1] / n, a[2] / n};
  }

  // Leaves hold one triangle; a node splits its triangles at the middle of their order
  // along the longest side of their box (by first vertex), each child in a sphere about
  // the mean of its triangles' corners.
  void BuildTree(int node, Sphere* sphere, std::vector<int>* order, int begin, int end) {
    if (end - begin == 1) {
      int t = (*order)[begin];
      nodes_[node].left = -1;
      nodes_[node].right = t;
      const Point &a = vert_[tri_[t][0]], &b = vert_[tri_[t][1]], &c = vert_[tri_[t][2]];
      for (int k = 0; k < 3; k++) sphere->centre[k] = (a[k] + b[k] + c[k]) / 3.0;
      sphere->radius = std::max(std::max(Length(Sub(a, sphere->centre)), Length(Sub(b, sphere->centre))),
                                Length(Sub(c, sphere->centre)));
      return;
    }
    Point top, bottom, centre = {0, 0, 0};
    top.fill(std::numeric_limits<double>::lowest());
    bottom.fill(std::numeric_limits<double>::max());
    for (int i = begin; i < end; i++) {
      for (int j = 0; j < 3; j++) {
        const Point& p = vert_[tri_[(*order)[i]][j]];
        for (int k = 0; k < 3; k++) {
          centre[k] += p[k];
          top[k] = std::max(top[k], p[k]);
          bottom[k] = std::min(bottom[k], p[k]);
        }
      }
    }
    for (double& x : centre) x /= static_cast<double>(3 * (end - begin));
    Point diagonal = Sub(top, bottom);
    int axis = static_cast<int>(std::max_element(diagonal.begin(), diagonal.end()) - diagonal.begin());
    double radius_sq = 0.0;
    for (int i = begin; i < end; i++) {
      for (int j = 0; j < 3; j++) {
        Point d = Sub(centre, vert_[tri_[(*order)[i]][j]]);
        radius_sq = std::max(radius_sq, Dot(d, d));
      }
    }
    sphere->centre = centre;
    sphere->radius = std::sqrt(radius_sq);
    // (stable: the reference's sort keeps equal keys in order for fewer than 30)
    std::stable_sort(order->begin() + begin, order->begin() + end, [&](int a, int b) {
      return vert_[tri_[a][0]][axis] < vert_[tri_[b][0]][axis];
    });
    int mid = static_cast<int>(0.5 * (begin + end));
    int left = static_cast<int>(nodes_.size());
    nodes_[node].left = left;
    nodes_.emplace_back();
    Sphere left_sphere, right_sphere;
    BuildTree(left, &left_sphere, order, begin, mid);
    nodes_[node].left_sphere = left_sphere;
    int right = static_cast<int>(nodes_.size());
    nodes_[node].right = right;
    nodes_.emplace_back();
    BuildTree(right, &right_sphere, order, mid, end);
    nodes_[node].right_sphere = right_sphere;
  }

  void Query(int node, const Point& p, Nearest* n) const {
    const Node& nd = nodes_[node];
    if (nd.left == -1) {
      NearestOnTriangle(nd.right, p, n);
      return;
    }
    double to_left = Length(Sub(p, nd.left_sphere.centre)) - nd.left_sphere.radius;
    double to_right = Length(Sub(p, nd.right_sphere.centre)) - nd.right_sphere.radius;
    if (to_left < to_right) {
      if (to_left < n->dist) Query(nd.left, p, n);
      if (to_right < n->dist) Query(nd.right, p, n);
    } else {
      if (to_right < n->dist) Query(nd.right, p, n);
      if (to_left < n->dist) Query(nd.left, p, n);
    }
  }

  // Triangle t's nearest feature to p (Ericson's regions, in the reference's form); kept
  // when nearer than the distance so far.
  void NearestOnTriangle(int t, const Point& p, Nearest* n) const {
    const Point &a = vert_[tri_[t][0]], &b = vert_[tri_[t][1]], &c = vert_[tri_[t][2]];
    const Point ab = Sub(b, a), ac = Sub(c, a), bc = Sub(c, b);
    // Projections on the three edges (from each end), and signed areas seen from p.
    const double snom = Dot(Sub(p, a), ab), sdenom = Dot(Sub(p, b), Sub(a, b));
    const double tnom = Dot(Sub(p, a), ac), tdenom = Dot(Sub(p, c), Sub(a, c));
    const double unom = Dot(Sub(p, b), bc), udenom = Dot(Sub(p, c), Sub(b, c));
    const Point normal = Cross(ab, ac);
    const double vc = Dot(normal, Cross(Sub(a, p), Sub(b, p)));
    const double va = Dot(normal, Cross(Sub(b, p), Sub(c, p)));
    const double vb = Dot(normal, Cross(Sub(c, p), Sub(a, p)));
    Feature feature;
    Point w;  // barycentric weights of a, b, c
    if (snom <= 0.0 && tnom <= 0.0) {
      feature = kV0, w = {1.0, 0.0, 0.0};
    } else if (sdenom <= 0.0 && unom <= 0.0) {
      feature = kV1, w = {0.0, 1.0, 0.0};
    } else if (tdenom <= 0.0 && udenom <= 0.0) {
      feature = kV2, w = {0.0, 0.0, 1.0};
    } else if (vc <= 0.0 && snom >= 0.0 && sdenom >= 0.0) {
      double s = snom / (snom + sdenom);
      feature = kE01, w = {1.0 - s, s, 0.0};
    } else if (va <= 0.0 && unom >= 0.0 && udenom >= 0.0) {
      double s = unom / (unom + udenom);
      feature = kE12, w = {0.0, 1.0 - s, s};
    } else if (vb <= 0.0 && tnom >= 0.0 && tdenom >= 0.0) {
      double s = tnom / (tnom + tdenom);
      feature = kE02, w = {1.0 - s, 0.0, s};
    } else {
      double u = va / (va + vb + vc), v = vb / (va + vb + vc);
      feature = kFace, w = {u, v, 1.0 - u - v};
    }
    // The nearest point: a vertex itself, or the weights' sum over the feature's ends.
    Point q;
    for (int k = 0; k < 3; k++) {
      switch (feature) {
        case kV0: q[k] = a[k]; break;
        case kV1: q[k] = b[k]; break;
        case kV2: q[k] = c[k]; break;
        case kE01: q[k] = w[0] * a[k] + w[1] * b[k]; break;
        case kE12: q[k] = w[1] * b[k] + w[2] * c[k]; break;
        case kE02: q[k] = w[0] * a[k] + w[2] * c[k]; break;
        case kFace: q[k] = w[0] * a[k] + w[1] * b[k] + w[2] * c[k]; break;
      }
    }
    Point d = Sub(p, q);
    double dist_sq = Dot(d, d);
    if (dist_sq < n->dist * n->dist) {
      n->feature = feature;
      n->bary = w;
      n->dist = std::sqrt(dist_sq);
      n->triangle = t;
    }
  }

  // Face normals; vertex normals weighted by the corner angles; edge normals, the sum of
  // the two faces' (each normalized).
  void MakePseudonormals() {
    size_t nv = vert_.size();
    face_normal_.resize(tri_.size());
    vert_normal_.assign(nv, {0, 0, 0});
    std::map<std::pair<int, int>, Point> edge_sum;
    auto add_edge = [&](int i, int j, const Point& normal) {
      auto [it, added] = edge_sum.try_emplace({std::min(i, j), std::max(i, j)}, normal);
      if (!added) {
        for (int k = 0; k < 3; k++) it->second[k] += normal[k];
      }
    };
    for (size_t i = 0; i < tri_.size(); i++) {
      const std::array<int, 3>& t = tri_[i];
      const Point &a = vert_[t[0]], &b = vert_[t[1]], &c = vert_[t[2]];
      Point normal = Unit(Cross(Sub(b, a), Sub(c, a)));
      face_normal_[i] = normal;
      double angle[3] = {math::Acos(Dot(Unit(Sub(b, a)), Unit(Sub(c, a)))),
                         math::Acos(Dot(Unit(Sub(a, b)), Unit(Sub(c, b)))),
                         math::Acos(Dot(Unit(Sub(b, c)), Unit(Sub(a, c))))};
      for (int j = 0; j < 3; j++) {
        for (int k = 0; k < 3; k++) vert_normal_[t[j]][k] += angle[j] * normal[k];
      }
      add_edge(t[0], t[1], normal);
      add_edge(t[1], t[2], normal);
      add_edge(t[0], t[2], normal);
    }
    for (Point& n : vert_normal_) {
      double len = Length(n);
      for (double& x : n) x /= len;
    }
    edge_normal_.resize(tri_.size());
    for (size_t i = 0; i < tri_.size(); i++) {
      const std::array<int, 3>& t = tri_[i];
      const int ends[3][2] = {{t[0], t[1]}, {t[1], t[2]}, {t[0], t[2]}};
      for (int e = 0; e < 3; e++) {
        edge_normal_[i][e] = Unit(edge_sum.at({std::min(ends[e][0], ends[e][1]), std::max(ends[e][0], ends[e][1])}));
      }
    }
  }

  std::vector<Point> vert_;
  std::vector<std::array<int, 3>> tri_;
  std::vector<Node> nodes_;
  std::vector<Point> face_normal_, vert_normal_;
  std::vector<std::array<Point, 3>> edge_normal_;
};

class OctreeBuilder {
 public:
  explicit OctreeBuilder(const MeshState& mesh) {
    for (size_t f = 0; f + 2 < mesh.face.size(); f += 3) {
      Triangle t;
      for (int j = 0; j < 3; j++) {
        for (int k = 0; k < 3; k++) t[j][k] = mesh.vert[3 * mesh.face[f + j] + k];
      }
      triangles_.push_back(t);
    }
  }

  // Cells split while triangles touch them, then balanced; hanging corners found.
  void Build(const double mesh_aamm[6]) {
    double root[6];
    for (int k = 0; k < 3; k++) {
      double centre = (mesh_aamm[k] + mesh_aamm[k + 3]) / 2;
      double half = (mesh_aamm[k + 3] - mesh_aamm[k]) / 2;
      root[k] = centre - kBoxScale * half;
      root[k + 3] = centre + kBoxScale * half;
    }
    struct Task {
      int cell;
      std::vector<int> triangles;
    };
    std::deque<Task> queue;
    std::vector<int> all(triangles_.size());
    for (size_t i = 0; i < all.size(); i++) all[i] = static_cast<int>(i);
    AddCell(-1, -1, root);
    queue.push_back({0, std::move(all)});
    while (!queue.empty()) {
      Task task = std::move(queue.front());
      queue.pop_front();
      std::vector<int> touching;
      for (int t : task.triangles) {
        if (TouchesBox(triangles_[t], cells_[task.cell].aamm.data())) touching.push_back(t);
      }
      if (touching.empty() || cells_[task.cell].level >= kMaxLevel) continue;
      for (int slot = 0; slot < 8; slot++) {
        int child = AddCell(task.cell, slot, nullptr);
        queue.push_back({child, touching});
      }
    }
    Balance();
    FindHanging();
  }

  // Each cell corner's value: the signed distance, or a hanging corner's mean, visiting
  // cells breadth first (coarser cells first).
  std::vector<double> CornerValues(const MeshDistance& distance) const {
    std::vector<double> value(corners_.size(), 0);
    std::vector<bool> done(corners_.size(), false);
    std::deque<int> queue = {0};
    while (!queue.empty()) {
      int c = queue.front();
      queue.pop_front();
      for (int j = 0; j < 8; j++) {
        int v = cells_[c].corner[j];
        if (done[v]) continue;
        if (hanging_[v].empty()) {
          value[v] = distance.Signed(corners_[v]);
        } else {
          double sum = 0;
          for (int u : hanging_[v]) sum += value[u];
          value[v] = sum / static_cast<double>(hanging_[v].size());
        }
        done[v] = true;
      }
      for (int child : cells_[c].child) {
        if (child != -1) queue.push_back(child);
      }
    }
    return value;
  }

  const std::vector<Cell>& cells() const { return cells_; }

 private:
  // A new cell: the root box, or the `slot` octant of its parent's.
  int AddCell(int parent, int slot, const double* aamm) {
    Cell cell;
    cell.parent = parent;
    cell.slot = slot;
    cell.child.fill(-1);
    if (parent < 0) {
      std::copy(aamm, aamm + 6, cell.aamm.begin());
    } else {
      const std::array<double, 6> p = cells_[parent].aamm;
      cell.level = cells_[parent].level + 1;
      for (int k = 0; k < 3; k++) {
        bool upper = slot & (1 << k);
        cell.aamm[k] = upper ? (p[k + 3] + p[k]) / 2 : p[k];
        cell.aamm[k + 3] = upper ? p[k + 3] : (p[k] + p[k + 3]) / 2;
      }
    }
    for (int j = 0; j < 8; j++) {
      Point p = {(j & 1) ? cell.aamm[3] : cell.aamm[0], (j & 2) ? cell.aamm[4] : cell.aamm[1],
                 (j & 4) ? cell.aamm[5] : cell.aamm[2]};
      for (double& x : p) x = x == 0 ? 0.0 : x;  // (-0 is +0)
      auto [it, added] = corner_ids_.try_emplace(p, static_cast<int>(corners_.size()));
      if (added) corners_.push_back(p);
      cell.corner[j] = it->second;
    }
    int id = static_cast<int>(cells_.size());
    cells_.push_back(cell);
    if (parent >= 0) cells_[parent].child[slot] = id;
    return id;
  }

  // The nearest cell across side `dir` (axis dir/2, upper side if dir is odd) at the same
  // level or coarser: up the tree until a sibling lies that way.
  int CoarseNeighbour(int cell, int dir) const {
    int parent = cells_[cell].parent;
    if (parent == -1) return -1;
    int bit = 1 << (dir / 2);
    bool upper = dir % 2;
    int slot = cells_[cell].slot;
    if (upper != ((slot & bit) != 0)) return cells_[parent].child[slot ^ bit];
    return CoarseNeighbour(parent, dir);
  }

  // The leaf across side `dir` that touches this cell's centre line.
  int Neighbour(int cell, int dir) const {
    int n = CoarseNeighbour(cell, dir);
    if (n == -1) return -1;
    const std::array<double, 6>& a = cells_[cell].aamm;
    double centre[3] = {(a[0] + a[3]) / 2, (a[1] + a[4]) / 2, (a[2] + a[5]) / 2};
    int bit = 1 << (dir / 2);
    bool near_side_upper = dir % 2 == 0;  // the neighbour's side that faces this cell
    while (cells_[n].child[0] != -1) {
      const std::array<double, 6>& b = cells_[n].aamm;
      int slot = 0;
      for (int k = 0; k < 3; k++) {
        if (centre[k] > (b[k] + b[k + 3]) / 2) slot |= 1 << k;
      }
      slot = (slot & ~bit) | (near_side_upper ? bit : 0);
      n = cells_[n].child[slot];
    }
    return n;
  }

  std::vector<int> Leaves() const {
    std::vector<int> leaves;
    for (size_t i = 0; i < cells_.size(); i++) {
      if (cells_[i].child[0] == -1) leaves.push_back(static_cast<int>(i));
    }
    return leaves;
  }

  // Splits leaves whose neighbours are more than one level finer, until none are.
  void Balance() {
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<int> split;
      for (int leaf : Leaves()) {
        for (int dir = 0; dir < 6; dir++) {
          int n = Neighbour(leaf, dir);
          if (n == -1) continue;
          if (cells_[n].level > cells_[leaf].level + 1) split.push_back(leaf);
          if (cells_[leaf].level > cells_[n].level + 1) split.push_back(n);
        }
      }
      for (int cell : split) {
        if (cells_[cell].child[0] != -1) continue;
        changed = true;
        for (int slot = 0; slot < 8; slot++) AddCell(cell, slot, nullptr);
      }
    }
  }

  // Corners of a leaf's side that lie on a coarser neighbour's side: on its edge (two
  // corners to average) or inside its face (four).
  void FindHanging() {
    hanging_.assign(corners_.size(), {});
    for (int leaf : Leaves()) {
      for (int dir = 0; dir < 6; dir++) {
        int n = Neighbour(leaf, dir);
        if (n == -1 || cells_[n].level >= cells_[leaf].level) continue;
        int axis = dir / 2, side = dir % 2;
        for (int i = 0; i < 4; i++) {
          int j = (side << axis) | ((i & 1) << ((axis + 1) % 3)) | (((i >> 1) & 1) << ((axis + 2) % 3));
          int v = cells_[leaf].corner[j];
          if (!hanging_[v].empty()) continue;
          HangOn(v, cells_[n]);
        }
      }
    }
  }

  void HangOn(int v, const Cell& coarse) {
    const Point& p = corners_[v];
    bool at_min[3], at_max[3];
    int planes = 0;
    for (int k = 0; k < 3; k++) {
      at_min[k] = std::abs(p[k] - coarse.aamm[k]) < kHangingTol;
      at_max[k] = std::abs(p[k] - coarse.aamm[k + 3]) < kHangingTol;
      planes += at_min[k] || at_max[k];
    }
    auto corner_of = [&](const int bits[3]) { return coarse.corner[(bits[2] << 2) | (bits[1] << 1) | bits[0]]; };
    if (planes == 2) {  // on an edge: its two ends
      int free_axis = 0;
      while (at_min[free_axis] || at_max[free_axis]) free_axis++;
      int bits[3];
      bits[(free_axis + 1) % 3] = at_max[(free_axis + 1) % 3];
      bits[(free_axis + 2) % 3] = at_max[(free_axis + 2) % 3];
      bits[free_axis] = 0;
      hanging_[v].push_back(corner_of(bits));
      bits[free_axis] = 1;
      hanging_[v].push_back(corner_of(bits));
    } else if (planes == 1) {  // inside a face: its four corners
      int face_axis = 0;
      while (!at_min[face_axis] && !at_max[face_axis]) face_axis++;
      int bits[3];
      bits[face_axis] = at_max[face_axis];
      for (int j = 0; j < 4; j++) {
        bits[(face_axis + 1) % 3] = j & 1;
        bits[(face_axis + 2) % 3] = (j >> 1) & 1;
        hanging_[v].push_back(corner_of(bits));
      }
    }
  }

  std::vector<Triangle> triangles_;
  std::vector<Cell> cells_;
  std::vector<Point> corners_;
  // Corners shared between cells: equal coordinates (to the bit, +0 and -0 alike) are one.
  std::map<Point, int> corner_ids_;
  std::vector<std::vector<int>> hanging_;
};

}  // namespace

void MakeMeshOctree(MeshState* mesh) {
  OctreeBuilder builder(*mesh);
  builder.Build(mesh->aamm);
  MeshDistance distance(*mesh);
  std::vector<double> value = builder.CornerValues(distance);
  const std::vector<Cell>& cells = builder.cells();
  mesh->oct_depth.clear();
  mesh->oct_child.clear();
  mesh->oct_aabb.clear();
  mesh->oct_coeff.clear();
  for (const Cell& c : cells) {
    mesh->oct_depth.push_back(c.level);
    mesh->oct_child.insert(mesh->oct_child.end(), c.child.begin(), c.child.end());
    for (int k = 0; k < 3; k++) mesh->oct_aabb.push_back((c.aamm[k] + c.aamm[k + 3]) / 2);
    for (int k = 0; k < 3; k++) mesh->oct_aabb.push_back((c.aamm[k + 3] - c.aamm[k]) / 2);
    for (int j = 0; j < 8; j++) mesh->oct_coeff.push_back(value[c.corner[j]]);
  }
}

}  // namespace simlab::compiler
