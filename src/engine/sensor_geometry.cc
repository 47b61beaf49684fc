// Geometric sensors of the position stage (MuJoCo's engine_sensor.c, with
// mj_geomDistance of engine_support.c and mju_insideGeom of engine_util_misc.c):
//
//   camprojection   where a site appears in a camera's image, in pixels
//   insidesite      1 when an object's position lies inside a site's shape
//   distance/normal/fromto
//                   the smallest signed distance between two geoms (or all geoms of two
//                   bodies), the unit normal and the segment between the nearest points,
//                   by the narrow phase run with the sensor's cutoff as margin
#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/collision.h"
#include "engine/collision_gjk.h"
#include "engine/sensor.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

// ---------------------------------------------------------------- camprojection

// Focal lengths in pixels: from the physical sensor (single precision, as MuJoCo
// computes them), else from the vertical field of view.
void FocalPixels(const Model& m, int cam, double* fx, double* fy) {
  const double* size = &m.cam_sensorsize[2 * cam];
  const double* intrinsic = &m.cam_intrinsic[4 * cam];
  const int* res = &m.cam_resolution[2 * cam];
  if (size[0] != 0 && size[1] != 0) {
    *fx = static_cast<float>(intrinsic[0]) / static_cast<float>(size[0]) * static_cast<float>(res[0]);
    *fy = static_cast<float>(intrinsic[1]) / static_cast<float>(size[1]) * static_cast<float>(res[1]);
  } else {
    *fx = *fy = 0.5 / std::tan(m.cam_fovy[cam] * std::numbers::pi / 360.0) * res[1];
  }
}

// The pinhole projection of a world point: into the camera frame, then image x grows
// to the right (the camera looks along -z) and y upward, centred on the image.
void ProjectPoint(const Model& m, const Data& d, int cam, const double* point, double* pixel) {
  double rel[3], local[3];
  Sub3(rel, point, &d.cam_xpos[3 * cam]);
  MulMatTVec3(local, &d.cam_xmat[9 * cam], rel);
  double fx, fy;
  FocalPixels(m, cam, &fx, &fy);
  double cx = m.cam_resolution[2 * cam] / 2.0;
  double cy = m.cam_resolution[2 * cam + 1] / 2.0;
  double u = -fx * local[0] + cx * local[2];
  double v = fy * local[1] + cy * local[2];

  // A point in the camera's plane would divide by zero: keep the depth's sign, away from 0.
  double w = local[2];
  if (std::abs(w) < kMinVal) w = w < 0 ? -kMinVal : kMinVal;
  pixel[0] = u / w;
  pixel[1] = v / w;
}

}  // namespace

// ---------------------------------------------------------------- insidesite

bool InsideShape(const double* pos, const double* mat, const double* size, int type,
                 const double* point) {
  double rel[3], p[3];
  Sub3(rel, point, pos);
  if (type == kGeomSphere) return Dot3(rel, rel) < size[0] * size[0];
  MulMatTVec3(p, mat, rel);
  switch (type) {
    case kGeomCapsule: {
      double beyond = p[2] - std::clamp(p[2], -size[1], size[1]);
      return p[0] * p[0] + p[1] * p[1] + beyond * beyond < size[0] * size[0];
    }
    case kGeomEllipsoid:
      return p[0] * p[0] / (size[0] * size[0]) + p[1] * p[1] / (size[1] * size[1]) +
                 p[2] * p[2] / (size[2] * size[2]) < 1;
    case kGeomCylinder:
      return std::abs(p[2]) < size[1] && p[0] * p[0] + p[1] * p[1] < size[0] * size[0];
    case kGeomBox:
      return std::abs(p[0]) < size[0] && std::abs(p[1]) < size[1] && std::abs(p[2]) < size[2];
    case kGeomPlane:
      return p[2] < 0;
    default:
      return false;
  }
}

namespace {

// ---------------------------------------------------------------- geom distance

// Distance by the native convex collider, which reports witness points directly.
double ConvexDistance(const Model& m, const Data& d, int g1, int g2, double distmax,
                      double fromto[6]) {
  ccd::CcdConfig config = ccd::ModelConfig(m, 1, distmax);
  ccd::ConvexShape s1 = ccd::GeomShape(m, d, g1, 0);
  ccd::ConvexShape s2 = ccd::GeomShape(m, d, g2, 0);
  ccd::CcdStatus status;
  double dist = ccd::Collide(config, &status, &s1, &s2);
  // Witness points exist only within the cutoff; beyond it the distance is the cutoff.
  if (status.nx > 0) {
    Copy3(fromto, status.x1);
    Copy3(fromto + 3, status.x2);
  }
  return dist < distmax ? dist : distmax;
}

// The geoms a distance sensor's object stands for: one geom, or all of a body's.
void GeomRange(const Model& m, int objtype, int objid, int* first, int* count) {
  if (objtype == kObjBody) {
    *first = m.body_geomadr[objid];
    *count = m.body_geomnum[objid];
  } else {
    *first = objid;
    *count = 1;
  }
}

}  // namespace

