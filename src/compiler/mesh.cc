// Meshes as MuJoCo's compiler processes them (mjCMesh::Compile): load the vertices and
// triangles, build the convex hull where a geom collides with the mesh, apply refpos /
// refquat / scale, compute volume (or area), centre of mass and principal inertia, and
// move the vertices into that inertial frame. mesh_pos/mesh_quat keep the frame, and
// the geoms that use the mesh are offset by it.
#include <algorithm>
#include <cmath>
#include <string>

#include "compiler/compiler.h"
#include "compiler/mesh_builtin.h"
#include "compiler/mesh_hull.h"
#include "compiler/mesh_io.h"
#include "compiler/orientation.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::kMeshConvex;
using mjcf::kMeshExact;
using mjcf::kMeshLegacy;
using mjcf::kMeshShell;
using mjcf::ThrowAt;

namespace {

// Area of a triangle, its unit normal and centre (the normal stays unnormalized and the
// area is 0 for a degenerate triangle).
double Triangle(double normal[3], double center[3], const double* a, const double* b,
                const double* c) {
  for (int k = 0; k < 3; k++) center[k] = (a[k] + b[k] + c[k]) / 3;
  double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  math::Cross3(normal, e1, e2);
  double len = std::sqrt(math::Dot3(normal, normal));
  if (len < kMinVal) return 0;
  for (int k = 0; k < 3; k++) normal[k] /= len;
  return 0.5 * len;
}

// ---------------------------------------------------------------- loading

// Vertices and faces from the file (among `assets` first) or the inline attributes
// (not both).
MeshData LoadGeometry(const mjcf::MeshSpec& s, const mjcf::AssetFiles* assets) {
  MeshData data;
  if (s.builtin != mjcf::kMeshBuiltinNone) {
    data = BuiltinMesh(s);
  } else if (!s.path.empty()) {
    data = ReadMeshFile(s, assets);
    if (!s.vertex.empty()) ThrowAt(s.src, "repeated vertex specification (file and vertex)");
    if (!data.face.empty() && !s.face.empty()) {
      ThrowAt(s.src, "repeated face specification (file and face)");
    }
  } else {
    data.vert = s.vertex;
  }
  if (data.face.empty()) data.face = s.face;
  if (data.normal.empty()) {
    data.normal = s.normal;
  } else if (!s.normal.empty()) {
    ThrowAt(s.src, "repeated normal specification");
  }
  if (data.texcoord.empty()) {
    data.texcoord = s.texcoord;
  } else if (!s.texcoord.empty()) {
    ThrowAt(s.src, "repeated texcoord specification");
  }
  return data;
}

void CheckGeometry(const mjcf::MeshSpec& s, const MeshData& data) {
  if (data.vert.size() % 3) ThrowAt(s.src, "vertex data must be a multiple of 3");
  if (data.face.size() % 3) ThrowAt(s.src, "face data must be a multiple of 3");
  if (data.normal.size() % 3) ThrowAt(s.src, "normal data must be a multiple of 3");
  if (data.texcoord.size() % 2) ThrowAt(s.src, "texcoord must be a multiple of 2");
  if (!data.texcoord.empty() && data.facetexcoord.empty() &&
      data.texcoord.size() != 2 * (data.vert.size() / 3)) {
    ThrowAt(s.src, "texcoord must be 2*nv if face texcoord indices are not provided in an OBJ file");
  }
  if (data.vert.size() < 12) ThrowAt(s.src, "at least 4 vertices required");
  for (float c : data.vert) {
    if (!std::isfinite(c)) ThrowAt(s.src, "vertex coordinates must be finite");
  }
  int nvert = static_cast<int>(data.vert.size() / 3);
  for (size_t i = 0; i < data.face.size(); i++) {
    if (data.face[i] < 0 || data.face[i] >= nvert) {
      ThrowAt(s.src, "in face " + std::to_string(i / 3) + ", vertex index " +
                         std::to_string(data.face[i]) + " does not exist");
    }
  }
}

// Exact inertia needs consistently wound faces: no directed edge may appear twice.
void CheckOrientation(const MeshState& mesh) {
  std::vector<std::pair<int, int>> edges;
  for (size_t i = 0; i < mesh.face.size(); i += 3) {
    const int* f = &mesh.face[i];
    double n[3], c[3];
    double area = Triangle(n, c, &mesh.vert[3 * f[0]], &mesh.vert[3 * f[1]], &mesh.vert[3 * f[2]]);
    if (area <= std::sqrt(kMinVal)) continue;
    edges.push_back({f[0], f[1]});
    edges.push_back({f[1], f[2]});
    edges.push_back({f[2], f[0]});
  }
  std::stable_sort(edges.begin(), edges.end());
  auto twice = std::adjacent_find(edges.begin(), edges.end());
  if (twice != edges.end()) {
    ThrowAt(mesh.spec->src, "faces of mesh '" + mesh.spec->src.name +
                                "' have inconsistent orientation; check the faces with vertices " +
                                std::to_string(twice->first + 1) + " and " +
                                std::to_string(twice->second + 1));
  }
}

void MakeHull(MeshState* mesh) {
  const mjcf::MeshSpec& s = *mesh->spec;
  std::string message;
  switch (ConvexHullGraph(mesh->vert, s.maxhullvert, &mesh->graph, &message)) {
    case HullResult::kOk: return;
    case HullResult::kQhullError: ThrowAt(s.src, "qhull error while making the convex hull: " + message);
    case HullResult::kBadGraph: ThrowAt(s.src, "could not construct the convex hull graph");
    case HullResult::kUnavailable: ThrowAt(s.src, "convex hulls are not supported yet in this build");
  }
}


// ---------------------------------------------------------------- normals

// Unit normal of face f (its cross product, as MuJoCo's compiler normalizes it); returns
// the cross product's length (0 for a degenerate face, whose normal stays unnormalized).
double FaceNormal(const MeshState& mesh, const int* f, double normal[3]) {
  double e1[3], e2[3];
  for (int k = 0; k < 3; k++) {
    e1[k] = mesh.vert[3 * f[1] + k] - mesh.vert[3 * f[0] + k];
    e2[k] = mesh.vert[3 * f[2] + k] - mesh.vert[3 * f[0] + k];
  }
  math::Cross3(normal, e1, e2);
  return NormalizeVec(normal, 3);
}

// Normalizes each float normal in place (float arithmetic); a vanishing one becomes +z.
void NormalizeFloatNormals(std::vector<float>* normal) {
  for (size_t i = 0; i < normal->size(); i += 3) {
    float* n = &(*normal)[i];
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > kMinVal) {
      for (int k = 0; k < 3; k++) n[k] /= len;
    } else {
      n[0] = n[1] = 0;
      n[2] = 1;
    }
  }
}

