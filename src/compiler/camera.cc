// Cameras (MuJoCo's mjCCamera::Compile and its mjModel rows): the pose in the body
// frame from the orientation alternatives and enclosing frames, the target body of the
// tracking modes, and the intrinsics: either fovy, or a physical sensor size with focal
// length and principal point in lengths or pixels (pixels win), from which fovy
// follows. After the constants at qpos0, the offsets the tracking modes keep
// (cam_pos0, cam_poscom0, cam_mat0) come from the cameras' fixed poses there.
#include <cmath>
#include <numbers>
#include <string>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "engine/engine.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

// A camera's spec with the id of the body it sits in.
struct CameraRef {
  const mjcf::CameraSpec* spec = nullptr;
  int body = 0;
};

// Cameras in body order (bodies are depth-first), each body's in XML order, then those
// of the bodies fused into it (with the pose they had there, as MuJoCo keeps it).
std::vector<CameraRef> CollectCameras(const CompileState& state) {
  std::vector<CameraRef> cams;
  for (const BodyState& b : state.bodies) {
    for (const mjcf::CameraSpec& c : b.spec->cameras) cams.push_back({&c, b.id});
    for (const mjcf::BodySpec* f : b.fused) {
      for (const mjcf::CameraSpec& c : f->cameras) cams.push_back({&c, b.id});
    }
  }
  return cams;
}

// Position and orientation in the body frame.
void CameraPose(const mjcf::CompilerSpec& model, const mjcf::CameraSpec& s, double* pos,
                double* quat) {
  const mjcf::CompilerSpec& c = mjcf::SettingsOf(s.compiler, model);
  math::Copy3(pos, s.pos.data());
  math::CopyQuat(quat, s.quat.data());
  if (const char* err = ResolveOrientation(quat, c.degree, c.eulerseq, s.alt)) {
    ThrowAt(s.src, std::string("orientation error: ") + err);
  }
  if (s.frame) {
    double fpos[3], fquat[4];
    FramePose(*s.frame, model, fpos, fquat);
    AccumulateChild(fpos, fquat, pos, quat);
  }
  NormalizeVec(quat, 4);
}

// cam_intrinsic (focal lengths, principal point) and cam_fovy. With a sensor size,
// pixel values are turned into lengths by the pixel density and fovy follows from
// the vertical focal length; without one, the focal lengths are the near plane.
// MuJoCo keeps these lengths in single precision, and so does this arithmetic.
void CameraIntrinsics(const mjcf::CameraSpec& s, float znear, double* fovy, double* intrinsic) {
  float size[2] = {static_cast<float>(s.sensorsize[0]), static_cast<float>(s.sensorsize[1])};
  float focal[2] = {static_cast<float>(s.focal[0]), static_cast<float>(s.focal[1])};
  float focalpx[2] = {static_cast<float>(s.focalpixel[0]), static_cast<float>(s.focalpixel[1])};
  float principal[2] = {static_cast<float>(s.principal[0]), static_cast<float>(s.principal[1])};
  float principalpx[2] = {static_cast<float>(s.principalpixel[0]),
                          static_cast<float>(s.principalpixel[1])};
  bool has_intrinsic = focal[0] || focal[1] || focalpx[0] || focalpx[1] || principal[0] ||
                       principal[1] || principalpx[0] || principalpx[1];
  bool has_size = size[0] > 0 && size[1] > 0;
  if (has_intrinsic && !has_size) ThrowAt(s.src, "focal/principal require sensorsize");
  if (has_size && (s.resolution[0] <= 0 || s.resolution[1] <= 0)) {
    ThrowAt(s.src, "sensorsize requires positive resolution");
  }

  float out[4] = {0, 0, 0, 0};
  *fovy = s.fovy;
  if (has_size) {
    float density[2] = {static_cast<float>(s.resolution[0]) / size[0],
                        static_cast<float>(s.resolution[1]) / size[1]};
    for (int k = 0; k < 2; k++) {
      out[k] = focalpx[k] ? focalpx[k] / density[k] : focal[k];
      out[2 + k] = principalpx[k] ? principalpx[k] / density[k] : principal[k];
    }
    *fovy = std::atan2(size[1] / 2, out[1]) * 360.0 / std::numbers::pi;
  } else {
    out[0] = out[1] = znear;
  }
  for (int k = 0; k < 4; k++) intrinsic[k] = out[k];
}

