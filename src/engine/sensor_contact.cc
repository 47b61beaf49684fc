// Contact sensors of the acceleration stage (MuJoCo's engine_sensor.c):
//
//   touch     the normal forces of the contacts on the site's body whose force ray,
//             cast from the contact point, meets the site's volume
//   contact   the contacts that match the sensor's two criteria (site volume, geom,
//             body or subtree on each side), reported per slot as the fields of the data
//             mask (found, force, torque, dist, pos, normal, tangent), either as found,
//             the nearest or strongest first, or summed into one net wrench
//
// Forces come from efc_force through ContactForce (MuJoCo's mj_contactForce).
#include <algorithm>

#include "engine/engine.h"
#include "engine/ray.h"
#include "engine/sensor.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// ---------------------------------------------------------------- touch

// The body of a contact's side k, or -1 for a side without a geom.
int ContactBody(const Model& m, const Contact& con, int k) {
  return con.geom[k] >= 0 ? m.geom_bodyid[con.geom[k]] : -1;
}

// Whether the ray from the contact point along the normal force (pointing away from
// the sensor's body) meets the site's volume.
bool ForceRayHitsSite(const Model& m, const Data& d, int site, const Contact& con,
                      double normal_force, bool flip) {
  double ray[3];
  Scale3(ray, con.frame, normal_force);
  Normalize3(ray);
  if (flip) Scale3(ray, ray, -1);
  return RayPrimitive(&d.site_xpos[3 * site], &d.site_xmat[9 * site], &m.site_size[3 * site],
                      con.pos, ray, m.site_type[site], nullptr) >= 0;
}

// ---------------------------------------------------------------- contact matching

// Reductions of a contact sensor (its second integer parameter).
enum Reduce { kReduceNone = 0, kReduceMinDist = 1, kReduceMaxForce = 2, kReduceNetForce = 3 };

// Whether one side of a contact (its body and geom) meets one criterion of the sensor.
// A site criterion was checked on the contact's position already; a subtree (xbody)
// criterion holds for the body and all its descendants.
bool SideMatches(const Model& m, int body, int geom, int type, int id) {
  switch (type) {
    case kObjUnknown:
    case kObjSite: return true;
    case kObjGeom: return id == geom;
    case kObjBody: return id == body;
    case kObjXBody:
      while (body > id) body = m.body_parentid[body];
      return body == id;
    default: return false;
  }
}

// How contact c matches the criteria (type1, id1) and (type2, id2): 0 not at all, 1 as
// it is, -1 with its sides swapped (the sensor then reports the opposite normal).
int MatchContact(const Model& m, const Data& d, int c, int type1, int id1, int type2,
                 int id2) {
  if (type1 == kObjUnknown && type2 == kObjUnknown) return 1;
  const Contact& con = d.contact[c];
  if (type1 == kObjSite &&
      !InsideShape(&d.site_xpos[3 * id1], &d.site_xmat[9 * id1], &m.site_size[3 * id1],
                   m.site_type[id1], con.pos)) {
    return 0;
  }

  // Each criterion must hold on at least one side.
  int body1 = ContactBody(m, con, 0), body2 = ContactBody(m, con, 1);
  bool m11 = SideMatches(m, body1, con.geom[0], type1, id1);
  bool m12 = SideMatches(m, body2, con.geom[1], type1, id1);
  bool m21 = SideMatches(m, body1, con.geom[0], type2, id2);
  bool m22 = SideMatches(m, body2, con.geom[1], type2, id2);
  if ((!m11 && !m12) || (!m21 && !m22)) return 0;

  // Direction: with both criteria, the order that holds (as it is when both do);
  // with one, the side it names comes first.
  if (type1 != kObjUnknown && type2 != kObjUnknown) {
    bool regular = m11 && m22, reverse = m12 && m21;
    if (regular) return 1;
    return reverse ? -1 : 0;
  }
  if (type1 != kObjUnknown) return m11 ? 1 : -1;
  return m22 ? 1 : -1;
}

// Where each field of the data mask goes in one slot (null when not reported), and
// the numbers a slot takes.
struct SlotLayout {
  double* field[kNConData] = {};
  int size = 0;
};

SlotLayout MakeSlotLayout(int mask, double* out) {
  static const int kWidths[kNConData] = {1, 3, 3, 1, 3, 3, 3};
  SlotLayout slot;
  for (int k = 0; k < kNConData; k++) {
    if (!(mask & (1 << k))) continue;
    slot.field[k] = out + slot.size;
    slot.size += kWidths[k];
  }
  return slot;
}

// One slot: contact c's fields. A swapped contact reports the opposite normal and
// tangent, and the opposite normal components of force and torque.
void FillSlot(const Model& m, const Data& d, const SlotLayout& slot, int c, bool flip,
              int nfound) {
  const Contact& con = d.contact[c];
  double* const* f = slot.field;
  if (f[kConDataFound]) f[kConDataFound][0] = nfound;
  if (f[kConDataForce] || f[kConDataTorque]) {
    double wrench[6];
    ContactForce(m, d, c, wrench);
    if (flip) wrench[2] = -wrench[2], wrench[5] = -wrench[5];
    if (f[kConDataForce]) Copy3(f[kConDataForce], wrench);
    if (f[kConDataTorque]) Copy3(f[kConDataTorque], wrench + 3);
  }
  if (f[kConDataDist]) f[kConDataDist][0] = con.dist;
  if (f[kConDataPos]) Copy3(f[kConDataPos], con.pos);
  double sign = flip ? -1 : 1;
  if (f[kConDataNormal]) Scale3(f[kConDataNormal], con.frame, sign);
  if (f[kConDataTangent]) Scale3(f[kConDataTangent], con.frame + 3, sign);
}

