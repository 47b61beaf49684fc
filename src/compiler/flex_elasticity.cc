// Flex elasticity at compile time (see flex_elasticity.h).
//
// Element stiffness (Weischedel's coordinate-free linear elements): each edge e of an
// element gets a 3x3 basis tensor, the symmetrized product of two vectors that the
// edges or faces away from e span; with trE[e] its trace and trEE[a][b] the trace of
// basis[a] basis[b], the metric between edges a and b is
//
//   mu trEE[a][b] + lambda trE[a] trE[b],
//
// with the Lame parameters scaled by a quarter of the element's size times its
// thickness. Bending (Wardetzky's cotangent operator, Garg's cubic shells): the flap's
// cotangent weights c give the operator c c^T cos(theta) k, with k = 3 mu t^3 / (24 A).
#include "compiler/flex_elasticity.h"

#include <cmath>

#include "compiler/orientation.h"
#include "engine/flex_elasticity.h"
#include "math/math.h"

namespace simlab::compiler {

namespace {

// Triangle layout (MuJoCo's Stencil2D, whose face and edge2face tables are this one):
// kTriangleSide[i] is the side opposite vertex i, and the basis of edge e comes from the
// two other sides, kTriangleSide[e] read as side numbers.
constexpr int kTriangleSide[3][2] = {{1, 2}, {2, 0}, {0, 1}};

// Tetrahedron layout (MuJoCo's Stencil3D): its four faces, and for each edge (in
// kFlexElemEdges order) the two faces that do not hold it.
constexpr int kTetFace[4][3] = {{2, 1, 0}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
constexpr int kTetEdgeFaces[6][2] = {{2, 3}, {1, 3}, {2, 1}, {1, 0}, {0, 2}, {0, 3}};

// The world position of vertex v.
const double* At(const std::vector<double>& x, int v) { return x.data() + 3 * v; }

// Area of triangle (v[0], v[1], v[2]); zero when its doubled area's square is below the
// compiler's epsilon (the normalization MuJoCo's ComputeVolume calls).
double TriangleArea(const std::vector<double>& x, const int* v) {
  double e1[3], e2[3], normal[3];
  math::Sub3(e1, At(x, v[1]), At(x, v[0]));
  math::Sub3(e2, At(x, v[2]), At(x, v[0]));
  math::Cross3(normal, e1, e2);
  return NormalizeVec(normal, 3) / 2;
}

// Signed volume of tetrahedron v (negative when right-handed as the compiler orders it).
double TetVolume(const std::vector<double>& x, const int* v) {
  double e1[3], e2[3], e3[3], normal[3];
  math::Sub3(e1, At(x, v[1]), At(x, v[0]));
  math::Sub3(e2, At(x, v[2]), At(x, v[0]));
  math::Sub3(e3, At(x, v[3]), At(x, v[0]));
  math::Cross3(normal, e1, e2);
  return math::Dot3(normal, e3) / 6;
}

// basis = (a b^T + b a^T) / scale, row-major.
void SymmetricProduct(double basis[9], const double* a, const double* b, double scale) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) basis[3 * i + j] = (a[i] * b[j] + b[i] * a[j]) / scale;
  }
}

// Basis of a triangle's edge: the in-plane normals of its two other sides (the `left`
// side taken from its second vertex to its first, the `right` side from first to second).
void TriangleEdgeBasis(double basis[9], const std::vector<double>& x, const int* v,
                       const int* left, const int* right, double area) {
  double side_left[3], side_right[3], normal[3], normal_left[3], normal_right[3];
  math::Sub3(side_left, At(x, v[left[0]]), At(x, v[left[1]]));
  math::Sub3(side_right, At(x, v[right[1]]), At(x, v[right[0]]));
  math::Cross3(normal, side_right, side_left);
  NormalizeVec(normal, 3);
  math::Cross3(normal_left, normal, side_left);
  math::Cross3(normal_right, side_right, normal);
  SymmetricProduct(basis, normal_left, normal_right, 8 * area * area);
}

