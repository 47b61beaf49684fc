// Convex pairs without an analytic formula (MuJoCo's mjc_Convex and mjc_PlaneConvex):
// the geoms become support functions and GJK/EPA (collision_gjk.cc) finds the deepest
// penetration. Ellipsoids, cylinders against anything but spheres and planes, capsules
// against cylinders, and every mesh pair land here.
//
// Margins inflate both shapes by margin/2, so "penetrating" means closer than the
// margin, and the reported distance adds the margin back. With the multiccd flag, a
// single contact between flat-sided shapes is complemented by re-running the query with
// the shapes tilted slightly about the contact point.
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "engine/collision.h"
#include "engine/collision_geom.h"
#include "engine/collision_gjk.h"
#include "math/math.h"

namespace simlab {

namespace {

using ccd::ConvexShape;
using math::Dot3;

// Meshes with fewer vertices than this are searched exhaustively (mjMESH_HILLCLIMB_MIN).
constexpr int kHillclimbMinVertices = 10;

// Contacts of a plane and a mesh: at most this many, none closer than this fraction of
// the mesh's bounding radius to the first.
constexpr int kPlaneMeshMaxContacts = 3;
constexpr double kPlaneMeshSpacing = 0.3;

// The multi-contact search tilts the shapes by this angle (radians) and keeps new
// contacts farther than this fraction of the smaller bounding radius from the others.
constexpr double kTiltAngle = 1e-3;
constexpr double kDistinctFraction = 1e-3;

// ---------------------------------------------------------------- frames

// res = mat * local + pos: a point of the shape's frame in world coordinates.
void ToWorld(double* res, const ConvexShape* s, const double* local) {
  math::MulMatVec3(res, s->mat, local);
  res[0] += s->pos[0];
  res[1] += s->pos[1];
  res[2] += s->pos[2];
}

// ---------------------------------------------------------------- support functions

void SphereSupport(double res[3], ConvexShape* s, const double dir[3]) {
  double radius = s->size[0];
  for (int i = 0; i < 3; i++) res[i] = radius * dir[i] + s->pos[i];
}

void CapsuleSupport(double res[3], ConvexShape* s, const double dir[3]) {
  double local_dir[3], local[3];
  math::MulMatTVec3(local_dir, s->mat, dir);
  math::Scale3(local, local_dir, s->size[0]);
  local[2] += local_dir[2] >= 0 ? s->size[1] : -s->size[1];
  ToWorld(res, s, local);
}

void EllipsoidSupport(double res[3], ConvexShape* s, const double dir[3]) {
  double local_dir[3], local[3];
  math::MulMatTVec3(local_dir, s->mat, dir);
  for (int i = 0; i < 3; i++) local[i] = local_dir[i] * s->size[i];
  double norm2 = Dot3(local, local);

  // direction too small to normalize: the end of the x semi-axis
  if (norm2 < kMinVal * kMinVal) {
    for (int i = 0; i < 3; i++) res[i] = s->mat[3 * i] * s->size[0] + s->pos[i];
    return;
  }
  double inv = 1 / std::sqrt(norm2);
  for (int i = 0; i < 3; i++) local[i] *= inv * s->size[i];
  ToWorld(res, s, local);
}

void CylinderSupport(double res[3], ConvexShape* s, const double dir[3]) {
  double local_dir[3], local[3];
  math::MulMatTVec3(local_dir, s->mat, dir);
  double n2 = local_dir[0] * local_dir[0] + local_dir[1] * local_dir[1];
  double scale = n2 >= kMinVal * kMinVal ? s->size[0] / std::sqrt(n2) : 0;
  local[0] = scale * local_dir[0];
  local[1] = scale * local_dir[1];
  local[2] = local_dir[2] >= 0 ? s->size[1] : -s->size[1];
  ToWorld(res, s, local);
}

void BoxSupport(double res[3], ConvexShape* s, const double dir[3]) {
  double local_dir[3], local[3];
  math::MulMatTVec3(local_dir, s->mat, dir);
  for (int i = 0; i < 3; i++) local[i] = local_dir[i] >= 0 ? s->size[i] : -s->size[i];

  // remember the corner: bit i set for the + side of axis i
  s->vertindex = (local[0] > 0 ? 1 : 0) | (local[1] > 0 ? 2 : 0) | (local[2] > 0 ? 4 : 0);
  ToWorld(res, s, local);
}

// The mesh vertex farthest along local_dir, beating (ibest, best) strictly: the first
// of equals wins.
int FarthestVertex(const ConvexShape& s, const double* local_dir, int ibest, double best) {
  for (int i = 0; i < s.nvert; i++) {
    double proj = Dot3(local_dir, s.vert + 3 * i);
    if (proj > best) {
      best = proj;
      ibest = i;
    }
  }
  return ibest;
}

// Mesh by testing every vertex, starting from the previous answer.
void MeshSupportExhaustive(double res[3], ConvexShape* s, const double dir[3]) {
  double local_dir[3];
  math::MulMatTVec3(local_dir, s->mat, dir);
  double best = -FLT_MAX;
  int ibest = 0;
  if (s->vertindex >= 0) {
    ibest = s->vertindex;
    best = Dot3(local_dir, s->vert + 3 * ibest);
  }
  ibest = FarthestVertex(*s, local_dir, ibest, best);
  s->vertindex = ibest;
  ToWorld(res, s, s->vert + 3 * ibest);
}

// The convex-hull graph of a mesh (MuJoCo's mesh_graph layout): numvert, numface, then
// per hull vertex its first edge and its mesh vertex, then the -1 terminated neighbour
// lists (hull numbering).
struct HullGraph {
  int numvert;
  const int* edgeadr;
  const int* globalid;
  const int* neighbours;
};

HullGraph ReadGraph(const int* graph) {
  int numvert = graph[0];
  return {numvert, graph + 2, graph + 2 + numvert, graph + 2 + 2 * numvert};
}

// Mesh by climbing the hull graph from the previous answer: move to a better neighbour
// until none is better.
void MeshSupportHillclimb(double res[3], ConvexShape* s, const double dir[3]) {
  HullGraph g = ReadGraph(s->graph);
  double local_dir[3];
  math::MulMatTVec3(local_dir, s->mat, dir);
  double best = -FLT_MAX;
  int previous = -1;
  int ibest = s->meshindex >= 0 ? s->meshindex : 0;
  while (ibest != previous) {
    previous = ibest;
    for (int e = g.edgeadr[previous], nb; (nb = g.neighbours[e]) >= 0; e++) {
      double proj = Dot3(local_dir, s->vert + 3 * g.globalid[nb]);
      if (proj > best) {
        best = proj;
        ibest = nb;
      }
    }
  }
  s->meshindex = ibest;
  s->vertindex = g.globalid[ibest];
  ToWorld(res, s, s->vert + 3 * s->vertindex);
}

// The shape of geom g, inflated by margin/2.
ConvexShape MakeShape(const Model& m, const Data& d, int g, double margin) {
  ConvexShape s;
  s.geom = g;
  s.type = m.geom_type[g];
  std::copy_n(&d.geom_xpos[3 * g], 3, s.pos);
  std::copy_n(&d.geom_xmat[9 * g], 9, s.mat);
  std::copy_n(&m.geom_size[3 * g], 3, s.size);
  s.margin = margin;
  s.model = &m;
  switch (s.type) {
    case kGeomSphere: s.support = SphereSupport; break;
    case kGeomCapsule: s.support = CapsuleSupport; break;
    case kGeomEllipsoid: s.support = EllipsoidSupport; break;
    case kGeomCylinder: s.support = CylinderSupport; break;
    case kGeomBox: s.support = BoxSupport; break;
    case kGeomMesh:
    case kGeomSdf: {  // (an sdf geom's convex shape is its mesh's: the plane collider's)
      int mesh = m.geom_dataid[g];
      s.vert = &m.mesh_vert[3 * m.mesh_vertadr[mesh]];
      s.nvert = m.mesh_vertnum[mesh];
      int graphadr = m.mesh_graphadr[mesh];
      s.graph = graphadr >= 0 ? &m.mesh_graph[graphadr] : nullptr;
      bool climb = s.graph && s.nvert >= kHillclimbMinVertices;
      s.support = climb ? MeshSupportHillclimb : MeshSupportExhaustive;
      break;
    }
    default: s.support = nullptr; break;
  }
  return s;
}

// ---------------------------------------------------------------- convex pairs

// How many contacts one query may return: one, except for pairs of flat-sided shapes
// (boxes, meshes) without margin: 8 for two boxes, 4 under multiccd (the corners of the
// polygon where their sides meet, collision_multiccd.cc).
int MaxContacts(const Model& m, const ConvexShape& s1, const ConvexShape& s2) {
  if (s1.margin > 0 || s2.margin > 0) return 1;
  if (s1.type == kGeomBox && s2.type == kGeomBox) return 8;
  auto flat = [](int type) { return type == kGeomBox || type == kGeomMesh; };
  bool multi = (m.opt.enableflags & kEnableMulticcd) != 0;
  if (flat(s1.type) && flat(s2.type)) return multi ? 4 : 1;
  return 1;
}


// Two unit tangents of the contact normal (as the driver's frame completion).
void TangentAxes(const double* normal, double* t1, double* t2) {
  double frame[9] = {normal[0], normal[1], normal[2], 0, 0, 0, 0, 0, 0};
  CompleteContactFrame(frame);
  math::Copy3(t1, frame + 3);
  math::Copy3(t2, frame + 6);
}

// Turns a shape's pose by rot about the world point origin.
void RotateAbout(ConvexShape* s, const double* origin, const double* rot) {
  double mat[9], rel[3], moved[3];
  math::MulMat3(mat, rot, s->mat);
  std::copy_n(mat, 9, s->mat);
  math::Sub3(rel, origin, s->pos);
  math::MulMatVec3(moved, rot, rel);
  for (int k = 0; k < 3; k++) moved[k] -= rel[k];
  for (int k = 0; k < 3; k++) s->pos[k] -= moved[k];
}

// Is the last of n contacts farther than tolerance from all the others?
bool IsDistinct(const Contact* con, int n, double tolerance) {
  for (int i = 0; i < n - 1; i++) {
    double dif[3];
    math::Sub3(dif, con[i].pos, con[n - 1].pos);
    if (math::Norm3(dif) <= tolerance) return false;
  }
  return true;
}

// multiccd: tilts geom 1 by +-kTiltAngle about the two tangents through the first
// contact (geom 2 the opposite way) and keeps each new contact that is distinct, with
// the first contact's depth.
int TiltedContacts(const Model& m, ConvexShape* s1, ConvexShape* s2, Contact* con,
                   double margin) {
  double t[2][3];
  TangentAxes(con[0].frame, t[0], t[1]);
  double tolerance =
      kDistinctFraction * std::min(m.geom_rbound[s1->geom], m.geom_rbound[s2->geom]);
  ConvexShape rest1 = *s1, rest2 = *s2;
  int ncon = 1;
  for (const double* axis : t) {
    for (double angle : {-kTiltAngle, kTiltAngle}) {
      double quat[4], rot[9], inverse[9];
      math::AxisAngleToQuat(quat, axis, angle);
      math::QuatToMat(rot, quat);
      for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) inverse[3 * i + j] = rot[3 * j + i];
      }
      RotateAbout(s1, con[0].pos, rot);
      RotateAbout(s2, con[0].pos, inverse);
      if (QueryContacts(m, s1, s2, con + ncon, 1, margin) &&
          IsDistinct(con, ncon + 1, tolerance)) {
        con[ncon].dist = con[0].dist;
        ncon++;
      }

      // back to the true poses (the vertex warm starts carry on)
      std::copy_n(rest1.pos, 3, s1->pos);
      std::copy_n(rest1.mat, 9, s1->mat);
      std::copy_n(rest2.pos, 3, s2->pos);
      std::copy_n(rest2.mat, 9, s2->mat);
    }
  }
  return ncon;
}

