// Reading mesh files: STL (binary as MuJoCo, ASCII in addition) and OBJ.
#include "compiler/mesh_io.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <utility>
#include <string>
#include <vector>

#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

// ---------------------------------------------------------------- helpers

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// "stl", "obj" or "msh" from the content type, else from the file extension.
std::string FileKind(const mjcf::MeshSpec& mesh) {
  if (!mesh.content_type.empty()) {
    std::string ct = Lower(mesh.content_type);
    if (ct == "model/stl") return "stl";
    if (ct == "model/obj") return "obj";
    if (ct == "model/vnd.mujoco.msh") return "msh";
    ThrowAt(mesh.src, "invalid content type: '" + mesh.content_type + "'");
  }
  size_t dot = mesh.path.find_last_of('.');
  size_t slash = mesh.path.find_last_of('/');
  std::string ext = (dot == std::string::npos || (slash != std::string::npos && dot < slash))
                        ? ""
                        : Lower(mesh.path.substr(dot + 1));
  if (ext == "stl" || ext == "obj" || ext == "msh") return ext;
  ThrowAt(mesh.src, "unknown or unsupported mesh file: '" + mesh.path + "'");
}

// The file's bytes: an asset with its name shadows the disk.
std::string ReadBytes(const mjcf::MeshSpec& mesh, const mjcf::AssetFiles* assets) {
  std::string bytes;
  if (!mjcf::ReadFileOrAsset(mesh.path, assets, &bytes)) {
    ThrowAt(mesh.src, "cannot open mesh file '" + mesh.path + "'" + mjcf::NotAmongAssets(assets));
  }
  return bytes;
}

bool RightHanded(const mjcf::MeshSpec& mesh) {
  return mesh.scale[0] * mesh.scale[1] * mesh.scale[2] > 0;
}

// ---------------------------------------------------------------- STL

// Appends one triangle given as 9 floats; a left-handed scale swaps its 2nd and 3rd corner.
void AddStlTriangle(const mjcf::MeshSpec& mesh, const float* corners, bool righthand,
                    MeshData* out) {
  int base = static_cast<int>(out->vert.size() / 3);
  const double limit = 1 << 30;
  for (int j = 0; j < 3; j++) {
    const float* v = corners + 3 * j;
    if (std::fabs(v[0]) > limit || std::fabs(v[1]) > limit || std::fabs(v[2]) > limit) {
      ThrowAt(mesh.src, "vertex in STL file '" + mesh.path + "' exceeds maximum bounds");
    }
    out->vert.insert(out->vert.end(), v, v + 3);
  }
  out->face.push_back(base);
  out->face.push_back(base + (righthand ? 1 : 2));
  out->face.push_back(base + (righthand ? 2 : 1));
}

void CheckFaceCount(const mjcf::MeshSpec& mesh, long nfaces) {
  if (nfaces < 1 || nfaces > 200000) {
    ThrowAt(mesh.src, "number of faces should be between 1 and 200000 in STL file '" +
                          mesh.path + "'");
  }
}

// Binary STL: 80-byte header, a face count, then 50 bytes per face.
bool ReadBinaryStl(const mjcf::MeshSpec& mesh, const std::string& bytes, MeshData* out) {
  int64_t nfaces = BinaryStlFaceCount(bytes);
  if (nfaces < 0) return false;
  CheckFaceCount(mesh, static_cast<long>(nfaces));
  bool righthand = RightHanded(mesh);
  for (int64_t i = 0; i < nfaces; i++) {
    float corners[9];
    std::memcpy(corners, bytes.data() + 84 + 50 * i + 12, sizeof(corners));
    AddStlTriangle(mesh, corners, righthand, out);
  }
  return true;
}

// ASCII STL: "facet normal ... outer loop vertex x y z (3x) endloop endfacet" blocks.
bool ReadAsciiStl(const mjcf::MeshSpec& mesh, const std::string& bytes, MeshData* out) {
  std::istringstream in(bytes);
  std::string word;
  if (!(in >> word) || word != "solid") return false;
  std::vector<float> corners;
  while (in >> word) {
    if (word != "vertex") continue;
    for (int k = 0; k < 3; k++) {
      std::string t;
      char* end = nullptr;
      if (!(in >> t)) ThrowAt(mesh.src, "truncated vertex in ASCII STL file '" + mesh.path + "'");
      corners.push_back(std::strtof(t.c_str(), &end));
      if (*end != '\0') ThrowAt(mesh.src, "bad number '" + t + "' in STL file '" + mesh.path + "'");
    }
  }
  if (corners.size() % 9 != 0) ThrowAt(mesh.src, "STL file '" + mesh.path + "' has an incomplete facet");
  CheckFaceCount(mesh, static_cast<long>(corners.size() / 9));
  bool righthand = RightHanded(mesh);
  for (size_t i = 0; i < corners.size(); i += 9) AddStlTriangle(mesh, &corners[i], righthand, out);
  return true;
}

