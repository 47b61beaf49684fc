// The bodies a contact acts on, with weights (MuJoCo's mj_contactJacobian,
// mj_diagApprox): a geom's body; a flex vertex's body; or the bodies of a flex element's
// vertices, weighted by inverse distance from the contact point (without the vertex on
// the other side, when the element holds it) and summing to one.
#ifndef SIMLAB_ENGINE_CONTACT_BODIES_H_
#define SIMLAB_ENGINE_CONTACT_BODIES_H_

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// The bodies of one side: up to 4 (a geom, a vertex, an element's vertices), or up to 27
// nodes of an interpolated flex (more for a shell: its interior nodes' boundary nodes).
// Only [0, n) is ever written before it is read: the arrays are left uninitialized, as a
// side is made several times per contact and step.
struct ContactSide {
  static constexpr int kMax = 729;  // (MuJoCo's 27 x 27)
  int n = 0;
  int body[kMax];
  double weight[kMax];
};

// Side k (0 or 1) of contact c. With `signed_weights` (the Jacobian's), side 0's weights
// are negative; an interpolated flex's nodes then keep MuJoCo 3.5.1's unsigned
// shape-function weights, found at the vertex place taken with those negative weights
// (as its mj_vertBodyWeight does), except for a flex made of cells (flex_cells.h),
// whose nodes' bodies come once each with the side's sign, as in MuJoCo 3.12. False
// when the side cannot be resolved (a bad index).
bool ContactSideBodies(const Model& m, const Data& d, const Contact& c, int k,
                       bool signed_weights, ContactSide* side);

// Does each side of c move with one body (a geom, or a vertex of a flex that is not
// interpolated)? Then its rows are the difference of two body Jacobians.
bool ContactOnTwoBodies(const Model& m, const Contact& c);

// Is a flex of the contact passive (flex_passive: its contacts make no rows)?
bool ContactOnPassiveFlex(const Model& m, const Contact& c);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_CONTACT_BODIES_H_