// Basis of a tetrahedron's edge: the area normals of the two faces that miss it.
void TetEdgeBasis(double basis[9], const std::vector<double>& x, const int* v,
                  const int* left, const int* right, double volume) {
  double l1[3], l2[3], r1[3], r2[3], normal_left[3], normal_right[3];
  math::Sub3(l1, At(x, v[left[1]]), At(x, v[left[0]]));
  math::Sub3(l2, At(x, v[left[2]]), At(x, v[left[0]]));
  math::Sub3(r1, At(x, v[right[1]]), At(x, v[right[0]]));
  math::Sub3(r2, At(x, v[right[2]]), At(x, v[right[0]]));
  math::Cross3(normal_left, l1, l2);
  math::Cross3(normal_right, r1, r2);
  SymmetricProduct(basis, normal_left, normal_right, 72 * volume * volume);
}

// The upper triangle of mu trEE + lambda trE trE^T over the element's nedge edges, row by
// row, into metric (the rest of its 21 numbers stay as they are).
void EdgeMetric(double* metric, double mu, double lambda, const double basis[6][9],
                int nedge) {
  // First invariant: the trace of each edge's basis.
  double trace[6] = {0, 0, 0, 0, 0, 0};
  for (int e = 0; e < nedge; e++) {
    for (int i = 0; i < 3; i++) trace[e] += basis[e][4 * i];
  }

  // Second invariant: trace(basis[a] basis[b]) for each pair.
  double trace2[6][6] = {};
  for (int a = 0; a < nedge; a++) {
    for (int b = 0; b < nedge; b++) {
      for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) trace2[a][b] += basis[a][3 * i + j] * basis[b][3 * j + i];
      }
    }
  }

  // The metric's upper triangle.
  int id = 0;
  for (int a = 0; a < nedge; a++) {
    for (int b = a; b < nedge; b++) metric[id++] = mu * trace2[a][b] + lambda * trace[b] * trace[a];
  }
}

// The 21 stiffness numbers of one element (vertices v) of dimension 2 or 3.
void ElementStiffness(double* metric, int dim, double young, double poisson, double thickness,
                      const std::vector<double>& x, const int* v) {
  double size = dim == 2 ? TriangleArea(x, v) : TetVolume(x, v);

  // Lame parameters times a quarter of the element's size and its thickness.
  double mu = young / (2 * (1 + poisson)) * std::abs(size) / 4 * thickness;
  double lambda = young * poisson / ((1 + poisson) * (1 - 2 * poisson)) * std::abs(size) / 4 *
                  thickness;

  // Each edge's basis, then the metric between edges.
  int nedge = kFlexElemEdgeCount[dim - 1];
  double basis[6][9] = {};
  for (int e = 0; e < nedge; e++) {
    if (dim == 2) {
      TriangleEdgeBasis(basis[e], x, v, kTriangleSide[kTriangleSide[e][0]],
                        kTriangleSide[kTriangleSide[e][1]], size);
    } else {
      TetEdgeBasis(basis[e], x, v, kTetFace[kTetEdgeFaces[e][0]], kTetFace[kTetEdgeFaces[e][1]],
                   size);
    }
  }
  EdgeMetric(metric, mu, lambda, basis, nedge);
}

// Cotangent of the angle at vertex a of triangle (a, b, c).
double Cotangent(const std::vector<double>& x, int a, int b, int c) {
  double ab[3], ac[3], normal[3];
  math::Sub3(ab, At(x, b), At(x, a));
  math::Sub3(ac, At(x, c), At(x, a));
  math::Cross3(normal, ab, ac);
  return math::Dot3(ab, ac) / math::Norm3(normal);
}

// Area of triangle (a, b, c), without the epsilon of TriangleArea.
double FlapTriangleArea(const std::vector<double>& x, int a, int b, int c) {
  double ab[3], ac[3], normal[3];
  math::Sub3(ab, At(x, b), At(x, a));
  math::Sub3(ac, At(x, c), At(x, a));
  math::Cross3(normal, ab, ac);
  return math::Norm3(normal) / 2;
}