bool Smooth(int type) { return type == kGeomSphere || type == kGeomEllipsoid; }

// ---------------------------------------------------------------- plane and convex

// The support point used against planes (MuJoCo's libccd-style support): an ellipsoid
// through a normalized scaled direction, a mesh by the hull graph whenever it has one.
void PlaneSideSupport(double res[3], ConvexShape* s, const double dir[3]) {
  double local_dir[3], local[3];
  math::MulMatTVec3(local_dir, s->mat, dir);
  if (s->type == kGeomEllipsoid) {
    for (int i = 0; i < 3; i++) local[i] = local_dir[i] * s->size[i];
    math::Normalize3(local);
    for (int i = 0; i < 3; i++) local[i] *= s->size[i];
    ToWorld(res, s, local);
    return;
  }

  // mesh without graph: every vertex
  int ibest;
  if (!s->graph) {
    ibest = FarthestVertex(*s, local_dir, -1, -1e10);
    s->meshindex = ibest;
  } else {
    // hill-climb from the first hull vertex
    HullGraph g = ReadGraph(s->graph);
    ibest = s->meshindex < 0 ? 0 : s->meshindex;
    double best = Dot3(local_dir, s->vert + 3 * g.globalid[ibest]);
    for (bool changed = true; changed;) {
      changed = false;
      for (int e = g.edgeadr[ibest], nb; (nb = g.neighbours[e]) >= 0; e++) {
        double proj = Dot3(local_dir, s->vert + 3 * g.globalid[nb]);
        if (proj > best) {
          best = proj;
          ibest = nb;
          changed = true;
        }
      }
    }
    s->meshindex = ibest;
    ibest = g.globalid[ibest];
  }
  if (ibest < 0) {
    math::Copy3(res, s->pos);
    return;
  }
  ToWorld(res, s, s->vert + 3 * ibest);
}