MeshData ReadStl(const mjcf::MeshSpec& mesh, const std::string& bytes) {
  if (bytes.empty()) ThrowAt(mesh.src, "STL file '" + mesh.path + "' is empty");
  MeshData out;
  if (!ReadBinaryStl(mesh, bytes, &out) && !ReadAsciiStl(mesh, bytes, &out)) {
    ThrowAt(mesh.src, "STL file '" + mesh.path + "' has a wrong size and is not ASCII STL");
  }
  MergeRepeatedVertices(&out);
  return out;
}

// ---------------------------------------------------------------- OBJ

// Point-in-polygon test by ray crossings (float, as the OBJ loader computes it).
bool InsideTriangle(const float* xs, const float* ys, float x, float y) {
  bool inside = false;
  for (int i = 0, j = 2; i < 3; j = i++) {
    if (((ys[i] > y) != (ys[j] > y)) &&
        (x < (xs[j] - xs[i]) * (y - ys[i]) / (ys[j] - ys[i]) + xs[i])) {
      inside = !inside;
    }
  }
  return inside;
}

// The two coordinate axes a polygon is projected on: those of the first corner whose
// cross product is not negligible, dropping its largest component.
void ProjectionAxes(const std::vector<float>& v, const std::vector<int>& poly, int axes[2]) {
  axes[0] = 1;
  axes[1] = 2;
  size_t n = poly.size();
  for (size_t k = 0; k < n; k++) {
    const float* a = &v[3 * poly[k]];
    const float* b = &v[3 * poly[(k + 1) % n]];
    const float* c = &v[3 * poly[(k + 2) % n]];
    float e0[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float e1[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    float cx = std::fabs(e0[1] * e1[2] - e0[2] * e1[1]);
    float cy = std::fabs(e0[2] * e1[0] - e0[0] * e1[2]);
    float cz = std::fabs(e0[0] * e1[1] - e0[1] * e1[0]);
    const float eps = std::numeric_limits<float>::epsilon();
    if (cx > eps || cy > eps || cz > eps) {
      if (!(cx > cy && cx > cz)) {
        axes[0] = 0;
        if (cz > cx && cz > cy) axes[1] = 1;
      }
      return;
    }
  }
}

// Cuts a polygon into triangles by ear clipping in its projection plane, in the order
// of MuJoCo's OBJ loader (a quad 0123 gives 012 and 023).
// `poly` holds the polygon's corners (0..n-1), `vertex_of` each corner's vertex; the
// triangles are given as corners too, so that each corner keeps its texture coordinate.
void Triangulate(const std::vector<float>& v, const std::vector<int>& vertex_of,
                 std::vector<int> poly, std::vector<int>* tris) {
  int axes[2];
  ProjectionAxes(v, vertex_of, axes);
  auto x = [&](int corner) { return v[3 * vertex_of[corner] + axes[0]]; };
  auto y = [&](int corner) { return v[3 * vertex_of[corner] + axes[1]]; };

  // Signed area of the projection (its sign tells convex from reflex corners).
  float area = 0;
  for (size_t k = 0; k < poly.size(); k++) {
    int a = poly[k], b = poly[(k + 1) % poly.size()];
    area += (x(a) * y(b) - y(a) * x(b)) * 0.5f;
  }

  size_t guess = 0, tries = poly.size(), last_size = poly.size();
  while (poly.size() > 3 && tries > 0) {
    size_t n = poly.size();
    if (guess >= n) guess -= n;
    if (last_size != n) {
      last_size = n;
      tries = n;
    } else {
      tries--;
    }

    // The candidate ear (guess, guess+1, guess+2): convex, and no other corner inside.
    int ear[3];
    float xs[3], ys[3];
    for (int k = 0; k < 3; k++) {
      ear[k] = poly[(guess + k) % n];
      xs[k] = x(ear[k]);
      ys[k] = y(ear[k]);
    }
    float cross = (xs[1] - xs[0]) * (ys[2] - ys[1]) - (ys[1] - ys[0]) * (xs[2] - xs[1]);
    bool reject = cross * area < 0.0f;
    for (size_t k = 3; k < n && !reject; k++) {
      int other = poly[(guess + k) % n];
      reject = InsideTriangle(xs, ys, x(other), y(other));
    }
    if (reject) {
      guess++;
      continue;
    }

    // Emit the ear and drop its middle corner.
    tris->insert(tris->end(), ear, ear + 3);
    poly.erase(poly.begin() + static_cast<long>((guess + 1) % n));
  }
  if (poly.size() == 3) tris->insert(tris->end(), poly.begin(), poly.end());
}

// One index of a face corner, 0-based (negative indices count back from the last of
// `count` read); `text` starts at the number.
int ObjIndex(const mjcf::MeshSpec& mesh, const char* text, int count, int line, const char** end) {
  char* stop = nullptr;
  long idx = std::strtol(text, &stop, 10);
  *end = stop;
  if (stop == text || (*stop != '\0' && *stop != '/') || idx == 0) {
    ThrowAt(mesh.src, "could not parse OBJ file '" + mesh.path + "' (line " +
                          std::to_string(line) + ": bad face index '" + text + "')");
  }
  long zero_based = idx > 0 ? idx - 1 : count + idx;
  if (zero_based < 0) {
    ThrowAt(mesh.src, "OBJ file '" + mesh.path + "' line " + std::to_string(line) +
                          ": index " + std::to_string(idx) + " does not exist");
  }
  return static_cast<int>(zero_based);
}

// A face corner "v", "v/vt", "v//vn" or "v/vt/vn": its vertex and texture coordinate
// (-1 when none is given).
struct ObjCorner {
  int vertex = 0, texcoord = -1;
};
ObjCorner ParseObjCorner(const mjcf::MeshSpec& mesh, const std::string& token, int nvert,
                         int ntexcoord, int line) {
  ObjCorner corner;
  const char* end = nullptr;
  corner.vertex = ObjIndex(mesh, token.c_str(), nvert, line, &end);
  if (end[0] == '/' && end[1] != '/' && end[1] != '\0') {
    corner.texcoord = ObjIndex(mesh, end + 1, ntexcoord, line, &end);
  }
  return corner;
}

// Only the first group or object with faces is used (MuJoCo takes the first shape).
MeshData ReadObj(const mjcf::MeshSpec& mesh, const std::string& bytes) {
  MeshData out;
  std::vector<std::vector<ObjCorner>> polygons;
  bool first_shape_done = false;
  std::istringstream in(bytes);
  std::string text;
  for (int line = 1; std::getline(in, text); line++) {
    std::istringstream words(text);
    std::string key;
    if (!(words >> key)) continue;
    if (key == "v" || key == "vn") {
      std::vector<float>* target = key == "v" ? &out.vert : &out.normal;
      for (int k = 0; k < 3; k++) {
        std::string t;
        double value = 0;
        if (words >> t) value = std::strtod(t.c_str(), nullptr);
        target->push_back(static_cast<float>(value));
      }
    } else if (key == "vt") {
      // u and v (a third number is ignored); v is flipped, as MuJoCo stores it
      for (int k = 0; k < 2; k++) {
        std::string t;
        double value = 0;
        if (words >> t) value = std::strtod(t.c_str(), nullptr);
        out.texcoord.push_back(k == 0 ? static_cast<float>(value) : 1 - static_cast<float>(value));
      }
    } else if (key == "f" && !first_shape_done) {
      std::vector<ObjCorner> poly;
      int nvert = static_cast<int>(out.vert.size() / 3);
      int ntexcoord = static_cast<int>(out.texcoord.size() / 2);
      for (std::string t; words >> t;) poly.push_back(ParseObjCorner(mesh, t, nvert, ntexcoord, line));
      if (poly.size() >= 3) polygons.push_back(std::move(poly));
    } else if ((key == "g" || key == "o") && !polygons.empty()) {
      first_shape_done = true;
    }
  }

  // Triangles; a left-handed scale swaps each triangle's 2nd and 3rd corner.
  bool righthand = RightHanded(mesh);
  int nvert = static_cast<int>(out.vert.size() / 3);
  int ntexcoord = static_cast<int>(out.texcoord.size() / 2);
  for (const std::vector<ObjCorner>& poly : polygons) {
    std::vector<int> vertex_of, corners;
    for (const ObjCorner& c : poly) {
      if (c.vertex >= nvert) {
        ThrowAt(mesh.src, "OBJ file '" + mesh.path + "': vertex index " +
                              std::to_string(c.vertex + 1) + " does not exist");
      }
      if (c.texcoord >= ntexcoord) {
        ThrowAt(mesh.src, "OBJ file '" + mesh.path + "': texture coordinate index " +
                              std::to_string(c.texcoord + 1) + " does not exist");
      }
      corners.push_back(static_cast<int>(vertex_of.size()));
      vertex_of.push_back(c.vertex);
    }
    std::vector<int> tris;
    Triangulate(out.vert, vertex_of, corners, &tris);
    for (size_t t = 0; t < tris.size(); t += 3) {
      for (int k : {0, righthand ? 1 : 2, righthand ? 2 : 1}) {
        const ObjCorner& c = poly[tris[t + k]];
        out.face.push_back(c.vertex);
        // (a corner without a coordinate takes the first, as MuJoCo's reader does)
        if (ntexcoord > 0) out.facetexcoord.push_back(std::max(c.texcoord, 0));
      }
    }
  }
  return out;
}

// ---------------------------------------------------------------- MSH

// Fills `out` (sized already) from raw bytes. An empty `out` copies nothing: memcpy
// wants valid pointers even for zero bytes, and an empty vector's data() may be null
// (a file without normals or faces).
template <typename T>
void CopyFromBytes(const char* bytes, std::vector<T>* out) {
  if (!out->empty()) std::memcpy(out->data(), bytes, out->size() * sizeof(T));
}

// MuJoCo's binary format: counts of vertices, normals, texture coordinates and faces
// (ints), then the floats of each, then the faces (ints).
MeshData ReadMsh(const mjcf::MeshSpec& mesh, const std::string& bytes) {
  const std::string where = "MSH file '" + mesh.path + "'";
  if (bytes.size() < 4 * sizeof(int)) ThrowAt(mesh.src, "missing header in " + where);
  int n[4];  // vertices, normals, texcoords, faces
  std::memcpy(n, bytes.data(), sizeof(n));
  if (n[0] < 4 || n[1] < 0 || n[2] < 0 || n[3] < 0 || (n[1] > 0 && n[1] != n[0]) ||
      (n[2] > 0 && n[2] != n[0]) || n[0] > (1 << 26) || n[3] > (1 << 26)) {
    ThrowAt(mesh.src, "invalid sizes in " + where);
  }
  size_t floats = 3 * static_cast<size_t>(n[0]) + 3 * static_cast<size_t>(n[1]) + 2 * static_cast<size_t>(n[2]);
  if (bytes.size() != sizeof(n) + floats * sizeof(float) + 3 * static_cast<size_t>(n[3]) * sizeof(int)) {
    ThrowAt(mesh.src, "unexpected file size in " + where);
  }
  MeshData out;
  out.vert.resize(3 * static_cast<size_t>(n[0]));
  out.normal.resize(3 * static_cast<size_t>(n[1]));
  out.texcoord.resize(2 * static_cast<size_t>(n[2]));
  out.face.resize(3 * static_cast<size_t>(n[3]));
  CopyFromBytes(bytes.data() + sizeof(n), &out.vert);
  CopyFromBytes(bytes.data() + sizeof(n) + out.vert.size() * sizeof(float), &out.normal);
  CopyFromBytes(bytes.data() + sizeof(n) + (out.vert.size() + out.normal.size()) * sizeof(float),
                &out.texcoord);
  CopyFromBytes(bytes.data() + sizeof(n) + floats * sizeof(float), &out.face);
  if (!RightHanded(mesh)) {
    for (size_t i = 0; i < out.face.size(); i += 3) std::swap(out.face[i + 1], out.face[i + 2]);
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------- entry points

// The type is checked before the file is opened, as MuJoCo does.
MeshData ReadMeshFile(const mjcf::MeshSpec& mesh, const mjcf::AssetFiles* assets) {
  FileKind(mesh);
  return ReadMeshBytes(mesh, ReadBytes(mesh, assets));
}

// The reader of the file's type.
MeshData ReadMeshBytes(const mjcf::MeshSpec& mesh, const std::string& bytes) {
  std::string kind = FileKind(mesh);
  return kind == "stl"   ? ReadStl(mesh, bytes)
         : kind == "obj" ? ReadObj(mesh, bytes)
                         : ReadMsh(mesh, bytes);
}

// The count at byte 80 when 50 bytes per face follow it exactly.
int64_t BinaryStlFaceCount(const std::string& bytes) {
  if (bytes.size() < 84) return -1;
  std::uint32_t nfaces = 0;
  std::memcpy(&nfaces, bytes.data() + 80, 4);
  return static_cast<size_t>(nfaces) * 50 == bytes.size() - 84 ? int64_t{nfaces} : -1;
}

// Each vertex's key maps to its first occurrence's new index.
void MergeRepeatedVertices(MeshData* data) {
  std::map<std::array<float, 3>, int> index;
  std::vector<float> unique;
  std::vector<int> renumber;
  for (size_t i = 0; i < data->vert.size(); i += 3) {
    std::array<float, 3> key = {data->vert[i], data->vert[i + 1], data->vert[i + 2]};
    auto [it, added] = index.emplace(key, static_cast<int>(unique.size() / 3));
    if (added) unique.insert(unique.end(), key.begin(), key.end());
    renumber.push_back(it->second);
  }
  for (int& f : data->face) f = renumber[f];
  data->vert = std::move(unique);
}

}  // namespace simlab::compiler