// The 17 bending numbers of one inner edge's flap v (shear modulus mu).
void FlapBending(double* bending, const std::vector<double>& x, const std::array<int, 4>& v,
                 double mu, double thickness) {
  // Cotangents at the edge's ends in both triangles, and the operator's weights.
  double a01 = Cotangent(x, v[0], v[1], v[2]);
  double a02 = Cotangent(x, v[0], v[3], v[1]);
  double a03 = Cotangent(x, v[1], v[2], v[0]);
  double a04 = Cotangent(x, v[1], v[0], v[3]);
  double weight[4] = {a03 + a04, a01 + a02, -(a01 + a03), -(a02 + a04)};
  double area = FlapTriangleArea(x, v[0], v[1], v[2]) + FlapTriangleArea(x, v[1], v[0], v[3]);
  double stiffness = 3 * mu * std::pow(thickness, 3) / (24 * area);

  // The flap's edges from v0 and v1, and the dihedral angle's cosine from the two
  // triangles' scaled normals within the flap.
  double e0[3], e1[3], e2[3], e3[3], e4[3], t0[3], t1[3];
  math::Sub3(e0, At(x, v[1]), At(x, v[0]));
  math::Sub3(e1, At(x, v[2]), At(x, v[0]));
  math::Sub3(e2, At(x, v[3]), At(x, v[0]));
  math::Sub3(e3, At(x, v[2]), At(x, v[1]));
  math::Sub3(e4, At(x, v[3]), At(x, v[1]));
  for (int k = 0; k < 3; k++) {
    t0[k] = -(a03 * e1[k] + a01 * e3[k]);
    t1[k] = -(a04 * e2[k] + a02 * e4[k]);
  }
  double sqr = math::Dot3(e0, e0);
  double cos_theta = -math::Dot3(t0, t1) / sqr;

  // The operator, then the curved reference's coefficient.
  for (int i = 0; i < 4; i++) {
    for (int j = 0; j < 4; j++) bending[4 * i + j] += weight[i] * weight[j] * cos_theta * stiffness;
  }
  double normal[3];
  math::Cross3(normal, e0, e1);
  bending[16] = math::Dot3(normal, e2) * (a01 - a03) * (a04 - a02) * stiffness /
                (sqr * std::sqrt(sqr));
}

// 1D Gauss-Legendre points and weights on [0, 1] as MuJoCo places them (with 3 points
// the outer two divide by sqrt(3/5) where the rule multiplies, landing outside [0, 1]).
void QuadraturePoints(double* points, double* weights, int npoint) {
  double mid = 0.5, half = 0.5;
  if (npoint == 2) {
    points[0] = -half / std::sqrt(3.0) + mid;
    points[1] = half / std::sqrt(3.0) + mid;
    weights[0] = half;
    weights[1] = half;
  } else {
    points[0] = mid;
    points[1] = -half / std::sqrt(3. / 5.) + mid;
    points[2] = half / std::sqrt(3. / 5.) + mid;
    weights[0] = 8. / 9. * half;
    weights[1] = 5. / 9. * half;
    weights[2] = 5. / 9. * half;
  }
}

using Mat3 = std::array<std::array<double, 3>, 3>;

// (a + a^T) / 2
Mat3 Symmetric(const Mat3& a) {
  Mat3 r;
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) r[i][j] = (a[i][j] + a[j][i]) / 2;
  }
  return r;
}

// trace(a b)
double TraceOfProduct(const Mat3& a, const Mat3& b) {
  Mat3 p;
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) p[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
  }
  return p[0][0] + p[1][1] + p[2][2];
}

double Trace(const Mat3& a) { return a[0][0] + a[1][1] + a[2][2]; }