// One extra plane-mesh contact at mesh vertex `local` unless it is too close to the
// first contact. Returns 1 if added.
int AddPlaneMeshContact(Contact* con, const ConvexShape& s, const double* local,
                        const double* plane_pos, const double* normal, const double* first,
                        double rbound) {
  double p[3], dif[3];
  ToWorld(p, &s, local);
  math::Sub3(dif, p, first);
  if (math::Norm3(dif) < kPlaneMeshSpacing * rbound) return 0;
  math::Sub3(dif, p, plane_pos);
  PlaneContactAt(*con, normal, p, Dot3(normal, dif));
  return 1;
}

// Further mesh vertices within the margin of the plane: the neighbours of the deepest
// vertex on the hull graph, or any vertex when there is no graph.
int MorePlaneMeshContacts(const Model& m, const ConvexShape& s, Contact* con,
                          const double* plane_pos, const double* normal, double margin) {
  double local_dir[3], dir[3] = {-normal[0], -normal[1], -normal[2]}, dif[3];
  math::MulMatTVec3(local_dir, s.mat, dir);
  math::Sub3(dif, s.pos, plane_pos);
  double threshold = Dot3(normal, dif) - margin;
  double rbound = m.geom_rbound[s.geom];
  int count = 1;
  auto consider = [&](int v) {
    if (Dot3(local_dir, s.vert + 3 * v) > threshold) {
      count += AddPlaneMeshContact(con + count, s, s.vert + 3 * v, plane_pos, normal,
                                   con[0].pos, rbound);
    }
  };
  if (!s.graph) {
    for (int i = 0; i < s.nvert && count < kPlaneMeshMaxContacts; i++) {
      if (i != s.meshindex) consider(i);
    }
  } else if (s.meshindex >= 0) {
    HullGraph g = ReadGraph(s.graph);
    for (int e = g.edgeadr[s.meshindex], nb;
         (nb = g.neighbours[e]) >= 0 && count < kPlaneMeshMaxContacts; e++) {
      consider(g.globalid[nb]);
    }
  }
  return count;
}

}  // namespace

