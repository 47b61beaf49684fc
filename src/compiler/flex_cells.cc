// Interpolated flexes made of cells at compile time (see flex_cells.h), in MuJoCo 3.12's
// order of operations.
#include "compiler/flex_cells.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "compiler/flex_elasticity.h"
#include "compiler/orientation.h"
#include "engine/flex_elasticity.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

// Young's modulus and Poisson's ratio of the stiffness whose eigenmodes the strain
// equality keeps (the modes' shapes do not depend on the material).
constexpr double kStrainYoung = 1e1;
constexpr double kStrainPoisson = 0.3;

// The cell of coordinate x on an axis from lo over extent d cut in n cells.
int CellOf(double x, double lo, double d, int n) {
  if (d <= 0) return 0;
  int c = static_cast<int>((x - lo) / d * n);
  return std::max(0, std::min(n - 1, c));
}

// The cells each element's bounding box overlaps.
std::vector<bool> CellsWithElements(const std::array<int, 3>& cells,
                                    const std::vector<double>& vpos, const std::vector<int>& elem,
                                    int dim, const double box[6]) {
  int cx = cells[0], cy = cells[1], cz = cells[2];
  std::vector<bool> has(static_cast<size_t>(cx) * cy * cz, false);
  int nvpe = dim + 1;
  for (size_t e = 0; e + nvpe <= elem.size(); e += nvpe) {
    double lo[3] = {1e30, 1e30, 1e30}, hi[3] = {-1e30, -1e30, -1e30};
    for (int v = 0; v < nvpe; v++) {
      const double* p = vpos.data() + 3 * elem[e + v];
      for (int k = 0; k < 3; k++) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
    int first[3], last[3];
    for (int k = 0; k < 3; k++) {
      first[k] = CellOf(lo[k], box[k], box[k + 3] - box[k], cells[k]);
      last[k] = CellOf(hi[k], box[k], box[k + 3] - box[k], cells[k]);
    }
    for (int ci = first[0]; ci <= last[0]; ci++) {
      for (int cj = first[1]; cj <= last[1]; cj++) {
        for (int ck = first[2]; ck <= last[2]; ck++) has[(ci * cy + cj) * cz + ck] = true;
      }
    }
  }
  return has;
}

// The cells without elements reachable from the box's boundary through such cells.
std::vector<bool> OutsideCells(const std::array<int, 3>& cells, const std::vector<bool>& has) {
  int cx = cells[0], cy = cells[1], cz = cells[2];
  std::vector<bool> outside(has.size(), false);
  std::queue<std::array<int, 3>> open;
  auto visit = [&](int ci, int cj, int ck) {
    int id = (ci * cy + cj) * cz + ck;
    if (has[id] || outside[id]) return;
    outside[id] = true;
    open.push({ci, cj, ck});
  };
  for (int ci = 0; ci < cx; ci++) {
    for (int cj = 0; cj < cy; cj++) {
      for (int ck = 0; ck < cz; ck++) {
        bool boundary = ci == 0 || ci == cx - 1 || cj == 0 || cj == cy - 1 || ck == 0 ||
                        ck == cz - 1;
        if (boundary) visit(ci, cj, ck);
      }
    }
  }
  static const int kStep[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                                  {0, 1, 0},  {0, 0, -1}, {0, 0, 1}};
  while (!open.empty()) {
    std::array<int, 3> c = open.front();
    open.pop();
    for (const auto& s : kStep) {
      int n[3] = {c[0] + s[0], c[1] + s[1], c[2] + s[2]};
      if (n[0] < 0 || n[0] >= cx || n[1] < 0 || n[1] >= cy || n[2] < 0 || n[2] >= cz) continue;
      visit(n[0], n[1], n[2]);
    }
  }
  return outside;
}

// The positions of element fe's nodes (a cell's or a face's), and a face's normal axis.
int ElementNodes(const FlexLattice& g, int fe, const std::vector<double>& nodes, double* pos) {
  int ids[27];
  int normal = FlexElementNodes(g, fe, ids);
  for (int n = 0; n < g.NodesPerElement(); n++) math::Copy3(pos + 3 * n, nodes.data() + 3 * ids[n]);
  return normal;
}

// The eigenvalues (diagonal of *mat when done) and eigenvectors (columns of vec) of a
// symmetric n x n matrix by cyclic Jacobi sweeps (MuJoCo's mjuu_eigendecompose).
void JacobiEigen(std::vector<double>* mat, std::vector<double>* vec, int n) {
  std::vector<double>& a = *mat;
  vec->assign(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; i++) (*vec)[i * n + i] = 1.0;
  const double tol = 1e-12;
  for (int sweep = 0; sweep < 200; sweep++) {
    double off = 0;
    for (int i = 0; i < n; i++) {
      for (int j = i + 1; j < n; j++) off += a[i * n + j] * a[i * n + j];
    }
    if (off < tol * tol) break;
    for (int p = 0; p < n; p++) {
      for (int q = p + 1; q < n; q++) {
        double apq = a[p * n + q];
        if (std::abs(apq) < tol * 1e-3) continue;

        // The rotation zeroing (p, q), applied to the matrix and the vectors.
        double tau = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
        double t = (tau >= 0 ? 1.0 : -1.0) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
        double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
        a[p * n + p] -= t * apq;
        a[q * n + q] += t * apq;
        a[p * n + q] = a[q * n + p] = 0;
        for (int r = 0; r < n; r++) {
          if (r == p || r == q) continue;
          double arp = a[r * n + p], arq = a[r * n + q];
          a[r * n + p] = a[p * n + r] = c * arp - s * arq;
          a[r * n + q] = a[q * n + r] = s * arp + c * arq;
        }
        for (int r = 0; r < n; r++) {
          double vrp = (*vec)[r * n + p], vrq = (*vec)[r * n + q];
          (*vec)[r * n + p] = c * vrp - s * vrq;
          (*vec)[r * n + q] = s * vrp + c * vrq;
        }
      }
    }
  }
}

// The stiff eigenmodes of k (n x n, stored negated): out[0] their count, then each as
// sqrt(lambda) v, for the physical eigenvalues lambda above 1e-8 of the largest (never
// NaN ones, and at most `most`, so that they fit in k's n x n block with their count).
// Returns the count.
int StiffModes(const std::vector<double>& k, int n, int most, double* out) {
  std::vector<double> mat = k, vec;
  JacobiEigen(&mat, &vec, n);
  double largest = 0;
  for (int i = 0; i < n; i++) largest = std::max(largest, std::abs(mat[i * n + i]));
  double threshold = largest * 1e-8;
  int count = 0;
  for (int i = 0; i < n; i++) {
    double lambda = -mat[i * n + i];
    if (!(lambda > threshold) || count == most) continue;
    double scale = std::sqrt(lambda);
    double* w = out + 1 + count * n;
    for (int j = 0; j < n; j++) w[j] = scale * vec[j * n + i];
    count++;
  }
  out[0] = count;
  return count;
}

// A face's warp mode (the twist (1 - 2s)(1 - 2t) along its normal) made orthogonal to
// the face's rigid motions and normalized (MuJoCo's ComputeWarpMode).
void WarpMode(double* warp, const double* pos, int order, int normal_axis) {
  int nbasis = order + 1, npe = nbasis * nbasis, ndof = 3 * npe;
  std::fill(warp, warp + ndof, 0.0);
  for (int b0 = 0; b0 < nbasis; b0++) {
    for (int b1 = 0; b1 < nbasis; b1++) {
      double s = static_cast<double>(b0) / (nbasis - 1), t = static_cast<double>(b1) / (nbasis - 1);
      warp[3 * (b0 * nbasis + b1) + normal_axis] = (1 - 2 * s) * (1 - 2 * t);
    }
  }

  // The rigid motions: three translations, three rotations about the centroid.
  double centroid[3] = {0, 0, 0};
  for (int n = 0; n < npe; n++) {
    for (int k = 0; k < 3; k++) centroid[k] += pos[3 * n + k];
  }
  for (int k = 0; k < 3; k++) centroid[k] /= npe;
  std::vector<double> rigid(6 * static_cast<size_t>(ndof), 0.0);
  for (int n = 0; n < npe; n++) {
    for (int k = 0; k < 3; k++) rigid[k * ndof + 3 * n + k] = 1;
    double r[3];
    math::Sub3(r, pos + 3 * n, centroid);
    rigid[3 * ndof + 3 * n + 1] = -r[2];
    rigid[3 * ndof + 3 * n + 2] = r[1];
    rigid[4 * ndof + 3 * n + 0] = r[2];
    rigid[4 * ndof + 3 * n + 2] = -r[0];
    rigid[5 * ndof + 3 * n + 0] = -r[1];
    rigid[5 * ndof + 3 * n + 1] = r[0];
  }

  // Orthonormalized (modified Gram-Schmidt), then projected out of the warp.
  auto dot = [&](const double* a, const double* b) {
    double sum = 0;
    for (int k = 0; k < ndof; k++) sum += a[k] * b[k];
    return sum;
  };
  auto normalize = [&](double* a) {
    double norm2 = dot(a, a);
    if (norm2 <= 1e-20) return;
    double inv = 1.0 / std::sqrt(norm2);
    for (int k = 0; k < ndof; k++) a[k] *= inv;
  };
  for (int i = 0; i < 6; i++) {
    double* ri = rigid.data() + i * ndof;
    for (int j = 0; j < i; j++) {
      const double* rj = rigid.data() + j * ndof;
      double d = dot(ri, rj);
      for (int k = 0; k < ndof; k++) ri[k] -= d * rj[k];
    }
    normalize(ri);
  }
  for (int i = 0; i < 6; i++) {
    const double* ri = rigid.data() + i * ndof;
    double d = dot(warp, ri);
    for (int k = 0; k < ndof; k++) warp[k] -= d * ri[k];
  }
  normalize(warp);
}

// The plate's stiffness against a face's warp: D (1 - nu) 4 / (d0 d1), D = E t^3 /
// (12 (1 - nu^2)), with d0, d1 the face's extents (0 for a degenerate face).
double WarpStiffness(const double* pos, int npe, int normal_axis, double young, double poisson,
                     double thickness) {
  int a0 = (normal_axis + 1) % 3, a1 = (normal_axis + 2) % 3;
  double d0 = std::abs(pos[3 * (npe - 1) + a0] - pos[a0]);
  double d1 = std::abs(pos[3 * (npe - 1) + a1] - pos[a1]);
  if (d0 < 1e-30 || d1 < 1e-30) return 0;
  double plate = young * thickness * thickness * thickness / (12.0 * (1.0 - poisson * poisson));
  return plate * (1.0 - poisson) * 4.0 / (d0 * d1);
}

// An edge between two face elements of a shell: the faces (global face element ids) and
// the edge's midpoint in each face's parametric square.
struct BendEdge {
  int face[2];
  double local[2][2];
};

// The face elements on each side of a shell, the first of each, and their count along
// the side's two in-plane axes (slow, fast).
struct ShellSides {
  int first[6], count0[6], count1[6];
  explicit ShellSides(const FlexLattice& g) {
    const int* c = g.cells.data();
    int sum = 0;
    for (int side = 0; side < 6; side++) {
      int normal = side / 2;
      count0[side] = c[(normal + 1) % 3];
      count1[side] = c[(normal + 2) % 3];
      first[side] = sum;
      sum += count0[side] * count1[side];
    }
  }
};

// The face across one edge of face (side, q0, q1): along in-plane direction dir (0 the
// slow axis, 1 the fast one) toward side `step` (+1 or -1); on the same side if it has
// one there, else on the side the edge folds onto. Sets the edge's midpoint in both
// faces and returns the other face's global id.
int NeighbourFace(const FlexLattice& g, const ShellSides& sides, int side, int q0, int q1, int dir,
                  int step, double mine[2], double theirs[2]) {
  int normal = side / 2, upper = side % 2;
  mine[0] = dir == 0 ? (step > 0 ? 1.0 : 0.0) : 0.5;
  mine[1] = dir == 1 ? (step > 0 ? 1.0 : 0.0) : 0.5;

  // A neighbour on the same side.
  int q = (dir == 0 ? q0 : q1) + step;
  int qmax = dir == 0 ? sides.count0[side] : sides.count1[side];
  if (q >= 0 && q < qmax) {
    theirs[0] = dir == 0 ? (step > 0 ? 0.0 : 1.0) : 0.5;
    theirs[1] = dir == 1 ? (step > 0 ? 0.0 : 1.0) : 0.5;
    int p0 = dir == 0 ? q : q0, p1 = dir == 0 ? q1 : q;
    return sides.first[side] + p0 * sides.count1[side] + p1;
  }

  // Across the lattice's edge: the side normal to the axis crossed, at this side's end
  // of this side's normal axis.
  int crossed = dir == 0 ? (normal + 1) % 3 : (normal + 2) % 3;
  int other = 2 * crossed + (step > 0 ? 1 : 0);
  int run = dir == 0 ? q1 : q0;
  int end = upper ? g.cells[normal] - 1 : 0;
  int p0 = dir == 0 ? run : end, p1 = dir == 0 ? end : run;
  theirs[0] = dir == 0 ? 0.5 : (upper ? 1.0 : 0.0);
  theirs[1] = dir == 0 ? (upper ? 1.0 : 0.0) : 0.5;
  return sides.first[other] + p0 * sides.count1[other] + p1;
}

// Each edge between two face elements once (from the face with the smaller id), faces in
// order, each face's four edges (slow axis down, up, fast axis down, up).
std::vector<BendEdge> ShellEdges(const FlexLattice& g) {
  ShellSides sides(g);
  std::vector<BendEdge> edges;
  for (int side = 0; side < 6; side++) {
    for (int q0 = 0; q0 < sides.count0[side]; q0++) {
      for (int q1 = 0; q1 < sides.count1[side]; q1++) {
        int face = sides.first[side] + q0 * sides.count1[side] + q1;
        for (int dir = 0; dir < 2; dir++) {
          for (int step = -1; step <= 1; step += 2) {
            BendEdge e;
            int other = NeighbourFace(g, sides, side, q0, q1, dir, step, e.local[0], e.local[1]);
            if (face >= other) continue;
            e.face[0] = face;
            e.face[1] = other;
            edges.push_back(e);
          }
        }
      }
    }
  }
  return edges;
}

// A face's unit normal at local, the lengths of its tangents along (l) and across (h)
// the edge through local (the parametric axis held at 0.5 runs along it); false for a
// degenerate normal.
bool FaceAtEdge(const FlexLattice& g, const std::vector<double>& nodes, int face,
                const double local[2], double normal[3], double* along, double* across) {
  double pos[3 * 9], t1[3], t2[3];
  ElementNodes(g, face, nodes, pos);
  FlexFaceNormal(g.order, pos, local, normal, t1, t2);
  if (NormalizeVec(normal, 3) < 1e-12) return false;
  bool first_along = local[0] == 0.5;
  double l1 = NormalizeVec(t1, 3), l2 = NormalizeVec(t2, 3);
  *along = first_along ? l1 : l2;
  *across = first_along ? l2 : l1;
  return true;
}

}  // namespace

