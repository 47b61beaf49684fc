// Pulling and turning a body with the mouse, as MuJoCo's viewers do (mjvPerturb,
// mjv_initPerturb, mjv_applyPerturbForce): a selected body is pulled by a critically
// damped spring from a point on it (localpos, in the body's frame) towards a reference
// point (refselpos), and/or turned towards a reference orientation (refquat, of its
// inertia frame), through its row of xfrc_applied. Springs: Model::vis.map.stiffness and
// stiffnessrot, scaled by the mass the selected point moves with and the body's inertia.
//
//   simlab::Perturb p;
//   p.select = body;  p.localpos = {...};
//   simlab::InitPerturb(m, d, &p);           // references at the body's pose now
//   p.active = simlab::kPerturbTranslate;     // then, each step:
//   p.refselpos = target;  simlab::ApplyPerturbForce(m, d, p);  simlab::Step(m, d);
#ifndef SIMLAB_PERTURB_H_
#define SIMLAB_PERTURB_H_

#include <array>

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// What a perturbation does (mjtPertBit).
enum PerturbFlag : int { kPerturbTranslate = 1, kPerturbRotate = 2 };

struct Perturb {
  int select = -1;                               // body id (above 0), or -1: none
  int active = 0;                                // PerturbFlag bits
  std::array<double, 3> localpos = {0, 0, 0};    // the point pulled, in the body's frame
  std::array<double, 3> refselpos = {0, 0, 0};   // where it is pulled to (world)
  std::array<double, 4> refquat = {1, 0, 0, 0};  // orientation the inertia frame is turned to
  double localmass = 1;                          // mass the point moves with (InitPerturb)
};

// The references at the selected body's pose now, and the mass its point moves with
// (3 / trace(J M^-1 J^T) for the point's Jacobian J). Needs positions and the factored
// inertia of d (after Forward or a Step). Nothing for no body or the world.
void InitPerturb(const Model& m, Data& d, Perturb* p);

// The selected point (localpos on the selected body) in world coordinates now.
void PerturbSelectionPoint(const Data& d, const Perturb& p, double out[3]);

// Sets the selected body's xfrc_applied to the springs' force and torque (MuJoCo's
// mjv_applyPerturbForce; nothing when inactive or no body is selected).
void ApplyPerturbForce(const Model& m, Data& d, const Perturb& p);

}  // namespace simlab

#endif  // SIMLAB_PERTURB_H_
