// Equality constraints: object lookups, the eq_* fields, and the parts of eq_data that
// MuJoCo fills from the pose at qpos0 (mj_setConst):
//
//   connect, bodies: data[0-2] anchor in body1's frame (as written), data[3-5] the same
//                    point in body2's frame at qpos0
//   connect, sites:  all zero (the sites themselves give the points)
//   weld, bodies:    data[0-2] anchor in body2's frame, data[3-9] body2's pose in body1's
//                    frame; when the written relpose has a zero quaternion, it is the
//                    pose at qpos0 (and the anchor seen from body1), else the written one
//                    with its quaternion normalized
//   weld, sites:     as written; only data[10] (torquescale) is used
//   joint, tendon:   data[0-4] polynomial coefficients
//   flexstrain:      data[0-2] the cell (x, y, z indices) of the interpolated flex, or
//                    data[0] the face of a shell (data[1-2] -1)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "compiler/compiler.h"
#include "engine/engine.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

// The objects equalities can name, indexed once for all of them.
struct EqualityNames {
  NameIndex joints, tendons, sites, bodies, flexes;
};

// The names and kind (for messages) of the objects an equality refers to.
const NameIndex& ObjectNames(const mjcf::EqualitySpec& eq, const EqualityNames& names,
                             std::string* kind) {
  switch (eq.type) {
    case kEqJoint: *kind = "joint"; return names.joints;
    case kEqTendon: *kind = "tendon"; return names.tendons;
    case kEqFlex:
    case kEqFlexVert:
    case kEqFlexStrain: *kind = "flex"; return names.flexes;
    default: break;
  }
  if (eq.objtype == kObjSite) {
    *kind = "site";
    return names.sites;
  }
  *kind = "body";
  return names.bodies;
}

// eq_obj1id, eq_obj2id: a missing second body is the world; a missing second joint or
// tendon is -1. Both objects must differ; joints must be hinges or slides.
void ResolveObjects(const mjcf::EqualitySpec& eq, const EqualityNames& all, int i, Model* m) {
  std::string kind;
  const NameIndex& names = ObjectNames(eq, all, &kind);
  int id1 = FindNamed(eq.src, names, eq.name1, kind);
  int id2 = eq.name2.empty() ? -1 : FindNamed(eq.src, names, eq.name2, kind);
  if (id2 < 0 && eq.objtype == kObjBody) id2 = 0;
  if (id1 == id2) ThrowAt(eq.src, kind + " '" + eq.name1 + "' is used twice");
  if (eq.type == kEqJoint) {
    for (int id : {id1, id2}) {
      if (id >= 0 && m->jnt_type[id] != kJointHinge && m->jnt_type[id] != kJointSlide) {
        ThrowAt(eq.src, "joint '" + m->jnt_names[id] + "' is not a hinge or a slide");
      }
    }
  }
  bool flex = eq.type == kEqFlex || eq.type == kEqFlexVert || eq.type == kEqFlexStrain;
  if (flex && m->flex_rigid[id1]) {
    ThrowAt(eq.src, "rigid flex '" + eq.name1 + "' in equality constraint " + std::to_string(i));
  }
  m->eq_obj1id[i] = id1;
  m->eq_obj2id[i] = id2;
}

// A flexstrain's flex must be interpolated, and its cell (or a shell's face) one of the
// flex's: MuJoCo reads whatever lies there.
void CheckStrainElement(const mjcf::EqualitySpec& eq, const mjcf::FlexSpec& flex, int interp) {
  if (interp == 0) {
    ThrowAt(eq.src, "flex '" + eq.name1 +
                        "' is not interpolated: a strain equality needs nodes (a flexcomp with "
                        "dof trilinear or quadratic, or a flex with node bodies)");
  }
  const std::array<int, 3>& c = flex.cellcount;
  const double* at = eq.data.data();
  if (interp < 0) {
    int nface = 2 * (c[1] * c[2] + c[0] * c[2] + c[0] * c[1]);
    if (at[0] != std::floor(at[0]) || at[0] < 0 || at[0] >= nface || at[1] != -1 || at[2] != -1) {
      ThrowAt(eq.src, "cell must be a face of the shell, 'f -1 -1' with f from 0 to " +
                          std::to_string(nface - 1));
    }
    return;
  }
  for (int k = 0; k < 3; k++) {
    if (at[k] != std::floor(at[k]) || at[k] < 0 || at[k] >= c[k]) {
      char cell[96];
      std::snprintf(cell, sizeof(cell), "%g %g %g", at[0], at[1], at[2]);
      ThrowAt(eq.src, std::string("cell '") + cell + "' is not one of the " +
                          std::to_string(c[0]) + " x " + std::to_string(c[1]) + " x " +
                          std::to_string(c[2]) + " cells of flex '" + eq.name1 + "'");
    }
  }
}

