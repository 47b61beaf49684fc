// Which narrow-phase function handles which pair of geom types: MuJoCo's table
// (mjCOLLISIONFUNC), by the types of the two geoms in increasing order. As in MuJoCo,
// planes and height fields never touch each other or themselves. A plane meets an sdf
// geom as the convex hull of its mesh, as in MuJoCo's reference build (its 3.5.1
// release skips that pair); hfield-sdf pairs are refused when the model compiles.
#include "engine/collision.h"

namespace simlab {

namespace {

constexpr int kNumGeomTypes = 9;

// Rows: type1, columns: type2 (plane, hfield, sphere, capsule, ellipsoid, cylinder, box,
// mesh, sdf). Null entries: no collision for this pair of types.
const CollideFn kTable[kNumGeomTypes][kNumGeomTypes] = {
    /* plane */ {nullptr, nullptr, CollidePlaneSphere, CollidePlaneCapsule,
                 CollidePlaneConvex, CollidePlaneCylinder, CollidePlaneBox,
                 CollidePlaneConvex, CollidePlaneConvex},
    /* hfield */ {nullptr, nullptr, CollideHFieldConvex, CollideHFieldConvex,
                  CollideHFieldConvex, CollideHFieldConvex, CollideHFieldConvex,
                  CollideHFieldConvex, nullptr},
    /* sphere */ {nullptr, nullptr, CollideSphereSphere, CollideSphereCapsule, CollideConvex,
                  CollideSphereCylinder, CollideSphereBox, CollideConvex, CollideSdf},
    /* capsule */ {nullptr, nullptr, nullptr, CollideCapsuleCapsule, CollideConvex,
                   CollideConvex, CollideCapsuleBox, CollideConvex, CollideSdf},
    /* ellipsoid */ {nullptr, nullptr, nullptr, nullptr, CollideConvex, CollideConvex,
                     CollideConvex, CollideConvex, CollideSdf},
    /* cylinder */ {nullptr, nullptr, nullptr, nullptr, nullptr, CollideConvex,
                    CollideConvex, CollideConvex, CollideSdf},
    /* box */ {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, CollideBoxBox,
               CollideConvex, CollideSdf},
    /* mesh */ {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                CollideConvex, CollideSdf},
    /* sdf */ {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
               CollideSdf},
};

}  // namespace

bool ChoosesTangent(CollideFn collide) {
  return collide == CollidePlaneCapsule || collide == CollideSdf;
}

CollideFn CollisionFunction(int type1, int type2) {
  if (type1 < 0 || type2 < 0 || type1 >= kNumGeomTypes || type2 >= kNumGeomTypes) {
    return nullptr;
  }
  return kTable[type1][type2];
}

}  // namespace simlab