std::vector<bool> EmptyFlexCells(const std::array<int, 3>& cells, const std::vector<double>& vpos,
                                 const std::vector<int>& elem, int dim, const double* bbox) {
  // The box: given, or the points'.
  double box[6] = {1e30, 1e30, 1e30, -1e30, -1e30, -1e30};
  if (bbox) {
    std::copy(bbox, bbox + 6, box);
  } else {
    for (size_t i = 0; i + 2 < vpos.size(); i += 3) {
      for (int k = 0; k < 3; k++) {
        box[k] = std::min(box[k], vpos[i + k]);
        box[k + 3] = std::max(box[k + 3], vpos[i + k]);
      }
    }
  }
  std::vector<bool> has = CellsWithElements(cells, vpos, elem, dim, box);
  if (dim == 2 && !elem.empty()) return OutsideCells(cells, has);
  std::vector<bool> empty(has.size());
  for (size_t c = 0; c < has.size(); c++) empty[c] = !has[c];
  return empty;
}

std::string UnrotatedFlexNodes(const FlexLattice& g, const std::vector<bool>& cell_empty,
                               const std::vector<double>& nodexpos, std::vector<double>* local,
                               double r0[9]) {
  // The first cell that is not empty, and its edges from its first node.
  int ref[3] = {0, 0, 0};
  bool found = false;
  for (int ci = 0; ci < g.cells[0] && !found; ci++) {
    for (int cj = 0; cj < g.cells[1] && !found; cj++) {
      for (int ck = 0; ck < g.cells[2] && !found; ck++) {
        int id = (ci * g.cells[1] + cj) * g.cells[2] + ck;
        if (cell_empty.empty() || !cell_empty[id]) {
          ref[0] = ci, ref[1] = cj, ref[2] = ck;
          found = true;
        }
      }
    }
  }
  int i0 = ref[0] * g.order, j0 = ref[1] * g.order, k0 = ref[2] * g.order;
  int origin = g.Node(i0, j0, k0);
  int corner[3] = {g.Node(i0 + g.order, j0, k0), g.Node(i0, j0 + g.order, k0),
                   g.Node(i0, j0, k0 + g.order)};
  for (int r = 0; r < 3; r++) {
    math::Sub3(r0 + 3 * r, nodexpos.data() + 3 * corner[r], nodexpos.data() + 3 * origin);
    NormalizeVec(r0 + 3 * r, 3);
  }

  // R0 must be a rotation (the lattice's cells are boxes).
  for (int a = 0; a < 3; a++) {
    for (int b = a; b < 3; b++) {
      double expected = a == b ? 1.0 : 0.0;
      if (std::abs(math::Dot3(r0 + 3 * a, r0 + 3 * b) - expected) > 1e-8) {
        return "flex grid rotation R0 is not orthonormal";
      }
    }
  }
  local->resize(nodexpos.size());
  for (size_t i = 0; i + 2 < nodexpos.size(); i += 3) {
    double p[3];
    math::MulMatVec3(p, r0, nodexpos.data() + i);
    math::Copy3(local->data() + i, p);
  }
  return "";
}

