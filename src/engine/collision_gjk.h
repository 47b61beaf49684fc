// Convex collision detection between two convex shapes given by support functions:
// GJK for the distance (or a proof of overlap), then EPA for the penetration depth and
// the witness points of a penetrating pair. This is MuJoCo's native CCD
// (engine_collision_gjk.c) in our own words; the steps follow it closely, because the
// witness points EPA returns depend on the exact sequence of polytope expansions.
//
// The shapes themselves (support functions of each geom type, margins, the pairs'
// special cases) live in collision_convex.cc.
#ifndef SIMLAB_ENGINE_COLLISION_GJK_H_
#define SIMLAB_ENGINE_COLLISION_GJK_H_

#include <cmath>

#include "engine/collision.h"

namespace simlab::ccd {

struct ConvexShape;

// The farthest point of a shape in a unit direction, in world coordinates.
using SupportFn = void (*)(double res[3], ConvexShape* shape, const double dir[3]);

// One geom as the convex collider sees it. Pose and size are copies, so a caller may
// perturb the pose (the multi-contact search does) without touching Data.
struct ConvexShape {
  int geom = -1;
  int type = 0;            // GeomType
  double pos[3] = {0, 0, 0};
  double mat[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double size[3] = {0, 0, 0};
  double margin = 0;       // inflates the shape by margin/2 in every direction
  SupportFn support = nullptr;

  // The model (meshes: their hull's polygons for multi-contact).
  const Model* model = nullptr;

  // Meshes: the vertices (local frame), and the convex-hull graph (null if absent).
  const double* vert = nullptr;
  int nvert = 0;
  const int* graph = nullptr;

  // Flex shapes (geom -1): an element (its vertices' positions, 2 to 4 of them) or a
  // vertex (one), each rounded by `radius` (which includes half the margin).
  const double* flexpoint[4] = {nullptr, nullptr, nullptr, nullptr};
  int nflexpoint = 0;
  double radius = 0;

  // Box corner (bits x, y, z) or mesh vertex of the last support point; the mesh search
  // warm-starts from it. meshindex is the last vertex in the hull graph's numbering.
  int vertindex = -1;
  int meshindex = -1;
};

// Limits for one query (MuJoCo's mjCCDConfig).
struct CcdConfig {
  int max_iterations = 35;   // for GJK and EPA each
  double tolerance = 1e-6;
  int max_contacts = 1;      // 0: only decide overlap, no penetration depth
  double dist_cutoff = 0;    // report distances of separated shapes up to this
  bool newer = false;        // MuJoCo 3.12's GJK and EPA (a model that follows 3.12)
};

// Are a and b the same point up to kMinVal per coordinate?
inline bool SamePoint(const double* a, const double* b) {
  return std::abs(a[0] - b[0]) < kMinVal && std::abs(a[1] - b[1]) < kMinVal &&
         std::abs(a[2] - b[2]) < kMinVal;
}

// A vertex of the Minkowski difference shape1 - shape2, with the two support points.
struct CcdVertex {
  double vert[3];   // vert1 - vert2
  double vert1[3];  // on shape 1
  double vert2[3];  // on shape 2
  int index1;       // box corner or mesh vertex of vert1 (-1 for smooth shapes)
  int index2;
};

// The answer of one query (MuJoCo's mjCCDStatus).
struct CcdStatus {
  double dist = 0;                 // distance, negative when penetrating
  double x1[3 * kMaxContactPair];  // witness points on shape 1
  double x2[3 * kMaxContactPair];  // witness points on shape 2
  int nx = 0;                      // number of witness pairs

  // The query's limits (the sphere and capsule core pass widens dist_cutoff for a while).
  CcdConfig config;

  int gjk_iterations = 0;
  int epa_iterations = 0;
  int epa_status = -1;             // kEpaNoContact, kEpaSuccess or a failure reason
  CcdVertex simplex[4];
  int nsimplex = 0;
  bool separated = false;          // 3.12: GJK proved the shapes apart
};

// EPA outcomes (MuJoCo's mjtEPAStatus).
enum EpaStatus : int {
  kEpaNoContact = -1,
  kEpaSuccess = 0,
  kEpaP2InvalidFaces,
  kEpaP2Nonconvex,
  kEpaP2OriginOnFace,
  kEpaP3BadNormal,
  kEpaP3InvalidV4,
  kEpaP3InvalidV5,
  kEpaP3MissingOrigin,
  kEpaP3OriginOnFace,
  kEpaP4MissingOrigin,
};

// A query's limits from the model's options (ccd_iterations, ccd_tolerance) and the MuJoCo
// release it follows (collision_convex.cc).
CcdConfig ModelConfig(const Model& m, int max_contacts, double dist_cutoff);

// The distance between two shapes: positive when apart (a huge value beyond the cutoff),
// negative when penetrating, with witness points in status (MuJoCo's mjc_ccd).
double Collide(const CcdConfig& config, CcdStatus* status, ConvexShape* s1, ConvexShape* s2);

// The contacts of two flat-sided shapes (boxes, meshes with polygons) over the polygon
// where their facing sides overlap, from EPA's nearest face (its three vertices): writes
// them into status (nx, x1, x2) when a face (or an edge) of one lies against a face of
// the other, else leaves EPA's single contact (MuJoCo's multicontact;
// collision_multiccd.cc).
void PolygonContacts(const CcdVertex* const face[3], CcdStatus* status, const ConvexShape& s1,
                     const ConvexShape& s2);

// Geom g as a convex shape inflated by margin/2 (MuJoCo's mjc_initCCDObj;
// collision_convex.cc).
ConvexShape GeomShape(const Model& m, const Data& d, int g, double margin);

// Support functions of a sphere's centre and a capsule's axis segment: GJK runs on these
// first and inflates the answer by the radius (collision_convex.cc).
void CentreSupport(double res[3], ConvexShape* shape, const double dir[3]);
void SegmentSupport(double res[3], ConvexShape* shape, const double dir[3]);

}  // namespace simlab::ccd

namespace simlab {

// One GJK/EPA query of two shapes (collision_convex.cc): up to max_contacts contacts into
// `con`, normals from shape 1 to shape 2, distances less the margin; returns how many.
int QueryContacts(const Model& m, ccd::ConvexShape* s1, ccd::ConvexShape* s2, Contact* con,
                  int max_contacts, double margin);

// A convex shape posed in height field g's frame, whose box there (without its margin)
// is [lo, hi], against the field's prisms under that box (collision_hfield.cc): one
// contact per penetrating prism, normals from the field to the shape; returns how many.
// MuJoCo's prism walk of mjc_ConvexHField and mjc_HFieldElem.
int CollideHFieldShape(const Model& m, const Data& d, Contact* con, int g,
                       ccd::ConvexShape* shape, const double lo[3], const double hi[3],
                       double margin);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_COLLISION_GJK_H_
