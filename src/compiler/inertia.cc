// Geoms and mass properties: geom size/pose (fromto), volume and inertia per geom type
// (solid or shell), and a body's inertial frame from its geoms.
//
// Volumes and inertias follow MuJoCo (user_objects.cc, mjCGeom::GetVolume/SetInertia):
// a capsule is a cylinder plus two hemispheres shifted along z; shells use surface
// areas. The body inertia sums geom inertias about the combined centre of mass
// (parallel-axis theorem), then takes principal axes.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

constexpr double kPi = std::numbers::pi;

// Number of size parameters each primitive type uses.
int SizeCount(int type) {
  switch (type) {
    case kGeomSphere: return 1;
    case kGeomCapsule:
    case kGeomCylinder: return 2;
    case kGeomEllipsoid:
    case kGeomBox: return 3;
    default: return 0;
  }
}

double Volume(int type, bool shell, const double* s) {
  switch (type) {
    case kGeomSphere:
      return shell ? 4 * kPi * s[0] * s[0] : 4 * kPi * s[0] * s[0] * s[0] / 3;
    case kGeomCapsule: {
      double h = 2 * s[1], r = s[0];
      return shell ? 4 * kPi * r * r + 2 * kPi * r * h : kPi * (r * r * h + 4 * r * r * r / 3);
    }
    case kGeomCylinder: {
      double h = 2 * s[1], r = s[0];
      return shell ? 2 * kPi * r * r + 2 * kPi * r * h : kPi * r * r * h;
    }
    case kGeomEllipsoid: {
      if (!shell) return 4 * kPi * s[0] * s[1] * s[2] / 3;
      // Thomsen's approximation of the ellipsoid surface area.
      double p = 1.6075;
      double t = std::pow(s[0] * s[1], p) + std::pow(s[1] * s[2], p) + std::pow(s[2] * s[0], p);
      return 4 * kPi * std::pow(t / 3, 1 / p);
    }
    case kGeomBox:
      return shell ? 8 * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]) : s[0] * s[1] * s[2] * 8;
    default:
      return 0;
  }
}

// Capsule: cylinder plus two hemispheres.
void CapsuleInertia(double m, bool shell, const double* s, double* I) {
  double r = s[0], half = s[1], h = 2 * s[1];
  if (!shell) {
    double msph = m * 4 * r / (4 * r + 3 * h), mcyl = m - msph;
    I[0] = I[1] = mcyl * (3 * r * r + h * h) / 12;
    I[2] = mcyl * r * r / 2;
    double isph = 2 * msph * r * r / 5;
    I[0] += isph + msph * h * (3 * r + 2 * h) / 8;
    I[1] += isph + msph * h * (3 * r + 2 * h) / 8;
    I[2] += isph;
    return;
  }
  double asph = 4 * kPi * r * r, acyl = 2 * kPi * r * h;
  double msph = m * asph / (asph + acyl), mcyl = m - msph;
  I[0] = I[1] = mcyl * (6 * r * r + h * h) / 12;
  I[2] = mcyl * r * r;
  double isph = 2 * msph * r * r / 3, com = r / 2, at = half + com;
  I[0] += isph + msph * (at * at - com * com);
  I[1] += isph + msph * (at * at - com * com);
  I[2] += isph;
}

// Cylinder: solid, or a tube with two end disks.
void CylinderInertia(double m, bool shell, const double* s, double* I) {
  double r = s[0], half = s[1], h = 2 * s[1];
  if (!shell) {
    I[0] = I[1] = m * (3 * r * r + h * h) / 12;
    I[2] = m * r * r / 2;
    return;
  }
  double adisk = kPi * r * r, acyl = 2 * kPi * r * h;
  double mdisk = m * adisk / (2 * adisk + acyl), mcyl = m - 2 * mdisk;
  I[0] = I[1] = mcyl * (6 * r * r + h * h) / 12;
  I[2] = mcyl * r * r;
  double dx = mdisk * r * r / 4 + mdisk * half * half, dz = mdisk * r * r / 2;
  I[0] += 2 * dx;
  I[1] += 2 * dx;
  I[2] += 2 * dz;
}