// The net reduction, written to the first slot: the matching contacts' total wrench
// about their force-weighted centroid, in the world frame. `match` holds each contact's
// match (0: none, else +-1).
void NetForce(const Model& m, Data& d, const SlotLayout& slot, const double* match, int nmatch) {
  // Each matching contact's wrench in its own frame, negated when swapped, and the
  // centroid weighted by its force magnitude.
  StackFrame frame(d);
  double* wrench = frame.Alloc(6 * static_cast<size_t>(d.ncon));
  double point[3] = {0, 0, 0}, total = 0;
  for (int c = 0; c < d.ncon; c++) {
    if (match[c] == 0) continue;
    double* w = wrench + 6 * c;
    ContactForce(m, d, c, w);
    if (match[c] < 0) {
      for (int k = 0; k < 6; k++) w[k] = -w[k];
    }
    double weight = Norm3(w);
    AddScaled3(point, d.contact[c].pos, weight);
    total += weight;
  }
  Scale3(point, point, 1 / std::max(total, kMinVal));

  // Forces, torques (world frame) and the moments of the forces about the centroid.
  double net_force[3] = {0, 0, 0}, net_torque[3] = {0, 0, 0};
  for (int c = 0; c < d.ncon; c++) {
    if (match[c] == 0) continue;
    double force[3], torque[3], arm[3], moment[3];
    MulMatTVec3(force, d.contact[c].frame, wrench + 6 * c);
    MulMatTVec3(torque, d.contact[c].frame, wrench + 6 * c + 3);
    Add3(net_force, net_force, force);
    Add3(net_torque, net_torque, torque);
    Sub3(arm, d.contact[c].pos, point);
    Cross3(moment, arm, force);
    Add3(net_torque, net_torque, moment);
  }

  double* const* f = slot.field;
  if (f[kConDataFound]) f[kConDataFound][0] = nmatch;
  if (f[kConDataForce]) Copy3(f[kConDataForce], net_force);
  if (f[kConDataTorque]) Copy3(f[kConDataTorque], net_torque);
  if (f[kConDataPos]) Copy3(f[kConDataPos], point);
  if (f[kConDataNormal]) f[kConDataNormal][0] = 1;
  if (f[kConDataTangent]) f[kConDataTangent][1] = 1;
}

// The sorted reductions' order: smaller criterion first, then lower contact index.
bool Before(const double* criterion, int a, int b) {
  if (criterion[a] != criterion[b]) return criterion[a] < criterion[b];
  return a < b;
}

// The next contact in that order after `prev` (-1: the first) among the matching ones,
// or -1 when none is left.
int NextInOrder(const Data& d, const double* match, const double* criterion, int prev) {
  int best = -1;
  for (int c = 0; c < d.ncon; c++) {
    if (match[c] == 0 || (prev >= 0 && !Before(criterion, prev, c))) continue;
    if (best < 0 || Before(criterion, c, best)) best = c;
  }
  return best;
}

}  // namespace

// ---------------------------------------------------------------- sensors

void TouchSensor(const Model& m, Data& d, int i, double* out) {
  int site = m.sensor_objid[i];
  int body = m.site_bodyid[site];
  out[0] = 0;
  for (int c = 0; c < d.ncon; c++) {
    // Contacts with rows on the site's body, pressing (positive normal force).
    const Contact& con = d.contact[c];
    int body1 = ContactBody(m, con, 0), body2 = ContactBody(m, con, 1);
    if (con.efc_address < 0 || (body != body1 && body != body2)) continue;
    double wrench[6];
    ContactForce(m, d, c, wrench);
    if (wrench[0] <= 0) continue;
    if (ForceRayHitsSite(m, d, site, con, wrench[0], body == body2)) out[0] += wrench[0];
  }
}

void ContactSensor(const Model& m, Data& d, int i, double* out) {
  const int* intprm = &m.sensor_intprm[kNSens * i];
  int reduce = intprm[1];
  std::fill(out, out + m.sensor_dim[i], 0.0);
  SlotLayout slot = MakeSlotLayout(intprm[0], out);
  if (slot.size == 0) return;
  int nslot_max = m.sensor_dim[i] / slot.size;

  // Each contact's match and, for the sorted reductions, its sort key: the distance,
  // or the negated squared force magnitude (strongest first).
  StackFrame frame(d);
  double* match = frame.Alloc(d.ncon);
  double* criterion = frame.Alloc(d.ncon);
  int nmatch = 0;
  for (int c = 0; c < d.ncon; c++) {
    match[c] = MatchContact(m, d, c, m.sensor_objtype[i], m.sensor_objid[i],
                            m.sensor_reftype[i], m.sensor_refid[i]);
    if (match[c] == 0) continue;
    nmatch++;
    if (reduce == kReduceMinDist) criterion[c] = d.contact[c].dist;
    if (reduce == kReduceMaxForce) {
      double wrench[6];
      ContactForce(m, d, c, wrench);
      criterion[c] = -Dot3(wrench, wrench);
    }
  }
  if (reduce == kReduceNetForce) return NetForce(m, d, slot, match, nmatch);

  // The slots: matching contacts in their order, or the first ones in sort order.
  bool sorted = reduce == kReduceMinDist || reduce == kReduceMaxForce;
  int c = -1;
  for (int s = 0; s < std::min(nslot_max, nmatch); s++) {
    if (sorted) {
      c = NextInOrder(d, match, criterion, c);
    } else {
      do c++; while (match[c] == 0);
    }
    FillSlot(m, d, slot, c, match[c] < 0, nmatch);
    for (double*& field : slot.field) {
      if (field) field += slot.size;
    }
  }
}

}  // namespace simlab