// One quadrature point's share of the stiffness between nodes i and j (shape gradients
// gi, gj): for node i's coordinate a and node j's coordinate b, the displacement
// gradients du (row a) and dv (row b) in lambda tr(du) tr(dv) + mu sym(du):sym(dv),
// subtracted from the (3i + a, 3j + b) entry of the ndof x ndof matrix k.
void SubtractNodePair(double* k, int ndof, int i, int j, const double* gi, const double* gj,
                      const double inv[3], double lambda, double mu, double dvol) {
  for (int a = 0; a < 3; a++) {
    for (int b = 0; b < 3; b++) {
      Mat3 du{}, dv{};
      for (int c = 0; c < 3; c++) {
        du[a][c] = inv[c] * gi[c];
        dv[b][c] = inv[c] * gj[c];
      }
      double& entry = k[static_cast<size_t>(ndof) * (3 * i + a) + 3 * j + b];
      entry -= lambda * Trace(du) * Trace(dv) * dvol;
      entry -= mu * TraceOfProduct(Symmetric(du), Symmetric(dv)) * dvol;
    }
  }
}

}  // namespace

std::vector<std::array<int, 4>> FlexFlaps(int dim, const std::vector<int>& elem,
                                          const std::vector<int>& elemedge, int nedge) {
  std::vector<std::array<int, 4>> flaps(nedge, {-1, -1, -1, -1});
  if (dim != 2) return flaps;

  // An edge's first triangle opens its flap, any later one closes it.
  std::vector<bool> opened(nedge, false);
  int ntriangle = static_cast<int>(elem.size()) / 3;
  for (int t = 0; t < ntriangle; t++) {
    const int* v = elem.data() + 3 * t;
    for (int e = 0; e < 3; e++) {
      const int* local = kFlexElemEdges[1][e];
      int opposite = v[(local[1] + 1) % 3];
      std::array<int, 4>& flap = flaps[elemedge[3 * t + e]];
      if (!opened[elemedge[3 * t + e]]) {
        opened[elemedge[3 * t + e]] = true;
        flap = {v[local[0]], v[local[1]], opposite, -1};
      } else {
        flap[3] = opposite;
      }
    }
  }
  return flaps;
}

void FlexElementStiffness(int dim, int elastic2d, double young, double poisson,
                          double thickness, const std::vector<double>& vertxpos,
                          const std::vector<int>& elem, std::vector<double>* stiffness) {
  int nelem = static_cast<int>(elem.size()) / (dim + 1);
  stiffness->assign(static_cast<size_t>(kFlexStiffnessSize) * nelem, 0.0);

  // Triangles only as membranes with a thickness; tetrahedra at MuJoCo's thickness 4.
  for (int t = 0; t < nelem; t++) {
    double* metric = stiffness->data() + kFlexStiffnessSize * t;
    const int* v = elem.data() + (dim + 1) * t;
    if (dim == 2 && elastic2d >= 2 && thickness > 0) {
      ElementStiffness(metric, dim, young, poisson, thickness, vertxpos, v);
    } else if (dim == 3) {
      ElementStiffness(metric, dim, young, poisson, 4, vertxpos, v);
    }
  }
}

void FlexBending(double young, double poisson, double thickness,
                 const std::vector<double>& vertxpos,
                 const std::vector<std::array<int, 4>>& flaps, std::vector<double>* bending) {
  bending->assign(static_cast<size_t>(kFlexBendingSize) * flaps.size(), 0.0);
  double mu = young / (2 * (1 + poisson));

  // Boundary edges (a flap of one triangle) stay zero.
  for (size_t e = 0; e < flaps.size(); e++) {
    if (flaps[e][3] == -1) continue;
    FlapBending(bending->data() + kFlexBendingSize * e, vertxpos, flaps[e], mu, thickness);
  }
}