// Ellipsoid: solid, or the difference of two slightly different solids.
void EllipsoidInertia(double m, bool shell, const double* s, double* I) {
  auto solid = [](double mass, double a, double b, double c, double* out) {
    out[0] = mass * (b * b + c * c) / 5;
    out[1] = mass * (a * a + c * c) / 5;
    out[2] = mass * (a * a + b * b) / 5;
  };
  if (!shell) {
    solid(m, s[0], s[1], s[2], I);
    return;
  }
  double eps = 1e-6;
  double va = 4 * kPi * s[0] * s[1] * s[2] / 3;
  double vb = 4 * kPi * (s[0] + eps) * (s[1] + eps) * (s[2] + eps) / 3;
  double density = m / (vb - va), ia[3], ib[3];
  solid(va * density, s[0], s[1], s[2], ia);
  solid(vb * density, s[0] + eps, s[1] + eps, s[2] + eps, ib);
  for (int i = 0; i < 3; i++) I[i] = ib[i] - ia[i];
}

// Box: solid, or six plates.
void BoxInertia(double m, bool shell, const double* s, double* I) {
  double s00 = s[0] * s[0], s11 = s[1] * s[1], s22 = s[2] * s[2];
  if (!shell) {
    I[0] = m * (s11 + s22) / 3;
    I[1] = m * (s00 + s22) / 3;
    I[2] = m * (s00 + s11) / 3;
    return;
  }
  double lx = 2 * s[0], ly = 2 * s[1], lz = 2 * s[2];
  double a0 = lx * ly, a1 = ly * lz, a2 = lz * lx, at = 2 * (a0 + a1 + a2);
  double m0 = m * a0 / at, m1 = m * a1 / at, m2 = m * a2 / at;
  double ix = m0 * ly * ly / 12 + m1 * (ly * ly + lz * lz) / 12 + m2 * lz * lz / 12;
  double iy = m0 * lx * lx / 12 + m1 * lz * lz / 12 + m2 * (lx * lx + lz * lz) / 12;
  double iz = m0 * (lx * lx + ly * ly) / 12 + m1 * ly * ly / 12 + m2 * lx * lx / 12;
  I[0] = 2 * (m0 * s22 + m2 * s11 + ix);
  I[1] = 2 * (m0 * s22 + m1 * s00 + iy);
  I[2] = 2 * (m1 * s00 + m2 * s11 + iz);
}

void SetInertia(int type, bool shell, double mass, const double* s, double* I) {
  switch (type) {
    case kGeomSphere:
      I[0] = I[1] = I[2] = 2 * mass * s[0] * s[0] / (shell ? 3 : 5);
      return;
    case kGeomCapsule: CapsuleInertia(mass, shell, s, I); return;
    case kGeomCylinder: CylinderInertia(mass, shell, s, I); return;
    case kGeomEllipsoid: EllipsoidInertia(mass, shell, s, I); return;
    case kGeomBox: BoxInertia(mass, shell, s, I); return;
    default: I[0] = I[1] = I[2] = 0; return;
  }
}

// fromto: the geom spans two points; z axis from the second point to the first.
void GeomFromTo(const mjcf::GeomSpec& s, GeomState* g) {
  if (s.type != kGeomCapsule && s.type != kGeomCylinder && s.type != kGeomEllipsoid &&
      s.type != kGeomBox) {
    ThrowAt(s.src, "fromto requires a capsule, cylinder, box or ellipsoid");
  }
  if (s.pos[0] != 0 || s.pos[1] != 0 || s.pos[2] != 0) ThrowAt(s.src, "both pos and fromto defined");
  double vec[3] = {s.fromto[0] - s.fromto[3], s.fromto[1] - s.fromto[4], s.fromto[2] - s.fromto[5]};
  g->size[1] = NormalizeVec(vec, 3) / 2;
  if (g->size[1] < kEps) ThrowAt(s.src, "fromto points are too close");
  if (s.type == kGeomEllipsoid || s.type == kGeomBox) {
    g->size[2] = g->size[1];
    g->size[1] = g->size[0];
  }
  for (int i = 0; i < 3; i++) g->pos[i] = (s.fromto[i] + s.fromto[i + 3]) / 2;
  ZAxisQuat(g->quat, vec);
}

void CheckSize(const mjcf::GeomSpec& s, const double* size) {
  if (s.type == kGeomPlane) {
    if (size[2] <= 0) ThrowAt(s.src, "plane size[2] (grid spacing) must be positive");
    return;
  }
  for (int i = 0; i < SizeCount(s.type); i++) {
    if (size[i] <= 0 || std::isnan(size[i])) {
      ThrowAt(s.src, "size[" + std::to_string(i) + "] must be positive");
    }
  }
}

}  // namespace