// Vertex normals when none are given (MuJoCo's MakeNormal): the sum of the adjacent faces'
// normals weighted by their doubled area; unless smoothnormal, faces more than ~37 degrees
// off that sum are taken out again.
void MakeVertexNormals(MeshState* mesh) {
  std::vector<float>& normal = mesh->normal;
  normal.assign(mesh->vert.size(), 0.0f);
  for (size_t i = 0; i < mesh->face.size(); i += 3) {
    const int* f = &mesh->face[i];
    double n[3];
    double weight = FaceNormal(*mesh, f, n);
    for (int j = 0; j < 3; j++) {
      for (int k = 0; k < 3; k++) normal[3 * f[j] + k] += n[k] * weight;
    }
  }
  if (!mesh->spec->smoothnormal) {
    std::vector<float> removed(normal.size(), 0.0f);
    for (size_t i = 0; i < mesh->face.size(); i += 3) {
      const int* f = &mesh->face[i];
      double n[3];
      double weight = FaceNormal(*mesh, f, n);
      for (int j = 0; j < 3; j++) {
        const float* sum = &normal[3 * f[j]];
        double direction[3] = {sum[0], sum[1], sum[2]};
        NormalizeVec(direction, 3);
        if (math::Dot3(n, direction) >= 0.8) continue;
        for (int k = 0; k < 3; k++) removed[3 * f[j] + k] += n[k] * weight;
      }
    }
    for (size_t i = 0; i < normal.size(); i++) normal[i] -= removed[i];
  }
  NormalizeFloatNormals(&normal);
}

