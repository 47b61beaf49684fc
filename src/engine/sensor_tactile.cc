// The tactile sensor (MuJoCo 3.5's mjSENS_TACTILE): the vertices of a mesh, placed on a
// geom, are taxels. For every geom in contact with the geom's weld body, each taxel
// that lies inside that geom (by its signed distance function) reports a pressure and
// its slip speeds along its two tangents. sensordata holds three channels of one number
// per taxel: pressure, |slip along tangent 1|, |slip along tangent 2|.
#include <cmath>
#include <string>

#include "engine/collision.h"
#include "engine/sensor.h"
#include "engine/stack.h"
#include "math/math.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

// MuJoCo's min, max and clip (their tie and NaN behaviour kept).
double MinOf(double a, double b) { return a <= b ? a : b; }
double MaxOf(double a, double b) { return a >= b ? a : b; }
double ClipTo(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

// ---------------------------------------------------------------- signed distances

// Unit field pointing from the box centre towards its surface, bent from radial to the
// face normals (a = |x| - size per axis, all negative inside).
void BoxRadialField(double field[3], const double a[3], const double x[3], const double* size) {
  for (int k = 0; k < 3; k++) field[k] = -size[k] / a[k];
  math::Normalize3(field);
  for (int k = 0; k < 3; k++) {
    if (x[k] < 0) field[k] = -field[k];
  }
}

// Box: the Euclidean distance outside; inside, how far the radial field's ray goes
// before it leaves through a face (negative).
double BoxDistance(const double x[3], const double* size) {
  double a[3] = {std::abs(x[0]) - size[0], std::abs(x[1]) - size[1], std::abs(x[2]) - size[2]};
  double b[3];
  if (a[0] >= 0 || a[1] >= 0 || a[2] >= 0) {
    for (int k = 0; k < 3; k++) b[k] = MaxOf(a[k], 0);
    return math::Norm3(b) + MinOf(MaxOf(a[0], MaxOf(a[1], a[2])), 0);
  }
  BoxRadialField(b, a, x, size);
  double t[3];
  for (int k = 0; k < 3; k++) t[k] = -a[k] / std::abs(b[k]);
  return -MinOf(t[0], MinOf(t[1], t[2])) * math::Norm3(b);
}

double CapsuleDistance(const double x[3], const double* size) {
  double a[3] = {x[0], x[1], x[2] - ClipTo(x[2], -size[1], size[1])};
  return math::Norm3(a) - size[0];
}

// Ellipsoid: the first-order distance k0 (k0 - 1) / k1 of the scaled radii.
double EllipsoidDistance(const double x[3], const double* size) {
  double a[3], b[3];
  for (int k = 0; k < 3; k++) {
    a[k] = x[k] / size[k];
    b[k] = a[k] / size[k];
  }
  double k0 = math::Norm3(a), k1 = math::Norm3(b);
  return k0 * (k0 - 1.0) / k1;
}

double CylinderDistance(const double x[3], const double* size) {
  double a[2] = {std::sqrt(x[0] * x[0] + x[1] * x[1]) - size[0], std::abs(x[2]) - size[1]};
  double b[2] = {MaxOf(a[0], 0), MaxOf(a[1], 0)};
  return MinOf(MaxOf(a[0], a[1]), 0) + std::sqrt(b[0] * b[0] + b[1] * b[1]);
}

// Signed distance from a point in geom g's frame to its surface (negative inside), as
// MuJoCo's analytic SDFs of the primitive shapes.
double PrimitiveDistance(const Model& m, int g, const double x[3]) {
  const double* size = &m.geom_size[3 * g];
  switch (m.geom_type[g]) {
    case kGeomPlane: return x[2];
    case kGeomSphere: return math::Norm3(x) - size[0];
    case kGeomBox: return BoxDistance(x, size);
    case kGeomCapsule: return CapsuleDistance(x, size);
    case kGeomEllipsoid: return EllipsoidDistance(x, size);
    default: return CylinderDistance(x, size);
  }
}

// The signed distance of any geom the sensor can read: an sdf geom's field (`field`, its
// plugin's if it has one), a mesh's octree, or a primitive's function.
double GeomDistance(const Model& m, const SdfField& field, int g, const double x[3]) {
  switch (m.geom_type[g]) {
    case kGeomSdf: return SdfGeomDistance(m, field, m.geom_dataid[g], x);
    case kGeomMesh: return MeshOctreeDistance(m, m.geom_dataid[g], x);
    default: return PrimitiveDistance(m, g, x);
  }
}

// ---------------------------------------------------------------- touching geoms

// The geom on the other side of contact k from the weld body, for side 0 (geom1 on the
// body: geom2) and side 1 (geom2 on the body: geom1); -1 when that side is not the body.
// Contacts with a flex (geom -1 on its side) are not read: MuJoCo reads past its arrays
// there.
int OtherGeom(const Model& m, const Data& d, int k, int side, int weld) {
  const Contact& c = d.contact[k];
  if (c.geom1 < 0 || c.geom2 < 0) return -1;
  int mine = side == 0 ? c.geom1 : c.geom2;
  if (m.body_weldid[m.geom_bodyid[mine]] != weld) return -1;
  return side == 0 ? c.geom2 : c.geom1;
}

// Whether geom g already came up at an earlier contact or side (each touching geom is
// visited once, in the order it first appears).
bool SeenBefore(const Model& m, const Data& d, int k, int side, int weld, int g) {
  for (int j = 0; j <= k; j++) {
    for (int s = 0; s < 2 && (j < k || s < side); s++) {
      if (OtherGeom(m, d, j, s, weld) == g) return true;
    }
  }
  return false;
}

// MuJoCo stops with an error when a height field touches the sensor (it has no signed
// distance); simlab throws.
void CheckHasDistance(const Model& m, int i, int g) {
  if (m.geom_type[g] != kGeomHfield) return;
  throw Error("tactile sensor '" + m.sensor_names[i] + "': geom " + std::to_string(g) +
              " is a height field, which has no signed distance function (MuJoCo stops "
              "with an error here too)");
}

// ---------------------------------------------------------------- taxels

// Taxel frame: normal and two tangents of mesh vertex j (9 floats per vertex), rotated
// by the mesh's inertial-frame quaternion as MuJoCo does.
void TaxelFrame(const Model& m, int mesh, int j, double frame[9]) {
  const double* stored = &m.mesh_normal[3 * m.mesh_normaladr[mesh] + 9 * j];
  const double* quat = &m.mesh_quat[4 * mesh];
  for (int k = 0; k < 3; k++) math::RotVecQuat(frame + 3 * k, stored + 3 * k, quat);
}

// Linear velocity of a point moving with body b (from its cvel about its tree's com).
void PointVelocity(const Model& m, const Data& d, int b, const double* point, double vel[3]) {
  double moved[6];
  math::TransformSpatial(moved, &d.cvel[6 * b], false, point,
                         &d.subtree_com[3 * m.body_rootid[b]], nullptr);
  math::Copy3(vel, moved + 3);
}

// Writes the three channels of every taxel inside `other` (ncon = taxel count), leaving
// the other taxels as they are.
void TouchOneGeom(const Model& m, const Data& d, int i, int other, double* channels) {
  int mesh = m.sensor_objid[i], geom = m.sensor_refid[i];
  int weld = m.body_weldid[m.geom_bodyid[geom]];
  int ntaxel = m.mesh_vertnum[mesh];
  const double* vert = &m.mesh_vert[3 * m.mesh_vertadr[mesh]];
  const double* geom_pos = &d.geom_xpos[3 * geom];
  const double* geom_mat = &d.geom_xmat[9 * geom];
  const double* other_pos = &d.geom_xpos[3 * other];
  const double* other_mat = &d.geom_xmat[9 * other];
  const SdfField field = SdfFieldOfGeom(m, d, other);
  for (int j = 0; j < ntaxel; j++) {
    // The taxel in the world, then in the other geom's frame.
    double xpos[3], rel[3], local[3];
    math::MulMatVec3(xpos, geom_mat, vert + 3 * j);
    math::Add3(xpos, xpos, geom_pos);
    math::Sub3(rel, xpos, other_pos);
    math::MulMatTVec3(local, other_mat, rel);
    double dist = GeomDistance(m, field, other, local);
    double depth = dist < 0 ? dist : 0;  // MuJoCo's min(dist, 0)
    if (depth == 0) continue;

    // Slip: the taxel's velocity on the weld body relative to the other geom's centre.
    double vel_sensor[3], vel_other[3], slip[3];
    PointVelocity(m, d, weld, xpos, vel_sensor);
    PointVelocity(m, d, m.geom_bodyid[other], other_pos, vel_other);
    math::Sub3(slip, vel_sensor, vel_other);

    // Pressure along the normal, saturating as the depth nears 5 cm.
    double frame[9], force[3];
    TaxelFrame(m, mesh, j, frame);
    double pressure = depth / MaxOf(0.05 - depth, kMinVal);
    for (int k = 0; k < 3; k++) force[k] = frame[k] * pressure;
    channels[j] = math::Dot3(force, frame);
    channels[ntaxel + j] = std::abs(math::Dot3(slip, frame + 3));
    channels[2 * ntaxel + j] = std::abs(math::Dot3(slip, frame + 6));
  }
}

}  // namespace

