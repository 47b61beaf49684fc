// The narrow phase of flexes (collision_flex_narrow.cc), for the flex collider
// (collision_flex.cc): shapes a flex is made of against geoms and each other.
//
// A flex element is a capsule (dim 1, its two vertices), a triangle (dim 2) or a
// tetrahedron (dim 3), each rounded by the flex radius; a vertex is a sphere of that
// radius. Each function writes up to kMaxContactPair contacts (dist, pos, the normal in
// frame[0..2] pointing from the first shape to the second, frame[3..5] zero) and
// returns how many.
#ifndef SIMLAB_ENGINE_COLLISION_FLEX_H_
#define SIMLAB_ENGINE_COLLISION_FLEX_H_

#include "engine/collision.h"

namespace simlab {

// A sphere (centre s, radius rs) and a triangle t1 t2 t3 rounded by rt (mjraw_SphereTriangle).
int SphereTriangle(Contact* con, double margin, const double* s, double rs, const double* t1,
                   const double* t2, const double* t3, double rt);
// A box (pos, mat, size) and a rounded triangle: the triangle's corners against the box's
// faces, then the box's corners against the triangle (mjraw_BoxTriangle).
int BoxTriangle(Contact* con, double margin, const double* pos, const double* mat,
                const double* size, const double* t1, const double* t2, const double* t3,
                double rt);
// A capsule (pos, mat, size) and a rounded triangle: its two end spheres against the
// triangle, the triangle's corners against its segment (mjraw_CapsuleTriangle).
int CapsuleTriangle(Contact* con, double margin, const double* pos, const double* mat,
                    const double* size, const double* t1, const double* t2, const double* t3,
                    double rt);

// Convex collision by GJK/EPA of side 1 (geom g1, or vertex v1 of flex f1, or element e1
// of f1) with element e2 of flex f2 (mjc_ConvexElem); against a triangle, the normal is
// taken from a rounded geom's surface (mjc_fixNormal).
int ConvexElem(const Model& m, const Data& d, Contact* con, int g1, int f1, int e1, int v1,
               int f2, int e2, double margin);

// Height field g against element e of flex f (mjc_HFieldElem): the element, in the
// field's frame, against the prisms under its vertices' box, one contact per penetrating
// prism (collision_hfield.cc's walk).
int HFieldElem(const Model& m, const Data& d, Contact* con, int g, int f, int e,
               double margin);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_COLLISION_FLEX_H_