// refquat and scale applied to the normals (as to the vertices), then renormalized in
// single precision.
void ReferenceNormals(const mjcf::MeshSpec& s, std::vector<float>* normal) {
  if (s.refquat[0] != 1 || s.refquat[1] != 0 || s.refquat[2] != 0 || s.refquat[3] != 0) {
    double q[4] = {s.refquat[0], s.refquat[1], s.refquat[2], s.refquat[3]}, mat[9];
    NormalizeVec(q, 4);
    math::QuatToMat(mat, q);
    for (size_t i = 0; i < normal->size(); i += 3) {
      float* n = &(*normal)[i];
      double before[3] = {n[0], n[1], n[2]}, after[3];
      math::MulMatTVec3(after, mat, before);
      for (int k = 0; k < 3; k++) n[k] = static_cast<float>(after[k]);
    }
  }
  if (s.scale[0] != 1 || s.scale[1] != 1 || s.scale[2] != 1) {
    for (size_t i = 0; i < normal->size(); i++) (*normal)[i] *= s.scale[i % 3];
  }
  for (size_t i = 0; i < normal->size(); i += 3) {
    float* n = &(*normal)[i];
    float sq = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (sq > kMinVal) {
      float inverse = 1 / std::sqrt(sq);
      for (int k = 0; k < 3; k++) n[k] *= inverse;
    } else {
      n[0] = n[1] = 0;
      n[2] = 1;
    }
  }
}

// refpos, then refquat (vertices rotated by its inverse), then scale.
void ApplyReference(const mjcf::MeshSpec& s, std::vector<double>* vert) {
  size_t n = vert->size() / 3;
  if (s.refpos[0] != 0 || s.refpos[1] != 0 || s.refpos[2] != 0) {
    for (size_t i = 0; i < n; i++) {
      for (int k = 0; k < 3; k++) (*vert)[3 * i + k] -= s.refpos[k];
    }
  }
  if (s.refquat[0] != 1 || s.refquat[1] != 0 || s.refquat[2] != 0 || s.refquat[3] != 0) {
    double q[4] = {s.refquat[0], s.refquat[1], s.refquat[2], s.refquat[3]}, mat[9];
    NormalizeVec(q, 4);
    math::QuatToMat(mat, q);
    for (size_t i = 0; i < n; i++) {
      double r[3];
      math::MulMatTVec3(r, mat, &(*vert)[3 * i]);
      math::Copy3(&(*vert)[3 * i], r);
    }
  }
  if (s.scale[0] != 1 || s.scale[1] != 1 || s.scale[2] != 1) {
    for (size_t i = 0; i < n; i++) {
      for (int k = 0; k < 3; k++) (*vert)[3 * i + k] *= s.scale[k];
    }
  }
}

// ---------------------------------------------------------------- mass properties

// Area-weighted centre of the faces; returns the total area.
double FaceCentroid(const MeshState& mesh, double facecen[3]) {
  double total = 0;
  math::Zero3(facecen);
  for (size_t i = 0; i < mesh.face.size(); i += 3) {
    const int* f = &mesh.face[i];
    double n[3], c[3];
    double area = Triangle(n, c, &mesh.vert[3 * f[0]], &mesh.vert[3 * f[1]], &mesh.vert[3 * f[2]]);
    math::AddScaled3(facecen, c, area);
    total += area;
  }
  if (total >= kMinVal) {
    for (int k = 0; k < 3; k++) facecen[k] /= total;
  }
  return total;
}

// The triangles the mass properties integrate: the hull's for convex inertia, else the
// mesh's own.
void MassFaces(const MeshState& mesh, const int** faces, int* nface) {
  bool convex = mesh.spec->inertia == kMeshConvex;
  *faces = convex ? HullFaces(mesh) : mesh.face.data();
  *nface = convex ? mesh.graph[1] : static_cast<int>(mesh.face.size() / 3);
}

// Volume and centre of mass from pyramids with apex at the face centroid (each
// pyramid's volume counted positive for legacy inertia); or the surface area and its
// centre for shell inertia.
double VolumeAndCom(const MeshState& mesh, const double facecen[3], double com[3]) {
  bool shell = mesh.spec->inertia == kMeshShell;
  const int* faces;
  int nface;
  MassFaces(mesh, &faces, &nface);
  double total = 0;
  math::Zero3(com);
  for (int i = 0; i < nface; i++) {
    const int* f = faces + 3 * i;
    double n[3], c[3];
    double area = Triangle(n, c, &mesh.vert[3 * f[0]], &mesh.vert[3 * f[1]], &mesh.vert[3 * f[2]]);
    double amount = area;
    if (!shell) {
      double d[3] = {c[0] - facecen[0], c[1] - facecen[1], c[2] - facecen[2]};
      amount = math::Dot3(d, n) * area / 3;
      if (mesh.spec->inertia == kMeshLegacy) amount = std::abs(amount);
    }
    total += amount;
    for (int k = 0; k < 3; k++) com[k] += amount * (c[k] * 3.0 / 4.0 + facecen[k] / 4.0);
  }
  if (total >= kMinVal) {
    for (int k = 0; k < 3; k++) com[k] /= total;
  }
  return total;
}

