// Builtin meshes (<mesh builtin=... params=...>): the vertices and triangles MuJoCo
// 3.5's compiler generates for each shape (mjs_makeMesh), with the same single- and
// double-precision steps so the vertices agree bit for bit.
#include "compiler/mesh_builtin.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "compiler/orientation.h"
#include "math/elementary.h"
#include "math/math.h"
#include "mjcf/error.h"
#include "mjcf/limits.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

constexpr double kPi = std::numbers::pi;

// Signed powers of cos and sin (the superquadric shape functions).
double SignedPowCos(double angle, double power) {
  return std::copysign(std::pow(std::abs(math::Cos(angle)), power), math::Cos(angle));
}
double SignedPowSin(double angle, double power) {
  return std::copysign(std::pow(std::abs(math::Sin(angle)), power), math::Sin(angle));
}

void PushVertex(MeshData* out, double x, double y, double z) {
  out->vert.push_back(static_cast<float>(x));
  out->vert.push_back(static_cast<float>(y));
  out->vert.push_back(static_cast<float>(z));
}

void PushFace(MeshData* out, int a, int b, int c) {
  out->face.push_back(a);
  out->face.push_back(b);
  out->face.push_back(c);
}

// ---------------------------------------------------------------- sphere (icosahedron)

// Index of the (float) midpoint of edge (a, b) pushed onto the unit sphere; made once
// per edge and subdivision level.
int EdgeMidpoint(int a, int b, std::map<std::pair<int, int>, int>* made, std::vector<float>* vert) {
  std::pair<int, int> key = std::minmax(a, b);
  auto found = made->find(key);
  if (found != made->end()) return found->second;
  float mid[3];
  for (int k = 0; k < 3; k++) mid[k] = ((*vert)[3 * a + k] + (*vert)[3 * b + k]) / 2.0f;
  float len = std::sqrt(mid[0] * mid[0] + mid[1] * mid[1] + mid[2] * mid[2]);
  int id = static_cast<int>(vert->size() / 3);
  for (float c : mid) vert->push_back(c / len);
  (*made)[key] = id;
  return id;
}

