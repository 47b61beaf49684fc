// Support functions on a computed Data (MuJoCo's engine_support): Jacobians, contact
// forces, rays, the inertia matrix, and the simulation state as one vector.
//
// Each reads what Forward (or a Step) left in Data: call them after the stage that
// computes their input (positions for Jacobians and rays, the constraint solve for
// contact forces).
#ifndef SIMLAB_SUPPORT_H_
#define SIMLAB_SUPPORT_H_

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// ---------------------------------------------------------------- Jacobians

// 3 x nv Jacobians (row-major) of a world point moving with `body`: translation jacp and
// rotation jacr, either may be null (mj_jac).
void Jac(const Model& m, const Data& d, double* jacp, double* jacr, const double point[3],
         int body);
// The same at the body's frame origin (mj_jacBody), its center of mass (mj_jacBodyCom),
// a site (mj_jacSite) or a geom's center (mj_jacGeom).
void JacBody(const Model& m, const Data& d, double* jacp, double* jacr, int body);
void JacBodyCom(const Model& m, const Data& d, double* jacp, double* jacr, int body);
void JacSite(const Model& m, const Data& d, double* jacp, double* jacr, int site);
void JacGeom(const Model& m, const Data& d, double* jacp, double* jacr, int geom);

// ---------------------------------------------------------------- contacts and rays

// Contact `id`'s force and torque in its own frame (normal, 2 tangents, spin, 2 rolls),
// decoded from the constraint forces (mj_contactForce).
void ContactForceInFrame(const Model& m, const Data& d, int id, double result[6]);

// Distance along pnt + x vec (x >= 0) to the nearest geom surface, or -1 (mj_ray).
// geomgroup: 6 flags (null: every group); include_static: geoms welded to the world;
// bodyexclude: a body whose geoms are skipped (-1: none); *geomid: the geom hit or -1;
// normal (if not null): the surface normal at the hit.
double RayCast(const Model& m, const Data& d, const double pnt[3], const double vec[3],
               const unsigned char* geomgroup, bool include_static, int bodyexclude,
               int* geomid, double normal[3] = nullptr);

// Distance along pnt + x vec (x >= 0) to flex `flexid`, or -1 (mj_rayFlex): the parts hit
// are those the viewer draws (vertices, edges, faces of layer `flex_layer` for a 3D flex,
// or the skin); *vertid (if not null): the flex's vertex nearest the hit; normal (if not
// null): the surface normal there.
double RayCastFlex(const Model& m, const Data& d, int flex_layer, bool vertices, bool edges,
                   bool faces, bool skin, int flexid, const double pnt[3], const double vec[3],
                   int* vertid, double normal[3] = nullptr);

// ---------------------------------------------------------------- the inertia matrix

// dst (nv x nv, row-major) = the full symmetric matrix of M given in MuJoCo's legacy
// layout (d.qM, nM numbers at dof_Madr) (mj_fullM).
void FullM(const Model& m, double* dst, const double* M);
// res (nv) = M vec, with the M of the last position stage (mj_mulM).
void MulM(const Model& m, const Data& d, double* res, const double* vec);

// ---------------------------------------------------------------- state vectors

// Parts of a simulation's state (MuJoCo's mjtState bits), in the order a state vector
// holds them.
enum StateBit : int {
  kStateTime = 1 << 0, kStateQpos = 1 << 1, kStateQvel = 1 << 2, kStateAct = 1 << 3,
  kStateHistory = 1 << 4, kStateWarmstart = 1 << 5, kStateCtrl = 1 << 6,
  kStateQfrcApplied = 1 << 7, kStateXfrcApplied = 1 << 8, kStateEqActive = 1 << 9,
  kStateMocapPos = 1 << 10, kStateMocapQuat = 1 << 11, kStateUserdata = 1 << 12,
  kStatePlugin = 1 << 13,
  kNStateBits = 14,
  kStatePhysics = kStateQpos | kStateQvel | kStateAct | kStateHistory,
  kStateFullPhysics = kStateTime | kStatePhysics | kStatePlugin,
  kStateUser = kStateCtrl | kStateQfrcApplied | kStateXfrcApplied | kStateEqActive |
               kStateMocapPos | kStateMocapQuat | kStateUserdata,
  kStateIntegration = kStateFullPhysics | kStateUser | kStateWarmstart
};

// Numbers in a state vector of the parts in `spec` (mj_stateSize). Throws Error for a
// spec outside [0, 2^14).
int StateSize(const Model& m, int spec);
// Copies the parts in `spec` from d into state, in bit order (mj_getState).
void GetState(const Model& m, const Data& d, double* state, int spec);
// Writes them back into d (mj_setState); eq_active takes nonzero as active.
void SetState(const Model& m, Data& d, const double* state, int spec);

}  // namespace simlab

#endif  // SIMLAB_SUPPORT_H_
