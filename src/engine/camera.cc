// Camera and light poses, part of the position stage (MuJoCo's mj_camlight): a camera
// or light starts at its fixed pose in its body's frame, then its mode adjusts it.
//
//   fixed          the body frame carries it
//   track          world orientation kept from qpos0, position at a fixed offset from the body
//   trackcom       the same, offset from the body's subtree centre of mass
//   targetbody     stays in place on its body but looks at the target body's origin
//   targetbodycom  ... or at the target's subtree centre of mass, with the camera's
//                  x axis horizontal (perpendicular to the world z axis)
#include "engine/engine.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

enum CamLightMode : int {
  kCamFixed = 0, kCamTrack = 1, kCamTrackCom = 2, kCamTargetBody = 3, kCamTargetBodyCom = 4
};

// Camera frame that looks from `eye` at `point`: z axis away from the point, x axis
// perpendicular to z and the world's vertical, y = z x x. Rows of the transpose are
// the axes, so they are filled as columns of xmat.
void LookAt(const double* eye, const double* point, double* xmat) {
  double axes[9];
  double* x = axes;
  double* y = axes + 3;
  double* z = axes + 6;
  Sub3(z, eye, point);
  Normalize3(z);
  const double up[3] = {0, 0, 1};
  Cross3(x, up, z);
  Normalize3(x);
  Cross3(y, z, x);
  Normalize3(y);
  for (int r = 0; r < 3; r++) {
    for (int c = 0; c < 3; c++) xmat[3 * r + c] = axes[3 * c + r];
  }
}

// The tracking modes: orientation of qpos0, position offset from the body or its com.
void TrackPose(const Model& m, Data& d, int i) {
  int body = m.cam_bodyid[i];
  for (int k = 0; k < 9; k++) d.cam_xmat[9 * i + k] = m.cam_mat0[9 * i + k];
  if (m.cam_mode[i] == kCamTrack) {
    Add3(&d.cam_xpos[3 * i], &d.xpos[3 * body], &m.cam_pos0[3 * i]);
  } else {
    Add3(&d.cam_xpos[3 * i], &d.subtree_com[3 * body], &m.cam_poscom0[3 * i]);
  }
}

// The point the targetbody modes look at: the target's origin, or its subtree centre of
// mass (targetbodycom).
const double* TargetPoint(const Data& d, int mode, int target) {
  return mode == kCamTargetBody ? &d.xpos[3 * target] : &d.subtree_com[3 * target];
}

}  // namespace

void CameraFixedPose(const Model& m, Data& d, int i) {
  LocalToGlobal(d, &d.cam_xpos[3 * i], &d.cam_xmat[9 * i], &m.cam_pos[3 * i],
                &m.cam_quat[4 * i], m.cam_bodyid[i], 0);
}

void LightFixedPose(const Model& m, Data& d, int i) {
  int body = m.light_bodyid[i];
  const double* xmat = &d.xmat[9 * body];
  MulMatVec3(&d.light_xpos[3 * i], xmat, &m.light_pos[3 * i]);
  Add3(&d.light_xpos[3 * i], &d.light_xpos[3 * i], &d.xpos[3 * body]);
  // (the direction turned by the body's quaternion, as MuJoCo 3.5 turns it)
  RotVecQuat(&d.light_xdir[3 * i], &m.light_dir[3 * i], &d.xquat[4 * body]);
}

namespace {

// A light's pose: fixed in its body, then adjusted by its mode as a camera's; the
// direction is a unit vector.
void LightPose(const Model& m, Data& d, int i) {
  LightFixedPose(m, d, i);
  int body = m.light_bodyid[i], target = m.light_targetbodyid[i];
  double* xpos = &d.light_xpos[3 * i];
  double* xdir = &d.light_xdir[3 * i];
  switch (m.light_mode[i]) {
    case kCamTrack:
    case kCamTrackCom:
      Copy3(xdir, &m.light_dir0[3 * i]);
      if (m.light_mode[i] == kCamTrack) {
        Add3(xpos, &d.xpos[3 * body], &m.light_pos0[3 * i]);
      } else {
        Add3(xpos, &d.subtree_com[3 * body], &m.light_poscom0[3 * i]);
      }
      break;
    case kCamTargetBody:
    case kCamTargetBodyCom:
      if (target >= 0) Sub3(xdir, TargetPoint(d, m.light_mode[i], target), xpos);
      break;
    default:
      break;
  }
  Normalize3(xdir);
}

}  // namespace

void CamLight(const Model& m, Data& d) {
  for (int i = 0; i < m.nlight; i++) LightPose(m, d, i);
  for (int i = 0; i < m.ncam; i++) {
    CameraFixedPose(m, d, i);
    int target = m.cam_targetbodyid[i];
    switch (m.cam_mode[i]) {
      case kCamTrack:
      case kCamTrackCom:
        TrackPose(m, d, i);
        break;
      case kCamTargetBody:
      case kCamTargetBodyCom:
        // Without a target body the camera stays fixed.
        if (target >= 0) {
          LookAt(&d.cam_xpos[3 * i], TargetPoint(d, m.cam_mode[i], target), &d.cam_xmat[9 * i]);
        }
        break;
      default:
        break;
    }
  }
}

}  // namespace simlab