// data[3-5] of a body connect: body1's anchor seen from body2 at qpos0.
void ConnectAtQpos0(const Data& d, int id1, int id2, double* data) {
  double world[3], rel[3];
  math::MulMatVec3(world, &d.xmat[9 * id1], data);
  math::Add3(world, world, &d.xpos[3 * id1]);
  math::Sub3(rel, world, &d.xpos[3 * id2]);
  math::MulMatTVec3(data + 3, &d.xmat[9 * id2], rel);
}

// data[3-9] of a body weld: the written pose (quaternion normalized), or, when its
// quaternion is zero, body2's anchor and orientation seen from body1 at qpos0.
void WeldAtQpos0(const Data& d, int id1, int id2, double* data) {
  double* quat = data + 6;
  if (quat[0] != 0 || quat[1] != 0 || quat[2] != 0 || quat[3] != 0) {
    math::NormalizeQuat(quat);
    return;
  }
  double world[3], rel[3], inv1[4];
  math::MulMatVec3(world, &d.xmat[9 * id2], data);
  math::Add3(world, world, &d.xpos[3 * id2]);
  math::Sub3(rel, world, &d.xpos[3 * id1]);
  math::MulMatTVec3(data + 3, &d.xmat[9 * id1], rel);
  math::NegQuat(inv1, &d.xquat[4 * id1]);
  math::MulQuat(quat, inv1, &d.xquat[4 * id2]);
}

}  // namespace

void CompileEqualities(const mjcf::ModelSpec& spec, Model* m) {
  EqualityNames names = {NameIndex(m->jnt_names), NameIndex(m->tendon_names),
                         NameIndex(m->site_names), NameIndex(m->body_names),
                         NameIndex(m->flex_names)};
  NameIndex seen;
  for (int i = 0; i < m->neq; i++) {
    const mjcf::EqualitySpec& eq = spec.equalities[i];
    if (!seen.Insert(eq.src.name, i)) {
      ThrowAt(eq.src, "repeated equality name '" + eq.src.name + "'");
    }
    m->eq_names[i] = eq.src.name;
    ResolveObjects(eq, names, i, m);
    if (eq.type == kEqFlexStrain) {
      int f = m->eq_obj1id[i];
      CheckStrainElement(eq, spec.flexes[f], m->flex_interp[f]);
    }

    // Everything else is copied as read.
    m->eq_type[i] = eq.type;
    m->eq_objtype[i] = eq.objtype;
    m->eq_active0[i] = eq.active ? 1 : 0;
    std::copy(eq.solref.begin(), eq.solref.end(), &m->eq_solref[kNRef * i]);
    std::copy(eq.solimp.begin(), eq.solimp.end(), &m->eq_solimp[kNImp * i]);
    std::copy(eq.data.begin(), eq.data.end(), &m->eq_data[kNEqData * i]);
  }
}

void EqualityConstants(Model* m) {
  if (m->neq == 0) return;
  // Body poses at qpos0, from the engine's kinematics.
  Data at_qpos0 = MakeData(*m);
  Kinematics(*m, at_qpos0);
  for (int i = 0; i < m->neq; i++) {
    double* data = &m->eq_data[kNEqData * i];
    int id1 = m->eq_obj1id[i], id2 = m->eq_obj2id[i];
    bool bodies = m->eq_objtype[i] == kObjBody;
    if (m->eq_type[i] == kEqConnect && bodies) {
      ConnectAtQpos0(at_qpos0, id1, id2, data);
    } else if (m->eq_type[i] == kEqConnect) {
      std::fill(data, data + kNEqData, 0.0);
    } else if (m->eq_type[i] == kEqWeld && bodies) {
      WeldAtQpos0(at_qpos0, id1, id2, data);
    }
  }
}

}  // namespace simlab::compiler
