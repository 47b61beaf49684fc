// The kinematic tree: bodies in depth-first XML order (world = 0), and their joints,
// geoms and sites in body order; then the model's tree layout (addresses, dof
// parents, the inertia-matrix layout, qpos0).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::kAuto;
using mjcf::kTrue;
using mjcf::ThrowAt;

namespace {

constexpr double kFrameEps = 1e-6;  // poses closer than this count as the same frame

// Depth-first walk: body ids in XML order, children's elements in body order.
void Visit(const mjcf::BodySpec& spec, int parent, CompileState* state) {
  BodyState body;
  body.spec = &spec;
  body.id = static_cast<int>(state->bodies.size());
  body.parent = parent;
  body.joint_begin = static_cast<int>(state->joints.size());
  body.geom_begin = static_cast<int>(state->geoms.size());
  body.site_begin = static_cast<int>(state->sites.size());
  body.joint_num = static_cast<int>(spec.joints.size());
  body.geom_num = static_cast<int>(spec.geoms.size());
  body.site_num = static_cast<int>(spec.sites.size());
  state->bodies.push_back(body);
  int id = body.id;
  for (const mjcf::JointSpec& j : spec.joints) {
    JointState js;
    js.spec = &j;
    js.body = id;
    state->joints.push_back(js);
  }
  for (const mjcf::GeomSpec& g : spec.geoms) {
    GeomState gs;
    gs.spec = &g;
    gs.body = id;
    state->geoms.push_back(gs);
  }
  for (const mjcf::SiteSpec& s : spec.sites) {
    SiteState ss;
    ss.spec = &s;
    ss.body = id;
    state->sites.push_back(ss);
  }
  for (const auto& child : spec.bodies) Visit(*child, id, state);
}

// Names must be unique within each kind of object.
template <typename T>
void CheckUnique(const std::vector<T>& items, const char* kind) {
  NameIndex seen;
  for (const T& item : items) {
    const mjcf::Source& src = item.spec->src;
    if (src.name.empty()) continue;
    if (!seen.Insert(src.name, 0)) {
      ThrowAt(src, std::string("repeated ") + kind + " name '" + src.name + "'");
    }
  }
}

// Number of numbers of qpos and qvel per joint type.
int JointNq(int type) { return type == kJointFree ? 7 : type == kJointBall ? 4 : 1; }
int JointNv(int type) { return type == kJointFree ? 6 : type == kJointBall ? 3 : 1; }

bool SameVec(const double* a, const double* b) {
  return std::abs(a[0] - b[0]) < kFrameEps && std::abs(a[1] - b[1]) < kFrameEps &&
         std::abs(a[2] - b[2]) < kFrameEps;
}

bool SameQuat(const double* a, const double* b) {
  bool minus = true, plus = true;
  for (int i = 0; i < 4; i++) {
    minus = minus && std::abs(a[i] - b[i]) < kFrameEps;
    plus = plus && std::abs(a[i] + b[i]) < kFrameEps;
  }
  return minus || plus;
}

const double kZero3[3] = {0, 0, 0};
const double kUnitQuat[4] = {1, 0, 0, 0};

// MuJoCo's mjtSameFrame for a geom or site pose within its body.
int SameFrame(const double* pos, const double* quat, const BodyState& body) {
  if (SameVec(pos, kZero3) && SameQuat(quat, kUnitQuat)) return 1;       // body
  if (SameQuat(quat, kUnitQuat)) return 3;                               // body rotation
  if (SameVec(pos, body.ipos) && SameQuat(quat, body.iquat)) return 2;  // inertia
  if (SameQuat(quat, body.iquat)) return 4;                              // inertia rotation
  return 0;
}

}  // namespace