std::string FlexCellStiffness(const FlexLattice& g, const std::vector<bool>& cell_empty,
                              const std::vector<double>& nodes, double young, double poisson,
                              double thickness, bool strain, std::vector<double>* stiffness) {
  int npe = g.NodesPerElement(), ndof = 3 * npe, nelem = g.ElementCount();
  size_t size = static_cast<size_t>(ndof) * ndof;
  stiffness->assign(size * nelem, 0.0);
  double e = strain ? kStrainYoung : young, nu = strain ? kStrainPoisson : poisson;
  std::vector<double> pos(3 * static_cast<size_t>(npe)), k;
  for (int fe = 0; fe < nelem; fe++) {
    if (!g.shell && !cell_empty.empty() && cell_empty[fe]) continue;
    int normal = ElementNodes(g, fe, nodes, pos.data());

    // The element's stiffness: a face's membrane, or a cell's volume.
    if (g.shell) {
      if (!FlexFaceStiffness(e, nu, thickness, g.order, normal, pos.data(), &k)) {
        return "degenerate 2D element with zero extent (face element " + std::to_string(fe) + ")";
      }
    } else {
      // (its extents, first node to last, divide: MuJoCo gets NaN from a flat cell)
      const double* last = pos.data() + 3 * (npe - 1);
      if (last[0] == pos[0] || last[1] == pos[1] || last[2] == pos[2]) {
        return "degenerate 3D element with zero extent (cell " + std::to_string(fe) + ")";
      }
      k.assign(size, 0.0);
      FlexInterpolatedStiffness(e, nu, g.order, pos, &k);
    }
    double* out = stiffness->data() + size * fe;
    if (!strain) {
      std::copy(k.begin(), k.end(), out);
      continue;
    }

    // Strain: the stiff modes, and a face's warp against its plate bending.
    // (room in the element's ndof x ndof block: the count, ndof - 1 modes, or one fewer
    // with a face's warp mode)
    int count = StiffModes(k, ndof, g.shell ? ndof - 2 : ndof - 1, out);
    if (!g.shell) continue;
    double warp = WarpStiffness(pos.data(), npe, normal, e, nu, thickness);
    if (warp <= 0) continue;
    double* mode = out + 1 + count * ndof;
    WarpMode(mode, pos.data(), g.order, normal);
    double scale = std::sqrt(warp);
    for (int j = 0; j < ndof; j++) mode[j] *= scale;
    out[0] = count + 1;
  }
  return "";
}