MeshData Sphere(int subdiv) {
  const float phi = static_cast<float>((1.0 + std::sqrt(5.0)) / 2.0);
  MeshData out;
  out.vert = {-1, phi, 0, 1, phi, 0, -1, -phi, 0, 1, -phi, 0,
              0, -1, phi, 0, 1, phi, 0, -1, -phi, 0, 1, -phi,
              phi, 0, -1, phi, 0, 1, -phi, 0, -1, -phi, 0, 1};
  const double len = std::sqrt(1.0 + phi * phi);
  for (float& v : out.vert) v = static_cast<float>(v / len);
  out.face = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
              11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8,
              3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};

  // Each level splits every triangle into four at its edge midpoints.
  for (int level = 0; level < subdiv; level++) {
    std::map<std::pair<int, int>, int> made;
    std::vector<int> faces;
    for (size_t f = 0; f < out.face.size(); f += 3) {
      int a = out.face[f], b = out.face[f + 1], c = out.face[f + 2];
      int ab = EdgeMidpoint(a, b, &made, &out.vert);
      int bc = EdgeMidpoint(b, c, &made, &out.vert);
      int ca = EdgeMidpoint(c, a, &made, &out.vert);
      faces.insert(faces.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    out.face = std::move(faces);
  }
  return out;
}

// ---------------------------------------------------------------- hemisphere

// Rows of points from the north pole down to the equator, each row four arcs between
// the equator's axis points, projected onto the unit sphere; plus a centre point.
void HemisphereVertices(int res, MeshData* out) {
  static constexpr double kEquator[4][3] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  PushVertex(out, 0, 0, 1);
  for (int row = 0; row <= res; row++) {
    double t = static_cast<double>(row + 1) / (res + 1);
    for (int side = 0; side < 4; side++) {
      const double* e0 = kEquator[side];
      const double* e1 = kEquator[(side + 1) % 4];
      double start[3] = {t * e0[0], t * e0[1], 1 + t * (e0[2] - 1)};
      double end[3] = {t * e1[0], t * e1[1], 1 + t * (e1[2] - 1)};
      for (int i = 0; i < row + 1; i++) {
        double p[3];
        for (int k = 0; k < 3; k++) p[k] = start[k] + i * ((end[k] - start[k]) / (row + 1));
        double norm = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        PushVertex(out, p[0] / norm, p[1] / norm, p[2] / norm);
      }
    }
  }
  PushVertex(out, 0, 0, 0);
}

void HemisphereFaces(int res, MeshData* out) {
  for (int k = 1; k <= 4; k++) PushFace(out, 0, k, k % 4 + 1);
  for (int row = 0; row < res; row++) {
    const int cur = 2 * row * (row + 1) + 1, ncur = 4 * (row + 1);
    const int next = cur + ncur, nnext = 4 * (row + 2);
    for (int side = 0; side < 4; side++) {
      for (int i = 0; i < row + 2; i++) {
        int c = i + (row + 1) * side, n = i + (row + 2) * side;
        PushFace(out, cur + c % ncur, next + n % nnext, next + (n + 1) % nnext);
        if (i < row + 1) PushFace(out, cur + c % ncur, next + (n + 1) % nnext, cur + (c + 1) % ncur);
      }
    }
  }

  // The flat bottom: a fan around the centre point.
  const int rim = 2 * res * (res + 1) + 1, nrim = 4 * (res + 1);
  const int centre = static_cast<int>(out->vert.size() / 3) - 1;
  for (int i = 0; i < nrim; i++) PushFace(out, rim + i, centre, rim + (i + 1) % nrim);
}

// ---------------------------------------------------------------- superquadrics

MeshData Supersphere(int res, double e, double n) {
  MeshData out;
  PushVertex(&out, 0, 0, -1);
  for (int i = 1; i < res; i++) {
    double v = -kPi / 2 + i * kPi / res;
    for (int j = 0; j < res; j++) {
      double u = -kPi + j * 2 * kPi / res;
      PushVertex(&out, SignedPowCos(v, n) * SignedPowCos(u, e),
                 SignedPowCos(v, n) * SignedPowSin(u, e), SignedPowSin(v, n));
    }
  }
  PushVertex(&out, 0, 0, 1);

  // Fans at the poles, two triangles per quad between rings.
  const int north = (res - 1) * res + 1, last = 1 + (res - 2) * res;
  for (int j = 0; j < res; j++) PushFace(&out, 0, 1 + (j + 1) % res, 1 + j);
  for (int i = 0; i < res - 2; i++) {
    for (int j = 0; j < res; j++) {
      int a = 1 + i * res + j, b = 1 + i * res + (j + 1) % res;
      int d = 1 + (i + 1) * res + j, c = 1 + (i + 1) * res + (j + 1) % res;
      PushFace(&out, a, b, d);
      PushFace(&out, b, c, d);
    }
  }
  for (int j = 0; j < res; j++) PushFace(&out, last + j, last + (j + 1) % res, north);
  return out;
}

MeshData Supertorus(int res, double radius, double s, double t) {
  MeshData out;
  for (int i = 0; i < res; i++) {
    for (int j = 0; j < res; j++) {
      double u = 2 * kPi * i / res, v = 2 * kPi * j / res;
      double ring = 1 + radius * SignedPowCos(v, s);
      PushVertex(&out, ring * SignedPowCos(u, t), ring * SignedPowSin(u, t),
                 radius * SignedPowSin(v, s));
    }
  }
  for (int i = 0; i < res; i++) {
    for (int j = 0; j < res; j++) {
      int inext = (i + 1) % res, jnext = (j + 1) % res;
      PushFace(&out, i * res + j, inext * res + j, i * res + jnext);
      PushFace(&out, inext * res + j, inext * res + jnext, i * res + jnext);
    }
  }
  return out;
}

// ---------------------------------------------------------------- wedge, plate, cone

// `n` evenly spaced numbers from lo to hi, by repeated addition.
std::vector<double> EvenlySpaced(double lo, double hi, int n) {
  std::vector<double> out(n);
  double step = n > 1 ? (hi - lo) / (n - 1) : 0;
  for (int i = 0; i < n; i++, lo += step) out[i] = lo;
  return out;
}

// Bin edges over [-1, 1], bent towards the centre by gamma, scaled to fov degrees.
std::vector<double> FovealEdges(int bins, double fov_deg, double gamma) {
  std::vector<double> edges = EvenlySpaced(-1, 1, bins + 1);
  for (double& x : edges) {
    if (gamma != 0) {
      double g = std::max(0.0, std::min(1.0, gamma));
      x = g * std::pow(x, 5) + (1 - g) * x;
    }
    x = fov_deg * kPi / 180 * x;
  }
  return edges;
}

// The frame of a wedge point (azimuth a, elevation e on the unit sphere): the outward
// normal (elevation tangent x azimuth tangent), then the unit azimuth and elevation
// tangents, each rounded to float.
void PushWedgeFrame(MeshData* out, double a, double e) {
  double along_a[3] = {math::Cos(e) * math::Cos(a), 0, math::Cos(e) * math::Sin(a)};
  double along_e[3] = {-math::Sin(e) * math::Sin(a), math::Cos(e), math::Sin(e) * math::Cos(a)};
  NormalizeVec(along_a, 3);
  NormalizeVec(along_e, 3);
  double normal[3];
  math::Cross3(normal, along_e, along_a);
  for (const double* v : {normal, along_a, along_e}) {
    for (int k = 0; k < 3; k++) out->normal.push_back(static_cast<float>(v[k]));
  }
}

// One vertex per bin centre on the unit sphere (azimuth, elevation) with its frame; no
// triangles.
MeshData Wedge(const int res[2], const double fov[2], double gamma) {
  std::vector<double> az = FovealEdges(res[0], fov[0], gamma);
  std::vector<double> el = FovealEdges(res[1], fov[1], gamma);
  MeshData out;
  for (int i = 0; i < res[0]; i++) {
    for (int j = 0; j < res[1]; j++) {
      double a = 0.5 * (az[i + 1] + az[i]), e = 0.5 * (el[j + 1] + el[j]);
      PushVertex(&out, math::Cos(e) * math::Sin(a), math::Sin(e), -math::Cos(e) * math::Cos(a));
      PushWedgeFrame(&out, a, e);
    }
  }
  return out;
}

// A grid of cell centres on z = -1, two triangles per cell between neighbours, with an
// identity frame per point.
MeshData Plate(const int res[2]) {
  MeshData out;
  out.face.assign(6 * static_cast<size_t>(res[0] - 1) * (res[1] - 1), 0);
  const double dx = 2.0 / res[0], dy = 2.0 / res[1];
  for (int i = 0; i < res[0]; i++) {
    for (int j = 0; j < res[1]; j++) {
      PushVertex(&out, -1 + (i + 0.5) * dx, -1 + (j + 0.5) * dy, -1);
      // Each point's frame is the identity (MuJoCo's "normal" is the x axis here).
      out.normal.insert(out.normal.end(), {1, 0, 0, 0, 1, 0, 0, 0, 1});
      if (i == 0 || j == 0) continue;
      int* f = &out.face[6 * static_cast<size_t>((i - 1) * (res[1] - 1) + j - 1)];
      int lo = (i - 1) * res[1], hi = i * res[1];
      int cell[6] = {lo + j - 1, hi + j - 1, lo + j, hi + j, lo + j, hi + j - 1};
      std::copy(cell, cell + 6, f);
    }
  }
  return out;
}

// A ring of nedge points at z = -1, and a ring of the given radius (or the apex) at z = 1.
MeshData Cone(int nedge, double radius) {
  MeshData out;
  for (int i = 0; i < nedge; i++) {
    PushVertex(&out, math::Cos(2 * i * kPi / nedge), math::Sin(2 * i * kPi / nedge), -1);
  }
  if (radius <= 0) {
    PushVertex(&out, 0, 0, 1);
    return out;
  }
  for (int i = nedge; i < 2 * nedge; i++) {
    PushVertex(&out, radius * math::Cos(2 * i * kPi / nedge), radius * math::Sin(2 * i * kPi / nedge), 1);
  }
  return out;
}

// ---------------------------------------------------------------- parameters

void NeedParams(const mjcf::MeshSpec& s, size_t n, const char* shape) {
  if (s.params.size() != n) {
    ThrowAt(s.src, std::string(shape) + " mesh type requires " + std::to_string(n) +
                       (n == 1 ? " parameter" : " parameters"));
  }
}

void Require(const mjcf::MeshSpec& s, bool ok, const char* message) {
  if (!ok) ThrowAt(s.src, message);
}

// The parameters as written, for messages.
std::string ParamsText(const mjcf::MeshSpec& s) {
  std::string text;
  for (double p : s.params) {
    char number[32];
    std::snprintf(number, sizeof(number), "%.17g", p);
    if (!text.empty()) text += ' ';
    text += number;
  }
  return text;
}

// Parameter k as an int (a resolution or a count), truncated as MuJoCo casts it; a value
// an int cannot hold (MuJoCo's cast is undefined then) is an error.
int IntParam(const mjcf::MeshSpec& s, size_t k) {
  double v = s.params[k];
  if (!(v > -2147483649.0 && v < 2147483648.0)) {
    ThrowAt(s.src, "params=\"" + ParamsText(s) + "\": parameter " + std::to_string(k + 1) +
                       " is out of the range of an integer");
  }
  return static_cast<int>(v);
}

// A shape of `vertices` vertices and `faces` triangles, with a frame (9 numbers) per
// vertex if `frames`, must fit the budget of one array: counted in double precision
// (no overflow) before anything is made, as the Model stores them.
void CheckBudget(const mjcf::MeshSpec& s, double vertices, double faces, bool frames) {
  double bytes = vertices * 3 * sizeof(double) + faces * 3 * sizeof(int) +
                 (frames ? vertices * 9 * sizeof(double) : 0.0);
  if (bytes <= static_cast<double>(mjcf::kMaxArrayBytes)) return;
  uint64_t shown = bytes < 1.8e19 ? static_cast<uint64_t>(bytes) : UINT64_MAX;
  ThrowAt(s.src, mjcf::OverBudget(mjcf::AttrText("params", ParamsText(s)), shown,
                                  "mesh vertices and faces", mjcf::kMaxArrayBytes));
}

MeshData SphereLike(const mjcf::MeshSpec& s, bool hemisphere) {
  NeedParams(s, 1, hemisphere ? "Hemisphere" : "Sphere");
  int subdiv = IntParam(s, 0);
  Require(s, subdiv >= 0, hemisphere ? "Hemisphere resolution cannot be negative"
                                     : "Sphere subdivision cannot be negative");
  Require(s, subdiv <= (hemisphere ? 10 : 4),
          hemisphere ? "Hemisphere resolution cannot be greater than 10"
                     : "Sphere subdivision cannot be greater than 4");
  if (!hemisphere) return Sphere(subdiv);
  MeshData out;
  HemisphereVertices(subdiv, &out);
  HemisphereFaces(subdiv, &out);
  return out;
}

MeshData SupersphereFrom(const mjcf::MeshSpec& s) {
  NeedParams(s, 3, "Supersphere");
  int res = IntParam(s, 0);
  Require(s, res >= 3, "Supersphere resolution must be greater than 2");
  Require(s, s.params[1] >= 0, "Supersphere 'e' cannot be negative");
  Require(s, s.params[2] >= 0, "Supersphere 'n' cannot be negative");
  CheckBudget(s, (res - 1.0) * res + 2, 2.0 * res * (res - 1), false);
  return Supersphere(res, s.params[1], s.params[2]);
}

MeshData SupertorusFrom(const mjcf::MeshSpec& s) {
  NeedParams(s, 4, "Supertorus");
  int res = IntParam(s, 0);
  Require(s, res >= 3, "Supertorus resolution must be greater than 3");
  Require(s, s.params[1] > 0 && s.params[1] <= 1, "Supertorus radius must be in (0, 1]");
  Require(s, s.params[2] > 0, "Supertorus 's' must be greater than 0");
  Require(s, s.params[3] > 0, "Supertorus 't' must be greater than 0");
  CheckBudget(s, 1.0 * res * res, 2.0 * res * res, false);
  return Supertorus(res, s.params[1], s.params[2], s.params[3]);
}

MeshData WedgeFrom(const mjcf::MeshSpec& s) {
  NeedParams(s, 5, "Wedge builtin");
  const int res[2] = {IntParam(s, 0), IntParam(s, 1)};
  const double fov[2] = {s.params[2], s.params[3]};
  Require(s, fov[0] > 0 && fov[0] <= 180, "fov[0] must be a float between (0, 180] degrees");
  Require(s, fov[1] > 0 && fov[1] <= 90, "fov[1] must be a float between (0, 90] degrees");
  Require(s, res[0] > 0 && res[1] > 0, "Horizontal and vertical resolutions must be positive");
  Require(s, s.params[4] >= 0 && s.params[4] <= 1, "gamma must be a float in [0, 1]");
  CheckBudget(s, 1.0 * res[0] * res[1], 0, true);
  return Wedge(res, fov, s.params[4]);
}

MeshData PlateFrom(const mjcf::MeshSpec& s) {
  NeedParams(s, 2, "Plate builtin");
  const int res[2] = {IntParam(s, 0), IntParam(s, 1)};
  Require(s, res[0] > 0 && res[1] > 0, "Horizontal and vertical resolutions must be positive");
  CheckBudget(s, 1.0 * res[0] * res[1], 2.0 * (res[0] - 1) * (res[1] - 1), true);
  return Plate(res);
}

MeshData ConeFrom(const mjcf::MeshSpec& s) {
  NeedParams(s, 2, "Cone");
  int nedge = IntParam(s, 0);
  Require(s, nedge >= 3, "Cone needs at least 3 edges");
  CheckBudget(s, 2.0 * nedge, 0, false);
  return Cone(nedge, s.params[1]);
}

}  // namespace

MeshData BuiltinMesh(const mjcf::MeshSpec& s) {
  switch (s.builtin) {
    case mjcf::kMeshBuiltinSphere: return SphereLike(s, false);
    case mjcf::kMeshBuiltinHemisphere: return SphereLike(s, true);
    case mjcf::kMeshBuiltinCone: return ConeFrom(s);
    case mjcf::kMeshBuiltinSupersphere: return SupersphereFrom(s);
    case mjcf::kMeshBuiltinSupertorus: return SupertorusFrom(s);
    case mjcf::kMeshBuiltinWedge: return WedgeFrom(s);
    case mjcf::kMeshBuiltinPlate: return PlateFrom(s);
    default: break;
  }
  ThrowAt(s.src, "Unsupported mesh type");
}

}  // namespace simlab::compiler