void FlexInterpolatedStiffness(double young, double poisson, int order,
                               const std::vector<double>& nodexpos,
                               std::vector<double>* stiffness) {
  int nbasis = order + 1;
  int n = nbasis * nbasis * nbasis;
  int ndof = 3 * n;
  if (stiffness->size() < static_cast<size_t>(ndof) * ndof) {
    stiffness->resize(static_cast<size_t>(ndof) * ndof, 0.0);
  }
  double* k = stiffness->data();

  // Quadrature on the unit cube; the box from the first node to the last maps onto it.
  double points[3], weights[3];
  QuadraturePoints(points, weights, nbasis);
  double dx = nodexpos[3 * (n - 1)] - nodexpos[0];
  double dy = nodexpos[3 * (n - 1) + 1] - nodexpos[1];
  double dz = nodexpos[3 * (n - 1) + 2] - nodexpos[2];
  double det = dx * dy * dz;
  double inv[3] = {1.0 / dx, 1.0 / dy, 1.0 / dz};
  double lambda = young * poisson / (1 + poisson) / (1 - 2 * poisson);
  double mu = young / (2 * (1 + poisson));

  std::vector<double> gradient(3 * n);
  for (int ps = 0; ps < nbasis; ps++) {
    for (int pt = 0; pt < nbasis; pt++) {
      for (int pu = 0; pu < nbasis; pu++) {
        double p[3] = {points[ps], points[pt], points[pu]};
        double dvol = weights[ps] * weights[pt] * weights[pu] * det;

        // Gradients of the nodes' shape functions (x slowest).
        int node = 0;
        for (int bx = 0; bx < nbasis; bx++) {
          for (int by = 0; by < nbasis; by++) {
            for (int bz = 0; bz < nbasis; bz++) {
              FlexShapeGradient(&gradient[3 * node++], p, bx, by, bz, order);
            }
          }
        }

        // Every pair of nodes.
        for (int i = 0; i < n; i++) {
          for (int j = 0; j < n; j++) {
            SubtractNodePair(k, ndof, i, j, &gradient[3 * i], &gradient[3 * j], inv, lambda, mu,
                             dvol);
          }
        }
      }
    }
  }
}

bool FlexFaceStiffness(double young, double poisson, double thickness, int order,
                       int normal_axis, const double* pos, std::vector<double>* stiffness) {
  int nbasis = order + 1, npe = nbasis * nbasis, ndof = 3 * npe;
  int axis0 = (normal_axis + 1) % 3, axis1 = (normal_axis + 2) % 3;
  double d0 = pos[3 * (npe - 1) + axis0] - pos[axis0];
  double d1 = pos[3 * (npe - 1) + axis1] - pos[axis1];
  if (d0 == 0 || d1 == 0) return false;
  stiffness->assign(static_cast<size_t>(ndof) * ndof, 0.0);
  double* k = stiffness->data();

  // Quadrature on the unit square; the face's extents along its axes map onto it.
  double points[3], weights[3];
  QuadraturePoints(points, weights, nbasis);
  double det = d0 * d1, inv0 = 1.0 / d0, inv1 = 1.0 / d1;
  double lambda = young * poisson / (1.0 - poisson * poisson);  // plane stress
  double mu = young / (2.0 * (1.0 + poisson));

  std::vector<double> gradient(2 * npe);
  const int inplane[2] = {axis0, axis1};
  for (int ps = 0; ps < nbasis; ps++) {
    for (int pt = 0; pt < nbasis; pt++) {
      double s = points[ps], t = points[pt];
      double dvol = weights[ps] * weights[pt] * det * thickness;
      int node = 0;
      for (int b0 = 0; b0 < nbasis; b0++) {
        for (int b1 = 0; b1 < nbasis; b1++, node++) {
          gradient[2 * node] = FlexShapeSlope(s, b0, order) * FlexShape(t, b1, order);
          gradient[2 * node + 1] = FlexShape(s, b0, order) * FlexShapeSlope(t, b1, order);
        }
      }

      // Every pair of nodes, in-plane displacements only (a membrane: no transverse
      // shear).
      for (int i = 0; i < npe; i++) {
        for (int j = 0; j < npe; j++) {
          for (int a : inplane) {
            for (int b : inplane) {
              Mat3 du{}, dv{};
              du[a][axis0] = inv0 * gradient[2 * i];
              du[a][axis1] = inv1 * gradient[2 * i + 1];
              dv[b][axis0] = inv0 * gradient[2 * j];
              dv[b][axis1] = inv1 * gradient[2 * j + 1];
              double& entry = k[static_cast<size_t>(ndof) * (3 * i + a) + 3 * j + b];
              entry -= lambda * Trace(du) * Trace(dv) * dvol;
              entry -= mu * TraceOfProduct(Symmetric(du), Symmetric(dv)) * dvol;
            }
          }
        }
      }
    }
  }
  return true;
}

}  // namespace simlab::compiler
