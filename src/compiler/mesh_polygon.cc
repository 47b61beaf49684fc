// The flat sides of a mesh's convex hull (or of the mesh itself, without a hull) as
// polygons (MuJoCo 3.5.1's mjCMesh::MakePolygons): the triangles are grouped by their
// normal's direction (two normals closer than cos = 0.99999872 are one direction), and
// the triangles of a group are merged into polygons by cancelling their shared edges. The groups are ordered as MuJoCo's std::set
// of them: by normal, x then y then z, largest first. The multi-contact collider
// (multiccd) clips these polygons against each other, and the first of two equally good
// edges wins there, so the order matters. Each polygon's normal is then taken exactly
// from its first three vertices in the mesh's final frame.
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

// Triangle (a, b, c)'s unit normal (b - a) x (c - a) as MuJoCo's mjuu_makenormal computes
// it (a degenerate triangle gets x over its tiny length).
void TriangleNormal(const double* a, const double* b, const double* c, double n[3]) {
  double ab[3], ac[3];
  math::Sub3(ab, b, a);
  math::Sub3(ac, c, a);
  math::Cross3(n, ab, ac);
  double norm = std::sqrt(math::Dot3(n, n));
  if (norm < kEps) {
    n[0] = 1;
    n[1] = n[2] = 0;
  }
  for (int k = 0; k < 3; k++) n[k] /= norm;
}

// The order of the groups: false for the same direction, else by x, y, z, larger first
// (components within kMinVal count as equal).
bool DirectionPrecedes(const double* n1, const double* n2) {
  if (n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2] > 0.99999872) return false;
  for (int k = 0; k < 3; k++) {
    if (std::abs(n1[k] - n2[k]) > kMinVal) return n1[k] > n2[k];
  }
  return false;
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

// One group: its direction (its first triangle's normal) and outline.
struct Side {
  double normal[3];
  mutable SideOutline outline;  // (not part of the order)
};

// The groups' order, as MuJoCo's set of them; a group is also found by a normal alone.
struct ByDirection {
  using is_transparent = void;
  static const double* Of(const Side& s) { return s.normal; }
  static const double* Of(const double* n) { return n; }
  template <class A, class B>
  bool operator()(const A& a, const B& b) const { return DirectionPrecedes(Of(a), Of(b)); }
};

}  // namespace

void MakeMeshPolygons(MeshState* mesh) {
  mesh->polygons.clear();

  // The hull's triangles, or the mesh's own when it has no hull.
  const bool hull = !mesh->graph.empty();
  const int* faces = hull ? HullFaces(*mesh) : mesh->face.data();
  const int numface = hull ? mesh->graph[1] : static_cast<int>(mesh->face.size() / 3);

  // Each triangle joins the group of its direction, or starts a new one.
  std::set<Side, ByDirection> sides;
  for (int f = 0; f < numface; f++) {
    const int* v = faces + 3 * f;
    double n[3];
    TriangleNormal(&mesh->vert[3 * v[0]], &mesh->vert[3 * v[1]], &mesh->vert[3 * v[2]], n);
    auto found = sides.find(static_cast<const double*>(n));
    if (found != sides.end()) {
      found->outline.Add(v[0], v[1], v[2]);
    } else {
      sides.insert(Side{{n[0], n[1], n[2]}, SideOutline(v[0], v[1], v[2])});
    }
  }
  for (const Side& side : sides) {
    for (std::vector<int>& path : side.outline.Paths()) {
      if (path.size() >= 3) mesh->polygons.push_back(std::move(path));
    }
  }
}

void MeshPolygonNormals(MeshState* mesh) {
  mesh->polynormal.assign(3 * mesh->polygons.size(), 0.0);
  for (size_t i = 0; i < mesh->polygons.size(); i++) {
    const std::vector<int>& p = mesh->polygons[i];
    TriangleNormal(&mesh->vert[3 * p[0]], &mesh->vert[3 * p[1]], &mesh->vert[3 * p[2]],
                   &mesh->polynormal[3 * i]);
  }
}

}  // namespace simlab::compiler
