// Rangefinder sensors (MuJoCo's mjSENS_RANGEFINDER): one ray along a site's z axis, or
// one ray per pixel of a camera (perspective: from the camera through the pixel
// centre; orthographic: parallel to the view axis from the pixel's place on the image
// plane). Each ray writes the fields its data mask selects, in the order dist, dir,
// origin, point, normal, depth. The sensor's own body is invisible to its rays.
#include <cmath>
#include <numbers>

#include "engine/ray.h"
#include "engine/sensor.h"
#include "math/math.h"

namespace simlab {

namespace {

constexpr int kOrthographic = 1;  // cam_projection of an orthographic camera

bool Has(int mask, int field) { return mask & (1 << field); }

// One ray's numbers at out; returns the position after them. cam_z (the camera's z
// axis, null for a site) turns depth into the distance along the view axis.
double* WriteRay(double* out, int mask, double dist, const double origin[3], const double dir[3],
                 const double normal[3], const double cam_pos[3], const double cam_z[3]) {
  const bool hit = dist >= 0;
  double point[3] = {0, 0, 0};
  if (hit) {
    for (int k = 0; k < 3; k++) point[k] = origin[k] + dist * dir[k];
  }
  auto put3 = [&out](const double* v, bool keep) {
    for (int k = 0; k < 3; k++) *out++ = keep ? v[k] : 0;
  };
  if (Has(mask, kRayDataDist)) *out++ = dist;
  if (Has(mask, kRayDataDir)) put3(dir, hit);
  if (Has(mask, kRayDataOrigin)) put3(origin, true);
  if (Has(mask, kRayDataPoint)) put3(point, true);
  if (Has(mask, kRayDataNormal)) put3(normal, hit);
  if (Has(mask, kRayDataDepth)) {
    if (!hit) {
      *out++ = -1;
    } else if (cam_z) {
      double rel[3];
      math::Sub3(rel, point, cam_pos);
      *out++ = -math::Dot3(rel, cam_z);
    } else {
      *out++ = dist;
    }
  }
  return out;
}

// Pixel geometry of a camera (mju_camIntrinsics): focal lengths and principal point
// in pixels; for orthographic cameras fovy is the image height in length units.
struct PixelGeometry {
  double fx, fy, cx, cy, extent;
};

PixelGeometry CameraPixels(const Model& m, int cam) {
  const int width = m.cam_resolution[2 * cam], height = m.cam_resolution[2 * cam + 1];
  const double* sensor = &m.cam_sensorsize[2 * cam];
  const double* intr = &m.cam_intrinsic[4 * cam];
  PixelGeometry p{0, 0, 0, 0, m.cam_fovy[cam]};
  if (m.cam_projection[cam] == kOrthographic) {
    p.fx = p.cx = width / 2.0;
    p.fy = p.cy = height / 2.0;
  } else if (sensor[0] != 0 && sensor[1] != 0) {
    // MuJoCo stores intrinsics and sensor size as floats and computes these in float.
    auto f = [](double v) { return static_cast<float>(v); };
    p.fx = f(intr[0]) / f(sensor[0]) * f(width);
    p.fy = f(intr[1]) / f(sensor[1]) * f(height);
    p.cx = f(intr[2]) / f(sensor[0]) * f(width);
    p.cy = f(intr[3]) / f(sensor[1]) * f(height);
  } else {
    p.fx = p.fy = 0.5 / std::tan(m.cam_fovy[cam] * std::numbers::pi / 360.0) * height;
    p.cx = width / 2.0;
    p.cy = height / 2.0;
  }
  return p;
}

// The ray of pixel (col, row), row 0 at the top (mju_camPixelRay).
void PixelRay(const Model& m, const Data& d, int cam, const PixelGeometry& p, int col, int row,
              double origin[3], double dir[3]) {
  const double* pos = &d.cam_xpos[3 * cam];
  const double* mat = &d.cam_xmat[9 * cam];
  const double px = col + 0.5 - p.cx, py = row + 0.5 - p.cy;
  if (m.cam_projection[cam] != kOrthographic) {
    math::Copy3(origin, pos);
    double local[3] = {px / p.fx, -py / p.fy, -1.0};
    math::MulMatVec3(dir, mat, local);
    math::Normalize3(dir);
    return;
  }
  for (int k = 0; k < 3; k++) dir[k] = -mat[3 * k + 2];
  const double half = p.extent / 2;
  double offset_local[3] = {px / p.fx * half, -py / p.fy * half, 0}, offset[3];
  math::MulMatVec3(offset, mat, offset_local);
  math::Add3(origin, pos, offset);
}

void SiteRangefinder(const Model& m, Data& d, int i, double* out) {
  const int site = m.sensor_objid[i], mask = m.sensor_intprm[kNSens * i];
  const double* origin = &d.site_xpos[3 * site];
  const double* mat = &d.site_xmat[9 * site];
  const double dir[3] = {mat[2], mat[5], mat[8]};
  RayFilter filter;
  filter.bodyexclude = m.site_bodyid[site];
  double normal[3] = {0, 0, 0};
  double dist = Ray(m, d, origin, dir, filter, nullptr, Has(mask, kRayDataNormal) ? normal : nullptr);
  WriteRay(out, mask, dist, origin, dir, normal, nullptr, nullptr);
}

void CameraRangefinder(const Model& m, Data& d, int i, double* out) {
  const int cam = m.sensor_objid[i], mask = m.sensor_intprm[kNSens * i];
  const double* mat = &d.cam_xmat[9 * cam];
  const double cam_z[3] = {mat[2], mat[5], mat[8]};
  const PixelGeometry p = CameraPixels(m, cam);
  RayFilter filter;
  filter.bodyexclude = m.cam_bodyid[cam];

  // Row by row from the top; normals only when the mask asks (they never change a distance).
  double normal[3] = {0, 0, 0};
  double* normal_out = Has(mask, kRayDataNormal) ? normal : nullptr;
  for (int row = 0; row < m.cam_resolution[2 * cam + 1]; row++) {
    for (int col = 0; col < m.cam_resolution[2 * cam]; col++) {
      double origin[3], dir[3];
      PixelRay(m, d, cam, p, col, row, origin, dir);
      double dist = Ray(m, d, origin, dir, filter, nullptr, normal_out);
      out = WriteRay(out, mask, dist, origin, dir, normal, &d.cam_xpos[3 * cam], cam_z);
    }
  }
}

}  // namespace

void RangefinderSensor(const Model& m, Data& d, int i, double* out) {
  if (m.sensor_objtype[i] == kObjSite) {
    SiteRangefinder(m, d, i, out);
  } else {
    CameraRangefinder(m, d, i, out);
  }
}

}  // namespace simlab