// ---------------------------------------------------------------- geoms

void CompileGeom(const mjcf::CompilerSpec& model, bool infer_inertia, GeomState* g) {
  const mjcf::GeomSpec& s = *g->spec;
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(s.compiler, model);
  if (s.condim != 1 && s.condim != 3 && s.condim != 4 && s.condim != 6) {
    ThrowAt(s.src, "condim must be 1, 3, 4 or 6");
  }

  // Size and pose: fromto, or pos and an orientation.
  math::Copy3(g->size, s.size.data());
  math::Copy3(g->pos, s.pos.data());
  math::CopyQuat(g->quat, s.quat.data());
  NormalizeVec(g->quat, 4);
  if (!std::isnan(s.fromto[0])) {
    GeomFromTo(s, g);
  } else if (const char* err = ResolveOrientation(g->quat, c.degree, c.eulerseq, s.alt)) {
    ThrowAt(s.src, std::string("orientation error: ") + err);
  }
  if (g->mesh) MeshGeomFrame(c, g);
  CheckSize(s, g->size);
  if (s.type == kGeomMesh || s.type == kGeomSdf) MeshGeomSize(g);
  if (g->hfield) HFieldGeomSize(g);

  // Mass from mass or density, then the principal inertia in the geom frame. A mesh
  // geom has its mesh's volume and the inertia of the mesh's equivalent box; an hfield
  // geom is the box of its size.
  bool mesh = s.type == kGeomMesh || s.type == kGeomSdf;  // (an sdf geom is its mesh's shape)
  int inertia_type = mesh || s.type == kGeomHfield ? kGeomBox : s.type;
  const double* inertia_size = mesh ? g->mesh->boxsz : g->size;
  if (infer_inertia) {
    double volume = mesh ? g->mesh->volume : Volume(inertia_type, s.shellinertia, g->size);
    double density = s.density;
    if (!std::isnan(s.mass)) {
      if (s.mass == 0) {
        g->mass = density = 0;
      } else if (volume > kEps) {
        g->mass = s.mass;
        density = s.mass / volume;
        SetInertia(inertia_type, s.shellinertia, g->mass, inertia_size, g->inertia);
      }
    } else if (density != 0) {
      g->mass = density * volume;
      SetInertia(inertia_type, s.shellinertia, g->mass, inertia_size, g->inertia);
    }
    if (g->mass < 0 || g->inertia[0] < 0 || g->inertia[1] < 0 || g->inertia[2] < 0 || density < 0) {
      ThrowAt(s.src, "mass, inertia and density must not be negative (mass=" +
                         std::to_string(g->mass) + ", density=" + std::to_string(density) + ")");
    }
  }

  // Enclosing frames.
  if (s.frame) {
    double fpos[3], fquat[4];
    FramePose(*s.frame, model, fpos, fquat);
    AccumulateChild(fpos, fquat, g->pos, g->quat);
  }
}

double GeomRBound(const GeomState& g) {
  const double* s = g.size;
  switch (g.spec->type) {
    case kGeomSphere: return s[0];
    case kGeomCapsule: return s[0] + s[1];
    case kGeomCylinder: return std::sqrt(s[0] * s[0] + s[1] * s[1]);
    case kGeomEllipsoid: return std::max(std::max(s[0], s[1]), s[2]);
    case kGeomBox:
    case kGeomMesh:
    case kGeomSdf: return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    case kGeomHfield: {
      const std::array<double, 4>& h = g.hfield->spec->size;
      return std::sqrt(h[0] * h[0] + h[1] * h[1] + std::max(h[2] * h[2], h[3] * h[3]));
    }
    default: return 0;
  }
}

