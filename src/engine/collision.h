// The collision stage: which geom pairs touch, and where (MuJoCo's mj_collision).
//
// The driver (collision_driver.cc) finds candidate body pairs (broad phase), applies
// MuJoCo's filters (contype/conaffinity, welded and parent bodies, <exclude>, bounding
// spheres), merges the explicit <pair>s, and calls one narrow-phase function per geom
// pair from the table below. Narrow-phase functions live in collision_primitive.cc
// (analytic pairs), collision_box.cc (box pairs), collision_convex.cc (GJK/EPA for
// every other convex pair, meshes included) and collision_hfield.cc (height fields).
#ifndef SIMLAB_ENGINE_COLLISION_H_
#define SIMLAB_ENGINE_COLLISION_H_

#include "engine/engine.h"
#include "simlab/data.h"
#include "simlab/model.h"

namespace simlab {

// Most contacts one geom pair may produce (mjMAXCONPAIR).
inline constexpr int kMaxContactPair = 50;

// A narrow-phase function. Geom g1's type is <= g2's type (the driver orders them).
// Writes up to kMaxContactPair contacts whose distance is below `margin` and returns
// how many. For each it sets dist, pos, and frame[0..2], the unit normal pointing from
// g1 to g2; those ChoosesTangent names also set frame[3..5] to a first tangent
// direction. The driver fills in everything else (ids, parameters, the rest of the frame).
using CollideFn = int (*)(const Model& m, const Data& d, Contact* con, int g1, int g2,
                          double margin);

// The narrow-phase function for a pair of geom types (type1 <= type2), or null when
// MuJoCo has none for it (collision_table.cc).
CollideFn CollisionFunction(int type1, int type2);
// Does `collide` choose the first tangent of its contacts' frames (frame[3..5])? The
// others write dist, pos and the normal only, and their tangents are left to SetContact.
// (The plane-capsule collider does: the capsule's axis; and the sdf collider, which
// completes its frames itself, as MuJoCo's does before its driver completes them again.)
bool ChoosesTangent(CollideFn collide);

// The whole collision stage: d.ncon and d.contact (collision_driver.cc).
void Collision(const Model& m, Data& d);

// Completes a contact frame (MuJoCo mju_makeFrame): row 0, the normal, is normalized;
// row 1 is the given tangent, else the world y axis (z when the normal is near y), made
// orthogonal to it; row 2 = row 0 x row 1 (collision_driver.cc).
void CompleteContactFrame(double frame[9]);

// ------------------------------------------------------------ narrow phase: analytic

int CollidePlaneSphere(const Model& m, const Data& d, Contact* con, int g1, int g2,
                       double margin);
int CollidePlaneCapsule(const Model& m, const Data& d, Contact* con, int g1, int g2,
                        double margin);
int CollidePlaneCylinder(const Model& m, const Data& d, Contact* con, int g1, int g2,
                         double margin);
int CollidePlaneBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                    double margin);
int CollideSphereSphere(const Model& m, const Data& d, Contact* con, int g1, int g2,
                        double margin);
int CollideSphereCapsule(const Model& m, const Data& d, Contact* con, int g1, int g2,
                         double margin);
int CollideSphereCylinder(const Model& m, const Data& d, Contact* con, int g1, int g2,
                          double margin);
int CollideSphereBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                     double margin);
int CollideCapsuleCapsule(const Model& m, const Data& d, Contact* con, int g1, int g2,
                          double margin);
int CollideCapsuleBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                      double margin);
int CollideBoxBox(const Model& m, const Data& d, Contact* con, int g1, int g2,
                  double margin);

// ------------------------------------------------------------ narrow phase: convex

// A plane and a convex geom (ellipsoid, mesh): MuJoCo's mjc_PlaneConvex.
int CollidePlaneConvex(const Model& m, const Data& d, Contact* con, int g1, int g2,
                       double margin);
// Any two convex geoms by GJK/EPA (MuJoCo's mjc_Convex with its native CCD).
int CollideConvex(const Model& m, const Data& d, Contact* con, int g1, int g2,
                  double margin);

// ------------------------------------------------------------ narrow phase: sdf

// A primitive, mesh or sdf geom (g1) and an sdf geom (g2), through the signed distance
// fields of both (MuJoCo's mjc_SDF; collision_sdf.cc).
int CollideSdf(const Model& m, const Data& d, Contact* con, int g1, int g2, double margin);
// The field of an sdf geom at point x of its frame: its plugin's (`field`, from
// SdfFieldOfGeom), else its mesh's octree (`mesh`, its geom_dataid); and its gradient (as
// MuJoCo's mjc_distance/mjc_gradient of one sdf).
double SdfGeomDistance(const Model& m, const SdfField& field, int mesh, const double x[3]);
void SdfGeomGradient(const Model& m, const SdfField& field, int mesh, double gradient[3],
                     const double x[3]);
// The signed distance of a mesh with an octree (mesh_octnum > 0) at point x of its frame.
double MeshOctreeDistance(const Model& m, int mesh, const double x[3]);

// ------------------------------------------------------------ narrow phase: height fields

// A height field (g1) and a convex geom: one contact per penetrating grid prism,
// MuJoCo's mjc_ConvexHField (collision_hfield.cc).
int CollideHFieldConvex(const Model& m, const Data& d, Contact* con, int g1, int g2,
                        double margin);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_COLLISION_H_
