// Collisions of flexes (MuJoCo's flex parts of mj_collision): with bodies' geoms, with
// other flexes and with themselves, through the flexes' bounding volume trees.
//
// A broad-phase pair of a body (or flex) and a flex is collided by walking both trees
// (the body's geoms in its inertial frame, the flex's elements in the world, boxes from
// Data::bvh_aabb_dyn), planes of a static body meeting every flex vertex directly; or,
// without trees, every geom with every element. The contacts from the trees are then
// sorted by what they touch, as MuJoCo does.
//
// The reference is MuJoCo as the npm oracle runs it (3.5.1, before its commit 8ba68cee3):
// a pair's flex contacts are not thinned. A model only MuJoCo 3.12 defines
// (Model::release) follows 3.12: each flex collision pair (a body or flex with a flex,
// per geom without the trees; a flex's internal and its element contacts) keeps at most
// kMaxContactPair of its contacts, spread apart (ThinFlexContacts).
//
// A flex collides with itself when its contype meets its conaffinity: internally
// (element-vertex pairs the compiler found, and each tetrahedron's vertices against its
// opposite faces) and between its active elements (by its tree, sweep and prune, or all
// pairs, per selfcollide). Self-collision ignores margins.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/collision_driver.h"
#include "engine/collision_flex.h"
#include "engine/collision_geom.h"
#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/sleep.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