void GeomAabb(const GeomState& g, double aabb[6]) {
  // Bounds (min x y z, max x y z) in the geom's frame, by type as MuJoCo's.
  const double* s = g.size;
  double aamm[6] = {-s[0], -s[1], -s[2], s[0], s[1], s[2]};
  switch (g.spec->type) {
    case kGeomHfield: {
      const std::array<double, 4>& h = g.hfield->spec->size;
      double bounds[6] = {-h[0], -h[1], -h[3], h[0], h[1], h[2]};
      std::copy(bounds, bounds + 6, aamm);
      break;
    }
    case kGeomSphere: aamm[1] = aamm[2] = -s[0], aamm[4] = aamm[5] = s[0]; break;
    case kGeomCapsule:
      aamm[1] = -s[0], aamm[4] = s[0];
      aamm[2] = -(s[0] + s[1]), aamm[5] = s[0] + s[1];
      break;
    case kGeomCylinder: aamm[1] = -s[0], aamm[4] = s[0], aamm[2] = -s[1], aamm[5] = s[1]; break;
    case kGeomMesh:
    case kGeomSdf:
      if (g.mesh) std::copy(g.mesh->aamm, g.mesh->aamm + 6, aamm);
      break;
    case kGeomPlane: {
      double bounds[6] = {-kMaxVal, -kMaxVal, -kMaxVal, kMaxVal, kMaxVal, 0};
      std::copy(bounds, bounds + 6, aamm);
      break;
    }
    default: break;
  }
  // As centre and half sizes.
  for (int k = 0; k < 3; k++) {
    aabb[k] = (aamm[k + 3] + aamm[k]) / 2;
    aabb[k + 3] = (aamm[k + 3] - aamm[k]) / 2;
  }
}

// ---------------------------------------------------------------- bodies

void InertiaFromGeoms(const mjcf::CompilerSpec& c, const std::vector<GeomState*>& geoms,
                      BodyState* body) {
  // Geoms in the inertia group range with a nonnegligible mass.
  std::vector<const GeomState*> sel;
  for (const GeomState* g : geoms) {
    if (g->spec->group >= c.inertiagrouprange[0] && g->spec->group <= c.inertiagrouprange[1] &&
        g->mass > kEps) {
      sel.push_back(g);
    }
  }
  if (sel.empty()) return;

  // One geom: its frame is the inertial frame.
  if (sel.size() == 1) {
    math::Copy3(body->ipos, sel[0]->pos);
    math::CopyQuat(body->iquat, sel[0]->quat);
    body->mass = sel[0]->mass;
    math::Copy3(body->inertia, sel[0]->inertia);
    return;
  }

  // Several: centre of mass, then inertias about it, then principal axes.
  double com[3] = {0, 0, 0}, total[6] = {0, 0, 0, 0, 0, 0};
  body->mass = 0;
  for (const GeomState* g : sel) {
    body->mass += g->mass;
    math::AddScaled3(com, g->pos, g->mass);
  }
  if (body->mass < kEps) ThrowAt(body->spec->src, "body mass is too small to compute the center of mass");
  for (int k = 0; k < 3; k++) body->ipos[k] = com[k] / body->mass;  // (divided, as MuJoCo)
  for (const GeomState* g : sel) {
    double local[6], d[3];
    GlobalInertia(local, g->inertia, g->quat);
    math::Sub3(d, g->pos, body->ipos);
    double shift[6];
    OffCenter(shift, g->mass, d);
    for (int k = 0; k < 6; k++) total[k] = total[k] + local[k] + shift[k];
  }
  if (const char* err = FullInertia(body->iquat, body->inertia, total)) {
    ThrowAt(body->spec->src, std::string("inertia from geoms: ") + err);
  }
}

void BoundMassInertia(const mjcf::CompilerSpec& c, BodyState* b) {
  // Lower bounds, then physical checks.
  b->mass = std::max(b->mass, c.boundmass);
  for (double& i : b->inertia) i = std::max(i, c.boundinertia);
  const mjcf::Source& src = b->spec->explicit_inertial ? b->spec->inertial_src : b->spec->src;
  if (b->mass < 0 || b->inertia[0] < 0 || b->inertia[1] < 0 || b->inertia[2] < 0) {
    ThrowAt(src, "mass and inertia must not be negative");
  }
  double* I = b->inertia;
  if (I[0] + I[1] < I[2] || I[0] + I[2] < I[1] || I[1] + I[2] < I[0]) {
    if (!c.balanceinertia) {
      ThrowAt(src, "inertia must satisfy A + B >= C; use balanceinertia to fix");
    }
    I[0] = I[1] = I[2] = (I[0] + I[1] + I[2]) / 3.0;
  }
}

}  // namespace simlab::compiler
