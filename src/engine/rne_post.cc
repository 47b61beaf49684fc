// Quantities computed on demand after the constraint solve (MuJoCo mj_rnePostConstraint,
// mj_subtreeVel, mj_contactForce), for the sensors that read them.
//
// cfrc_ext(b) is every external force on body b as a com-based spatial force (torque,
// force at the subtree com of b's root): xfrc_applied, the contacts' forces and the
// connect/weld constraint forces. cacc(b) is b's acceleration including qacc, and
// cfrc_int(b) = sum over b's subtree of (cinert cacc + cvel x* cinert cvel - cfrc_ext):
// the force b's parent exerts on the subtree rooted at b.
#include <algorithm>

#include "engine/engine.h"
#include "engine/flex_strain.h"
#include "engine/sensor.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// cfrc_ext(body) += sign * the world torque:force `wrench` acting at world point `point`,
// moved to the com-based frame. The world body collects nothing.
void AddExternal(const Model& m, Data& d, int body, const double* wrench, const double* point,
                 double sign) {
  if (body == 0) return;
  double com_based[6];
  TransformSpatial(com_based, wrench, true, &d.subtree_com[3 * m.body_rootid[body]], point,
                   nullptr);
  double* ext = &d.cfrc_ext[6 * body];
  for (int k = 0; k < 6; k++) ext[k] += sign * com_based[k];
}

// xfrc_applied (force, torque at the body's com) as torque:force.
void AddAppliedForces(const Model& m, Data& d) {
  for (int b = 1; b < m.nbody; b++) {
    const double* f = &d.xfrc_applied[6 * b];
    if (f[0] == 0 && f[1] == 0 && f[2] == 0 && f[3] == 0 && f[4] == 0 && f[5] == 0) continue;
    double wrench[6] = {f[3], f[4], f[5], f[0], f[1], f[2]};
    AddExternal(m, d, b, wrench, &d.xipos[3 * b], 1);
  }
}

// Each contact with rows pushes geom[1]'s body along its frame and geom[0]'s back.
void AddContactForces(const Model& m, Data& d) {
  for (int i = 0; i < d.ncon; i++) {
    const Contact& c = d.contact[i];
    if (c.efc_address < 0 || c.geom[0] < 0 || c.geom[1] < 0) continue;
    double local[6], wrench[6];
    ContactForce(m, d, i, local);
    MulMatTVec3(wrench, c.frame, local + 3);
    MulMatTVec3(wrench + 3, c.frame, local);
    AddExternal(m, d, m.geom_bodyid[c.geom[0]], wrench, c.pos, -1);
    AddExternal(m, d, m.geom_bodyid[c.geom[1]], wrench, c.pos, 1);
  }
}

// World position of side `side` (0, 1) of a connect or weld: the site, or the body's
// anchor (a connect's anchors are eq_data 0-2 and 3-5; a weld's are stored the other
// way round).
void EqualityAnchor(const Model& m, const Data& d, int eq, int side, int* body, double* pos) {
  int obj = side == 0 ? m.eq_obj1id[eq] : m.eq_obj2id[eq];
  const double* offset;
  if (m.eq_objtype[eq] == kObjBody) {
    *body = obj;
    bool first_slot = (m.eq_type[eq] == kEqWeld) == (side == 1);
    offset = &m.eq_data[static_cast<size_t>(kNEqData) * eq + (first_slot ? 0 : 3)];
  } else {
    *body = m.site_bodyid[obj];
    offset = &m.site_pos[3 * obj];
  }
  MulMatVec3(pos, &d.xmat[9 * *body], offset);
  AddScaled3(pos, &d.xpos[3 * *body], 1);
}

// Connect (force) and weld (force and torque) rows act on both sides, opposite ways.
// Joint, tendon and flex equalities move no body directly and are skipped: a row at a
// time, but a flexstrain by MuJoCo's count (FlexStrainRneStep), which can step over the
// rows of the equalities after it, as MuJoCo's does.
void AddEqualityForces(const Model& m, Data& d) {
  for (int i = 0; i < d.ne;) {
    int eq = d.efc_id[i];
    int type = m.eq_type[eq];
    if (type == kEqFlexStrain) {
      i += std::max(1, FlexStrainRneStep(m, eq));
      continue;
    }
    if (type != kEqConnect && type != kEqWeld) {
      i++;
      continue;
    }
    double wrench[6] = {0, 0, 0, d.efc_force[i], d.efc_force[i + 1], d.efc_force[i + 2]};
    if (type == kEqWeld) Copy3(wrench, &d.efc_force[i + 3]);
    for (int side = 0; side < 2; side++) {
      int body;
      double pos[3];
      EqualityAnchor(m, d, eq, side, &body, pos);
      AddExternal(m, d, body, wrench, pos, side == 0 ? 1 : -1);
    }
    i += type == kEqWeld ? 6 : 3;
  }
}