int FindName(const std::vector<std::string>& names, const std::string& name) {
  for (size_t i = 0; i < names.size(); i++) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

int FindNamed(const mjcf::Source& src, const std::vector<std::string>& names,
              const std::string& name, const std::string& kind) {
  int id = name.empty() ? -1 : FindName(names, name);
  if (id < 0) ThrowAt(src, "unknown " + kind + " '" + name + "'");
  return id;
}

NameIndex::NameIndex(const std::vector<std::string>& names) {
  ids_.reserve(names.size());
  for (size_t i = 0; i < names.size(); i++) Insert(names[i], static_cast<int>(i));
}

bool NameIndex::Insert(const std::string& name, int id) {
  if (name.empty()) return true;
  return ids_.emplace(name, id).second;
}

int NameIndex::Find(const std::string& name) const {
  auto it = ids_.find(name);
  return it == ids_.end() ? -1 : it->second;
}

NameIndex BodyNames(const CompileState& state) {
  NameIndex bodies;
  for (size_t b = 0; b < state.bodies.size(); b++) {
    const mjcf::BodySpec* spec = state.bodies[b].spec;
    bodies.Insert(spec ? spec->src.name : "world", static_cast<int>(b));
  }
  return bodies;
}

NameIndex MaterialNames(const mjcf::ModelSpec& spec) {
  NameIndex materials;
  for (size_t i = 0; i < spec.materials.size(); i++) {
    materials.Insert(spec.materials[i].src.name, static_cast<int>(i));
  }
  return materials;
}

int FindNamed(const mjcf::Source& src, const NameIndex& names, const std::string& name,
              const std::string& kind) {
  int id = name.empty() ? -1 : names.Find(name);
  if (id < 0) ThrowAt(src, "unknown " + kind + " '" + name + "'");
  return id;
}

// ---------------------------------------------------------------- flatten

void FlattenTree(const mjcf::ModelSpec& spec, CompileState* state) {
  state->spec = &spec;
  Visit(spec.world, -1, state);
  CheckUnique(state->bodies, "body");
  CheckUnique(state->joints, "joint");
  CheckUnique(state->geoms, "geom");
  CheckUnique(state->sites, "site");
  for (const BodyState& b : state->bodies) {
    if (b.id > 0 && b.spec->src.name == "world") ThrowAt(b.spec->src, "repeated body name 'world'");
  }

  // weldid: the body itself if it has joints, else its parent's.
  for (BodyState& b : state->bodies) {
    b.weldid = (b.id == 0 || b.joint_num > 0) ? b.id : state->bodies[b.parent].weldid;
  }
}

// ---------------------------------------------------------------- joints

namespace {

// The limited flag as MuJoCo resolves it (auto: limited if the range is nonempty).
bool ResolveLimited(const mjcf::CompilerSpec& c, const mjcf::Source& src, int limited,
                    const std::array<double, 2>& range, const char* what) {
  bool hasrange = !(range[0] == 0 && range[1] == 0);
  if (limited == kAuto && !c.autolimits && hasrange) {
    ThrowAt(src, std::string("has ") + what + "range but not " + what +
                     "limited; set autolimits=\"true\" in <compiler>, set " + what +
                     "limited, or remove " + what + "range");
  }
  return limited == kTrue || (limited == kAuto && range[0] < range[1]);
}

// Limits, axis and anchor of one joint (under its own model's settings; `model`: this
// model's); returns its number of dofs.
int CompileJoint(const mjcf::CompilerSpec& model, JointState* j) {
  const mjcf::JointSpec& s = *j->spec;
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(s.compiler, model);
  int type = s.type;
  j->range[0] = s.range[0];
  j->range[1] = s.range[1];

  // Position limits: free joints never; degrees to radians for rotations.
  j->limited = type != kJointFree && ResolveLimited(c, s.src, s.limited, s.range, "");
  if (j->limited) {
    if (s.range[0] >= s.range[1] && type != kJointBall) {
      ThrowAt(s.src, "range[0] should be smaller than range[1]");
    }
    if (s.range[0] != 0 && type == kJointBall) ThrowAt(s.src, "range[0] should be 0 in a ball joint");
    if (c.degree && (type == kJointHinge || type == kJointBall)) {
      for (double& r : j->range) r = r * std::numbers::pi / 180.0;
    }
  }

  // Actuator force limits: only for hinge and slide joints.
  bool scalar = (type == kJointHinge || type == kJointSlide);
  j->actfrclimited = scalar && ResolveLimited(c, s.src, s.actfrclimited, s.actfrcrange, "actuatorfrc");
  if (j->actfrclimited && s.actfrcrange[0] >= s.actfrcrange[1]) {
    ThrowAt(s.src, "actuatorfrcrange[0] should be smaller than actuatorfrcrange[1]");
  }

  // Axis and anchor, through the enclosing frames.
  double fpos[3] = {0, 0, 0}, fquat[4] = {1, 0, 0, 0};
  if (s.frame) FramePose(*s.frame, model, fpos, fquat);
  math::Copy3(j->axis, s.axis.data());
  math::Copy3(j->pos, s.pos.data());
  if (!scalar) {
    j->axis[0] = j->axis[1] = 0;
    j->axis[2] = 1;
  } else if (s.frame) {
    double a[3];
    math::RotVecQuat(a, j->axis, fquat);
    math::Copy3(j->axis, a);
  }
  if (NormalizeVec(j->axis, 3) < kEps) ThrowAt(s.src, "joint axis is too small");
  if (type == kJointFree) {
    math::Zero3(j->pos);
  } else if (s.frame) {
    double q[4] = {1, 0, 0, 0};
    AccumulateChild(fpos, fquat, j->pos, q);
  }

  // Reference positions of hinges in radians.
  double scale = (type == kJointHinge && c.degree) ? std::numbers::pi / 180.0 : 1.0;
  j->ref = s.ref * scale;
  j->springref = s.springref * scale;
  return JointNv(type);
}

// ---------------------------------------------------------------- sites

void CompileSite(const mjcf::CompilerSpec& model, SiteState* site) {
  const mjcf::SiteSpec& s = *site->spec;
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(s.compiler, model);
  if (s.type == kGeomMesh || s.type == kGeomHfield || s.type == kGeomPlane || s.type == kGeomSdf) {
    ThrowAt(s.src, "meshes, hfields and planes are not allowed in sites");
  }
  math::Copy3(site->size, s.size.data());
  math::Copy3(site->pos, s.pos.data());
  math::CopyQuat(site->quat, s.quat.data());

  // fromto: position, orientation and length from two points.
  if (!std::isnan(s.fromto[0])) {
    if (s.type != kGeomCapsule && s.type != kGeomCylinder && s.type != kGeomEllipsoid &&
        s.type != kGeomBox) {
      ThrowAt(s.src, "fromto requires a capsule, cylinder, box or ellipsoid");
    }
    if (s.pos[0] != 0 || s.pos[1] != 0 || s.pos[2] != 0) ThrowAt(s.src, "both pos and fromto defined");
    double vec[3] = {s.fromto[0] - s.fromto[3], s.fromto[1] - s.fromto[4], s.fromto[2] - s.fromto[5]};
    site->size[1] = NormalizeVec(vec, 3) / 2;
    if (site->size[1] < kEps) ThrowAt(s.src, "fromto points are too close");
    if (s.type == kGeomEllipsoid || s.type == kGeomBox) {
      site->size[2] = site->size[1];
      site->size[1] = site->size[0];
    }
    for (int i = 0; i < 3; i++) site->pos[i] = (s.fromto[i] + s.fromto[i + 3]) / 2;
    ZAxisQuat(site->quat, vec);
  } else if (const char* err = ResolveOrientation(site->quat, c.degree, c.eulerseq, s.alt)) {
    ThrowAt(s.src, std::string("orientation error: ") + err);
  }

  // Enclosing frames, then normalize.
  if (s.frame) {
    double fpos[3], fquat[4];
    FramePose(*s.frame, model, fpos, fquat);
    AccumulateChild(fpos, fquat, site->pos, site->quat);
  }
  NormalizeVec(site->quat, 4);
}

// ---------------------------------------------------------------- bodies

// Pose and explicit inertial of one body, before its geoms.
void BodyFrame(const mjcf::CompilerSpec& c, BodyState* b) {
  const mjcf::BodySpec& s = *b->spec;
  math::Copy3(b->pos, s.pos.data());
  math::CopyQuat(b->quat, s.quat.data());
  NormalizeVec(b->quat, 4);
  if (const char* err = ResolveOrientation(b->quat, c.degree, c.eulerseq, s.alt)) {
    ThrowAt(s.src, std::string("orientation error: ") + err);
  }
  math::Copy3(b->ipos, s.ipos.data());
  math::CopyQuat(b->iquat, s.iquat.data());
  NormalizeVec(b->iquat, 4);
  b->mass = s.mass;
  math::Copy3(b->inertia, s.inertia.data());
  if (!std::isnan(s.fullinertia[0])) {
    if (const char* err = FullInertia(b->iquat, b->inertia, s.fullinertia.data())) {
      ThrowAt(s.inertial_src, std::string("fullinertia: ") + err);
    }
  }
  if (const char* err = ResolveOrientation(b->iquat, c.degree, c.eulerseq, s.ialt)) {
    ThrowAt(s.inertial_src, std::string("orientation error: ") + err);
  }
}

// Free-joint alignment applies to a body whose one joint is free and that has no child
// bodies, when the joint says align="true", or "auto" under <compiler alignfree="true">.
bool AlignsFree(const mjcf::CompilerSpec& c, const mjcf::BodySpec& s) {
  if (s.joints.size() != 1 || s.joints[0].type != kJointFree || !s.bodies.empty()) return false;
  return s.joints[0].align == kTrue || (s.joints[0].align == kAuto && c.alignfree);
}

// The body frame moves onto the inertial frame (as MuJoCo's compiler does it: the frame
// accumulated, the inverse kept for the body's elements), its geoms by the inverse.
void AlignToInertia(BodyState* b, const std::vector<GeomState*>& geoms) {
  double ipos[3], iquat[4];
  math::Copy3(ipos, b->ipos);
  math::CopyQuat(iquat, b->iquat);
  AccumulateChild(b->pos, b->quat, ipos, iquat);
  // (the inverse: the inertial position seen from the rotated-back frame, negated)
  const double conj[4] = {b->iquat[0], -b->iquat[1], -b->iquat[2], -b->iquat[3]};
  double mat[9];
  math::QuatToMat(mat, conj);
  math::MulMatVec3(b->align_pos, mat, b->ipos);
  for (int k = 0; k < 3; k++) b->align_pos[k] = -b->align_pos[k];
  math::CopyQuat(b->align_quat, conj);
  math::Copy3(b->pos, ipos);
  math::CopyQuat(b->quat, iquat);
  math::Zero3(b->ipos);
  math::SetIdentityQuat(b->iquat);
  b->aligned = true;
  for (GeomState* g : geoms) AccumulateChild(b->align_pos, b->align_quat, g->pos, g->quat);
}

}  // namespace

void AlignedPose(const BodyState& b, double pos[3], double quat[4]) {
  if (b.aligned) AccumulateChild(b.align_pos, b.align_quat, pos, quat);
}

namespace {

void CompileBody(CompileState* state, int id) {
  BodyState& b = state->bodies[id];
  const mjcf::BodySpec& s = *b.spec;
  // (an attached body and its elements keep their own model's settings)
  const mjcf::CompilerSpec& model = state->spec->compiler;
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(s.compiler, model);
  BodyFrame(c, &b);

  // Geoms, then the inertial frame from geoms where MuJoCo infers it.
  std::vector<GeomState*> geoms;
  for (size_t k = 0; k < s.geoms.size(); k++) {
    GeomState& g = state->geoms[b.geom_begin + k];
    bool in_group = g.spec->group >= c.inertiagrouprange[0] && g.spec->group <= c.inertiagrouprange[1];
    bool infer = id > 0 && (!s.explicit_inertial || c.inertiafromgeom == kTrue) && in_group;
    if (g.spec->type == kGeomPlane && b.weldid != 0) {
      ThrowAt(g.spec->src, "planes are only allowed in static bodies");
    }
    CompileGeom(model, infer, &g);
    geoms.push_back(&g);
  }
  if (id > 0 && (c.inertiafromgeom == kTrue || (std::isnan(b.ipos[0]) && c.inertiafromgeom == kAuto))) {
    InertiaFromGeoms(c, geoms, &b);
  }
  if (std::isnan(b.ipos[0])) {
    math::Copy3(b.ipos, b.pos);
    math::CopyQuat(b.iquat, b.quat);
  }
  if (id > 0) BoundMassInertia(c, &b);

  // The enclosing frames move the body within its parent.
  if (s.frame) {
    double fpos[3], fquat[4];
    FramePose(*s.frame, model, fpos, fquat);
    AccumulateChild(fpos, fquat, b.pos, b.quat);
  }
  if (id > 0 && AlignsFree(c, s)) AlignToInertia(&b, geoms);

  // Joints: at most 6 dofs, no rotation after a ball joint.
  bool ball = false;
  for (size_t k = 0; k < s.joints.size(); k++) {
    JointState& j = state->joints[b.joint_begin + k];
    b.dofnum += CompileJoint(model, &j);
    int type = j.spec->type;
    if (ball && (type == kJointBall || type == kJointHinge)) ThrowAt(j.spec->src, "a ball joint is followed by a rotation in the same body");
    ball = ball || type == kJointBall;
    if (type == kJointFree && (s.joints.size() > 1)) ThrowAt(j.spec->src, "a free joint can only appear by itself");
    if (type == kJointFree && b.parent != 0) ThrowAt(j.spec->src, "a free joint can only be used on a child of the world body");
  }
  if (b.dofnum > 6) ThrowAt(s.src, "more than 6 dofs in one body");
  if (s.mocap && (b.dofnum > 0 || b.parent != 0)) {
    ThrowAt(s.src, "a mocap body must be a fixed child of the world body");
  }
  for (size_t k = 0; k < s.sites.size(); k++) {
    SiteState& site = state->sites[b.site_begin + k];
    CompileSite(model, &site);
    AlignedPose(b, site.pos, site.quat);
  }
}

}  // namespace

void CompileBodies(CompileState* state) {
  for (size_t i = 0; i < state->bodies.size(); i++) CompileBody(state, static_cast<int>(i));
}

// A moving body needs mass and inertia, its own or from a static child (`children`
// lists each body's child bodies).
namespace {
bool HasMassInertia(const CompileState& state, const std::vector<std::vector<int>>& children,
                    int id) {
  const BodyState& b = state.bodies[id];
  if (b.mass >= kMinVal && b.inertia[0] >= kMinVal && b.inertia[1] >= kMinVal &&
      b.inertia[2] >= kMinVal) {
    return true;
  }
  for (int child : children[id]) {
    if (state.bodies[child].joint_num > 0) continue;
    if (HasMassInertia(state, children, child)) return true;
  }
  return false;
}
}  // namespace

void CheckMovingBodies(const CompileState& state) {
  std::vector<std::vector<int>> children(state.bodies.size());
  for (const BodyState& b : state.bodies) {
    if (b.parent >= 0) children[b.parent].push_back(b.id);
  }
  for (const BodyState& b : state.bodies) {
    if (b.id == 0 || b.joint_num == 0) continue;
    if (!HasMassInertia(state, children, b.id)) {
      ThrowAt(b.spec->src, "mass and inertia of a moving body must be positive (mass=" +
                               std::to_string(b.mass) + ")");
    }
  }
}

// ---------------------------------------------------------------- layout

namespace {

void LayoutBody(const CompileState& state, const BodyState& b, Model* m) {
  int i = b.id;
  m->body_parentid[i] = b.parent < 0 ? 0 : b.parent;
  m->body_weldid[i] = b.weldid;
  m->body_rootid[i] = (i == 0 || b.parent == 0) ? i : m->body_rootid[b.parent];
  m->body_dofnum[i] = b.dofnum;
  math::Copy3(&m->body_pos[3 * i], b.pos);
  math::CopyQuat(&m->body_quat[4 * i], b.quat);
  math::Copy3(&m->body_ipos[3 * i], b.ipos);
  math::CopyQuat(&m->body_iquat[4 * i], b.iquat);
  m->body_mass[i] = b.mass;
  math::Copy3(&m->body_inertia[3 * i], b.inertia);
  m->body_gravcomp[i] = b.spec->gravcomp;
  if (b.spec->gravcomp > 0) m->ngravcomp++;
  bool body_frame = SameVec(b.ipos, kZero3) && SameQuat(b.iquat, kUnitQuat);
  m->body_sameframe[i] = body_frame ? 1 : SameQuat(b.iquat, kUnitQuat) ? 3 : 0;
  m->body_names[i] = i == 0 ? "world" : b.spec->src.name;
}

void LayoutJoint(const JointState& j, int jid, int qadr, int dadr, Model* m) {
  const mjcf::JointSpec& s = *j.spec;
  m->jnt_type[jid] = s.type;
  m->jnt_group[jid] = s.group;
  m->jnt_limited[jid] = j.limited;
  m->jnt_actfrclimited[jid] = j.actfrclimited;
  m->jnt_actgravcomp[jid] = s.actgravcomp;
  m->jnt_qposadr[jid] = qadr;
  m->jnt_dofadr[jid] = dadr;
  m->jnt_bodyid[jid] = j.body;
  math::Copy3(&m->jnt_pos[3 * jid], j.pos);
  math::Copy3(&m->jnt_axis[3 * jid], j.axis);
  m->jnt_stiffness[jid] = s.stiffness;
  m->jnt_range[2 * jid] = j.range[0];
  m->jnt_range[2 * jid + 1] = j.range[1];
  m->jnt_actfrcrange[2 * jid] = s.actfrcrange[0];
  m->jnt_actfrcrange[2 * jid + 1] = s.actfrcrange[1];
  for (int k = 0; k < kNRef; k++) m->jnt_solref[kNRef * jid + k] = s.solref_limit[k];
  for (int k = 0; k < kNImp; k++) m->jnt_solimp[kNImp * jid + k] = s.solimp_limit[k];
  m->jnt_margin[jid] = s.margin;
  m->jnt_names[jid] = s.src.name;
}

// qpos0 and qpos_spring of one joint.
void JointQpos(const JointState& j, const BodyState& b, int qadr, Model* m) {
  switch (j.spec->type) {
    case kJointFree:
      for (int k = 0; k < 3; k++) m->qpos0[qadr + k] = b.pos[k];
      for (int k = 0; k < 4; k++) m->qpos0[qadr + 3 + k] = b.quat[k];
      for (int k = 0; k < 7; k++) m->qpos_spring[qadr + k] = m->qpos0[qadr + k];
      break;
    case kJointBall:
      m->qpos0[qadr] = m->qpos_spring[qadr] = 1;
      break;
    default:
      m->qpos0[qadr] = j.ref;
      m->qpos_spring[qadr] = j.springref;
      break;
  }
}

// dof fields of one joint; dof_parentid chains through the body's ancestors.
void LayoutDofs(const JointState& j, int jid, int* dadr, std::vector<int>* lastdof, Model* m) {
  const mjcf::JointSpec& s = *j.spec;
  for (int k = 0; k < JointNv(s.type); k++) {
    int d = (*dadr)++;
    m->dof_bodyid[d] = j.body;
    m->dof_jntid[d] = jid;
    for (int r = 0; r < kNRef; r++) m->dof_solref[kNRef * d + r] = s.solref_friction[r];
    for (int r = 0; r < kNImp; r++) m->dof_solimp[kNImp * d + r] = s.solimp_friction[r];
    m->dof_frictionloss[d] = s.frictionloss;
    m->dof_armature[d] = s.armature;
    m->dof_damping[d] = s.damping;
    m->dof_parentid[d] = (*lastdof)[j.body];
    (*lastdof)[j.body] = d;
  }
}

void LayoutGeom(const GeomState& g, int gid, const BodyState& b, Model* m) {
  const mjcf::GeomSpec& s = *g.spec;
  m->geom_type[gid] = s.type;
  m->geom_contype[gid] = s.contype;
  m->geom_conaffinity[gid] = s.conaffinity;
  m->geom_condim[gid] = s.condim;
  m->geom_bodyid[gid] = g.body;
  m->geom_group[gid] = s.group;
  m->geom_priority[gid] = s.priority;
  math::Copy3(&m->geom_size[3 * gid], g.size);
  math::Copy3(&m->geom_pos[3 * gid], g.pos);
  math::CopyQuat(&m->geom_quat[4 * gid], g.quat);
  math::Copy3(&m->geom_friction[3 * gid], s.friction.data());
  m->geom_solmix[gid] = s.solmix;
  for (int k = 0; k < kNRef; k++) m->geom_solref[kNRef * gid + k] = s.solref[k];
  for (int k = 0; k < kNImp; k++) m->geom_solimp[kNImp * gid + k] = s.solimp[k];
  m->geom_margin[gid] = s.margin;
  m->geom_gap[gid] = s.gap;
  // Colors are single precision in MuJoCo.
  for (int k = 0; k < 4; k++) m->geom_rgba[4 * gid + k] = static_cast<float>(s.rgba[k]);
  m->geom_sameframe[gid] = SameFrame(g.pos, g.quat, b);
  m->geom_rbound[gid] = GeomRBound(g);
  GeomAabb(g, &m->geom_aabb[6 * gid]);
  m->geom_dataid[gid] = g.meshid;  // the mesh of a mesh geom, else -1
  GeomFluid(g, &m->geom_fluid[kNFluid * gid]);
  m->geom_names[gid] = s.src.name;
}

void LayoutSite(const SiteState& st, int sid, const BodyState& b, Model* m) {
  const mjcf::SiteSpec& s = *st.spec;
  m->site_type[sid] = s.type;
  m->site_bodyid[sid] = st.body;
  m->site_group[sid] = s.group;
  math::Copy3(&m->site_size[3 * sid], st.size);
  math::Copy3(&m->site_pos[3 * sid], st.pos);
  math::CopyQuat(&m->site_quat[4 * sid], st.quat);
  for (int k = 0; k < 4; k++) m->site_rgba[4 * sid + k] = static_cast<float>(s.rgba[k]);
  m->site_sameframe[sid] = SameFrame(st.pos, st.quat, b);
  m->site_names[sid] = s.src.name;
}

// The CSR rows of the symmetric dof-dof pattern D (MuJoCo's D_rownnz, D_rowadr, D_diag,
// D_colind, the layout of qDeriv): row i holds i's ancestor dofs, i, then its
// descendant dofs, ascending; row i of M is its beginning.
void LayoutDofDofMatrix(Model* m) {
  int nv = m->nv;
  std::vector<int> descendants(nv, 0);
  for (int i = 0; i < nv; i++) {
    for (int j = m->dof_parentid[i]; j >= 0; j = m->dof_parentid[j]) descendants[j]++;
  }
  int adr = 0;
  for (int i = 0; i < nv; i++) {
    m->D_rowadr[i] = adr;
    m->D_diag[i] = m->M_rownnz[i] - 1;
    m->D_rownnz[i] = m->M_rownnz[i] + descendants[i];
    std::copy_n(&m->M_colind[m->M_rowadr[i]], m->M_rownnz[i], &m->D_colind[adr]);
    adr += m->D_rownnz[i];
  }
  // Descendants in ascending order: each dof appended to its ancestors' rows.
  std::vector<int> filled(m->M_rownnz.begin(), m->M_rownnz.end());
  for (int i = 0; i < nv; i++) {
    for (int j = m->dof_parentid[i]; j >= 0; j = m->dof_parentid[j]) {
      m->D_colind[m->D_rowadr[j] + filled[j]++] = i;
    }
  }
}

// The CSR rows of the body-dof pattern B (MuJoCo's B_rownnz, B_rowadr, B_colind): row b
// holds the dofs of b's ancestors, then those of its subtree, which follow b's first
// dof contiguously (bodies and dofs are numbered parents first).
void LayoutBodyDofMatrix(Model* m) {
  std::vector<int> first(m->nbody, 0), subtree(m->body_dofnum.begin(), m->body_dofnum.end());
  for (int b = 1; b < m->nbody; b++) first[b] = first[b - 1] + m->body_dofnum[b - 1];
  for (int b = m->nbody - 1; b > 0; b--) subtree[m->body_parentid[b]] += subtree[b];
  int adr = 0;
  for (int b = 0; b < m->nbody; b++) {
    m->B_rowadr[b] = adr;
    int* row = m->B_colind.data() + adr;
    int n = 0;
    for (int a = m->body_parentid[b]; b > 0 && a > 0; a = m->body_parentid[a]) {
      for (int k = m->body_dofnum[a] - 1; k >= 0; k--) row[n++] = m->body_dofadr[a] + k;
    }
    std::reverse(row, row + n);
    for (int k = 0; k < subtree[b]; k++) row[n++] = first[b] + k;
    m->B_rownnz[b] = n;
    adr += n;
  }
}

// dof_Madr and the CSR rows of M: each row holds the dof's ancestors, then itself.
void LayoutInertiaMatrix(Model* m) {
  int adr = 0;
  for (int i = 0; i < m->nv; i++) {
    m->dof_Madr[i] = adr;
    m->M_rowadr[i] = adr;
    int count = 0;
    for (int j = i; j >= 0; j = m->dof_parentid[j]) count++;
    m->M_rownnz[i] = count;
    int k = adr + count - 1;
    for (int j = i; j >= 0; j = m->dof_parentid[j]) m->M_colind[k--] = j;
    adr += count;
  }
  LayoutDofDofMatrix(m);
  LayoutBodyDofMatrix(m);
}

// Trees: dof_treeid counts the roots of the dof forest; bodies take their weld's.
void LayoutTrees(Model* m) {
  int ntree = 0;
  for (int i = 0; i < m->nv; i++) {
    if (m->dof_parentid[i] == -1) ntree++;
    m->dof_treeid[i] = ntree - 1;
  }
  for (int i = 0; i < m->nbody; i++) {
    int weld = m->body_weldid[i];
    m->body_treeid[i] = m->body_dofnum[weld] ? m->dof_treeid[m->body_dofadr[weld]] : -1;
  }
}

}  // namespace

void LayoutTree(const CompileState& state, Model* m) {
  int jid = 0, qadr = 0, dadr = 0, gid = 0, sid = 0, mocap = 0;
  std::vector<int> lastdof(state.bodies.size(), -1);
  for (const BodyState& b : state.bodies) {
    LayoutBody(state, b, m);
    int i = b.id;
    lastdof[i] = b.parent >= 0 ? lastdof[b.parent] : -1;
    m->body_mocapid[i] = b.spec->mocap ? mocap++ : -1;

    // Joints and dofs.
    m->body_jntadr[i] = b.joint_num == 0 ? -1 : jid;
    m->body_jntnum[i] = b.joint_num;
    m->body_dofadr[i] = b.dofnum ? dadr : -1;
    for (; jid < m->njnt && state.joints[jid].body == i; jid++) {
      const JointState& j = state.joints[jid];
      LayoutJoint(j, jid, qadr, dadr, m);
      JointQpos(j, b, qadr, m);
      LayoutDofs(j, jid, &dadr, &lastdof, m);
      qadr += JointNq(j.spec->type);
    }

    // Geoms and sites.
    m->body_geomadr[i] = b.geom_num == 0 ? -1 : gid;
    m->body_geomnum[i] = b.geom_num;
    for (; gid < m->ngeom && state.geoms[gid].body == i; gid++) LayoutGeom(state.geoms[gid], gid, b, m);
    for (; sid < m->nsite && state.sites[sid].body == i; sid++) LayoutSite(state.sites[sid], sid, b, m);
  }
  LayoutInertiaMatrix(m);
  LayoutTrees(m);
}

// Sizes of the tree part of the model.
void TreeSizes(const CompileState& state, Model* m) {
  m->nbody = static_cast<int>(state.bodies.size());
  m->njnt = static_cast<int>(state.joints.size());
  m->ngeom = static_cast<int>(state.geoms.size());
  m->nsite = static_cast<int>(state.sites.size());
  m->nq = m->nv = m->nmocap = 0;
  for (const JointState& j : state.joints) {
    m->nq += JointNq(j.spec->type);
    m->nv += JointNv(j.spec->type);
  }
  for (const BodyState& b : state.bodies) m->nmocap += b.spec->mocap ? 1 : 0;

  // nM: each dof contributes its depth in the dof forest.
  std::vector<int> parent, lastdof(state.bodies.size(), -1);
  for (const BodyState& b : state.bodies) {
    lastdof[b.id] = b.parent >= 0 ? lastdof[b.parent] : -1;
    for (int n = 0; n < b.joint_num; n++) {
      const JointState& j = state.joints[b.joint_begin + n];
      for (int k = 0; k < JointNv(j.spec->type); k++) {
        parent.push_back(lastdof[b.id]);
        lastdof[b.id] = static_cast<int>(parent.size()) - 1;
      }
    }
  }
  m->ntree = static_cast<int>(std::count(parent.begin(), parent.end(), -1));
  m->nM = 0;
  for (size_t i = 0; i < parent.size(); i++) {
    for (int j = static_cast<int>(i); j >= 0; j = parent[j]) m->nM++;
  }
  // D holds both triangles: every nonzero of M below the diagonal twice, the diagonal once.
  m->nD = 2 * m->nM - static_cast<int>(parent.size());

  // nB: each body's ancestors' dofs and its subtree's (bodies come parents first).
  size_t nbody = state.bodies.size();
  std::vector<int> dofnum(nbody, 0), above(nbody, 0), subtree(nbody, 0);
  for (const BodyState& b : state.bodies) {
    for (int n = 0; n < b.joint_num; n++) dofnum[b.id] += JointNv(state.joints[b.joint_begin + n].spec->type);
    if (b.parent >= 0) above[b.id] = above[b.parent] + dofnum[b.parent];
  }
  for (size_t i = nbody; i-- > 0;) {
    subtree[i] += dofnum[i];
    if (state.bodies[i].parent >= 0) subtree[state.bodies[i].parent] += subtree[i];
  }
  m->nB = 0;
  for (size_t i = 0; i < nbody; i++) m->nB += above[i] + subtree[i];
}

}  // namespace simlab::compiler