namespace {

using math::Dot3;

bool MidphaseDisabled(const Model& m) { return (m.opt.disableflags & kDisableMidphase) != 0; }

// ---------------------------------------------------------------- flex geometry

const double* VertexPos(const Model& m, const Data& d, int f, int v) {
  return &d.flexvert_xpos[3 * static_cast<size_t>(m.flex_vertadr[f] + v)];
}

// The vertices (flex numbering) of element e of flex f: dim + 1 of them.
const int* ElementVertices(const Model& m, int f, int e) {
  return &m.flex_elem[m.flex_elemdataadr[f] + e * (m.flex_dim[f] + 1)];
}

// The world box (centre, half sizes) of element e of flex f.
const double* ElementBox(const Model& m, const Data& d, int f, int e) {
  return &d.flexelem_aabb[6 * static_cast<size_t>(m.flex_elemadr[f] + e)];
}

// Does element e take part in collisions? (tetrahedra only in the active layers)
bool ElementActive(const Model& m, int f, int e) {
  return m.flex_dim[f] < 3 || m.flex_elemlayer[m.flex_elemadr[f] + e] < m.flex_activelayers[f];
}

// The body of vertex v of flex f.
int VertexBody(const Model& m, int f, int v) { return m.flex_vertbodyid[m.flex_vertadr[f] + v]; }

// A line element (vertices vid) as a capsule: centre, axis frame and size (radius, half
// length) (mj_makeCapsule).
void EdgeCapsule(const Model& m, const Data& d, int f, const int* vid, double pos[3],
                 double mat[9], double size[3]) {
  const double* v1 = VertexPos(m, d, f, vid[0]);
  const double* v2 = VertexPos(m, d, f, vid[1]);
  double dif[3];
  math::Sub3(dif, v1, v2);
  size[0] = m.flex_radius[f];
  size[1] = 0.5 * math::Normalize3(dif);
  size[2] = 0;
  math::Add3(pos, v1, v2);
  math::Scale3(pos, pos, 0.5);

  // The rotation taking z to the edge direction (mju_quatZ2Vec, which normalizes again).
  double quat[4];
  math::QuatZToVec(quat, dif);
  math::QuatToMat(mat, quat);
}

// Is the sphere (centre, radius `bound`) beyond the box (centre, half sizes; world axes)
// along some axis? (MuJoCo's filterSphereBox, and the same test of a vertex's sphere
// against an element's box)
bool SphereOutsideBox(const double* centre, double bound, const double* box) {
  for (int k = 0; k < 3; k++) {
    if (centre[k] + bound < box[k] - box[k + 3] || centre[k] - bound > box[k] + box[k + 3]) {
      return true;
    }
  }
  return false;
}

// ---------------------------------------------------------------- recording contacts

// Who touches whom in a contact with a flex.
struct ContactIds {
  int geom[2] = {-1, -1};
  int flex[2] = {-1, -1};
  int elem[2] = {-1, -1};
  int vert[2] = {-1, -1};
};

// Completes the contacts con[0, num) the narrow phase wrote at the end of d.contact and
// counts them in (mj_setContact for each). No flex collider chooses a tangent: each
// frame's second row is cleared here, for SetContact to complete the frame from none.
void Record(const Model& m, Data& d, Contact* con, int num, const ContactParams& p,
            double includemargin, const ContactIds& ids) {
  for (int i = 0; i < num; i++) {
    Contact& c = con[i];
    math::Zero3(c.frame + 3);
    SetContact(m, p, includemargin, ids.geom[0], ids.geom[1], &c);
    for (int k = 0; k < 2; k++) {
      c.flex[k] = ids.flex[k];
      c.elem[k] = ids.elem[k];
      c.vert[k] = ids.vert[k];
    }
  }
  d.ncon += num;
}

// ---------------------------------------------------------------- narrow phase calls

// Every vertex of flex f against plane geom g (mj_collidePlaneFlex).
void CollidePlaneFlex(const Model& m, Data& d, int g, int f) {
  double radius = m.flex_radius[f];
  const double* pos = &d.geom_xpos[3 * g];
  const double* mat = &d.geom_xmat[9 * g];
  double normal[3] = {mat[2], mat[5], mat[8]};
  double margin = AssignMargin(m, m.geom_margin[g] + m.flex_margin[f]);
  ContactParams p = MixedParams(m, g, -1, -1, f);
  ContactIds ids;
  ids.geom[0] = g;
  ids.flex[1] = f;
  for (int i = 0; i < m.flex_vertnum[f]; i++) {
    const double* v = VertexPos(m, d, f, i);
    double dif[3];
    math::Sub3(dif, v, pos);
    double dist = Dot3(dif, normal);
    if (dist > margin + radius) continue;
    Contact* c = ContactRoom(d, 1);
    c->dist = dist - radius;
    double along = -c->dist * 0.5 - radius;
    for (int k = 0; k < 3; k++) c->pos[k] = v[k] + normal[k] * along;
    math::Copy3(c->frame, normal);
    ids.vert[1] = i;
    Record(m, d, c, 1, p, margin - p.gap, ids);
  }
}

// Geom g against element e of flex f (mj_collideGeomElem).
void CollideGeomElem(const Model& m, Data& d, int g, int f, int e) {
  double margin = AssignMargin(m, m.geom_margin[g] + m.flex_margin[f]);
  int dim = m.flex_dim[f], type = m.geom_type[g];
  // (the midphase's sphere-box test, when there is no midphase)
  if (MidphaseDisabled(m) &&
      SphereOutsideBox(&d.geom_xpos[3 * g], m.geom_rbound[g] + margin, ElementBox(m, d, f, e))) {
    return;
  }
  // Not against an element with a vertex on the geom's body.
  const int* vert = ElementVertices(m, f, e);
  int body = m.geom_bodyid[g];
  for (int i = 0; i <= dim; i++) {
    if (body == VertexBody(m, f, vert[i])) return;
  }

  Contact* con = ContactRoom(d, kMaxContactPair);
  GeomPose geom = PoseOf(m, d, g);
  const double* t[3] = {nullptr, nullptr, nullptr};
  for (int i = 0; i < 3 && i <= dim; i++) t[i] = VertexPos(m, d, f, vert[i]);
  double radius = m.flex_radius[f];
  int num = 0;
  if (dim == 1 && (type == kGeomSphere || type == kGeomCapsule || type == kGeomBox)) {
    double pos[3], mat[9], size[3];
    EdgeCapsule(m, d, f, vert, pos, mat, size);
    GeomPose capsule{pos, mat, size};
    if (type == kGeomSphere) {
      num = SphereCapsulePoses(con, margin, geom, capsule);
    } else if (type == kGeomCapsule) {
      num = CapsuleCapsulePoses(con, margin, geom, capsule);
    } else {
      // (the box is second there: its normals turned around)
      num = CapsuleBoxPoses(con, margin, capsule, geom);
      for (int i = 0; i < num; i++) math::Scale3(con[i].frame, con[i].frame, -1);
    }
  } else if (type == kGeomHfield) {
    num = HFieldElem(m, d, con, g, f, e, margin);
  } else if (type == kGeomSphere && dim == 2) {
    num = SphereTriangle(con, margin, geom.pos, geom.size[0], t[0], t[1], t[2], radius);
  } else if (type == kGeomBox && dim == 2) {
    num = BoxTriangle(con, margin, geom.pos, geom.mat, geom.size, t[0], t[1], t[2], radius);
  } else if (type == kGeomCapsule && dim == 2) {
    num = CapsuleTriangle(con, margin, geom.pos, geom.mat, geom.size, t[0], t[1], t[2], radius);
  } else if (type != kGeomPlane) {
    num = ConvexElem(m, d, con, g, -1, -1, -1, f, e, margin);
  }
  if (num <= 0) return;
  ContactParams p = MixedParams(m, g, -1, -1, f);
  ContactIds ids;
  ids.geom[0] = g;
  ids.flex[1] = f;
  ids.elem[1] = e;
  Record(m, d, con, num, p, margin - p.gap, ids);
}

// Element e1 of flex f1 against element e2 of flex f2 (mj_collideElems); no margin or
// gap within one flex.
void CollideElems(const Model& m, Data& d, int f1, int e1, int f2, int e2) {
  double margin = f1 == f2 ? 0 : AssignMargin(m, m.flex_margin[f1] + m.flex_margin[f2]);
  if (AxisBoxesApart(ElementBox(m, d, f1, e1), ElementBox(m, d, f2, e2), margin)) return;
  // Not when the elements share a body.
  int dim1 = m.flex_dim[f1], dim2 = m.flex_dim[f2];
  const int* vert1 = ElementVertices(m, f1, e1);
  const int* vert2 = ElementVertices(m, f2, e2);
  int bodies2[4];
  for (int i2 = 0; i2 <= dim2; i2++) bodies2[i2] = VertexBody(m, f2, vert2[i2]);
  for (int i1 = 0; i1 <= dim1; i1++) {
    int b1 = VertexBody(m, f1, vert1[i1]);
    if (b1 < 0) continue;
    for (int i2 = 0; i2 <= dim2; i2++) {
      if (b1 == bodies2[i2]) return;
    }
  }
  Contact* con = ContactRoom(d, kMaxContactPair);
  int num;
  if (dim1 == 1 && dim2 == 1) {
    double pos1[3], mat1[9], size1[3], pos2[3], mat2[9], size2[3];
    EdgeCapsule(m, d, f1, vert1, pos1, mat1, size1);
    EdgeCapsule(m, d, f2, vert2, pos2, mat2, size2);
    num = CapsuleCapsulePoses(con, margin, GeomPose{pos1, mat1, size1}, GeomPose{pos2, mat2, size2});
  } else {
    num = ConvexElem(m, d, con, -1, f1, e1, -1, f2, e2, margin);
  }
  if (num <= 0) return;
  ContactParams p = MixedParams(m, -1, -1, f1, f2);
  if (f1 == f2) p.gap = 0;
  ContactIds ids;
  ids.flex[0] = f1;
  ids.flex[1] = f2;
  ids.elem[0] = e1;
  ids.elem[1] = e2;
  Record(m, d, con, num, p, margin - p.gap, ids);
}

// Vertex v of flex f against its element e (mj_collideElemVert), without margin.
void CollideElemVert(const Model& m, Data& d, int f, int e, int v) {
  double margin = AssignMargin(m, m.flex_margin[f]);
  double radius = m.flex_radius[f];
  const double* vert = VertexPos(m, d, f, v);
  if (SphereOutsideBox(vert, margin + radius, ElementBox(m, d, f, e))) return;
  int dim = m.flex_dim[f];
  const int* evert = ElementVertices(m, f, e);
  Contact* con = ContactRoom(d, kMaxContactPair);
  int num;
  if (dim == 1) {
    static constexpr double kIdentity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    double pos[3], mat[9], size[3], sphere_size[3] = {radius, 0, 0};
    EdgeCapsule(m, d, f, evert, pos, mat, size);
    num = SphereCapsulePoses(con, 0, GeomPose{vert, kIdentity, sphere_size},
                             GeomPose{pos, mat, size});
  } else if (dim == 2) {
    num = SphereTriangle(con, 0, vert, radius, VertexPos(m, d, f, evert[0]),
                         VertexPos(m, d, f, evert[1]), VertexPos(m, d, f, evert[2]), radius);
  } else {
    num = ConvexElem(m, d, con, -1, f, -1, v, f, e, 0);
  }
  if (num <= 0) return;
  ContactParams p = MixedParams(m, -1, -1, f, f);
  ContactIds ids;
  ids.flex[0] = ids.flex[1] = f;
  ids.elem[1] = e;
  ids.vert[0] = v;
  Record(m, d, con, num, p, 0, ids);
}

// Vertex v against the plane of face (t0, t1, t2) of a tetrahedron, from inside: a
// contact when it is less than two radii beyond (planeVertex). Writes pos, the normal
// and dist.
bool FaceVertex(Contact* c, const double* xpos, double radius, int t0, int t1, int t2, int v) {
  double e1[3], e2[3], ev[3], normal[3];
  math::Sub3(e1, xpos + 3 * t1, xpos + 3 * t0);
  math::Sub3(e2, xpos + 3 * t2, xpos + 3 * t0);
  math::Sub3(ev, xpos + 3 * v, xpos + 3 * t0);
  math::Cross3(normal, e1, e2);
  math::Normalize3(normal);
  double dist = Dot3(ev, normal);
  if (dist <= -2 * radius) return false;
  c->dist = -dist - 2 * radius;
  math::Scale3(c->frame, normal, -1);
  for (int k = 0; k < 3; k++) c->pos[k] = xpos[3 * v + k] + normal[k] * (-0.5 * dist);
  return true;
}

// A flex's internal collisions (mj_collideFlexInternal): its element-vertex pairs, then
// (tetrahedra) each vertex against the opposite face, frictionless and without margin.
void CollideFlexInternal(const Model& m, Data& d, int f) {
  for (int i = 0; i < m.flex_evpairnum[f]; i++) {
    const int* ev = &m.flex_evpair[2 * (m.flex_evpairadr[f] + i)];
    CollideElemVert(m, d, f, ev[0], ev[1]);
  }
  if (m.flex_dim[f] != 3) return;
  ContactParams p = MixedParams(m, -1, -1, f, f);
  p.condim = 1;
  const double* xpos = VertexPos(m, d, f, 0);
  double radius = m.flex_radius[f];
  static constexpr int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  ContactIds ids;
  ids.flex[0] = ids.flex[1] = f;
  for (int e = 0; e < m.flex_elemnum[f]; e++) {
    const int* t = ElementVertices(m, f, e);
    ids.elem[0] = e;
    for (const int* face : kFaces) {
      Contact* c = ContactRoom(d, 1);
      if (!FaceVertex(c, xpos, radius, t[face[0]], t[face[1]], t[face[2]], t[face[3]])) continue;
      ids.vert[1] = t[face[3]];
      Record(m, d, c, 1, p, 0, ids);
    }
  }
}

// ---------------------------------------------------------------- trees

// One side of a tree walk: a body's tree (static boxes in its inertial frame) or a
// flex's (boxes in the world, this step's).
struct TreeSide {
  int bodyflex, body = -1, flex = -1, adr = 0, num = 0;
  const double* boxes = nullptr;  // node boxes, 6 per node from the tree's first

