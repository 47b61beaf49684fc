// Support functions of the public API (simlab/support.h): Jacobians at named frames,
// contact forces, rays, the inertia matrix, and state vectors (MuJoCo engine_support.c).
#include "simlab/support.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/engine.h"
#include "engine/ray.h"
#include "simlab/simlab.h"

namespace simlab {

// ---------------------------------------------------------------- Jacobians

void Jac(const Model& m, const Data& d, double* jacp, double* jacr, const double point[3],
         int body) {
  Jacobian(m, d, jacp, jacr, point, body);
}

void JacBody(const Model& m, const Data& d, double* jacp, double* jacr, int body) {
  Jacobian(m, d, jacp, jacr, &d.xpos[3 * body], body);
}

void JacBodyCom(const Model& m, const Data& d, double* jacp, double* jacr, int body) {
  Jacobian(m, d, jacp, jacr, &d.xipos[3 * body], body);
}

void JacSite(const Model& m, const Data& d, double* jacp, double* jacr, int site) {
  JacobianSite(m, d, jacp, jacr, site);
}

void JacGeom(const Model& m, const Data& d, double* jacp, double* jacr, int geom) {
  Jacobian(m, d, jacp, jacr, &d.geom_xpos[3 * geom], m.geom_bodyid[geom]);
}

// ---------------------------------------------------------------- contacts and rays

void ContactForceInFrame(const Model& m, const Data& d, int id, double result[6]) {
  ContactForce(m, d, id, result);
}

double RayCast(const Model& m, const Data& d, const double pnt[3], const double vec[3],
               const unsigned char* geomgroup, bool include_static, int bodyexclude,
               int* geomid, double normal[3]) {
  RayFilter filter;
  filter.geomgroup = geomgroup;
  filter.include_static = include_static;
  filter.bodyexclude = bodyexclude;
  return Ray(m, d, pnt, vec, filter, geomid, normal);
}

double RayCastFlex(const Model& m, const Data& d, int flex_layer, bool vertices, bool edges,
                   bool faces, bool skin, int flexid, const double pnt[3], const double vec[3],
                   int* vertid, double normal[3]) {
  RayFlexParts parts;
  parts.layer = flex_layer;
  parts.vertices = vertices;
  parts.edges = edges;
  parts.faces = faces;
  parts.skin = skin;
  return RayFlex(m, d, flexid, parts, pnt, vec, vertid, normal);
}

// ---------------------------------------------------------------- the inertia matrix

void FullM(const Model& m, double* dst, const double* M) {
  // Row i of the legacy layout: the diagonal, then the ancestors' entries up the tree.
  const int nv = m.nv;
  std::fill(dst, dst + static_cast<size_t>(nv) * nv, 0.0);
  int adr = 0;
  for (int i = 0; i < nv; i++) {
    for (int j = i; j >= 0; j = m.dof_parentid[j], adr++) {
      dst[i * nv + j] = M[adr];
      dst[j * nv + i] = M[adr];
    }
  }
}

void MulM(const Model& m, const Data& d, double* res, const double* vec) {
  MulSymLayout(m.nv, m.M_rownnz.data(), m.M_rowadr.data(), m.M_colind.data(), d.M.data(), vec,
               res);
}

// ---------------------------------------------------------------- state vectors

namespace {

// Numbers of one part of the state.
int PartSize(const Model& m, int bit) {
  switch (bit) {
    case kStateTime: return 1;
    case kStateQpos: return m.nq;
    case kStateQvel: return m.nv;
    case kStateAct: return m.na;
    case kStateHistory: return m.nhistory;
    case kStateWarmstart: return m.nv;
    case kStateCtrl: return m.nu;
    case kStateQfrcApplied: return m.nv;
    case kStateXfrcApplied: return 6 * m.nbody;
    case kStateEqActive: return m.neq;
    case kStateMocapPos: return 3 * m.nmocap;
    case kStateMocapQuat: return 4 * m.nmocap;
    default: return 0;  // user data and plugin state: none in simlab models
  }
}

// The numbers of one real-valued part in d (not eq_active, which holds ints); D is Data
// or const Data.
template <typename D>
auto PartOf(D& d, int bit) -> decltype(d.qpos.data()) {
  switch (bit) {
    case kStateTime: return &d.time;
    case kStateQpos: return d.qpos.data();
    case kStateQvel: return d.qvel.data();
    case kStateAct: return d.act.data();
    case kStateHistory: return d.history.data();
    case kStateWarmstart: return d.qacc_warmstart.data();
    case kStateCtrl: return d.ctrl.data();
    case kStateQfrcApplied: return d.qfrc_applied.data();
    case kStateXfrcApplied: return d.xfrc_applied.data();
    case kStateMocapPos: return d.mocap_pos.data();
    case kStateMocapQuat: return d.mocap_quat.data();
    default: return nullptr;
  }
}

void CheckSpec(int spec) {
  if (spec < 0) throw Error("invalid state signature " + std::to_string(spec) + " < 0");
  if (spec >= (1 << kNStateBits)) {
    throw Error("invalid state signature " + std::to_string(spec) + " >= 2^mjNSTATE");
  }
}

// Calls visit(bit, offset, size) for each part in `spec`, in bit order, with the part's
// offset in the state vector.
template <typename Visit>
int ForEachPart(const Model& m, int spec, Visit visit) {
  CheckSpec(spec);
  int offset = 0;
  for (int i = 0; i < kNStateBits; i++) {
    const int bit = 1 << i;
    if (!(spec & bit)) continue;
    const int n = PartSize(m, bit);
    if (n > 0) visit(bit, offset, n);
    offset += n;
  }
  return offset;
}

}  // namespace

int StateSize(const Model& m, int spec) {
  return ForEachPart(m, spec, [](int, int, int) {});
}

void GetState(const Model& m, const Data& d, double* state, int spec) {
  ForEachPart(m, spec, [&](int bit, int offset, int n) {
    // eq_active holds ints; every other part is copied as it is.
    if (bit == kStateEqActive) std::copy_n(d.eq_active.begin(), n, state + offset);
    else std::memcpy(state + offset, PartOf(d, bit), sizeof(double) * n);
  });
}

void SetState(const Model& m, Data& d, const double* state, int spec) {
  ForEachPart(m, spec, [&](int bit, int offset, int n) {
    if (bit != kStateEqActive) {
      std::memcpy(PartOf(d, bit), state + offset, sizeof(double) * n);
      return;
    }
    for (int j = 0; j < n; j++) d.eq_active[j] = std::trunc(state[offset + j]) != 0;
  });
}

}  // namespace simlab