int QueryContacts(const Model& m, ccd::ConvexShape* s1, ccd::ConvexShape* s2, Contact* con,
                  int max_contacts, double margin) {
  ccd::CcdConfig config = ccd::ModelConfig(m, max_contacts, 0);
  ccd::CcdStatus status;
  double dist = ccd::Collide(config, &status, s1, s2);
  if (!(dist < 0)) return 0;
  for (int i = 0; i < status.nx; i++) {
    Contact& c = con[i];
    const double* x1 = status.x1 + 3 * i;
    const double* x2 = status.x2 + 3 * i;
    c.dist = margin + dist;
    math::Sub3(c.frame, x1, x2);
    math::Normalize3(c.frame);
    for (int k = 0; k < 3; k++) c.pos[k] = 0.5 * (x1[k] + x2[k]);
    math::Zero3(c.frame + 3);
  }
  return status.nx;
}

// ---------------------------------------------------------------- entry points

void ccd::CentreSupport(double res[3], ConvexShape* s, const double dir[3]) {
  math::Copy3(res, s->pos);
}

void ccd::SegmentSupport(double res[3], ConvexShape* s, const double dir[3]) {
  double along = s->mat[2] * dir[0] + s->mat[5] * dir[1] + s->mat[8] * dir[2];
  double half = along >= 0 ? s->size[1] : -s->size[1];
  res[0] = s->mat[2] * half + s->pos[0];
  res[1] = s->mat[5] * half + s->pos[1];
  res[2] = s->mat[8] * half + s->pos[2];
}