  const int* Child(const Model& m, int node) const { return &m.bvh_child[2 * (adr + node)]; }
  bool Leaf(const Model& m, int node) const {
    const int* child = Child(m, node);
    return child[0] < 0 && child[1] < 0;
  }
  const double* Box(int node) const { return boxes + 6 * node; }
};

TreeSide SideOf(const Model& m, const Data& d, int bodyflex) {
  TreeSide s;
  s.bodyflex = bodyflex;
  if (bodyflex < m.nbody) {
    s.body = bodyflex;
    s.adr = m.body_bvhadr[bodyflex];
    s.num = m.body_bvhnum[bodyflex];
    s.boxes = &m.bvh_aabb[6 * static_cast<size_t>(s.adr)];
  } else {
    s.flex = bodyflex - m.nbody;
    s.adr = m.flex_bvhadr[s.flex];
    s.num = m.flex_bvhnum[s.flex];
    s.boxes = &d.bvh_aabb_dyn[6 * static_cast<size_t>(s.adr - m.nbvhstatic)];
  }
  return s;
}

// MuJoCo's "surface" of a node box, taken from its centre and half sizes as if they were
// its corners; it only decides which tree to open, and so the order of the contacts.
double OpeningArea(const double* box) {
  double x = box[3] - box[0], y = box[4] - box[1], z = box[5] - box[2];
  return x * y + y * z + z * x;
}

// Two leaves of a body's and a flex's trees: the geom against the element, after the
// bitmask, sphere-box and oriented box tests (planes are met vertex by vertex instead).
void BodyFlexLeaves(const Model& m, Data& d, const TreeSide& s1, int node1, const TreeSide& s2,
                    int node2) {
  int g = m.bvh_nodeid[s1.adr + node1], e = m.bvh_nodeid[s2.adr + node2], f = s2.flex;
  double margin = AssignMargin(m, m.geom_margin[g] + m.flex_margin[f]);
  if (BitmaskRejects(m.geom_contype[g], m.geom_conaffinity[g], m.flex_contype[f],
                     m.flex_conaffinity[f])) {
    return;
  }
  const double* s = &d.geom_xpos[3 * g];
  const double* box = s2.Box(node2);
  if (SphereOutsideBox(s, m.geom_rbound[g] + margin, box)) return;
  if (BoxesApartOriented(&m.geom_aabb[6 * g], s, &d.geom_xmat[9 * g], box, nullptr, nullptr,
                         margin)) {
    return;
  }
  if (m.geom_type[g] != kGeomPlane) CollideGeomElem(m, d, g, f, e);
}

// Do two inner nodes (or an inner node and a leaf) overlap enough to open? (frames: a
// body side's inertial frame and the flex's, the world's)
bool NodesMeet(const Model& m, TreeFrames& frames, const TreeSide& s1, int node1,
               const TreeSide& s2, int node2) {
  if (s1.body >= 0) {
    double margin = AssignMargin(m, m.body_margin[s1.body] + m.flex_margin[s2.flex]);
    return !frames.Apart(s1.Box(node1), s2.Box(node2), margin);
  }
  double margin = AssignMargin(m, m.flex_margin[s1.flex] + m.flex_margin[s2.flex]);
  return !AxisBoxesApart(s1.Box(node1), s2.Box(node2), margin);
}

// Walks the trees of bodyflex b1 (a body or flex) and flex b2 together (MuJoCo's
// mj_collideTree with a flex): pairs of nodes whose boxes are apart are dropped, the
// larger (by OpeningArea) of two inner nodes or the inner one of a leaf and an inner
// node is opened; leaf pairs go to the narrow phase. Within one flex (b1 == b2) each
// node pair is visited once. The callers have filtered the pair by contype and
// conaffinity.
void CollideTreesWithFlex(const Model& m, Data& d, int b1, int b2) {
  // (the pair's contype and conaffinity already met: in the broad phase, or, for a flex
  // with itself, in CollideFlexSelf)
  TreeSide s1 = SideOf(m, d, b1), s2 = SideOf(m, d, b2);

  // A static body's planes meet the flex's vertices directly.
  if (s1.body >= 0 && m.body_weldid[s1.body] == 0) {
    for (int g = m.body_geomadr[s1.body]; g < m.body_geomadr[s1.body] + m.body_geomnum[s1.body]; g++) {
      if (m.geom_type[g] == kGeomPlane) CollidePlaneFlex(m, d, g, s2.flex);
    }
  }

  SolverFrame ints(d.solver_scratch);
  size_t capacity = 2 * static_cast<size_t>(s1.num + s2.num);
  int* stack = ints.IntsToWrite(capacity);
  size_t nstack = 1;
  stack[0] = stack[1] = 0;
  auto push = [&](int n1, int n2) {
    if (2 * nstack + 2 > capacity) return;  // (cannot happen: each pop pushes at most two)
    stack[2 * nstack] = n1;
    stack[2 * nstack + 1] = n2;
    nstack++;
  };
  TreeFrames frames(s1.body >= 0 ? &d.xipos[3 * s1.body] : nullptr,
                    s1.body >= 0 ? &d.ximat[9 * s1.body] : nullptr, nullptr, nullptr);
  while (nstack) {
    nstack--;
    int node1 = stack[2 * nstack], node2 = stack[2 * nstack + 1];
    bool leaf1 = s1.Leaf(m, node1), leaf2 = s2.Leaf(m, node2);
    if (b1 == b2 && node1 > node2) continue;
    if (leaf1 && leaf2) {
      if (s1.body >= 0) {
        BodyFlexLeaves(m, d, s1, node1, s2, node2);
      } else {
        CollideElems(m, d, s1.flex, m.bvh_nodeid[s1.adr + node1], s2.flex,
                     m.bvh_nodeid[s2.adr + node2]);
      }
      continue;
    }
    if (!NodesMeet(m, frames, s1, node1, s2, node2)) continue;
    bool open1 = !leaf1 && (leaf2 || OpeningArea(s1.Box(node1)) > OpeningArea(s2.Box(node2)));
    const int* child = open1 ? s1.Child(m, node1) : s2.Child(m, node2);
    for (int i = 0; i < 2; i++) {
      if (child[i] == -1) continue;
      if (open1) {
        push(child[i], node2);
      } else {
        push(node1, child[i]);
      }
    }
  }
}

// ---------------------------------------------------------------- sweep and prune

// The interval ends of flex f's n active elements (active[i]) along `axis`, sorted
// (SortEnds, from last step's order kept per flex).
std::vector<uint64_t>& SortedElementEnds(const Model& m, Data& d, int f, const int* active,
                                         int n, int axis) {
  std::vector<std::vector<uint64_t>>& per_flex = d.broadphase.flex_ends;
  if (per_flex.size() < static_cast<size_t>(m.nflex)) per_flex.resize(m.nflex);
  std::vector<uint64_t>& ends = per_flex[f];
  SortEnds(ends, 2 * static_cast<size_t>(n), [&](uint32_t tie) {
    const double* box = ElementBox(m, d, f, active[tie >> 1]);
    double value = (tie & 1) ? box[axis] + box[axis + 3] : box[axis] - box[axis + 3];
    return SweepKey(value, static_cast<int>(tie));
  });
  return ends;
}

// The active elements of flex f against each other by sweep and prune along the longest
// side of the flex's box (mj_collideFlexSAP), in the order the sweep finds them.
void CollideFlexSweep(const Model& m, Data& d, int f) {
  SolverFrame scratch(d.solver_scratch);
  int* active = scratch.IntsToWrite(std::max(m.flex_elemnum[f], 1));
  int n = 0;
  for (int e = 0; e < m.flex_elemnum[f]; e++) {
    if (ElementActive(m, f, e)) active[n++] = e;
  }
  if (n < 2) return;
  const double* root = &d.bvh_aabb_dyn[6 * static_cast<size_t>(m.flex_bvhadr[f] - m.nbvhstatic)];
  int axis = (root[3] > root[4] && root[3] > root[5]) ? 0 : (root[4] > root[5] ? 1 : 2);
  int other[2] = {axis == 0 ? 1 : 0, axis == 2 ? 1 : 2};
  long max_pairs = std::min(static_cast<long>(n) * (n - 1) / 2, 1000000L);

  // Each element's bounds on the two other axes (lo, hi, lo, hi), for the test against
  // every open element.
  double* bounds = scratch.RealsToWrite(4 * static_cast<size_t>(n));
  for (int i = 0; i < n; i++) {
    const double* box = ElementBox(m, d, f, active[i]);
    for (int j = 0; j < 2; j++) {
      bounds[4 * i + 2 * j] = box[other[j]] - box[other[j] + 3];
      bounds[4 * i + 2 * j + 1] = box[other[j]] + box[other[j] + 3];
    }
  }
  std::vector<uint64_t>& ends = SortedElementEnds(m, d, f, active, n, axis);

  // The sweep; an open element's bounds are kept beside its id.
  std::vector<int>& open = d.broadphase.open;
  std::vector<double>& open_bounds = d.broadphase.open_bounds;
  open.clear();
  open_bounds.clear();
  long npairs = 0;
  for (uint64_t end : ends) {
    int id = static_cast<int>((end & 0xFFFFFFFFu) >> 1);
    if (end & 1) {
      size_t j = std::find(open.begin(), open.end(), id) - open.begin();
      if (j == open.size()) continue;
      open.erase(open.begin() + j);
      open_bounds.erase(open_bounds.begin() + 4 * j, open_bounds.begin() + 4 * j + 4);
      continue;
    }
    const double* b2 = &bounds[4 * id];
    for (size_t j = 0; j < open.size(); j++) {
      const double* b1 = &open_bounds[4 * j];
      // (one branch for the four tests: which of them fails is not predictable)
      bool apart = (b1[0] > b2[1]) | (b2[0] > b1[1]) | (b1[2] > b2[3]) | (b2[2] > b1[3]);
      if (apart) continue;
      CollideElems(m, d, f, active[open[j]], f, active[id]);
      if (++npairs >= max_pairs) return;
    }
    open.push_back(id);
    open_bounds.insert(open_bounds.end(), b2, b2 + 4);
  }
}

// A flex's active elements against each other, per its selfcollide mode.
void CollideFlexElements(const Model& m, Data& d, int f) {
  int mode = m.flex_selfcollide[f];
  bool tree = !MidphaseDisabled(m) && mode != kFlexSelfNarrow && m.flex_bvhadr[f] >= 0;
  if (tree) {
    if (mode == kFlexSelfBvh || (mode == kFlexSelfAuto && m.flex_dim[f] == 3)) {
      CollideTreesWithFlex(m, d, m.nbody + f, m.nbody + f);
    } else {
      CollideFlexSweep(m, d, f);
    }
    return;
  }
  for (int e1 = 0; e1 < m.flex_elemnum[f]; e1++) {
    if (!ElementActive(m, f, e1)) continue;
    for (int e2 = e1 + 1; e2 < m.flex_elemnum[f]; e2++) {
      if (ElementActive(m, f, e2)) CollideElems(m, d, f, e1, f, e2);
    }
  }
}

// A flex pair's contacts [first, d.ncon) thinned to kMaxContactPair as MuJoCo 3.12's
// filterFlexContacts (only for models that follow 3.12): the deepest contact first, then
// again and again the one farthest from all chosen so far. Each choice is swapped into the
// next slot but the marks of the chosen stay with the slots they were chosen in, and the
// last choice is not moved: which contacts survive depends on this, so it is kept as is.
void ThinFlexContacts(const Model& m, Data& d, int first) {
  int n = d.ncon - first;
  if (m.release != Release::k3_12 || n <= kMaxContactPair) return;
  Contact* con = d.contact.data() + first;
  SolverFrame frame(d.solver_scratch);
  int* chosen = frame.Ints(n);
  double* nearest = frame.RealsToWrite(n);  // squared distance to the nearest chosen
  std::fill(nearest, nearest + n, kMaxVal);

  // The deepest contact (the first of equals).
  int best = 0;
  for (int i = 1; i < n; i++) {
    if (con[i].dist < con[best].dist) best = i;
  }
  // Choose, and find the unchosen slot farthest from every choice (the first of equals).
  int nchosen = 0;
  while (nchosen < kMaxContactPair && best >= 0) {
    chosen[best] = 1;
    const double* at = con[best].pos;
    int next = -1;
    double farthest = -1;
    for (int i = 0; i < n; i++) {
      if (chosen[i]) continue;
      double dx = con[i].pos[0] - at[0], dy = con[i].pos[1] - at[1], dz = con[i].pos[2] - at[2];
      double d2 = dx * dx + dy * dy + dz * dz;
      nearest[i] = std::min(nearest[i], d2);
      if (nearest[i] > farthest) {
        farthest = nearest[i];
        next = i;
      }
    }
    if (nchosen < kMaxContactPair - 1) {
      std::swap(con[nchosen], con[best]);
      if (next == nchosen) next = best;
    }
    nchosen++;
    best = next;
  }
  d.ncon = first + nchosen;
}

}  // namespace

