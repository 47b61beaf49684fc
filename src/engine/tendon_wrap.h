// Wrapping a tendon segment around a sphere or a cylinder (MuJoCo mju_wrap).
#ifndef SIMLAB_ENGINE_TENDON_WRAP_H_
#define SIMLAB_ENGINE_TENDON_WRAP_H_

namespace simlab {

// The shortest path from x0 to x1 that stays outside a sphere (type kWrapSphere) or an
// infinite cylinder (kWrapCylinder, axis = the geom's z) of `radius` centred at xpos
// with orientation xmat. If the straight segment misses the obstacle (or is on the side
// away from the optional `side` point), returns -1. Otherwise writes the two tangent
// points to wpnt (world frame, 6 numbers) and returns the length of the arc between
// them. A side point inside the obstacle asks for a path through it (inside wrap).
double WrapAroundGeom(double wpnt[6], const double x0[3], const double x1[3],
                      const double xpos[3], const double xmat[9], double radius, int type,
                      const double* side);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_TENDON_WRAP_H_