// One camera's row of the model.
void LayoutCamera(const mjcf::ModelSpec& spec, const CameraRef& ref, const NameIndex& bodies,
                  int id, Model* m) {
  const mjcf::CameraSpec& s = *ref.spec;
  CameraPose(spec.compiler, s, &m->cam_pos[3 * id], &m->cam_quat[4 * id]);
  m->cam_names[id] = s.src.name;
  m->cam_bodyid[id] = ref.body;
  m->cam_mode[id] = s.mode;
  m->cam_targetbodyid[id] =
      s.target.empty() ? -1 : FindNamed(s.src, bodies, s.target, "target body");
  if (s.fovy >= 180) ThrowAt(s.src, "fovy too large (must be below 180 degrees)");
  m->cam_projection[id] = s.projection;
  m->cam_ipd[id] = s.ipd;
  m->cam_output[id] = s.output;
  for (int k = 0; k < 2; k++) {
    m->cam_resolution[2 * id + k] = s.resolution[k];
    m->cam_sensorsize[2 * id + k] = static_cast<float>(s.sensorsize[k]);
  }
  CameraIntrinsics(s, static_cast<float>(spec.znear), &m->cam_fovy[id], &m->cam_intrinsic[4 * id]);
}

}  // namespace

int CameraCount(const CompileState& state) {
  return static_cast<int>(CollectCameras(state).size());
}

void CompileCameras(const mjcf::ModelSpec& spec, const CompileState& state, Model* m) {
  std::vector<CameraRef> cams = CollectCameras(state);
  NameIndex seen, bodies(m->body_names);
  for (size_t i = 0; i < cams.size(); i++) {
    const mjcf::Source& src = cams[i].spec->src;
    if (!seen.Insert(src.name, static_cast<int>(i))) {
      ThrowAt(src, "repeated camera name '" + src.name + "'");
    }
    LayoutCamera(spec, cams[i], bodies, static_cast<int>(i), m);
    AlignedPose(state.bodies[cams[i].body], &m->cam_pos[3 * i], &m->cam_quat[4 * i]);
  }
}

void CamLightConstants(Model* m) {
  if (m->ncam == 0 && m->nlight == 0) return;
  // The fixed poses at qpos0 (every camera and light as if its mode were fixed).
  Data d = MakeData(*m);
  Kinematics(*m, d);
  ComPos(*m, d);
  for (int i = 0; i < m->ncam; i++) {
    CameraFixedPose(*m, d, i);
    int body = m->cam_bodyid[i];
    int target = m->cam_targetbodyid[i];
    int com_body = target >= 0 ? target : body;
    math::Sub3(&m->cam_pos0[3 * i], &d.cam_xpos[3 * i], &d.xpos[3 * body]);
    math::Sub3(&m->cam_poscom0[3 * i], &d.cam_xpos[3 * i], &d.subtree_com[3 * com_body]);
    for (int k = 0; k < 9; k++) m->cam_mat0[9 * i + k] = d.cam_xmat[9 * i + k];
  }
  for (int i = 0; i < m->nlight; i++) {
    LightFixedPose(*m, d, i);
    int body = m->light_bodyid[i];
    int target = m->light_targetbodyid[i];
    int com_body = target >= 0 ? target : body;
    math::Sub3(&m->light_pos0[3 * i], &d.light_xpos[3 * i], &d.xpos[3 * body]);
    math::Sub3(&m->light_poscom0[3 * i], &d.light_xpos[3 * i], &d.subtree_com[3 * com_body]);
    math::Normalize3(&d.light_xdir[3 * i]);  // (as MuJoCo's camlight leaves every light's)
    math::Copy3(&m->light_dir0[3 * i], &d.light_xdir[3 * i]);
  }
}

}  // namespace simlab::compiler