// Inertia per unit density (xx yy zz xy xz yz) about `com`; returns the recomputed
// volume (or area).
double UnitInertia(const MeshState& mesh, const double com[3], double inert[6]) {
  std::vector<double> v(mesh.vert.size());
  for (size_t i = 0; i < v.size(); i++) v[i] = mesh.vert[i] - com[i % 3];
  bool shell = mesh.spec->inertia == kMeshShell;
  const int* faces;
  int nface;
  MassFaces(mesh, &faces, &nface);
  static const int kPairs[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {0, 2}, {1, 2}};
  double products[6] = {0, 0, 0, 0, 0, 0}, total = 0;
  for (int i = 0; i < nface; i++) {
    const double* D = &v[3 * faces[3 * i]];
    const double* E = &v[3 * faces[3 * i + 1]];
    const double* F = &v[3 * faces[3 * i + 2]];
    double n[3], c[3];
    double area = Triangle(n, c, D, E, F);
    double amount = shell ? area : math::Dot3(c, n) * area / 3;
    if (mesh.spec->inertia == kMeshLegacy) amount = std::abs(amount);
    total += amount;
    double divisor = shell ? 12 : 20;
    for (int j = 0; j < 6; j++) {
      int a = kPairs[j][0], b = kPairs[j][1];
      products[j] += amount / divisor *
                     (2 * (D[a] * D[b] + E[a] * E[b] + F[a] * F[b]) + D[a] * E[b] + D[b] * E[a] +
                      D[a] * F[b] + D[b] * F[a] + E[a] * F[b] + E[b] * F[a]);
    }
  }
  inert[0] = products[1] + products[2];
  inert[1] = products[0] + products[2];
  inert[2] = products[0] + products[1];
  inert[3] = -products[3];
  inert[4] = -products[4];
  inert[5] = -products[5];
  return total;
}

// Volume (area), centre of mass, principal axes and the equivalent inertia box.
void MassProperties(MeshState* mesh, double com[3], double quat[4]) {
  const mjcf::MeshSpec& s = *mesh->spec;
  const std::string& name = s.src.name;
  double facecen[3];
  if (FaceCentroid(*mesh, facecen) < kMinVal) ThrowAt(s.src, "mesh surface area is too small: " + name);
  double amount = VolumeAndCom(*mesh, facecen, com);
  if (amount < kMinVal) {
    if (s.inertia == kMeshShell) ThrowAt(s.src, "mesh surface area is too small: " + name);
    ThrowAt(s.src, amount < 0 ? "mesh volume is negative (misoriented triangles): " + name
                              : "mesh volume is too small: " + name + "; try inertia=\"shell\"");
  }
  double inert[6];
  mesh->volume = UnitInertia(*mesh, com, inert);

  // Principal axes, in MuJoCo's eigenvalue order.
  double full[9] = {inert[0], inert[3], inert[4], inert[3], inert[1], inert[5],
                    inert[4], inert[5], inert[2]};
  double eig[3];
  Eig3(eig, quat, full);
  if (eig[2] <= 0) ThrowAt(s.src, "eigenvalue of mesh inertia must be positive: " + name);
  const double atol = 1e-9, rtol = 1e-6;
  if (eig[0] + eig[1] < eig[2] * (1 - rtol) - atol || eig[0] + eig[2] < eig[1] * (1 - rtol) - atol ||
      eig[1] + eig[2] < eig[0] * (1 - rtol) - atol) {
    ThrowAt(s.src, "eigenvalues of mesh inertia violate A + B >= C: " + name);
  }
  mesh->boxsz[0] = 0.5 * std::sqrt(6 * (eig[1] + eig[2] - eig[0]) / mesh->volume);
  mesh->boxsz[1] = 0.5 * std::sqrt(6 * (eig[0] + eig[2] - eig[1]) / mesh->volume);
  mesh->boxsz[2] = 0.5 * std::sqrt(6 * (eig[0] + eig[1] - eig[2]) / mesh->volume);
}