ccd::CcdConfig ccd::ModelConfig(const Model& m, int max_contacts, double dist_cutoff) {
  CcdConfig config;
  config.max_iterations = m.opt.ccd_iterations;
  config.tolerance = m.opt.ccd_tolerance;
  config.max_contacts = max_contacts;
  config.dist_cutoff = dist_cutoff;
  config.newer = m.release == Release::k3_12;
  return config;
}

ConvexShape ccd::GeomShape(const Model& m, const Data& d, int g, double margin) {
  return MakeShape(m, d, g, margin);
}

int CollideConvex(const Model& m, const Data& d, Contact* con, int g1, int g2,
                  double margin) {
  ConvexShape s1 = MakeShape(m, d, g1, margin), s2 = MakeShape(m, d, g2, margin);
  int max_contacts = MaxContacts(m, s1, s2);
  int ncon = QueryContacts(m, &s1, &s2, con, max_contacts, margin);
  if (max_contacts > 1) return ncon;

  // multiccd: more contacts for pairs without smooth shapes
  bool multi = (m.opt.enableflags & kEnableMulticcd) != 0;
  if (ncon == 1 && multi && !Smooth(s1.type) && !Smooth(s2.type)) {
    ncon = TiltedContacts(m, &s1, &s2, con, margin);
  }
  return ncon;
}

int CollidePlaneConvex(const Model& m, const Data& d, Contact* con, int g1, int g2,
                       double margin) {
  GeomPose plane = PoseOf(m, d, g1);
  double normal[3], dir[3];
  ZAxisOf(plane, normal);
  math::Scale3(dir, normal, -1);

  // the deepest point of the convex geom below the plane
  ConvexShape s = MakeShape(m, d, g2, 0);
  double deepest[3], dif[3];
  PlaneSideSupport(deepest, &s, dir);
  math::Sub3(dif, deepest, plane.pos);
  double dist = Dot3(normal, dif);
  if (dist > margin) return 0;
  PlaneContactAt(con[0], normal, deepest, dist);
  if (m.geom_dataid[g2] == -1) return 1;
  return MorePlaneMeshContacts(m, s, con, plane.pos, normal, margin);
}

}  // namespace simlab
