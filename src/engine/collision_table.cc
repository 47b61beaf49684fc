// Which narrow-phase function handles which pair of geom types: MuJoCo's table
// (mjCOLLISIONFUNC), by the types of the two geoms in increasing order. As in MuJoCo,
// planes and height fields never touch each other or themselves; SDFs have no
// functions yet, so their pairs make no contacts.
#include "engine/collision.h"

namespace simlab {

namespace {

constexpr int kNumGeomTypes = 9;

// Rows: type1, columns: type2 (plane, hfield, sphere, capsule, ellipsoid, cylinder, box,
// mesh, sdf). Null entries: no collision for this pair of types.
const CollideFn kTable[kNumGeomTypes][kNumGeomTypes] = {
    /* plane */ {nullptr, nullptr, CollidePlaneSphere, CollidePlaneCapsule,
                 CollidePlaneConvex, CollidePlaneCylinder, CollidePlaneBox,
                 CollidePlaneConvex, nullptr},
    /* hfield */ {nullptr, nullptr, CollideHFieldConvex, CollideHFieldConvex,
                  CollideHFieldConvex, CollideHFieldConvex, CollideHFieldConvex,
                  CollideHFieldConvex, nullptr},
    /* sphere */ {nullptr, nullptr, CollideSphereSphere, CollideSphereCapsule, CollideConvex,
                  CollideSphereCylinder, CollideSphereBox, CollideConvex, nullptr},
    /* capsule */ {nullptr, nullptr, nullptr, CollideCapsuleCapsule, CollideConvex,
                   CollideConvex, CollideCapsuleBox, CollideConvex, nullptr},
    /* ellipsoid */ {nullptr, nullptr, nullptr, nullptr, CollideConvex, CollideConvex,
                     CollideConvex, CollideConvex, nullptr},
    /* cylinder */ {nullptr, nullptr, nullptr, nullptr, nullptr, CollideConvex,
                    CollideConvex, CollideConvex, nullptr},
    /* box */ {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, CollideBoxBox,
               CollideConvex, nullptr},
    /* mesh */ {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
                CollideConvex, nullptr},
    /* sdf */ {nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr,
               nullptr},
};

}  // namespace

bool ChoosesTangent(CollideFn collide) { return collide == CollidePlaneCapsule; }

CollideFn CollisionFunction(int type1, int type2) {
  if (type1 < 0 || type2 < 0 || type1 >= kNumGeomTypes || type2 >= kNumGeomTypes) {
    return nullptr;
  }
  return kTable[type1][type2];
}

}  // namespace simlab