// ---------------------------------------------------------------- entry points

void FlexBox(const Model& m, const Data& d, int f, const double* frame, double* lo,
             double* hi) {
  for (int i = 0; i < m.flex_vertnum[f]; i++) {
    const double* x = VertexPos(m, d, f, i);
    for (int k = 0; k < 3; k++) {
      double c = Dot3(frame + 3 * k, x);
      lo[k] = i == 0 ? c : std::min(lo[k], c);
      hi[k] = i == 0 ? c : std::max(hi[k], c);
    }
  }
  bool override = (m.opt.enableflags & kEnableOverride) != 0;
  double bound = m.flex_radius[f] + (override ? 0.5 * m.opt.o_margin : m.flex_margin[f]);
  for (int k = 0; k < 3; k++) {
    lo[k] -= bound;
    hi[k] += bound;
  }
}

void CollideWithFlex(const Model& m, Data& d, int b1, int b2) {
  int nbody = m.nbody, f2 = b2 - nbody;
  bool body1 = b1 < nbody;
  int bvh1 = body1 ? m.body_bvhadr[b1] : m.flex_bvhadr[b1 - nbody];
  int first = d.ncon;
  if (!MidphaseDisabled(m) && bvh1 >= 0 && m.flex_bvhadr[f2] >= 0) {
    CollideTreesWithFlex(m, d, b1, b2);
    ThinFlexContacts(m, d, first);
    SortContacts(d, first);
    return;
  }
  if (!body1) {
    // Every element of one flex with every element of the other.
    int f1 = b1 - nbody;
    for (int e1 = 0; e1 < m.flex_elemnum[f1]; e1++) {
      for (int e2 = 0; e2 < m.flex_elemnum[f2]; e2++) CollideElems(m, d, f1, e1, f2, e2);
    }
    ThinFlexContacts(m, d, first);
    return;
  }
  // Every geom of the body with every element (planes with every vertex).
  for (int g = m.body_geomadr[b1]; g < m.body_geomadr[b1] + m.body_geomnum[b1]; g++) {
    if (BitmaskRejects(m.geom_contype[g], m.geom_conaffinity[g], m.flex_contype[f2],
                       m.flex_conaffinity[f2])) {
      continue;
    }
    int geom_first = d.ncon;
    if (m.geom_type[g] == kGeomPlane) {
      CollidePlaneFlex(m, d, g, f2);
    } else {
      for (int e = 0; e < m.flex_elemnum[f2]; e++) CollideGeomElem(m, d, g, f2, e);
    }
    ThinFlexContacts(m, d, geom_first);
  }
}

