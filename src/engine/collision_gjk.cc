// GJK and EPA on the Minkowski difference of two convex shapes (MuJoCo's native CCD).
//
// GJK walks a simplex (1 to 4 vertices of shape1 - shape2) towards the origin; the
// closest point of the simplex to the origin comes from the signed-volume subdistance
// algorithm (Montanari et al. 2017). When only contact matters, a simplex that reaches 4
// vertices is handed to a tetrahedron walk that decides whether the origin is inside.
// If the shapes overlap, EPA grows a polytope from the final simplex towards the
// boundary of the difference: the face nearest the origin gives the penetration depth,
// its normal the contact normal, and its barycentric coordinates the witness points.
#include "engine/collision_gjk.h"

#include <cfloat>
#include <cmath>
#include <vector>

#include "math/math.h"

namespace simlab::ccd {

namespace {

using math::Cross3;
using math::Dot3;
using math::Norm3;
using math::Scale3;
using math::Sub3;

constexpr double kMinVal2 = kMinVal * kMinVal;
constexpr double kMaxVal2 = kMaxVal * kMaxVal;
constexpr double kHuge = DBL_MAX;         // "no answer" distance (mjMAX_LIMIT)
constexpr int kEpaStaticIterations = 170;  // polytope storage covers this many iterations

// ---------------------------------------------------------------- small vector helpers

// Determinant of the 3x3 matrix with columns a, b, c: a . (b x c).
double Det3(const double* a, const double* b, const double* c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// res = sum of coef[i] * v[i] over the first n of up to four vectors.
void Combine(double* res, const double* coef, int n, const double* v0, const double* v1,
             const double* v2, const double* v3) {
  const double* v[4] = {v0, v1, v2, v3};
  if (n < 1 || n > 4) return;
  for (int c = 0; c < 3; c++) {
    double sum = coef[0] * v[0][c];
    for (int i = 1; i < n; i++) sum += coef[i] * v[i][c];
    res[c] = sum;
  }
}

// 1 when a and b are both positive, -1 when both negative, else 0.
int SignMatch(double a, double b) {
  if (a > 0 && b > 0) return 1;
  if (a < 0 && b < 0) return -1;
  return 0;
}

// ---------------------------------------------------------------- projections

// The origin projected onto the plane through a, b, c (into res). Returns false when
// the three points do not span a plane. Three normal formulas are tried in turn, the
// first with a usable (nonzero, not tiny) normal wins.
bool ProjectOriginOnPlane(double* res, const double* a, const double* b, const double* c) {
  double ba[3], ca[3], cb[3], n[3];
  Sub3(ba, b, a);
  Sub3(ca, c, a);
  Sub3(cb, c, b);
  const double* pairs[3][3] = {{cb, ba, b}, {ba, ca, a}, {ca, cb, c}};
  for (int i = 0; i < 3; i++) {
    Cross3(n, pairs[i][0], pairs[i][1]);
    double nv = Dot3(n, pairs[i][2]);
    double nn = Dot3(n, n);
    if (i < 2) {
      if (nn == 0) return false;
      if (!(nv != 0 && nn > kMinVal)) continue;
    }
    Scale3(res, n, nv / nn);
    return true;
  }
  return true;  // not reached: the last formula always answers
}

// The origin projected onto the line through a and b.
void ProjectOriginOnLine(double* res, const double* a, const double* b) {
  double ab[3];
  Sub3(ab, b, a);
  double t = -(Dot3(b, ab) / Dot3(ab, ab));
  res[0] = b[0] + t * ab[0];
  res[1] = b[1] + t * ab[1];
  res[2] = b[2] + t * ab[2];
}

// The two coordinate axes of the plane onto which the triangle s1 s2 s3 projects with the
// largest area, and that signed area (twice it): the minor of the dropped axis.
double LargestProjection(const double* s1, const double* s2, const double* s3, int* x,
                         int* y) {
  auto minor = [&](int a, int b) {
    return s2[a] * s3[b] - s2[b] * s3[a] - s1[a] * s3[b] + s1[b] * s3[a] + s1[a] * s2[b] -
           s1[b] * s2[a];
  };
  double m_yz = minor(1, 2), m_xz = minor(0, 2), m_xy = minor(0, 1);
  double a_yz = std::abs(m_yz), a_xz = std::abs(m_xz), a_xy = std::abs(m_xy);
  if (a_yz >= a_xz && a_yz >= a_xy) {
    *x = 1, *y = 2;
    return m_yz;
  }
  if (a_xz >= a_xy) {
    *x = 0, *y = 2;
    return m_xz;
  }
  *x = 0, *y = 1;
  return m_xy;
}

// Twice the signed area of the 2D triangle (p, a, b) in axes x, y.
double SignedArea2(const double* p, const double* a, const double* b, int x, int y) {
  return p[x] * a[y] + p[y] * b[x] + a[x] * b[y] - p[x] * b[y] - p[y] * a[x] - b[x] * a[y];
}

// Barycentric coordinates of p (in the triangle's plane) with respect to v1 v2 v3.
void TriangleCoordinates(double lambda[3], const double* v1, const double* v2,
                         const double* v3, const double* p) {
  int x, y;
  double area = LargestProjection(v1, v2, v3, &x, &y);
  lambda[0] = SignedArea2(p, v2, v3, x, y) / area;
  lambda[1] = SignedArea2(p, v3, v1, x, y) / area;
  lambda[2] = SignedArea2(p, v1, v2, x, y) / area;
}

// ---------------------------------------------------------------- subdistance

// Barycentric coordinates of the point of segment s1 s2 closest to the origin.
void ClosestOnSegment(double lambda[2], const double* s1, const double* s2) {
  double p[3];
  ProjectOriginOnLine(p, s1, s2);

  // measure along the axis where the segment is longest
  int axis = 0;
  double extent = s1[0] - s2[0];
  for (int i = 1; i < 3; i++) {
    double e = s1[i] - s2[i];
    if (std::abs(e) >= std::abs(extent)) {
      extent = e;
      axis = i;
    }
  }
  double c1 = p[axis] - s2[axis];
  double c2 = s1[axis] - p[axis];
  bool inside = SignMatch(extent, c1) && SignMatch(extent, c2);
  lambda[0] = inside ? c1 / extent : 0;
  lambda[1] = inside ? c2 / extent : 1;
}

// Barycentric coordinates of the point of triangle s1 s2 s3 closest to the origin.
void ClosestOnTriangle(double lambda[3], const double* s1, const double* s2,
                       const double* s3) {
  double p[3];
  if (!ProjectOriginOnPlane(p, s1, s2, s3)) {
    ClosestOnSegment(lambda, s1, s2);
    lambda[2] = 0;
    return;
  }
  int x, y;
  double area = LargestProjection(s1, s2, s3, &x, &y);
  double c[3] = {SignedArea2(p, s2, s3, x, y), SignedArea2(p, s3, s1, x, y),
                 SignedArea2(p, s1, s2, x, y)};
  int match[3] = {SignMatch(area, c[0]), SignMatch(area, c[1]), SignMatch(area, c[2])};

  // the projection lies inside the triangle
  if (match[0] && match[1] && match[2]) {
    for (int i = 0; i < 3; i++) lambda[i] = c[i] / area;
    return;
  }

  // otherwise the nearest of the edges facing the projection (edge i omits vertex i)
  const double* s[3] = {s1, s2, s3};
  double best = kHuge;
  for (int i = 0; i < 3; i++) {
    if (match[i]) continue;
    int a = i == 0 ? 1 : 0, b = i == 2 ? 1 : 2;
    double l[2], q[3];
    ClosestOnSegment(l, s[a], s[b]);
    Combine(q, l, 2, s[a], s[b], nullptr, nullptr);
    double dist2 = Dot3(q, q);
    if (i == 0 || dist2 < best) {
      lambda[i] = 0;
      lambda[a] = l[0];
      lambda[b] = l[1];
      best = dist2;
    }
  }
}

// Barycentric coordinates of the point of tetrahedron s1..s4 closest to the origin.
// As MuJoCo 3.5, when the face opposite s4 wins after another face was taken, the
// coordinate of s4 keeps that earlier face's value.
void ClosestOnTetrahedron(double lambda[4], const double* s1, const double* s2,
                          const double* s3, const double* s4) {
  double c[4] = {-Det3(s2, s3, s4), Det3(s1, s3, s4), -Det3(s1, s2, s4), Det3(s1, s2, s3)};
  double volume = c[0] + c[1] + c[2] + c[3];
  int match[4];
  for (int i = 0; i < 4; i++) match[i] = SignMatch(volume, c[i]);

  // the origin is inside
  if (match[0] && match[1] && match[2] && match[3]) {
    for (int i = 0; i < 4; i++) lambda[i] = c[i] / volume;
    return;
  }

  // otherwise the nearest of the faces facing the origin (face i omits vertex i)
  const double* s[4] = {s1, s2, s3, s4};
  double best = kHuge;
  for (int i = 0; i < 4; i++) {
    if (match[i]) continue;
    int idx[3], k = 0;
    for (int j = 0; j < 4; j++) {
      if (j != i) idx[k++] = j;
    }
    double l[3], q[3];
    ClosestOnTriangle(l, s[idx[0]], s[idx[1]], s[idx[2]]);
    Combine(q, l, 3, s[idx[0]], s[idx[1]], s[idx[2]], nullptr);
    double dist2 = Dot3(q, q);
    if (i == 0 || dist2 < best) {
      if (i < 3) lambda[i] = 0;
      for (int j = 0; j < 3; j++) lambda[idx[j]] = l[j];
      best = dist2;
    }
  }
}

// Barycentric coordinates of the point of an n-vertex simplex closest to the origin.
void ClosestOnSimplex(double lambda[4], int n, const CcdVertex simplex[4]) {
  lambda[0] = lambda[1] = lambda[2] = lambda[3] = 0;
  const double *s1 = simplex[0].vert, *s2 = simplex[1].vert;
  if (n == 4) {
    ClosestOnTetrahedron(lambda, s1, s2, simplex[2].vert, simplex[3].vert);
  } else if (n == 3) {
    ClosestOnTriangle(lambda, s1, s2, simplex[2].vert);
  } else if (n == 2) {
    ClosestOnSegment(lambda, s1, s2);
  } else {
    lambda[0] = 1;
  }
}

// ---------------------------------------------------------------- support points

// Both shapes are polytopes without margin (boxes, meshes): GJK and EPA then converge in
// finitely many steps and use no tolerance.
bool BothDiscrete(const ConvexShape* s1, const ConvexShape* s2) {
  if (s1->margin != 0 || s2->margin != 0) return false;
  auto discrete = [](int type) {
    return type == kGeomMesh || type == kGeomBox || type == kGeomHfield;
  };
  return discrete(s1->type) && discrete(s2->type);
}

// The vertex of shape1 - shape2 farthest along dir (unit): shape1's support along dir
// minus shape2's along -dir, each pushed out by half its margin.
void MinkowskiSupport(CcdVertex* v, ConvexShape* s1, ConvexShape* s2, const double* dir,
                      const double* dir_neg) {
  s1->support(v->vert1, s1, dir);
  if (s1->margin > 0 && s1->geom >= 0) {
    double half = 0.5 * s1->margin;
    for (int i = 0; i < 3; i++) v->vert1[i] += dir[i] * half;
  }
  s2->support(v->vert2, s2, dir_neg);
  if (s2->margin > 0 && s2->geom >= 0) {
    double half = 0.5 * s2->margin;
    for (int i = 0; i < 3; i++) v->vert2[i] += dir_neg[i] * half;
  }
  Sub3(v->vert, v->vert1, v->vert2);
  v->index1 = s1->vertindex;
  v->index2 = s2->vertindex;
}

// GJK's support vertex towards the origin from the current point x (norm x_norm).
void SupportTowardsOrigin(CcdVertex* v, ConvexShape* s1, ConvexShape* s2, const double* x,
                          double x_norm) {
  double dir[3], dir_neg[3];
  Scale3(dir_neg, x, 1 / x_norm);
  Scale3(dir, dir_neg, -1);
  MinkowskiSupport(v, s1, s2, dir, dir_neg);
}

// ---------------------------------------------------------------- tetrahedron walk

// Unit normal of the triangle (v1, v2, v3) as (v3 - v1) x (v2 - v1), and the signed
// distance of its plane from the origin; kHuge when the normal is degenerate.
double PlaneDistance(double* normal, const CcdVertex* v1, const CcdVertex* v2,
                     const CcdVertex* v3) {
  double e1[3], e2[3];
  Sub3(e1, v3->vert, v1->vert);
  Sub3(e2, v2->vert, v1->vert);
  Cross3(normal, e1, e2);
  double norm2 = Dot3(normal, normal);
  if (norm2 > kMinVal2 && norm2 < kMaxVal2) {
    Scale3(normal, normal, 1 / std::sqrt(norm2));
    return Dot3(normal, v1->vert);
  }
  return kHuge;
}

// Decides overlap from GJK's tetrahedron by walking it towards the origin: 1 when the
// origin is enclosed (status->simplex then holds the enclosing tetrahedron), 0 when a
// separating plane is found, -1 when undecided (degenerate or out of iterations).
int TetrahedronWalk(CcdStatus* status, ConvexShape* s1, ConvexShape* s2) {
  CcdVertex simplex[4] = {status->simplex[0], status->simplex[1], status->simplex[2],
                          status->simplex[3]};
  int s[4] = {0, 1, 2, 3};
  int k = status->gjk_iterations;
  for (; k < status->config.max_iterations; k++) {
    // distance of each face's plane (face i omits vertex i), outward normals
    double dist[4], normals[12];
    dist[0] = PlaneDistance(normals + 0, simplex + s[2], simplex + s[1], simplex + s[3]);
    dist[1] = PlaneDistance(normals + 3, simplex + s[0], simplex + s[2], simplex + s[3]);
    dist[2] = PlaneDistance(normals + 6, simplex + s[1], simplex + s[0], simplex + s[3]);
    dist[3] = PlaneDistance(normals + 9, simplex + s[0], simplex + s[1], simplex + s[2]);
    if (!dist[3] || !dist[2] || !dist[1] || !dist[0]) {
      status->gjk_iterations = k;
      return -1;
    }

    // the face nearest the origin; all positive: the origin is inside
    int a = dist[0] < dist[1] ? 0 : 1;
    int b = dist[2] < dist[3] ? 2 : 3;
    int near = dist[a] < dist[b] ? a : b;
    if (dist[near] > 0) {
      status->nsimplex = 4;
      for (int i = 0; i < 4; i++) status->simplex[i] = simplex[s[i]];
      status->gjk_iterations = k;
      return 1;
    }

    // replace the vertex opposite that face by the support beyond it
    const double* n = normals + 3 * near;
    double n_neg[3] = {-n[0], -n[1], -n[2]};
    MinkowskiSupport(simplex + s[near], s1, s2, n, n_neg);
    if (Dot3(n, simplex[s[near]].vert) < 0) {
      status->nsimplex = 0;
      status->gjk_iterations = k;
      return 0;
    }

    // keep the orientation of the tetrahedron
    int i = (near + 1) & 3, j = (near + 2) & 3;
    int swap = s[i];
    s[i] = s[j];
    s[j] = swap;
  }
  status->gjk_iterations = k;
  return -1;
}

// ---------------------------------------------------------------- GJK

// Ends GJK without an answer: the shapes are apart (beyond the cutoff).
void GjkApart(CcdStatus* status, int k) {
  status->gjk_iterations = k;
  status->nsimplex = 0;
  status->nx = 0;
  status->dist = kHuge;
  status->separated = true;
}

// Has GJK reached its answer before the next support point? 3.5.1 stops when x is at
// the origin (leaving |x|^2 as the distance, as MuJoCo 3.5.1 does); 3.12 (newer) when
// |x| is within tolerance of it (kMinVal for two polytopes) or stopped shrinking. Sets
// x_norm to |x| for the support point.
bool GjkAtRest(bool newer, double min_norm, const double* x, double* x_norm,
               double x_norm_prev) {
  if (newer) return *x_norm < min_norm || std::abs(x_norm_prev - *x_norm) < kMinVal;
  *x_norm = Dot3(x, x);
  if (*x_norm < kMinVal2) return true;
  *x_norm = std::sqrt(*x_norm);
  return false;
}

// 3.12 ends GJK by one more support point along x: beyond the origin, the shapes are
// apart. (With x at the origin the answer is "not apart" without asking.)
void GjkFinalSeparation(CcdStatus* status, ConvexShape* s1, ConvexShape* s2,
                        const double* x, double x_norm) {
  if (!(x_norm > 0)) return;
  CcdVertex probe;
  SupportTowardsOrigin(&probe, s1, s2, x, x_norm);
  if (Dot3(x, probe.vert) > 0) status->separated = true;
}

// GJK from the start points status->x1, x2: the distance (or 0 if overlapping) in
// status->dist, witness points in x1, x2, and the final simplex.
void Gjk(CcdStatus* status, ConvexShape* s1, ConvexShape* s2) {
  const CcdConfig& config = status->config;
  bool newer = config.newer;
  bool want_dist = config.dist_cutoff > 0;
  bool try_walk = !want_dist;  // contact only: decide overlap by the tetrahedron walk
  bool discrete = BothDiscrete(s1, s2);
  CcdVertex* simplex = status->simplex;
  int n = 0, k = 0;
  double x[3], lambda[4] = {1, 0, 0, 0};
  double epsilon = discrete ? 0 : 0.5 * config.tolerance * config.tolerance;
  double min_norm = discrete ? kMinVal : config.tolerance;  // 3.12's rest test
  Sub3(x, status->x1, status->x2);
  double x_norm = Norm3(x), x_norm_prev = 0;
  status->separated = false;

  for (; k < config.max_iterations; k++) {
    // support vertex towards the origin
    if (GjkAtRest(newer, min_norm, x, &x_norm, x_norm_prev)) break;
    SupportTowardsOrigin(simplex + n, s1, s2, x, x_norm);
    const double* sk = simplex[n].vert;

    // converged: the Frank-Wolfe duality gap <x, x - s> is below epsilon
    double gap[3];
    Sub3(gap, x, sk);
    if (Dot3(x, gap) < epsilon) {
      if (!k && !newer) n = 1;
      break;
    }

    // a separating plane: apart (or farther than the cutoff). 3.12 compares the lower
    // bound <x, s> / |x| with the cutoff; 3.5.1 its square
    double xs = Dot3(x, sk);
    if (!want_dist) {
      if (xs > 0) return GjkApart(status, k);
    } else if (config.dist_cutoff < kHuge && xs > 0) {
      bool beyond = newer ? xs >= config.dist_cutoff * x_norm
                          : xs * xs / Dot3(x, x) >= config.dist_cutoff * config.dist_cutoff;
      if (beyond) return GjkApart(status, k);
    }

    // a full tetrahedron and only contact wanted: try the tetrahedron walk once
    if (n == 3 && try_walk) {
      status->gjk_iterations = k;
      int walk = TetrahedronWalk(status, s1, s2);
      if (walk != -1) {
        status->nx = 0;
        status->separated = walk == 0;
        status->dist = walk > 0 ? 0 : kHuge;
        return;
      }
      k = status->gjk_iterations;
      try_walk = false;
    }

    // closest point of the simplex; drop the vertices it does not use
    ClosestOnSimplex(lambda, n + 1, simplex);
    n = 0;
    for (int i = 0; i < 4; i++) {
      if (!lambda[i]) continue;
      simplex[n] = simplex[i];
      lambda[n++] = lambda[i];
    }
    if (n < 1) return GjkApart(status, k);

    // the next point: 3.5.1 stops when it equals x
    double next[3];
    Combine(next, lambda, n, simplex[0].vert, simplex[1].vert, simplex[2].vert,
            simplex[3].vert);
    if (!newer && SamePoint(next, x)) break;
    math::Copy3(x, next);
    if (newer) {
      x_norm_prev = x_norm;
      x_norm = Norm3(x);
    }

    // the origin is inside a tetrahedron
    if (n == 4) {
      if (!newer) x_norm = 0;
      break;
    }
  }

  if (n > 0 || !newer) {
    Combine(status->x1, lambda, n, simplex[0].vert1, simplex[1].vert1, simplex[2].vert1,
            simplex[3].vert1);
    Combine(status->x2, lambda, n, simplex[0].vert2, simplex[1].vert2, simplex[2].vert2,
            simplex[3].vert2);
  }
  if (newer) GjkFinalSeparation(status, s1, s2, x, x_norm);
  status->nx = 1;
  status->gjk_iterations = k;
  status->nsimplex = n;
  status->dist = newer && n == 4 && !status->separated ? 0 : x_norm;
}

// ---------------------------------------------------------------- EPA polytope

// A triangle of the polytope.
struct Face {
  int verts[3];   // vertex indices, counter-clockwise seen from outside
  int adj[3];     // neighbouring faces across edges (v0 v1), (v1 v2), (v2 v0)
  double v[3];    // the origin projected on the face's plane (outward normal * distance)
  double dist2;   // |v|^2
  int index;      // slot in the candidate list; -1 not listed, -2 deleted
};

// The expanding polytope: vertices, faces, the candidate faces (those that may still
// be nearest), and the horizon seen from a new vertex.
struct Polytope {
  std::vector<CcdVertex> verts;
  int nverts = 0;
  std::vector<Face> faces;
  int nfaces = 0;
  int maxfaces = 0;
  std::vector<int> map;        // candidate face indices
  int nmap = 0;
  std::vector<int> hor_faces;  // horizon: faces beyond each horizon edge ...
  std::vector<int> hor_edges;  // ... and which of their edges it is
  int nedges = 0;
  const double* w = nullptr;   // the new vertex the horizon is seen from

  // 3.12 turns each face's normal away from the initial polytope's centre
  bool newer = false;
  double center[3] = {0, 0, 0};

  // Storage for `iterations` expansions (as MuJoCo: at least 170).
  void Reset(int iterations) {
    int n = iterations > kEpaStaticIterations ? iterations : kEpaStaticIterations;
    maxfaces = 6 * n;
    if (static_cast<int>(faces.size()) < maxfaces) {
      verts.resize(5 + n);
      faces.resize(maxfaces);
      map.resize(maxfaces);
      hor_faces.resize(6 + n);
      hor_edges.resize(6 + n);
    }
    nverts = nfaces = nmap = nedges = 0;
  }
};

// Copies a vertex into the polytope; returns its index.
int AddVertex(Polytope* pt, const CcdVertex& v) {
  pt->verts[pt->nverts] = v;
  return pt->nverts++;
}

// Adds the support vertex along d (norm dnorm; a tiny d means +x); returns its index.
int AddSupportVertex(Polytope* pt, ConvexShape* s1, ConvexShape* s2, const double* d,
                     double dnorm) {
  double dir[3] = {1, 0, 0}, dir_neg[3] = {-1, 0, 0};
  if (dnorm > kMinVal) {
    for (int i = 0; i < 3; i++) dir[i] = d[i] / dnorm;
    Scale3(dir_neg, dir, -1);
  }
  int n = pt->nverts++;
  MinkowskiSupport(&pt->verts[n], s1, s2, dir, dir_neg);
  return n;
}

// Appends face (v1, v2, v3) with neighbours adj1..3; returns its squared distance from
// the origin, or 0 when the face is degenerate.
double AddFace(Polytope* pt, int v1, int v2, int v3, int adj1, int adj2, int adj3) {
  Face& face = pt->faces[pt->nfaces++];
  face.verts[0] = v1, face.verts[1] = v2, face.verts[2] = v3;
  face.adj[0] = adj1, face.adj[1] = adj2, face.adj[2] = adj3;
  if (!ProjectOriginOnPlane(face.v, pt->verts[v3].vert, pt->verts[v2].vert,
                            pt->verts[v1].vert)) {
    return 0;
  }
  if (pt->newer) {
    double outward[3];
    Sub3(outward, pt->verts[v1].vert, pt->center);
    if (Dot3(face.v, outward) < 0) Scale3(face.v, face.v, -1);
  }
  face.dist2 = Dot3(face.v, face.v);
  face.index = -1;
  return face.dist2;
}

// Makes the first `count` faces the candidate list.
void ListAllFaces(Polytope* pt, int count) {
  for (int i = 0; i < count; i++) {
    pt->map[i] = i;
    pt->faces[i].index = i;
  }
  pt->nmap = count;
}

// Puts the last added face on the candidate list.
void ListLastFace(Polytope* pt) {
  int slot = pt->nmap++;
  pt->map[slot] = pt->nfaces - 1;
  pt->faces[pt->nfaces - 1].index = slot;
}

// Restarts from the triangle (v1, v2, v3) of the polytope as GJK's simplex.
void RestartFromTriangle(Polytope* pt, CcdStatus* status, int v1, int v2, int v3) {
  status->nsimplex = 3;
  status->simplex[0] = pt->verts[v1];
  status->simplex[1] = pt->verts[v2];
  status->simplex[2] = pt->verts[v3];
  pt->nfaces = pt->nverts = pt->nmap = 0;
}

// Do the origin and p3 lie strictly on the same side of the plane p0 p1 p2?
bool SameSideAsOrigin(const double* p0, const double* p1, const double* p2,
                      const double* p3) {
  double e1[3], e2[3], e3[3], to_origin[3], n[3];
  Sub3(e1, p1, p0);
  Sub3(e2, p2, p0);
  Cross3(n, e1, e2);
  Sub3(e3, p3, p0);
  double d1 = Dot3(n, e3);
  Scale3(to_origin, p0, -1);
  double d2 = Dot3(n, to_origin);
  return (d1 > 0 && d2 > 0) || (d1 < 0 && d2 < 0);
}

// Is the origin inside the tetrahedron p0 p1 p2 p3?
bool TetrahedronHasOrigin(const double* p0, const double* p1, const double* p2,
                          const double* p3) {
  return SameSideAsOrigin(p0, p1, p2, p3) && SameSideAsOrigin(p1, p2, p3, p0) &&
         SameSideAsOrigin(p2, p3, p0, p1) && SameSideAsOrigin(p3, p0, p1, p2);
}

// Rotation by 120 degrees about `axis`.
void Rotation120(double r[9], const double* axis) {
  double n = Norm3(axis);
  double u1 = axis[0] / n, u2 = axis[1] / n, u3 = axis[2] / n;
  const double s = 0.86602540378;  // sin 120 deg, to MuJoCo's 11 digits
  const double c = -0.5;
  r[0] = c + u1 * u1 * (1 - c);
  r[1] = u1 * u2 * (1 - c) - u3 * s;
  r[2] = u1 * u3 * (1 - c) + u2 * s;
  r[3] = u2 * u1 * (1 - c) + u3 * s;
  r[4] = c + u2 * u2 * (1 - c);
  r[5] = u2 * u3 * (1 - c) - u1 * s;
  r[6] = u1 * u3 * (1 - c) - u2 * s;
  r[7] = u2 * u3 * (1 - c) + u1 * s;
  r[8] = c + u3 * u3 * (1 - c);
}

// Does the ray from v1 through v2 pass through triangle v3 v4 v5 (either orientation)?
bool RayHitsTriangle(const double* v1, const double* v2, const double* v3, const double* v4,
                     const double* v5) {
  double d2[3], d3[3], d4[3], d5[3];
  Sub3(d2, v2, v1);
  Sub3(d3, v3, v1);
  Sub3(d4, v4, v1);
  Sub3(d5, v5, v1);
  double vol1 = Det3(d3, d4, d2), vol2 = Det3(d4, d5, d2), vol3 = Det3(d5, d3, d2);
  return (vol1 >= 0 && vol2 >= 0 && vol3 >= 0) || (vol1 <= 0 && vol2 <= 0 && vol3 <= 0);
}

// Does p lie in triangle v1 v2 v3?
bool TriangleHasPoint(const double* v1, const double* v2, const double* v3, const double* p) {
  double l[3];
  TriangleCoordinates(l, v1, v2, v3, p);
  if (l[0] < 0 || l[1] < 0 || l[2] < 0) return false;
  double q[3], diff[3];
  for (int i = 0; i < 3; i++) q[i] = v1[i] * l[0] + v2[i] * l[1] + v3[i] * l[2];
  Sub3(diff, q, p);
  return Norm3(diff) < kMinVal;
}

// Neighbours of the six faces of a double pyramid built as (apex1, a, b), (apex1, c, a),
// (apex1, b, c), (apex2, b, a), (apex2, a, c), (apex2, c, b).
constexpr int kPyramidAdjacency[6][3] = {{1, 3, 2}, {2, 4, 0}, {0, 5, 1},
                                         {5, 0, 4}, {3, 1, 5}, {4, 2, 3}};

// Adds `count` faces in order; returns the first whose distance from the origin is below
// kMinVal2 (the origin on its plane, or degenerate), -1 when all are fine.
int AddFaces(Polytope* pt, const int tri[][3], const int adj[][3], int count) {
  for (int i = 0; i < count; i++) {
    if (AddFace(pt, tri[i][0], tri[i][1], tri[i][2], adj[i][0], adj[i][1], adj[i][2]) <
        kMinVal2) {
      return i;
    }
  }
  return -1;
}

int PolytopeFromTriangle(Polytope* pt, CcdStatus* status, ConvexShape* s1, ConvexShape* s2);

// The initial polytope's centre (3.12 only; AddFace's outward test): the mean of GJK's
// simplex, summed in order and scaled by 1/count, as 3.12 rounds it.
void SetCenter(Polytope* pt, const double* const* points, int count) {
  if (!pt->newer) return;
  double sum[3];
  math::Copy3(sum, points[0]);
  for (int i = 1; i < count; i++) math::Add3(sum, sum, points[i]);
  Scale3(pt->center, sum, count == 2 ? 0.5 : count == 4 ? 0.25 : 1.0 / 3.0);
}

// Initial polytope from a segment: three support points around it at 120 degrees make
// a double pyramid with the segment's ends as apexes.
int PolytopeFromSegment(Polytope* pt, CcdStatus* status, ConvexShape* s1, ConvexShape* s2) {
  const double *v1 = status->simplex[0].vert, *v2 = status->simplex[1].vert;
  const double* ends[2] = {v1, v2};
  SetCenter(pt, ends, 2);
  double diff[3];
  Sub3(diff, v2, v1);

  // a direction normal to the segment, from the axis it is least aligned with
  int axis = 0;
  double smallest = kHuge;
  for (int i = 0; i < 3; i++) {
    if (std::abs(diff[i]) < smallest) {
      smallest = std::abs(diff[i]);
      axis = i;
    }
  }
  double e[3] = {0, 0, 0}, d1[3], d2[3], d3[3], r[9];
  e[axis] = 1;
  Cross3(d1, e, diff);
  Rotation120(r, diff);
  math::MulMatVec3(d2, r, d1);
  math::MulMatVec3(d3, r, d2);

  int i1 = AddVertex(pt, status->simplex[0]);
  int i2 = AddVertex(pt, status->simplex[1]);
  int i3 = AddSupportVertex(pt, s1, s2, d1, Norm3(d1));
  int i4 = AddSupportVertex(pt, s1, s2, d2, Norm3(d2));
  int i5 = AddSupportVertex(pt, s1, s2, d3, Norm3(d3));

  // faces around apex i1 over (i3, i4, i5), then apex i2; a face through the origin
  // restarts from that triangle
  const int tri[6][3] = {{i1, i3, i4}, {i1, i5, i3}, {i1, i4, i5},
                         {i2, i4, i3}, {i2, i3, i5}, {i2, i5, i4}};
  int bad = AddFaces(pt, tri, kPyramidAdjacency, 6);
  if (bad >= 0) {
    RestartFromTriangle(pt, status, tri[bad][0], tri[bad][1], tri[bad][2]);
    return PolytopeFromTriangle(pt, status, s1, s2);
  }
  if (!RayHitsTriangle(v1, v2, pt->verts[i3].vert, pt->verts[i4].vert, pt->verts[i5].vert)) {
    return kEpaP2Nonconvex;
  }
  ListAllFaces(pt, 6);
  return kEpaSuccess;
}

// Initial polytope from a triangle: the support points on both sides of it are the
// apexes of a double pyramid.
int PolytopeFromTriangle(Polytope* pt, CcdStatus* status, ConvexShape* s1, ConvexShape* s2) {
  const double *v1 = status->simplex[0].vert, *v2 = status->simplex[1].vert,
               *v3 = status->simplex[2].vert;
  const double* corners[3] = {v1, v2, v3};
  SetCenter(pt, corners, 3);
  double e1[3], e2[3], n[3], n_neg[3];
  Sub3(e1, v2, v1);
  Sub3(e2, v3, v1);
  Cross3(n, e1, e2);
  double n_norm = Norm3(n);
  if (n_norm < kMinVal) return kEpaP3BadNormal;
  Scale3(n_neg, n, -1);

  int i1 = AddVertex(pt, status->simplex[0]);
  int i2 = AddVertex(pt, status->simplex[1]);
  int i3 = AddVertex(pt, status->simplex[2]);
  int i5 = AddSupportVertex(pt, s1, s2, n_neg, n_norm);
  int i4 = AddSupportVertex(pt, s1, s2, n, n_norm);
  const double* v4 = pt->verts[i4].vert;
  const double* v5 = pt->verts[i5].vert;
  if (TriangleHasPoint(v1, v2, v3, v4)) return kEpaP3InvalidV4;
  if (TriangleHasPoint(v1, v2, v3, v5)) return kEpaP3InvalidV5;

  // unless the origin is on the triangle, one of the pyramids must hold it
  if (status->dist > 10 * kMinVal && !TetrahedronHasOrigin(v1, v2, v3, v4) &&
      !TetrahedronHasOrigin(v1, v2, v3, v5)) {
    return kEpaP3MissingOrigin;
  }

  // faces (i4, x, y) over the triangle's edges and (i5, y, x) under them
  const int tri[6][3] = {{i4, i1, i2}, {i4, i3, i1}, {i4, i2, i3},
                         {i5, i2, i1}, {i5, i1, i3}, {i5, i3, i2}};
  if (AddFaces(pt, tri, kPyramidAdjacency, 6) >= 0) return kEpaP3OriginOnFace;
  ListAllFaces(pt, 6);
  return kEpaSuccess;
}

// Initial polytope from GJK's tetrahedron.
int PolytopeFromTetrahedron(Polytope* pt, CcdStatus* status, ConvexShape* s1,
                            ConvexShape* s2) {
  int i1 = AddVertex(pt, status->simplex[0]);
  int i2 = AddVertex(pt, status->simplex[1]);
  int i3 = AddVertex(pt, status->simplex[2]);
  int i4 = AddVertex(pt, status->simplex[3]);
  const double* corners[4] = {pt->verts[i1].vert, pt->verts[i2].vert, pt->verts[i3].vert,
                              pt->verts[i4].vert};
  SetCenter(pt, corners, 4);

  // a face through the origin restarts from that triangle
  const int tri[4][3] = {{i1, i2, i3}, {i1, i4, i2}, {i1, i3, i4}, {i4, i3, i2}};
  const int adj[4][3] = {{1, 3, 2}, {2, 3, 0}, {0, 3, 1}, {2, 0, 1}};
  int bad = AddFaces(pt, tri, adj, 4);
  if (bad >= 0) {
    RestartFromTriangle(pt, status, tri[bad][0], tri[bad][1], tri[bad][2]);
    return PolytopeFromTriangle(pt, status, s1, s2);
  }
  if (!TetrahedronHasOrigin(pt->verts[i1].vert, pt->verts[i2].vert, pt->verts[i3].vert,
                            pt->verts[i4].vert)) {
    return kEpaP4MissingOrigin;
  }
  ListAllFaces(pt, 4);
  return kEpaSuccess;
}

// ---------------------------------------------------------------- EPA horizon

// Removes a face from the polytope (and from the candidate list if it is there).
void DeleteFace(Polytope* pt, Face* face) {
  if (face->index >= 0) {
    int moved = pt->map[--pt->nmap];
    pt->map[face->index] = moved;
    pt->faces[moved].index = face->index;
  }
  face->index = -2;
}

// Records horizon edge `edge` of face `face`.
void AddHorizonEdge(Polytope* pt, int face, int edge) {
  pt->hor_edges[pt->nedges] = edge;
  pt->hor_faces[pt->nedges++] = face;
}

// Which edge of `face` starts at `vertex`.
int EdgeStartingAt(const Face& face, int vertex) {
  if (face.verts[0] == vertex) return 0;
  if (face.verts[1] == vertex) return 1;
  return 2;
}

// Deletes `face` if the new vertex sees it, then explores its other two edges (entered
// through edge e); returns whether it was visible.
bool ExploreHorizon(Polytope* pt, Face* face, int e) {
  if (Dot3(face->v, pt->w) - face->dist2 <= kMinVal) return false;
  DeleteFace(pt, face);
  for (int k = 1; k < 3; k++) {
    int i = (e + k) % 3;
    Face* next = &pt->faces[face->adj[i]];
    if (next->index > -2) {
      int next_edge = EdgeStartingAt(*next, face->verts[(i + 1) % 3]);
      if (!ExploreHorizon(pt, next, next_edge)) AddHorizonEdge(pt, face->adj[i], next_edge);
    }
  }
  return true;
}

// The horizon seen from pt->w, starting at the visible face `face`.
void BuildHorizon(Polytope* pt, Face* face) {
  DeleteFace(pt, face);
  for (int i = 0; i < 3; i++) {
    Face* next = &pt->faces[face->adj[i]];
    int next_edge = EdgeStartingAt(*next, face->verts[(i + 1) % 3]);
    if (i > 0 && next->index <= -2) continue;
    if (!ExploreHorizon(pt, next, next_edge)) AddHorizonEdge(pt, face->adj[i], next_edge);
  }
}

// Witness points of the face: its barycentric coordinates of the origin's projection
// applied to both shapes' support points. Returns the signed (negative) distance.
double FaceWitness(const Polytope* pt, const Face* face, double* x1, double* x2) {
  const CcdVertex& v1 = pt->verts[face->verts[0]];
  const CcdVertex& v2 = pt->verts[face->verts[1]];
  const CcdVertex& v3 = pt->verts[face->verts[2]];
  double lambda[3];
  TriangleCoordinates(lambda, v1.vert, v2.vert, v3.vert, face->v);
  Combine(x1, lambda, 3, v1.vert1, v2.vert1, v3.vert1, nullptr);
  Combine(x2, lambda, 3, v1.vert2, v2.vert2, v3.vert2, nullptr);
  return -std::sqrt(face->dist2);
}

// Has the polytope already got a vertex with w's pair of polytope features?
bool RepeatedVertex(const Polytope* pt, const CcdVertex& w) {
  for (int i = 0; i < pt->nverts - 1; i++) {
    if (w.index1 == pt->verts[i].index1 && w.index2 == pt->verts[i].index2) return true;
  }
  return false;
}

// Replaces the faces the new vertex wi sees by a fan of faces from wi to the horizon,
// listing those whose distance lies within [lower2, upper2]. Returns false on a
// degenerate face.
bool AttachFan(Polytope* pt, int wi, double lower2, double upper2) {
  int first = pt->nfaces, nedges = pt->nedges;
  for (int i = 0; i < nedges; i++) {
    int cur = first + i;
    int prev = i == 0 ? first + nedges - 1 : cur - 1;
    int next = first + (i + 1) % nedges;
    int hor = pt->hor_faces[i], edge = pt->hor_edges[i];
    Face& hor_face = pt->faces[hor];
    int v1 = hor_face.verts[edge], v2 = hor_face.verts[(edge + 1) % 3];
    hor_face.adj[edge] = cur;
    double dist2 = AddFace(pt, wi, v2, v1, prev, hor, next);
    if (dist2 == 0) return false;
    if (dist2 >= lower2 && dist2 <= upper2) ListLastFace(pt);
  }
  return true;
}

// EPA: expands the polytope until the nearest face's distance is within tolerance of the
// support distance along its normal. Returns that face (null on failure) and writes
// the distance and witness points to status.
Face* Epa(CcdStatus* status, Polytope* pt, ConvexShape* s1, ConvexShape* s2) {
  double upper = kHuge, upper2 = kHuge;
  Face *face = nullptr, *previous = nullptr;
  bool discrete = BothDiscrete(s1, s2);
  double tolerance = discrete ? kMinVal : status->config.tolerance;
  int kmax = status->config.max_iterations;
  if (status->config.newer && kmax > 1000) kmax = 1000;

  int k = 0;
  for (; k < kmax; k++) {
    previous = face;

    // the candidate face nearest the origin: a lower bound on the depth
    double lower2 = kHuge;
    for (int i = 0; i < pt->nmap; i++) {
      Face* f = &pt->faces[pt->map[i]];
      if (f->dist2 < lower2) {
        face = f;
        lower2 = f->dist2;
      }
    }
    if (lower2 > upper2 || !face) {
      face = previous;
      break;
    }
    if (lower2 <= 0) break;  // the origin lies on a face's plane

    // the support point along its normal: an upper bound
    double lower = std::sqrt(lower2);
    int wi = AddSupportVertex(pt, s1, s2, face->v, lower);
    const CcdVertex& w = pt->verts[wi];
    double upper_k = Dot3(face->v, w.vert) / lower;
    if (upper_k < upper) {
      upper = upper_k;
      upper2 = upper * upper;
    }
    if (upper - lower < tolerance) {
      // 3.12: the support distance below the face's on the first step means no contact
      if (status->config.newer && k == 0 && upper < lower - 1e-10) face = nullptr;
      break;
    }
    if (discrete && RepeatedVertex(pt, w)) break;

    // replace what w sees by faces to w
    pt->w = w.vert;
    BuildHorizon(pt, face);
    if (pt->nedges < 3) {
      face = nullptr;
      break;
    }
    if (pt->nedges > pt->maxfaces - pt->nfaces) break;  // out of face storage
    if (!AttachFan(pt, wi, lower2, upper2)) face = nullptr;
    pt->nedges = 0;
    if (!pt->nmap || !face) break;
  }

  status->epa_iterations = k;
  if (face) {
    status->dist = FaceWitness(pt, face, status->x1, status->x2);
    status->nx = 1;
  } else {
    status->nx = 0;
    status->dist = 0;
  }
  return face;
}

// ---------------------------------------------------------------- driver

// Moves the witness points apart by the radii shrunk away (sphere, capsule) and
// reduces the distance accordingly.
void Inflate(CcdStatus* status, double radius1, double radius2) {
  double n[3];
  Sub3(n, status->x2, status->x1);
  math::Normalize3(n);
  if (radius1) {
    for (int i = 0; i < 3; i++) status->x1[i] += radius1 * n[i];
  }
  if (radius2) {
    for (int i = 0; i < 3; i++) status->x2[i] -= radius2 * n[i];
  }
  status->dist -= (radius1 + radius2);
}

// A sphere becomes its centre and a capsule its segment; returns the radius (plus half
// the margin) taken away, 0 for other shapes.
double ShrinkToCore(ConvexShape* s) {
  if (s->type != kGeomSphere && s->type != kGeomCapsule) return 0;
  double radius = s->size[0] + 0.5 * s->margin;
  s->support = s->type == kGeomSphere ? CentreSupport : SegmentSupport;
  s->margin = 0;
  return radius;
}

// Spheres and capsules: GJK on their cores first. Returns true when that settles the
// query (apart or shallow); false means deep penetration, to be redone on full shapes.
bool CollideCores(const CcdConfig& config, CcdStatus* status, ConvexShape* s1,
                  ConvexShape* s2, double* result) {
  ConvexShape core1 = *s1, core2 = *s2;
  double radius1 = ShrinkToCore(&core1), radius2 = ShrinkToCore(&core2);
  status->config.dist_cutoff += radius1 + radius2;
  Gjk(status, &core1, &core2);
  status->config.dist_cutoff = config.dist_cutoff;

  // the meshes' warm starts carry over to the full shapes
  s1->vertindex = core1.vertindex, s1->meshindex = core1.meshindex;
  s2->vertindex = core2.vertindex, s2->meshindex = core2.meshindex;

  if (status->dist > status->config.tolerance) {
    Inflate(status, radius1, radius2);
    if (status->dist > status->config.dist_cutoff) status->dist = kHuge;
    *result = status->dist;
    return true;
  }
  if (!config.max_contacts) {
    status->nx = 0;
    status->dist = 0;
    *result = 0;
    return true;
  }
  return false;
}

// EPA from GJK's final simplex; the polytope storage is reused between calls.
void PenetrationDepth(const CcdConfig& config, CcdStatus* status, ConvexShape* s1,
                      ConvexShape* s2) {
  thread_local Polytope pt;
  pt.Reset(config.max_iterations);
  pt.newer = config.newer;
  int ret;
  if (status->nsimplex == 2) {
    ret = PolytopeFromSegment(&pt, status, s1, s2);
  } else if (status->nsimplex == 3) {
    ret = PolytopeFromTriangle(&pt, status, s1, s2);
  } else {
    ret = PolytopeFromTetrahedron(&pt, status, s1, s2);
  }
  status->epa_status = ret;
  if (ret != kEpaSuccess) return;
  Face* face = Epa(status, &pt, s1, s2);
  // (multiccd: the polygon of contact of flat sides)
  if (config.max_contacts > 1 && face) {
    const CcdVertex* corners[3] = {&pt.verts[face->verts[0]], &pt.verts[face->verts[1]], &pt.verts[face->verts[2]]};
    PolygonContacts(corners, status, *s1, *s2);
  }
}

}  // namespace

double Collide(const CcdConfig& config, CcdStatus* status, ConvexShape* s1, ConvexShape* s2) {
  math::Copy3(status->x1, s1->pos);
  math::Copy3(status->x2, s2->pos);
  status->gjk_iterations = 0;
  status->epa_iterations = 0;
  status->epa_status = kEpaNoContact;
  status->config = config;

  // spheres and capsules: try their cores first
  bool rounded = s1->type == kGeomSphere || s2->type == kGeomSphere ||
                 s1->type == kGeomCapsule || s2->type == kGeomCapsule;
  if (rounded) {
    double result;
    if (CollideCores(config, status, s1, s2, &result)) return result;
    status->gjk_iterations = 0;
    math::Copy3(status->x1, s1->pos);
    math::Copy3(status->x2, s2->pos);
  }
  Gjk(status, s1, s2);
  if (!config.max_contacts) return status->dist;

  // overlapping: the penetration depth by EPA (3.12: unless GJK proved them apart)
  bool apart = config.newer && status->separated;
  if (status->dist <= config.tolerance && status->nsimplex > 1 && !apart) {
    status->dist = 0;
    PenetrationDepth(config, status, s1, s2);
  }
  return status->dist;
}

}  // namespace simlab::ccd
