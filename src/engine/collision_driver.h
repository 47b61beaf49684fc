// What the collision driver (collision_driver.cc) shares with the flex collider
// (collision_flex.cc): contact parameters, margins, filters and room in d.contact.
#ifndef SIMLAB_ENGINE_COLLISION_DRIVER_H_
#define SIMLAB_ENGINE_COLLISION_DRIVER_H_

#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/collision.h"

namespace simlab {

// Condim, gap, solref, solimp and 5-d friction of a contact (MuJoCo mj_contactParam).
struct ContactParams {
  int condim = 3;
  double gap = 0;
  double solref[kNRef] = {0, 0};
  double solreffriction[kNRef] = {0, 0};
  double solimp[kNImp] = {0, 0, 0, 0, 0};
  double friction[5] = {0, 0, 0, 0, 0};
};

// The margin, or the global override's (mj_assignMargin).
double AssignMargin(const Model& m, double margin);
// True when neither side's contype meets the other's conaffinity.
bool BitmaskRejects(int contype1, int conaffinity1, int contype2, int conaffinity2);
// The parameters of a contact between side 1 (geom g1, or flex f1 when f1 >= 0) and
// side 2 (g2, or f2): the higher priority side's, else mixed (mj_contactParam).
ContactParams MixedParams(const Model& m, int g1, int g2, int f1, int f2);
// Fills in a new contact's ids (geoms g1, g2; flexes, elements and vertices -1) and
// parameters, with the global overrides, and completes its frame (mj_setContact).
void SetContact(const Model& m, const ContactParams& p, double includemargin, int g1, int g2,
                Contact* c);
// Room for `n` more contacts past d.ncon; returns the first.
Contact* ContactRoom(Data& d, int n);
// Sorts the contacts [first, d.ncon) by the object of side 0, then of side 1 (a geom,
// else a flex element, else a flex vertex; for geom-geom contacts the geom pair), keeping
// the order of equals (MuJoCo's contactSort after a tree walk).
void SortContacts(Data& d, int first);
// One interval end of a sweep and prune as an integer key that sorts as MuJoCo's sweeps
// do: the value in single precision (a NaN as +inf), then `tie` (>= 0) among equals.
uint64_t SweepKey(double x, int tie);
// Sorts the interval ends of count / 2 intervals into `ends`: ties 0..count-1 (2 i for
// interval i's lower end, + 1 for its upper), key key_of(tie) (a SweepKey; the tie is a
// key's low 32 bits). `ends` keeps the last sort's order between steps: when it holds as
// many ends, their keys are recomputed in that order and insertion-sorted (a step moves
// little: about one pass), falling back to std::sort past 8 count + 64 moves; otherwise
// it starts anew. Keys are unique, so the order is the one std::sort gives.
template <typename KeyOf>
void SortEnds(std::vector<uint64_t>& ends, size_t count, KeyOf key_of) {
  if (ends.size() != count) {
    ends.resize(count);
    for (size_t t = 0; t < count; t++) ends[t] = t;
  }
  for (uint64_t& end : ends) end = key_of(static_cast<uint32_t>(end));
  size_t moves = 0, limit = 8 * count + 64;
  uint64_t* a = ends.data();
  for (size_t i = 1; i < count; i++) {
    uint64_t key = a[i];
    size_t j = i;
    for (; j > 0 && a[j - 1] > key; j--) a[j] = a[j - 1];
    a[j] = key;
    moves += i - j;
    if (moves > limit) {
      std::sort(a, a + count);
      return;
    }
  }
}
// True when two boxes (centre, half sizes; world axes) are farther apart than margin on
// some axis (MuJoCo's filterBox).
// (inline: the flexes' element pairs call it thousands of times a step)
inline bool AxisBoxesApart(const double* aabb1, const double* aabb2, double margin) {
  for (int k = 0; k < 3; k++) {
    if (aabb1[k] + aabb1[k + 3] + margin < aabb2[k] - aabb2[k + 3]) return true;
  }
  for (int k = 0; k < 3; k++) {
    if (aabb2[k] + aabb2[k + 3] + margin < aabb1[k] - aabb1[k + 3]) return true;
  }
  return false;
}
// True when oriented boxes (centre and half sizes in a frame) are apart (mj_collideOBB
// from the boxes' centres; see collision_driver.cc). A null mat is the world's axes, a
// null pos the origin.
bool BoxesApartOriented(const double* aabb1, const double* pos1, const double* mat1,
                        const double* aabb2, const double* pos2, const double* mat2,
                        double margin);

// The box test of a walk over two trees whose nodes sit in two fixed frames (a body's
// inertial frame; null for a flex's, the world's): how each frame's axes and origin
// project on the other's axes, made once at the walk's first test and shared by every
// node pair (MuJoCo's product and offset in mj_collideOBB, with its arithmetic).
class TreeFrames {
 public:
  TreeFrames(const double* pos1, const double* mat1, const double* pos2, const double* mat2);
  // Are node boxes aabb1 (frame 1) and aabb2 (frame 2) farther than margin apart along
  // one of their face normals?
  bool Apart(const double* aabb1, const double* aabb2, double margin);

 private:
  void Make();
  const double* pos_[2];
  const double* mat_[2];
  bool made_ = false;
  double product_[2][2][3][3];  // [i][j][k][l]: axis l of frame i on axis k of frame j
  double offset_[2][2][3];      // [i][j][k]: origin of frame i on axis k of frame j
};

// ---------------------------------------------------------------- flexes (collision_flex.cc)

// Collides a body or flex with a flex: bodyflex ids b1 < b2, b2 >= nbody (a flex
// f = b2 - nbody), as MuJoCo's driver does for such a broad-phase pair.
void CollideWithFlex(const Model& m, Data& d, int b1, int b2);
// Every flex's collisions with itself (internal and between its active elements),
// but a sleeping flex's.
void CollideFlexSelf(const Model& m, Data& d);
// A flex's box in the rows of `frame`: its vertices' extent grown by radius and margin.
void FlexBox(const Model& m, const Data& d, int f, const double* frame, double* lo,
             double* hi);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_COLLISION_DRIVER_H_