double GeomDistance(const Model& m, const Data& d, int geom1, int geom2, double distmax,
                    double fromto[6], Contact* con) {
  std::fill(fromto, fromto + 6, 0.0);

  // The narrow phase takes the geom of the smaller type first.
  bool flip = m.geom_type[geom1] > m.geom_type[geom2];
  int g1 = flip ? geom2 : geom1;
  int g2 = flip ? geom1 : geom2;
  CollideFn collide = CollisionFunction(m.geom_type[g1], m.geom_type[g2]);
  if (!collide) return distmax;
  bool native_ccd = !(m.opt.disableflags & kDisableNativeccd);
  if (native_ccd && (collide == CollideConvex || collide == CollideBoxBox)) {
    return ConvexDistance(m, d, geom1, geom2, distmax, fromto);
  }

  // Contacts within distmax; the closest one gives the distance and the segment,
  // oriented from geom1 to geom2.
  int n = collide(m, d, con, g1, g2, distmax);
  double dist = distmax;
  int closest = -1;
  for (int k = 0; k < n; k++) {
    if (con[k].dist < dist) {
      dist = con[k].dist;
      closest = k;
    }
  }
  if (closest >= 0) {
    double half = 0.5 * (flip ? -1 : 1) * dist;
    const Contact& c = con[closest];
    for (int k = 0; k < 3; k++) {
      fromto[k] = c.pos[k] - half * c.frame[k];
      fromto[3 + k] = c.pos[k] + half * c.frame[k];
    }
  }
  return dist;
}

void CamProjectionSensor(const Model& m, Data& d, int i, double* out) {
  ProjectPoint(m, d, m.sensor_refid[i], &d.site_xpos[3 * m.sensor_objid[i]], out);
}

void InsideSiteSensor(const Model& m, Data& d, int i, double* out) {
  int site = m.sensor_refid[i];
  ObjectFrame obj = GetObjectFrame(m, d, m.sensor_objtype[i], m.sensor_objid[i]);
  out[0] = InsideShape(&d.site_xpos[3 * site], &d.site_xmat[9 * site], &m.site_size[3 * site],
                       m.site_type[site], obj.pos);
}

void GeomDistanceSensor(const Model& m, Data& d, int i, double* out) {
  // Every pair of the two objects' geoms; the closest pair within the cutoff wins.
  double cutoff = m.sensor_cutoff[i];
  double dist = cutoff;
  double fromto[6] = {0, 0, 0, 0, 0, 0};
  int first1, count1, first2, count2;
  GeomRange(m, m.sensor_objtype[i], m.sensor_objid[i], &first1, &count1);
  GeomRange(m, m.sensor_reftype[i], m.sensor_refid[i], &first2, &count2);
  // The narrow phase writes into scratch kept in Data, not a fresh (zero-filled) array.
  if (d.distance_scratch.size() < kMaxContactPair) d.distance_scratch.resize(kMaxContactPair);
  Contact* con = d.distance_scratch.data();
  for (int g1 = first1; g1 < first1 + count1; g1++) {
    for (int g2 = first2; g2 < first2 + count2; g2++) {
      double pair_fromto[6];
      double pair_dist = GeomDistance(m, d, g1, g2, cutoff, pair_fromto, con);
      if (pair_dist < dist) {
        dist = pair_dist;
        std::copy(pair_fromto, pair_fromto + 6, fromto);
      }
    }
  }

  switch (m.sensor_type[i]) {
    case kSensGeomDist:
      out[0] = dist;
      break;
    case kSensGeomNormal: {
      double normal[3];
      Sub3(normal, fromto + 3, fromto);
      if (normal[0] != 0 || normal[1] != 0 || normal[2] != 0) Normalize3(normal);
      Copy3(out, normal);
      break;
    }
    default:
      std::copy(fromto, fromto + 6, out);
  }
}

}  // namespace simlab