// Vertices into the inertial frame (com, quat), their bounding box there, and the
// normals rotated alike.
void MoveToInertialFrame(MeshState* mesh, const double com[3], const double quat[4]) {
  double inverse[4], mat[9];
  math::NegQuat(inverse, quat);
  math::QuatToMat(mat, inverse);
  for (int k = 0; k < 3; k++) mesh->aamm[k] = 1e10, mesh->aamm[k + 3] = -1e10;
  for (size_t i = 0; i < mesh->vert.size(); i += 3) {
    double* v = &mesh->vert[i];
    double centered[3] = {v[0] - com[0], v[1] - com[1], v[2] - com[2]};
    math::MulMatVec3(v, mat, centered);
    for (int k = 0; k < 3; k++) {
      mesh->aamm[k] = std::min(mesh->aamm[k], v[k]);
      mesh->aamm[k + 3] = std::max(mesh->aamm[k + 3], v[k]);
    }
  }
  for (size_t i = 0; i < mesh->normal.size(); i += 3) {
    float* n = &mesh->normal[i];
    double before[3] = {n[0], n[1], n[2]}, after[3];
    math::MulMatVec3(after, mat, before);
    for (int k = 0; k < 3; k++) n[k] = static_cast<float>(after[k]);
  }
  math::Copy3(mesh->pos, com);
  math::CopyQuat(mesh->quat, quat);
}

// The level set of the mesh's signed distance field plugin, which is all its geometry.
MeshData PluginMesh(const mjcf::ModelSpec& spec, const mjcf::MeshSpec& s) {
  if (!s.path.empty() || !s.vertex.empty() || !s.face.empty() || s.builtin != mjcf::kMeshBuiltinNone) {
    ThrowAt(s.src, "a mesh made by a plugin has no file, vertex, face or builtin");
  }
  if (s.scale[0] != 1 || s.scale[1] != 1 || s.scale[2] != 1) {
    ThrowAt(s.src, "attribute scale is not compatible with SDFs in mesh '" + s.src.name + "'");
  }
  std::vector<double> attributes;
  const Plugin& plugin = SdfPluginOf(spec, s.src, s.plugin, &attributes);
  try {
    return LevelSetMesh(plugin, attributes);
  } catch (const Error& e) {
    ThrowAt(s.src, e.what());
  }
}

// A mesh from its file, attributes or builtin, or its plugin's level set.
void CompileMesh(const mjcf::ModelSpec& spec, bool needhull, MeshState* mesh) {
  const mjcf::MeshSpec& s = *mesh->spec;
  MeshData data = s.plugin.active ? PluginMesh(spec, s) : LoadGeometry(s, spec.assets.get());
  CheckGeometry(s, data);
  mesh->vert.assign(data.vert.begin(), data.vert.end());
  mesh->face = std::move(data.face);
  mesh->normal = std::move(data.normal);
  mesh->texcoord = std::move(data.texcoord);
  if (s.inertia == kMeshExact) CheckOrientation(*mesh);

  // The hull (on the vertices as read); a mesh without faces takes the hull's.
  if (needhull || mesh->face.empty() || s.inertia == kMeshConvex) MakeHull(mesh);
  if (mesh->face.empty()) {
    if (mesh->graph.empty()) ThrowAt(s.src, "the mesh has no faces and no convex hull");
    const int* hull = HullFaces(*mesh);
    mesh->face.assign(hull, hull + 3 * mesh->graph[1]);
  }
  // Texture coordinates per face corner: the file's, else the corner's vertex.
  if (!mesh->texcoord.empty()) {
    mesh->facetexcoord = data.facetexcoord.empty() ? mesh->face : std::move(data.facetexcoord);
  }
  if (mesh->normal.empty()) MakeVertexNormals(mesh);
  MakeMeshPolygons(mesh);

  ApplyReference(s, &mesh->vert);
  ReferenceNormals(s, &mesh->normal);
  double com[3], quat[4];
  MassProperties(mesh, com, quat);
  if (s.plugin.active) {
    // A plugin's level set stays in the plugin's frame (MuJoCo does not reorient meshes
    // made by marching cubes; their inertia keeps the principal moments in eigenvalue
    // order all the same).
    com[0] = com[1] = com[2] = 0;
    quat[0] = 1, quat[1] = quat[2] = quat[3] = 0;
  }
  MoveToInertialFrame(mesh, com, quat);
  MeshPolygonNormals(mesh);
}

// ---------------------------------------------------------------- geoms that use meshes