void FlexShellBending(const FlexLattice& g, const std::vector<double>& nodes, double young,
                      double poisson, double thickness, std::vector<double>* bending) {
  double plate = young * thickness * thickness * thickness / (12.0 * (1.0 - poisson * poisson));
  std::vector<BendEdge> edges = ShellEdges(g);
  bending->assign(1 + edges.size() * kFlexShellBendSize, 0.0);
  (*bending)[0] = static_cast<double>(edges.size());
  for (size_t e = 0; e < edges.size(); e++) {
    const BendEdge& edge = edges[e];

    // Both faces' rest normals at the edge, and their sizes along and across it.
    double normal[2][3], along[2], across[2];
    bool ok = true;
    for (int k = 0; k < 2 && ok; k++) {
      ok = FaceAtEdge(g, nodes, edge.face[k], edge.local[k], normal[k], &along[k], &across[k]);
    }
    if (!ok) continue;

    // Faces, midpoints, stiffness D l / h, rest normal jump.
    double* out = bending->data() + 1 + e * kFlexShellBendSize;
    out[0] = edge.face[0];
    out[1] = edge.face[1];
    out[2] = edge.local[0][0];
    out[3] = edge.local[0][1];
    out[4] = edge.local[1][0];
    out[5] = edge.local[1][1];
    double h = (across[0] + across[1]) / 2, l = (along[0] + along[1]) / 2;
    out[6] = plate * l / std::max(h, 1e-12);
    math::Sub3(out + 7, normal[0], normal[1]);
  }
}

}  // namespace simlab::compiler
