// Ray casting against geoms, as MuJoCo's mj_ray (engine_ray.c): the nearest surface
// along pnt + x vec (x >= 0), its geom and its outward normal. Used by rangefinders.
#ifndef SIMLAB_ENGINE_RAY_H_
#define SIMLAB_ENGINE_RAY_H_

#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// Which geoms a ray can hit (mj_ray's geomgroup, flg_static and bodyexclude). Geoms
// with a transparent colour (alpha 0) are never hit.
struct RayFilter {
  const unsigned char* geomgroup = nullptr;  // kNGroup flags; null: every group
  bool include_static = true;                // geoms welded to the world
  int bodyexclude = -1;                      // geoms of this body are skipped
};

// Geom groups a ray filter distinguishes (mjNGROUP).
inline constexpr int kNGroup = 6;

// Distance x to the nearest hit (-1 for none); *geomid (if given) is its geom or -1 and
// normal (if given) its unit surface normal, zero without a hit. vec need not be unit:
// the distance is measured in multiples of it.
double Ray(const Model& m, const Data& d, const double pnt[3], const double vec[3],
           const RayFilter& filter, int* geomid, double normal[3]);

// One primitive geom (plane, sphere, capsule, ellipsoid, cylinder, box) at pos/mat.
double RayPrimitive(const double pos[3], const double mat[9], const double size[3],
                    const double pnt[3], const double vec[3], int type, double normal[3]);
// One mesh geom (its triangles), one height-field geom, and one sdf geom (marching
// along the ray by its field's distance).
double RaySdf(const Model& m, const Data& d, int geom, const double pnt[3], const double vec[3],
              double normal[3]);
double RayMesh(const Model& m, const Data& d, int geom, const double pnt[3], const double vec[3],
               double normal[3]);
double RayHfield(const Model& m, const Data& d, int geom, const double pnt[3],
                 const double vec[3], double normal[3]);

// What of a flex a ray can hit (mj_rayFlex's flags, as the viewer draws the flex): its
// vertices' spheres, its edges' capsules, its elements' faces (of a 3D flex, those of
// layer `layer` only), or its skin (the outer faces and, for 2D and 3D flexes, the
// edges).
struct RayFlexParts {
  int layer = 0;
  bool vertices = false;
  bool edges = false;
  bool faces = false;
  bool skin = false;
};

// Ray against flex f (MuJoCo mj_rayFlex): distance to the nearest hit or -1; *vertid (if
// given) the flex vertex nearest the hit, normal (if given) the hit's unit normal, zero
// without a hit.
double RayFlex(const Model& m, const Data& d, int f, const RayFlexParts& parts,
               const double pnt[3], const double vec[3], int* vertid, double normal[3]);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_RAY_H_