bool InPair(const mjcf::ModelSpec& spec, const std::string& geom) {
  if (geom.empty()) return false;
  for (const mjcf::PairSpec& p : spec.pairs) {
    if (p.geom1 == geom || p.geom2 == geom) return true;
  }
  return false;
}

// The mesh id each geom names (-1 for none); checks that mesh geoms name one.
std::vector<int> GeomMeshIds(const std::vector<std::string>& names, const CompileState& state) {
  NameIndex index(names);
  std::vector<int> ids;
  for (const GeomState& g : state.geoms) {
    const mjcf::GeomSpec& s = *g.spec;
    int id = -1;
    if (!s.mesh.empty()) {
      id = index.Find(s.mesh);
      if (id < 0) ThrowAt(s.src, "unknown mesh '" + s.mesh + "'");
    } else if (s.type == kGeomMesh || s.type == kGeomSdf) {
      ThrowAt(s.src, std::string("a") + (s.type == kGeomSdf ? "n sdf" : " mesh") + " geom needs a mesh");
    }
    ids.push_back(id);
  }
  return ids;
}

}  // namespace

// Triangles of the hull (the graph's face_globalid block).
const int* HullFaces(const MeshState& mesh) {
  return mesh.graph.data() + 2 + 3 * (mesh.graph[0] + mesh.graph[1]);
}

void CompileMeshes(const mjcf::ModelSpec& spec, CompileState* state) {
  // Names: unique; a mesh without one is named after its file.
  std::vector<std::string> names;
  for (const mjcf::MeshSpec& s : spec.meshes) {
    if (!s.src.name.empty() && FindName(names, s.src.name) >= 0) {
      ThrowAt(s.src, "repeated mesh name '" + s.src.name + "'");
    }
    names.push_back(s.src.name);
  }
  std::vector<int> ids = GeomMeshIds(names, *state);

  // A mesh gets its convex hull when a mesh or sdf geom can collide with it, or for convex
  // inertia; its signed distance octree when an sdf geom uses it.
  std::vector<bool> needhull(spec.meshes.size(), false), needsdf(spec.meshes.size(), false);
  for (size_t i = 0; i < state->geoms.size(); i++) {
    const mjcf::GeomSpec& s = *state->geoms[i].spec;
    if (ids[i] < 0 || (s.type != kGeomMesh && s.type != kGeomSdf)) continue;
    if (s.contype || s.conaffinity || InPair(spec, s.src.name)) needhull[ids[i]] = true;
    if (s.type == kGeomSdf) needsdf[ids[i]] = true;
  }

  // (a plugin's mesh has no octree: contacts come from the plugin's field)
  state->meshes.resize(spec.meshes.size());
  for (size_t i = 0; i < spec.meshes.size(); i++) {
    state->meshes[i].spec = &spec.meshes[i];
    CompileMesh(spec, needhull[i], &state->meshes[i]);
    if (needsdf[i] && !spec.meshes[i].plugin.active) MakeMeshOctree(&state->meshes[i]);
  }
  for (size_t i = 0; i < state->geoms.size(); i++) {
    if (ids[i] < 0) continue;
    // geom_dataid keeps the mesh of a fitted primitive too (as MuJoCo 3.5.1 does).
    state->geoms[i].mesh = &state->meshes[ids[i]];
    state->geoms[i].meshid = ids[i];
  }
}

// ---------------------------------------------------------------- geom sizes and frames

namespace {

// Size of a primitive fitted to the mesh: to its equivalent inertia box, or (fitaabb)
// to its bounding box, whose centre is returned in `center`. Scaled by fitscale.
void FitPrimitive(const mjcf::CompilerSpec& c, const MeshState& mesh, GeomState* g,
                  double center[3]) {
  const mjcf::GeomSpec& s = *g->spec;
  double* size = g->size;
  int type = s.type;
  if (type != kGeomSphere && type != kGeomCapsule && type != kGeomCylinder &&
      type != kGeomEllipsoid && type != kGeomBox) {
    ThrowAt(s.src, "invalid geom type for fitting mesh '" + mesh.spec->src.name + "'");
  }
  if (!c.fitaabb) {
    const double* box = mesh.boxsz;
    if (type == kGeomSphere) {
      size[0] = (box[0] + box[1] + box[2]) / 3;
    } else if (type == kGeomCapsule) {
      size[0] = (box[0] + box[1]) / 2;
      size[1] = std::max(0.0, box[2] - size[0] / 2);
    } else if (type == kGeomCylinder) {
      size[0] = (box[0] + box[1]) / 2;
      size[1] = box[2];
    } else {
      math::Copy3(size, box);
    }
  } else {
    const double* aamm = mesh.aamm;
    double half[3];
    for (int k = 0; k < 3; k++) {
      center[k] = (aamm[k] + aamm[k + 3]) / 2;
      half[k] = aamm[k + 3] - center[k];
    }
    if (type == kGeomSphere) {
      size[0] = std::max(std::max(half[0], half[1]), half[2]);
    } else if (type == kGeomCapsule || type == kGeomCylinder) {
      size[0] = std::max(half[0], half[1]);
      size[1] = half[2];
      if (type == kGeomCapsule) size[1] -= size[0];
    } else {
      math::Copy3(size, half);
    }
  }
  for (int k = 0; k < 3; k++) size[k] *= s.fitscale;
}

}  // namespace