void TactileSensor(const Model& m, Data& d, int i, double* out) {
  int dim = m.sensor_dim[i];
  for (int k = 0; k < dim; k++) out[k] = 0;
  int weld = m.body_weldid[m.geom_bodyid[m.sensor_refid[i]]];
  StackFrame frame(d);
  double* channels = nullptr;

  // Every geom touching the weld body, once, in the order of the contacts; mesh geoms
  // without an octree (MuJoCo builds one only for meshes of sdf geoms) are skipped as in
  // MuJoCo.
  for (int k = 0; k < d.ncon; k++) {
    for (int side = 0; side < 2; side++) {
      int other = OtherGeom(m, d, k, side, weld);
      if (other < 0 || SeenBefore(m, d, k, side, weld, other)) continue;
      if (m.geom_type[other] == kGeomMesh && m.mesh_octnum[m.geom_dataid[other]] == 0) continue;
      CheckHasDistance(m, i, other);
      if (!channels) channels = frame.Alloc(dim);
      TouchOneGeom(m, d, i, other, channels);
    }
  }
  if (!channels) return;

  // A channel that stayed all zero is left out (MuJoCo adds only non-zero channels).
  int ntaxel = m.mesh_vertnum[m.sensor_objid[i]];
  for (int c = 0; c < 3; c++) {
    const double* channel = channels + c * ntaxel;
    bool all_zero = true;
    for (int j = 0; j < ntaxel && all_zero; j++) all_zero = channel[j] == 0;
    if (all_zero) continue;
    for (int j = 0; j < ntaxel; j++) out[c * ntaxel + j] += channel[j];
  }
}

}  // namespace simlab
