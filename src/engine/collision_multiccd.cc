// Polygon contacts of two flat-sided shapes from EPA's answer (MuJoCo's multiccd,
// mjc_ccd's multicontact): the three vertices of the nearest face of the polytope tell
// which feature of each shape touches (a vertex, an edge or a face, by how many distinct
// corners of the shape they use). If a face of one shape faces a face of the other (or
// an edge lies in a face), that face (or edge) is clipped against the other face, and
// the clipped polygon's corners become the contacts, all with EPA's depth.
//
// Boxes number their corners by bits (x, y, z positive); meshes use their hull's flat
// sides (mesh_poly*: the polygons each vertex belongs to, their vertices and normals).
#include <cmath>

#include "engine/collision_gjk.h"
#include "math/math.h"

namespace simlab::ccd {

namespace {

using math::Cross3;
using math::Dot3;
using math::Sub3;

constexpr double kFaceTolerance = 0.99999872;   // cos of the angle of facing faces (mjFACE_TOL)
constexpr double kEdgeTolerance = 0.00159999931;  // |cos| of an edge lying in a face (mjEDGE_TOL)
constexpr int kMaxPolygon = 150;                // vertices of a polygon used (mjMAX_POLYVERT)

// res = mat * (x, y, z) (+ pos).
void ToWorld(double* res, const double* mat, const double* pos, double x, double y, double z) {
  res[0] = mat[0] * x + mat[1] * y + mat[2] * z;
  res[1] = mat[3] * x + mat[4] * y + mat[5] * z;
  res[2] = mat[6] * x + mat[7] * y + mat[8] * z;
  if (pos) {
    for (int k = 0; k < 3; k++) res[k] += pos[k];
  }
}

// ---------------------------------------------------------------- polygon clipping

// Area of the quadrilateral a b c d.
double QuadArea(const double* a, const double* b, const double* c, const double* d) {
  double ad[3], db[3], bc[3], ca[3], e[3], f[3];
  Sub3(ad, d, a);
  Sub3(db, b, d);
  Sub3(bc, c, b);
  Sub3(ca, a, c);
  Cross3(e, ad, db);
  Cross3(f, bc, ca);
  for (int k = 0; k < 3; k++) e[k] += f[k];
  return 0.5 * std::sqrt(Dot3(e, e));
}

// The vertex after p of an n-vertex polygon.
const double* NextVertex(const double* polygon, int n, const double* p) {
  return p == polygon + 3 * (n - 1) ? polygon : p + 3;
}

// Four vertices of a polygon spanning (about) the largest quadrilateral: each corner is
// advanced while that grows the area, for every choice of the first.
void LargestQuad(const double* res[4], const double* polygon, int n) {
  const double *a = polygon, *b = polygon + 3, *c = polygon + 6, *d = polygon + 9;
  res[0] = a, res[1] = b, res[2] = c, res[3] = d;
  double best = QuadArea(a, b, c, d);
  for (; a < polygon + 3 * n; a += 3) {
    for (;;) {
      double area = QuadArea(a, b, c, NextVertex(polygon, n, d));
      if (area <= best) break;
      best = area;
      d = NextVertex(polygon, n, d);
      res[0] = a, res[1] = b, res[2] = c, res[3] = d;
      while ((area = QuadArea(a, b, NextVertex(polygon, n, c), d)) > best) {
        best = area;
        c = NextVertex(polygon, n, c);
        res[0] = a, res[1] = b, res[2] = c, res[3] = d;
      }
      while ((area = QuadArea(a, NextVertex(polygon, n, b), c, d)) > best) {
        best = area;
        b = NextVertex(polygon, n, b);
        res[0] = a, res[1] = b, res[2] = c, res[3] = d;
      }
    }
    if (b == a) {
      b = NextVertex(polygon, n, b);
      if (c == b) {
        c = NextVertex(polygon, n, c);
        if (d == c) d = NextVertex(polygon, n, d);
      }
    }
  }
}

// The plane through edge (v1, v2) that contains the face normal n: its normal (into res)
// and offset.
double EdgePlane(double* res, const double* v1, const double* v2, const double* n) {
  double v3[3], e1[3], e2[3];
  for (int k = 0; k < 3; k++) v3[k] = v1[k] + n[k];
  Sub3(e1, v2, v1);
  Sub3(e2, v3, v1);
  Cross3(res, e1, e2);
  return Dot3(res, v1);
}

// Is p on the inner side of the plane through a with normal n (or on it)?
bool Inside(const double* a, const double* n, const double* p) {
  double dif[3];
  Sub3(dif, p, a);
  return Dot3(dif, n) > -kMinVal;
}

// Where segment (a, b) meets the plane (pn, pd): the parameter t (kMaxVal if parallel),
// and the point into res when 0 <= t <= 1.
double SegmentPlane(double* res, const double* pn, double pd, const double* a, const double* b) {
  double ab[3];
  Sub3(ab, b, a);
  double along = Dot3(pn, ab);
  if (along == 0.0) return kMaxVal;
  double t = (pd - Dot3(pn, a)) / along;
  if (t >= 0.0 && t <= 1.0) {
    for (int k = 0; k < 3; k++) res[k] = a[k] + t * ab[k];
  }
  return t;
}

// Writes contact i's witness points: x2 at p, x1 = p - dir.
void SetWitness(CcdStatus* status, int i, const double* p, const double* dir) {
  math::Copy3(status->x2 + 3 * i, p);
  Sub3(status->x1 + 3 * i, p, dir);
}

// Clips polygon `face2` (n2 vertices) by the side planes of polygon `face1` (n1 >= 3,
// normal n) and writes the corners as contacts (x1 displaced by -dir from x2): at most
// four when the query asked for fewer than five, duplicates dropped.
void ClipPolygons(CcdStatus* status, const double* face1, int n1, const double* face2, int n2,
                  const double* n, const double* dir) {
  if (n1 < 3) return;
  double pn[3 * kMaxPolygon], pd[kMaxPolygon];
  for (int i = 0; i < n1; i++) {
    pd[i] = EdgePlane(&pn[3 * i], &face1[3 * i], &face1[3 * ((i + 1) % n1)], n);
  }

  // (a clipped polygon has at most twice the sides)
  double buffer1[6 * kMaxPolygon], buffer2[6 * kMaxPolygon];
  double *polygon = buffer1, *clipped = buffer2;
  int npolygon = n2, nclipped = 0;
  std::copy_n(face2, 3 * n2, polygon);
  for (int e = 0; e < n1; e++) {
    const double* a = face1 + 3 * e;
    const double* normal = pn + 3 * e;
    for (int i = 0; i < npolygon; i++) {
      const double* p = polygon + 3 * i;
      const double* q = i < npolygon - 1 ? p + 3 : polygon;
      bool inside_p = Inside(a, normal, p), inside_q = Inside(a, normal, q);
      if (!inside_p && !inside_q) continue;
      if (inside_p && inside_q) {
        math::Copy3(clipped + 3 * nclipped++, q);
        continue;
      }
      // (the crossing point, then q if it is back inside)
      double t = SegmentPlane(clipped + 3 * nclipped, normal, pd[e], p, q);
      if (t >= 0.0 && t <= 1.0) nclipped++;
      if (inside_q) math::Copy3(clipped + 3 * nclipped++, q);
    }
    std::swap(polygon, clipped);
    npolygon = nclipped;
    nclipped = 0;
  }
  if (npolygon < 1) return;

  // The corners as contacts.
  if (status->config.max_contacts < 5 && npolygon > 4) {
    const double* quad[4];
    LargestQuad(quad, polygon, npolygon);
    for (int i = 0; i < 4; i++) SetWitness(status, i, quad[i], dir);
    status->nx = 4;
    return;
  }
  if (npolygon > kMaxContactPair) {
    for (int i = 0; i < kMaxContactPair; i++) SetWitness(status, i, polygon + 3 * i, dir);
    status->nx = kMaxContactPair;
    return;
  }
  int count = 0;
  for (int i = 0; i < npolygon; i++) {
    bool seen = false;
    for (int j = 0; j < count && !seen; j++) seen = SamePoint(status->x2 + 3 * j, polygon + 3 * i);
    if (!seen) SetWitness(status, count++, polygon + 3 * i, dir);
  }
  status->nx = count;
}

// ---------------------------------------------------------------- features of boxes

// A box face normal near n (world), if any: writes it and its face index (0..5: +x -x
// +y -y +z -z).
int BoxFaceNearNormal(double* res, int* index, const double* mat, const double* n) {
  static const double kNormals[18] = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  double local[3] = {mat[0] * n[0] + mat[3] * n[1] + mat[6] * n[2], mat[1] * n[0] + mat[4] * n[1] + mat[7] * n[2],
                     mat[2] * n[0] + mat[5] * n[1] + mat[8] * n[2]};
  double scale = 1 / std::sqrt(Dot3(local, local));
  for (double& x : local) x *= scale;
  for (int i = 0; i < 6; i++) {
    if (Dot3(local, kNormals + 3 * i) > kFaceTolerance) {
      ToWorld(res, mat, nullptr, kNormals[3 * i], kNormals[3 * i + 1], kNormals[3 * i + 2]);
      index[0] = i;
      return 1;
    }
  }
  return 0;
}

// +1 when every corner has the bit set, -1 when none has, else 0.
int CommonSide(int bit, const int* corners, int n) {
  bool all = true, none = true;
  for (int k = 0; k < n; k++) {
    all = all && (corners[k] & bit);
    none = none && !(corners[k] & bit);
  }
  return all ? 1 : (none ? -1 : 0);
}

// The face normals of a box a feature of dim corners (1 to 3) may touch with, and the
// faces' indices; a 3-corner feature not on one face (or a 2-corner one not an edge) falls
// back to the face nearest dir.
int BoxNormals(double* res, int* index, int dim, const ConvexShape& s, const int* corners, const double* dir) {
  const double* mat = s.mat;
  if (dim == 3 || dim == 2) {
    int x = CommonSide(1, corners, dim), y = CommonSide(2, corners, dim), z = CommonSide(4, corners, dim);
    if (dim == 3) {
      int c = 0;
      ToWorld(res, mat, nullptr, x, y, z);
      if (x) index[c++] = 0;
      if (y) index[c++] = 2;
      if (z) index[c++] = 4;
      if (x + y + z == -1) index[0]++;
      return c == 1 ? 1 : BoxFaceNearNormal(res, index, mat, dir);
    }
    int c = 0;
    if (x) {
      ToWorld(res, mat, nullptr, x, 0, 0);
      index[c++] = x > 0 ? 0 : 1;
    }
    if (y) {
      ToWorld(res + 3 * c, mat, nullptr, 0, y, 0);
      index[c++] = y > 0 ? 2 : 3;
    }
    if (z) {
      // (as MuJoCo: the z normal goes to the second slot)
      ToWorld(res + 3, mat, nullptr, 0, 0, z);
      index[c++] = z > 0 ? 4 : 5;
    }
    return c == 2 ? 2 : BoxFaceNearNormal(res, index, mat, dir);
  }
  if (dim == 1) {
    double x = (corners[0] & 1) ? 1 : -1, y = (corners[0] & 2) ? 1 : -1, z = (corners[0] & 4) ? 1 : -1;
    ToWorld(res, mat, nullptr, x, 0, 0);
    ToWorld(res + 3, mat, nullptr, 0, y, 0);
    ToWorld(res + 6, mat, nullptr, 0, 0, z);
    index[0] = x > 0 ? 0 : 1;
    index[1] = y > 0 ? 2 : 3;
    index[2] = z > 0 ? 4 : 5;
    return 3;
  }
  return 0;
}

// Directions of the three box edges from corner v1 (their far ends into ends).
int BoxCornerEdges(double* res, double* ends, const ConvexShape& s, const double* v1, int corner) {
  double x = (corner & 1) ? s.size[0] : -s.size[0];
  double y = (corner & 2) ? s.size[1] : -s.size[1];
  double z = (corner & 4) ? s.size[2] : -s.size[2];
  const double far[3][3] = {{-x, y, z}, {x, -y, z}, {x, y, -z}};
  for (int i = 0; i < 3; i++) {
    ToWorld(ends + 3 * i, s.mat, s.pos, far[i][0], far[i][1], far[i][2]);
    Sub3(res + 3 * i, ends + 3 * i, v1);
    math::Normalize3(res + 3 * i);
  }
  return 3;
}

// The corners of box face `index` (world), in MuJoCo's order.
int BoxFace(double* res, const ConvexShape& s, int index) {
  static const int kSigns[6][4][3] = {
      {{1, 1, 1}, {1, 1, -1}, {1, -1, -1}, {1, -1, 1}},     {{-1, 1, -1}, {-1, 1, 1}, {-1, -1, 1}, {-1, -1, -1}},
      {{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}},     {{-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, {-1, -1, -1}},
      {{-1, 1, 1}, {1, 1, 1}, {1, -1, 1}, {-1, -1, 1}},     {{1, 1, -1}, {-1, 1, -1}, {-1, -1, -1}, {1, -1, -1}}};
  if (index < 0 || index > 5) return 0;
  for (int i = 0; i < 4; i++) {
    const int* sg = kSigns[index][i];
    ToWorld(res + 3 * i, s.mat, s.pos, sg[0] * s.size[0], sg[1] * s.size[1], sg[2] * s.size[2]);
  }
  return 4;
}

// ---------------------------------------------------------------- features of meshes

// Up to two numbers common to a and b (in a's order); returns how many.
int Common(int* res, const int* a, int na, const int* b, int nb) {
  int count = 0;
  for (int i = 0; i < na; i++) {
    for (int j = 0; j < nb; j++) {
      if (a[i] != b[j]) continue;
      res[count++] = a[i];
      if (count == 2) return 2;
    }
  }
  return count;
}

// Mesh data of a shape: its polygons and, per vertex, the polygons that hold it.
struct MeshSides {
  const Model& m;
  int mesh, polyadr, vertadr;
  MeshSides(const ConvexShape& s)
      : m(*s.model), mesh(s.model->geom_dataid[s.geom]), polyadr(m.mesh_polyadr[mesh]), vertadr(m.mesh_vertadr[mesh]) {}
  const int* PolygonsOf(int v) const { return m.mesh_polymap.data() + m.mesh_polymapadr[vertadr + v]; }
  int CountOf(int v) const { return m.mesh_polymapnum[vertadr + v]; }
  const double* Normal(int p) const { return &m.mesh_polynormal[3 * (polyadr + p)]; }
};

// The polygon normals of a mesh a feature of dim vertices may touch with: the polygon of
// three vertices, the (up to two) of an edge, or those around one vertex.
int MeshNormals(double* res, int* index, int dim, const ConvexShape& s, const int* verts) {
  MeshSides sides(s);
  int found[2], n = 0;
  if (dim == 3 || dim == 2) {
    n = Common(found, sides.PolygonsOf(verts[0]), sides.CountOf(verts[0]), sides.PolygonsOf(verts[1]),
               sides.CountOf(verts[1]));
    if (n == 0) return 0;
    if (dim == 3) {
      n = Common(found, found, n, sides.PolygonsOf(verts[2]), sides.CountOf(verts[2]));
      if (n == 0) return 0;
      n = 1;
    }
    for (int i = 0; i < n; i++) {
      const double* normal = sides.Normal(found[i]);
      ToWorld(res + 3 * i, s.mat, nullptr, normal[0], normal[1], normal[2]);
      index[i] = found[i];
    }
    return n;
  }
  if (dim == 1) {
    n = std::min(sides.CountOf(verts[0]), kMaxPolygon);
    for (int i = 0; i < n; i++) {
      int p = sides.PolygonsOf(verts[0])[i];
      const double* normal = sides.Normal(p);
      ToWorld(res + 3 * i, s.mat, nullptr, normal[0], normal[1], normal[2]);
      index[i] = p;
    }
    return n;
  }
  return 0;
}

// Directions of the mesh edges from vertex v1: to the previous vertex of each polygon
// around it (their far ends into ends).
int MeshVertexEdges(double* res, double* ends, const ConvexShape& s, const double* v1, int vertex) {
  MeshSides sides(s);
  const Model& m = sides.m;
  int n = std::min(sides.CountOf(vertex), kMaxPolygon);
  for (int i = 0; i < n; i++) {
    int p = sides.PolygonsOf(vertex)[i];
    int adr = m.mesh_polyvertadr[sides.polyadr + p], nvert = m.mesh_polyvertnum[sides.polyadr + p];
    for (int j = 0; j < nvert; j++) {
      if (m.mesh_polyvert[adr + j] != vertex) continue;
      int prev = m.mesh_polyvert[adr + (j == 0 ? nvert - 1 : j - 1)];
      const double* v = &m.mesh_vert[3 * (sides.vertadr + prev)];
      ToWorld(ends + 3 * i, s.mat, s.pos, v[0], v[1], v[2]);
      Sub3(res + 3 * i, ends + 3 * i, v1);
      math::Normalize3(res + 3 * i);
      break;
    }
  }
  return n;
}

// The vertices (world) of mesh polygon `index`, in reverse order.
int MeshFace(double* res, const ConvexShape& s, int index) {
  MeshSides sides(s);
  const Model& m = sides.m;
  int adr = m.mesh_polyvertadr[sides.polyadr + index];
  int nvert = std::min(m.mesh_polyvertnum[sides.polyadr + index], kMaxPolygon);
  for (int i = nvert - 1, j = 0; i >= 0; i--, j++) {
    const double* v = &m.mesh_vert[3 * (sides.vertadr + m.mesh_polyvert[adr + i])];
    ToWorld(res + 3 * j, s.mat, s.pos, v[0], v[1], v[2]);
  }
  return nvert;
}

// ---------------------------------------------------------------- matching features

// The first pair of normals facing each other (i of a, j of b).
bool FacingPair(int* res, const double* a, int na, const double* b, int nb) {
  for (int i = 0; i < na; i++) {
    for (int j = 0; j < nb; j++) {
      if (Dot3(a + 3 * i, b + 3 * j) < -kFaceTolerance) {
        res[0] = i, res[1] = j;
        return true;
      }
    }
  }
  return false;
}

// The first edge (j) lying in a face (i): res = (j, i).
bool EdgeInFace(int* res, const double* edges, int nedge, const double* faces, int nface) {
  for (int i = 0; i < nface; i++) {
    for (int j = 0; j < nedge; j++) {
      if (std::abs(Dot3(edges + 3 * j, faces + 3 * i)) < kEdgeTolerance) {
        res[0] = j, res[1] = i;
        return true;
      }
    }
  }
  return false;
}

// How many distinct corners of one shape the face's three vertices use (1 to 3); a
// repeated corner is moved out of the second slot.
int FeatureDim(int* corners, const double** points) {
  if (corners[0] != corners[1]) return (corners[2] == corners[0] || corners[2] == corners[1]) ? 2 : 3;
  if (corners[0] != corners[2]) {
    corners[1] = corners[2];
    points[1] = points[2];
    return 2;
  }
  return 1;
}

int FeatureNormals(double* res, int* index, int dim, const ConvexShape& s, const int* corners, const double* dir) {
  if (s.type == kGeomBox) return BoxNormals(res, index, dim, s, corners, dir);
  if (s.type == kGeomMesh) return MeshNormals(res, index, dim, s, corners);
  return 0;
}

// Directions of the edges a feature may touch with, and their far ends: an edge itself
// (dim 2), or the edges from a corner (dim 1).
int FeatureEdges(double* res, double* ends, int dim, const ConvexShape& s, const double* const* points,
                 const int* corners) {
  if (dim == 2) {
    math::Copy3(ends, points[1]);
    Sub3(res, points[1], points[0]);
    math::Normalize3(res);
    return 1;
  }
  if (dim != 1) return 0;
  if (s.type == kGeomBox) return BoxCornerEdges(res, ends, s, points[0], corners[0]);
  if (s.type == kGeomMesh) return MeshVertexEdges(res, ends, s, points[0], corners[0]);
  return 0;
}

int FeatureFace(double* res, const ConvexShape& s, int index) {
  if (s.type == kGeomBox) return BoxFace(res, s, index);
  if (s.type == kGeomMesh) return MeshFace(res, s, index);
  return 0;
}

bool HasSides(const ConvexShape& s) {
  return s.type != kGeomMesh || s.model->mesh_polynum[s.model->geom_dataid[s.geom]] > 0;
}

}  // namespace

void PolygonContacts(const CcdVertex* const face[3], CcdStatus* status, const ConvexShape& s1,
                     const ConvexShape& s2) {
  if (!HasSides(s1) || !HasSides(s2)) return;

  // The touching feature of each shape.
  int corners1[3] = {face[0]->index1, face[1]->index1, face[2]->index1};
  int corners2[3] = {face[0]->index2, face[1]->index2, face[2]->index2};
  const double* points1[3] = {face[0]->vert1, face[1]->vert1, face[2]->vert1};
  const double* points2[3] = {face[0]->vert2, face[1]->vert2, face[2]->vert2};
  int dim1 = FeatureDim(corners1, points1), dim2 = FeatureDim(corners2, points2);

  // Their candidate face normals.
  double dir[3], dir_neg[3];
  Sub3(dir, status->x2, status->x1);
  Sub3(dir_neg, status->x1, status->x2);
  double n1[3 * kMaxPolygon], n2[3 * kMaxPolygon], ends[3 * kMaxPolygon];
  int idx1[kMaxPolygon], idx2[kMaxPolygon];
  int nn1 = FeatureNormals(n1, idx1, dim1, s1, corners1, dir_neg);
  int nn2 = FeatureNormals(n2, idx2, dim2, s2, corners2, dir);

  // Facing faces, else an edge of the lower-dimensional feature lying in a face.
  int match[2];
  bool edge1 = false, edge2 = false;
  if (!FacingPair(match, n1, nn1, n2, nn2)) {
    if (dim1 < 3 && dim1 <= dim2) {
      nn1 = FeatureEdges(n1, ends, dim1, s1, points1, corners1);
      if (!EdgeInFace(match, n1, nn1, n2, nn2)) return;
      edge1 = true;
    } else if (dim2 < 3) {
      nn2 = FeatureEdges(n2, ends, dim2, s2, points2, corners2);
      if (!EdgeInFace(match, n2, nn2, n1, nn1)) return;
      edge2 = true;
    } else {
      return;
    }
  }
  int i = match[0], j = match[1];

  // The two features as polygons (an edge as two points).
  double poly1[3 * kMaxPolygon], poly2[3 * kMaxPolygon];
  int np1, np2;
  if (edge1) {
    math::Copy3(poly1, face[0]->vert1);
    math::Copy3(poly1 + 3, ends + 3 * i);
    np1 = 2;
  } else {
    np1 = FeatureFace(poly1, s1, edge2 ? idx1[j] : idx1[i]);
  }
  if (edge2) {
    math::Copy3(poly2, face[0]->vert2);
    math::Copy3(poly2 + 3, ends + 3 * i);
    np2 = 2;
  } else {
    np2 = FeatureFace(poly2, s2, idx2[j]);
  }

  // Clip the edge or face of one against the face of the other; every corner takes
  // the single contact's displacement along the face normal (as MuJoCo approximates it).
  double length = std::sqrt(Dot3(dir, dir)), approx[3];
  if (edge1) {
    math::Scale3(approx, n2 + 3 * j, length);
    ClipPolygons(status, poly2, np2, poly1, np1, n2 + 3 * j, approx);
  } else if (edge2) {
    math::Scale3(approx, n1 + 3 * j, -length);
    ClipPolygons(status, poly1, np1, poly2, np2, n1 + 3 * j, approx);
  } else {
    math::Scale3(approx, n2 + 3 * j, length);
    ClipPolygons(status, poly1, np1, poly2, np2, n1 + 3 * i, approx);
  }
}

}  // namespace simlab::ccd