// Each body's own momentum: subtree_linvel = mass v, subtree_angmom = R I R^T w.
void BodyMomenta(const Model& m, Data& d, const double* body_vel) {
  for (int i = 0; i < m.nbody; i++) {
    const double* vel = body_vel + 6 * i;
    Scale3(&d.subtree_linvel[3 * i], vel + 3, m.body_mass[i]);
    double local[3];
    MulMatTVec3(local, &d.ximat[9 * i], vel);
    for (int k = 0; k < 3; k++) local[k] *= m.body_inertia[3 * i + k];
    MulMatVec3(&d.subtree_angmom[3 * i], &d.ximat[9 * i], local);
  }
}

// Linear momenta summed leaves to root, then divided by the subtree masses.
void SubtreeLinearVelocity(const Model& m, Data& d) {
  for (int i = m.nbody - 1; i >= 0; i--) {
    double* lin = &d.subtree_linvel[3 * i];
    if (i > 0) AddScaled3(&d.subtree_linvel[3 * m.body_parentid[i]], lin, 1);
    Scale3(lin, lin, 1 / std::max(kMinVal, m.body_subtreemass[i]));
  }
}

// Angular momenta about the subtree coms: a body's own momentum about its subtree's com,
// then the subtree's momentum moved to the parent's subtree com.
void SubtreeAngularMomentum(const Model& m, Data& d, const double* body_vel) {
  for (int i = m.nbody - 1; i > 0; i--) {
    int parent = m.body_parentid[i];
    double dx[3], dv[3], dp[3], dl[3];
    Sub3(dx, &d.xipos[3 * i], &d.subtree_com[3 * i]);
    Sub3(dv, body_vel + 6 * i + 3, &d.subtree_linvel[3 * i]);
    Scale3(dp, dv, m.body_mass[i]);
    Cross3(dl, dx, dp);
    AddScaled3(&d.subtree_angmom[3 * i], dl, 1);
    AddScaled3(&d.subtree_angmom[3 * parent], &d.subtree_angmom[3 * i], 1);

    Sub3(dx, &d.subtree_com[3 * i], &d.subtree_com[3 * parent]);
    Sub3(dv, &d.subtree_linvel[3 * i], &d.subtree_linvel[3 * parent]);
    Scale3(dv, dv, m.body_subtreemass[i]);
    Cross3(dl, dx, dv);
    AddScaled3(&d.subtree_angmom[3 * parent], dl, 1);
  }
}

}  // namespace

void ContactForce(const Model& m, const Data& d, int contact, double result[6]) {
  for (int k = 0; k < 6; k++) result[k] = 0;
  if (contact < 0 || contact >= d.ncon || d.contact[contact].efc_address < 0) return;
  const Contact& c = d.contact[contact];
  const double* f = &d.efc_force[c.efc_address];
  if (m.opt.cone != kConePyramidal || c.dim == 1) {
    for (int k = 0; k < c.dim; k++) result[k] = f[k];
    return;
  }
  // Pyramid edges come in pairs (normal + mu_j t_j, normal - mu_j t_j): every edge pushes
  // along the normal, each pair's difference along its tangent direction.
  for (int k = 0; k < 2 * (c.dim - 1); k++) result[0] += f[k];
  for (int j = 0; j < c.dim - 1; j++) result[j + 1] = (f[2 * j] - f[2 * j + 1]) * c.friction[j];
}

void RnePostConstraint(const Model& m, Data& d) {
  // The world accelerates upward at g, as in Rne.
  for (int k = 0; k < 6; k++) d.cacc[k] = 0;
  if (!(m.opt.disableflags & kDisableGravity)) Scale3(&d.cacc[3], m.opt.gravity.data(), -1);

  // External forces on each body.
  std::fill(d.cfrc_ext.begin(), d.cfrc_ext.end(), 0.0);
  AddAppliedForces(m, d);
  AddContactForces(m, d);
  AddEqualityForces(m, d);

  // Forward pass: accelerations with qacc; each body's net force less the external ones.
  for (int k = 0; k < 6; k++) d.cfrc_int[k] = 0;
  for (int b = 1; b < m.nbody; b++) {
    double* internal = &d.cfrc_int[6 * b];
    RneBodyStep(m, d, b, true, d.cacc.data(), internal);
    for (int k = 0; k < 6; k++) internal[k] -= d.cfrc_ext[6 * b + k];
  }

  // Backward pass: a subtree's force includes its children's.
  for (int b = m.nbody - 1; b > 0; b--) {
    for (int k = 0; k < 6; k++) d.cfrc_int[6 * m.body_parentid[b] + k] += d.cfrc_int[6 * b + k];
  }
  d.flg_rnepost = true;
}

void SubtreeVel(const Model& m, Data& d) {
  StackFrame frame(d);
  double* body_vel = frame.Alloc(6 * m.nbody);
  for (int i = 0; i < m.nbody; i++) ObjectVelocity(m, d, kObjBody, i, body_vel + 6 * i, false);
  BodyMomenta(m, d, body_vel);
  SubtreeLinearVelocity(m, d);
  SubtreeAngularMomentum(m, d, body_vel);
  d.flg_subtreevel = true;
}

}  // namespace simlab