void CollideFlexSelf(const Model& m, Data& d) {
  bool any_asleep = AnyAsleep(m, d);
  for (int f = 0; f < m.nflex; f++) {
    if (m.flex_rigid[f] || !(m.flex_contype[f] & m.flex_conaffinity[f])) continue;
    if (any_asleep && ElementSleepState(m, d, kObjFlex, f) == kAsleep) continue;  // (asleep)
    int first = d.ncon;
    if (m.flex_internal[f]) CollideFlexInternal(m, d, f);
    ThinFlexContacts(m, d, first);
    first = d.ncon;
    if (m.flex_selfcollide[f] != kFlexSelfNone) CollideFlexElements(m, d, f);
    ThinFlexContacts(m, d, first);
  }
}

void FlexBoundingVolumes(const Model& m, Data& d) {
  if (MidphaseDisabled(m)) return;
  for (int f = 0; f < m.nflex; f++) {
    int adr = m.flex_bvhadr[f], num = m.flex_bvhnum[f];
    if (adr < 0) continue;
    double* boxes = &d.bvh_aabb_dyn[6 * static_cast<size_t>(adr - m.nbvhstatic)];
    // Leaves: their elements' boxes; then every inner node from its children, children
    // coming after their parents.
    for (int i = 0; i < num; i++) {
      int e = m.bvh_nodeid[adr + i];
      if (e >= 0) std::copy_n(ElementBox(m, d, f, e), 6, boxes + 6 * i);
    }
    for (int i = num - 1; i >= 0; i--) {
      if (m.bvh_nodeid[adr + i] >= 0) continue;
      const int* child = &m.bvh_child[2 * (adr + i)];
      const double* a = boxes + 6 * child[0];
      const double* b = boxes + 6 * child[1];
      double lo[3], hi[3];
      for (int k = 0; k < 3; k++) {
        lo[k] = std::min(a[k] - a[k + 3], b[k] - b[k + 3]);
        hi[k] = std::max(a[k] + a[k + 3], b[k] + b[k + 3]);
      }
      for (int k = 0; k < 3; k++) {
        boxes[6 * i + k] = 0.5 * (hi[k] + lo[k]);
        boxes[6 * i + k + 3] = 0.5 * (hi[k] - lo[k]);
      }
    }
  }
}

}  // namespace simlab