void MeshGeomFrame(const mjcf::CompilerSpec& c, GeomState* g) {
  const mjcf::GeomSpec& s = *g->spec;
  const MeshState& mesh = *g->mesh;
  if (!std::isnan(s.fromto[0])) ThrowAt(s.src, "fromto cannot be used with a mesh geom");
  double center[3] = {0, 0, 0};
  if (s.type != kGeomMesh && s.type != kGeomSdf) {
    FitPrimitive(c, mesh, g, center);
  } else if (s.shellinertia) {
    ThrowAt(s.src, "for mesh geoms, inertia should be specified in the mesh asset");
  }

  // The geom frame moves to the mesh's inertial frame (plus a fitted box's centre).
  double mat[9], offset[3], shifted[3], quat[4];
  math::QuatToMat(mat, mesh.quat);
  math::MulMatVec3(offset, mat, center);
  math::Add3(offset, offset, mesh.pos);
  math::QuatToMat(mat, g->quat);
  math::MulMatVec3(shifted, mat, offset);
  math::Add3(g->pos, g->pos, shifted);
  math::MulQuat(quat, g->quat, mesh.quat);
  NormalizeVec(quat, 4);
  math::CopyQuat(g->quat, quat);
}

void MeshGeomSize(GeomState* g) {
  const double* aamm = g->mesh->aamm;
  for (int k = 0; k < 3; k++) g->size[k] = std::max(std::abs(aamm[k]), std::abs(aamm[k + 3]));
}

// ---------------------------------------------------------------- model arrays

void MeshSizes(const CompileState& state, Model* m) {
  m->nmesh = static_cast<int>(state.meshes.size());
  m->nmeshvert = m->nmeshface = m->nmeshgraph = m->nmeshnormal = m->nmeshtexcoord = 0;
  m->nmeshpoly = m->nmeshpolyvert = m->nmeshpolymap = 0;
  for (const MeshState& mesh : state.meshes) {
    m->nmeshtexcoord += static_cast<int>(mesh.texcoord.size() / 2);
    m->nmeshvert += static_cast<int>(mesh.vert.size() / 3);
    m->nmeshnormal += static_cast<int>(mesh.normal.size() / 3);
    m->nmeshface += static_cast<int>(mesh.face.size() / 3);
    m->nmeshgraph += static_cast<int>(mesh.graph.size());
    m->nmeshpoly += static_cast<int>(mesh.polygons.size());
    for (const std::vector<int>& p : mesh.polygons) m->nmeshpolyvert += static_cast<int>(p.size());
  }
  m->nmeshpolymap = m->nmeshpolyvert;  // (each polygon vertex maps back to its polygon)
  m->noct = 0;
  for (const MeshState& mesh : state.meshes) m->noct += static_cast<int>(mesh.oct_depth.size());
}

