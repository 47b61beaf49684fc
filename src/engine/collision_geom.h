// A geom as the narrow phase sees it: world position, orientation and size, read
// from Model and Data (MuJoCo's mjGETINFO). Shared by the analytic and box pairs.
#ifndef SIMLAB_ENGINE_COLLISION_GEOM_H_
#define SIMLAB_ENGINE_COLLISION_GEOM_H_

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

struct GeomPose {
  const double* pos;   // centre (3)
  const double* mat;   // orientation, row-major (9); column 2 is the local z axis
  const double* size;  // geom_size (3)
};

inline GeomPose PoseOf(const Model& m, const Data& d, int g) {
  return {&d.geom_xpos[3 * g], &d.geom_xmat[9 * g], &m.geom_size[3 * g]};
}

// The geom's local z axis in world coordinates (a capsule's or cylinder's axis, a
// plane's normal).
inline void ZAxisOf(const GeomPose& g, double* axis) {
  axis[0] = g.mat[2];
  axis[1] = g.mat[5];
  axis[2] = g.mat[8];
}

// Starts a contact: its normal (frame row 0) and a zero rest of the frame.
inline void SetContactNormal(Contact& con, const double* normal) {
  for (int i = 0; i < 9; i++) con.frame[i] = i < 3 ? normal[i] : 0;
}

// A plane contact at `point` of the other geom, at signed height `dist` above the plane:
// the contact sits halfway back towards the plane.
inline void PlaneContactAt(Contact& con, const double* normal, const double* point,
                           double dist) {
  SetContactNormal(con, normal);
  con.dist = dist;
  for (int i = 0; i < 3; i++) con.pos[i] = point[i] + normal[i] * (-dist * 0.5);
}

// Pairs on poses rather than geoms (MuJoCo's mjraw_*), for flex elements made into
// capsules: a sphere (size[0]) and a capsule (size[0] radius, size[1] half length), two
// capsules, a capsule and a box. The normal points from the first to the second.
int SphereCapsulePoses(Contact* con, double margin, const GeomPose& sphere,
                       const GeomPose& capsule);
int CapsuleCapsulePoses(Contact* con, double margin, const GeomPose& c1, const GeomPose& c2);
int CapsuleBoxPoses(Contact* con, double margin, const GeomPose& capsule, const GeomPose& box);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_COLLISION_GEOM_H_
