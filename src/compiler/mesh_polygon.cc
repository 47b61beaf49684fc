// The flat sides of a mesh's convex hull as polygons (MuJoCo's mjCMesh::MakePolygons):
// the hull's triangles are grouped by their normal's direction, rounded to 0.01 rad in
// azimuth and polar angle, and the triangles of a group are merged into polygons by
// cancelling their shared edges. The multi-contact collider (multiccd) clips these
// polygons against each other. Each polygon's normal is then taken exactly from its
// first three vertices in the mesh's final frame.
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "compiler/compiler.h"
#include "math/elementary.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

constexpr double kAngleTolerance = 0.01;

// (b - a) x (c - a) into n; returns its length.
double TriangleCross(const double* a, const double* b, const double* c, double n[3]) {
  double ab[3], ac[3];
  math::Sub3(ab, b, a);
  math::Sub3(ac, c, a);
  math::Cross3(n, ab, ac);
  return std::sqrt(math::Dot3(n, n));
}

// The rounded (azimuth, polar) angles of triangle (a, b, c)'s normal, in units of the
// tolerance; false for a degenerate triangle.
bool DirectionKey(const double* a, const double* b, const double* c, std::pair<double, double>* key) {
  double n[3];
  double norm = TriangleCross(a, b, c, n);
  if (norm < kMinVal) return false;
  // (+0.0 turns a -0 into +0: atan2 tells them apart)
  for (double& x : n) x = x / norm + 0.0;
  if (std::abs(n[2]) > 1.0 - 1e-7) {
    *key = {0.0, n[2] < 0 ? std::round(std::numbers::pi / kAngleTolerance) : 0.0};
    return true;
  }
  *key = {std::round(math::Atan2(n[1], n[0]) / kAngleTolerance), std::round(math::Acos(n[2]) / kAngleTolerance)};
  return true;
}

// The boundary of the triangles of one direction: directed edges, each labelled with the
// connected piece it belongs to (triangles that share no edge yet are separate pieces
// until a later triangle joins them).
class SideOutline {
 public:
  SideOutline(int v1, int v2, int v3) : edges_{{v1, v2}, {v2, v3}, {v3, v1}}, piece_{0, 0, 0} {}

  // Adds triangle (v1, v2, v3): an edge it shares (reversed) with the outline is removed,
  // the others are added; pieces it touches become one.
  void Add(int v1, int v2, int v3) {
    int piece = -1;
    bool keep1 = !Cancel(v2, v1, &piece);
    bool keep2 = !Cancel(v3, v2, &piece);
    bool keep3 = !Cancel(v1, v3, &piece);
    if (piece == -1) piece = npiece_++;
    if (keep1) Push(v1, v2, piece);
    if (keep2) Push(v2, v3, piece);
    if (keep3) Push(v3, v1, piece);
  }

  // Each piece as a closed path of vertices.
  std::vector<std::vector<int>> Paths() const {
    if (edges_.size() == 3) return {{edges_[0].first, edges_[1].first, edges_[2].first}};
    std::vector<std::vector<int>> paths;
    for (int p = 0; p < npiece_; p++) {
      std::vector<int> path;
      for (size_t j = 0; j < edges_.size() && path.empty(); j++) {
        if (piece_[j] == p) path = {edges_[j].first, edges_[j].second};
      }
      if (path.empty()) continue;
      int next = path.back();
      for (size_t step = 0; step < edges_.size(); step++) {
        bool closed = false;
        for (size_t k = 1; k < edges_.size(); k++) {
          if (piece_[k] != p || edges_[k].first != next) continue;
          next = edges_[k].second;
          closed = next == path[0];
          if (closed) {
            paths.push_back(path);
          } else {
            path.push_back(next);
          }
          break;
        }
        if (closed) break;
      }
    }
    return paths;
  }

 private:
  // Removes edge (a, b) if present; the piece it belonged to joins *piece.
  bool Cancel(int a, int b, int* piece) {
    for (size_t i = 0; i < edges_.size(); i++) {
      if (edges_[i].first != a || edges_[i].second != b) continue;
      int other = piece_[i];
      edges_.erase(edges_.begin() + static_cast<std::ptrdiff_t>(i));
      piece_.erase(piece_.begin() + static_cast<std::ptrdiff_t>(i));
      if (*piece == -1) {
        *piece = other;
      } else if (other != *piece) {
        Merge(piece, other);
      }
      return true;
    }
    return false;
  }

  // Pieces *kept and other become the lower-numbered one; the numbers above close up.
  void Merge(int* kept, int other) {
    if (other < *kept) std::swap(*kept, other);
    for (int& p : piece_) {
      if (p == other) {
        p = *kept;
      } else if (p > other) {
        p--;
      }
    }
    npiece_--;
  }

  void Push(int a, int b, int piece) {
    edges_.push_back({a, b});
    piece_.push_back(piece);
  }

  std::vector<std::pair<int, int>> edges_;
  std::vector<int> piece_;
  int npiece_ = 1;
};

}  // namespace

void MakeMeshPolygons(MeshState* mesh) {
  mesh->polygons.clear();
  if (mesh->graph.empty()) return;
  const int numvert = mesh->graph[0], numface = mesh->graph[1];
  const int* faces = mesh->graph.data() + 2 + 3 * (numvert + numface);
  // (groups in the order of their first triangle)
  std::vector<std::pair<double, double>> keys;
  std::vector<SideOutline> sides;
  for (int f = 0; f < numface; f++) {
    const int* v = faces + 3 * f;
    std::pair<double, double> key;
    if (!DirectionKey(&mesh->vert[3 * v[0]], &mesh->vert[3 * v[1]], &mesh->vert[3 * v[2]], &key)) continue;
    size_t g = 0;
    while (g < keys.size() && keys[g] != key) g++;
    if (g == keys.size()) {
      keys.push_back(key);
      sides.emplace_back(v[0], v[1], v[2]);
    } else {
      sides[g].Add(v[0], v[1], v[2]);
    }
  }
  for (const SideOutline& side : sides) {
    for (std::vector<int>& path : side.Paths()) {
      if (path.size() >= 3) mesh->polygons.push_back(std::move(path));
    }
  }
}

void MeshPolygonNormals(MeshState* mesh) {
  mesh->polynormal.assign(3 * mesh->polygons.size(), 0.0);
  for (size_t i = 0; i < mesh->polygons.size(); i++) {
    const std::vector<int>& p = mesh->polygons[i];
    double n[3];
    double norm = TriangleCross(&mesh->vert[3 * p[0]], &mesh->vert[3 * p[1]], &mesh->vert[3 * p[2]], n);
    for (int k = 0; k < 3; k++) mesh->polynormal[3 * i + k] = n[k] / norm;
  }
}

}  // namespace simlab::compiler