namespace {

// mesh_poly*: each mesh's polygons (vertex paths and normals) and, per vertex, the
// polygons it belongs to (ascending); vertex and polygon numbers are the mesh's own.
void LayoutMeshPolygons(const CompileState& state, Model* m) {
  int poly = 0, polyvert = 0, polymap = 0;
  for (int i = 0; i < m->nmesh; i++) {
    const MeshState& mesh = state.meshes[i];
    int npoly = static_cast<int>(mesh.polygons.size());
    m->mesh_polyadr[i] = poly;
    m->mesh_polynum[i] = npoly;
    std::vector<std::vector<int>> of_vertex(m->mesh_vertnum[i]);
    for (int p = 0; p < npoly; p++) {
      const std::vector<int>& path = mesh.polygons[p];
      m->mesh_polyvertadr[poly + p] = polyvert;
      m->mesh_polyvertnum[poly + p] = static_cast<int>(path.size());
      std::copy(path.begin(), path.end(), m->mesh_polyvert.begin() + polyvert);
      polyvert += static_cast<int>(path.size());
      for (int k = 0; k < 3; k++) m->mesh_polynormal[3 * (poly + p) + k] = mesh.polynormal[3 * p + k];
      for (int v : path) of_vertex[v].push_back(p);
    }
    for (int v = 0; v < m->mesh_vertnum[i]; v++) {
      int global = m->mesh_vertadr[i] + v;
      m->mesh_polymapadr[global] = polymap;
      m->mesh_polymapnum[global] = static_cast<int>(of_vertex[v].size());
      std::copy(of_vertex[v].begin(), of_vertex[v].end(), m->mesh_polymap.begin() + polymap);
      polymap += static_cast<int>(of_vertex[v].size());
    }
    poly += npoly;
  }
}

}  // namespace

void LayoutMeshes(const CompileState& state, Model* m) {
  int vert = 0, face = 0, graph = 0, normal = 0, texcoord = 0;
  for (int i = 0; i < m->nmesh; i++) {
    const MeshState& mesh = state.meshes[i];
    m->mesh_vertadr[i] = vert;
    m->mesh_vertnum[i] = static_cast<int>(mesh.vert.size() / 3);
    m->mesh_faceadr[i] = face;
    m->mesh_facenum[i] = static_cast<int>(mesh.face.size() / 3);
    m->mesh_graphadr[i] = mesh.graph.empty() ? -1 : graph;
    math::Copy3(&m->mesh_scale[3 * i], mesh.spec->scale.data());
    math::Copy3(&m->mesh_pos[3 * i], mesh.pos);
    math::CopyQuat(&m->mesh_quat[4 * i], mesh.quat);

    // Vertices are single precision in MuJoCo's model.
    for (size_t k = 0; k < mesh.vert.size(); k++) {
      m->mesh_vert[3 * vert + k] = static_cast<float>(mesh.vert[k]);
    }
    std::copy(mesh.face.begin(), mesh.face.end(), m->mesh_face.begin() + 3 * face);
    std::copy(mesh.graph.begin(), mesh.graph.end(), m->mesh_graph.begin() + graph);
    m->mesh_normaladr[i] = normal;
    m->mesh_normalnum[i] = static_cast<int>(mesh.normal.size() / 3);
    std::copy(mesh.normal.begin(), mesh.normal.end(), m->mesh_normal.begin() + 3 * normal);
    normal += m->mesh_normalnum[i];
    // (faces of a mesh without coordinates keep coordinate 0, as in MuJoCo)
    m->mesh_texcoordadr[i] = mesh.texcoord.empty() ? -1 : texcoord;
    m->mesh_texcoordnum[i] = static_cast<int>(mesh.texcoord.size() / 2);
    std::copy(mesh.texcoord.begin(), mesh.texcoord.end(), m->mesh_texcoord.begin() + 2 * texcoord);
    std::copy(mesh.facetexcoord.begin(), mesh.facetexcoord.end(),
              m->mesh_facetexcoord.begin() + 3 * face);
    texcoord += m->mesh_texcoordnum[i];
    vert += m->mesh_vertnum[i];
    face += m->mesh_facenum[i];
    graph += static_cast<int>(mesh.graph.size());
    m->mesh_names[i] = mesh.spec->src.name;
  }
  LayoutMeshPolygons(state, m);

  // Octrees, one after another.
  int oct = 0;
  for (int i = 0; i < m->nmesh; i++) {
    const MeshState& mesh = state.meshes[i];
    int n = static_cast<int>(mesh.oct_depth.size());
    m->mesh_octadr[i] = n ? oct : -1;
    m->mesh_octnum[i] = n;
    std::copy(mesh.oct_depth.begin(), mesh.oct_depth.end(), m->oct_depth.begin() + oct);
    std::copy(mesh.oct_child.begin(), mesh.oct_child.end(), m->oct_child.begin() + 8 * oct);
    std::copy(mesh.oct_aabb.begin(), mesh.oct_aabb.end(), m->oct_aabb.begin() + 6 * oct);
    std::copy(mesh.oct_coeff.begin(), mesh.oct_coeff.end(), m->oct_coeff.begin() + 8 * oct);
    oct += n;
  }
}

}  // namespace simlab::compiler
