// Keyframes: missing values take the model's defaults (qpos0, zeros, mocap body
// poses); a qpos shorter than nq is padded with qpos0, as MuJoCo does.
#include <string>

#include "compiler/compiler.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

// Copies `given` into row k of `field` (width n); empty means `fallback` (or zeros).
void FillRow(const mjcf::KeySpec& key, const char* what, const std::vector<double>& given,
             int n, bool allow_short, const double* fallback, double* row) {
  int count = static_cast<int>(given.size());
  if (count > n || (count > 0 && count < n && !allow_short)) {
    ThrowAt(key.src, std::string("invalid ") + what + " size, expected " + std::to_string(n) +
                         ", got " + std::to_string(count));
  }
  for (int i = 0; i < n; i++) {
    if (i < count) {
      row[i] = given[i];
    } else {
      row[i] = fallback ? fallback[i] : 0;
    }
  }
}

// Unit quaternions in the ball and free joints of a keyframe's qpos.
void NormalizeQuats(const Model& m, double* qpos) {
  for (int j = 0; j < m.njnt; j++) {
    int adr = m.jnt_qposadr[j];
    if (m.jnt_type[j] == kJointBall) math::NormalizeQuat(qpos + adr);
    if (m.jnt_type[j] == kJointFree) math::NormalizeQuat(qpos + adr + 3);
  }
}

}  // namespace

void CompileKeyframes(const mjcf::ModelSpec& spec, Model* m) {
  // Mocap bodies' poses, the default mpos and mquat.
  std::vector<double> mpos(3 * m->nmocap), mquat(4 * m->nmocap);
  for (int b = 0; b < m->nbody; b++) {
    int id = m->body_mocapid[b];
    if (id < 0) continue;
    for (int k = 0; k < 3; k++) mpos[3 * id + k] = m->body_pos[3 * b + k];
    for (int k = 0; k < 4; k++) mquat[4 * id + k] = m->body_quat[4 * b + k];
  }
  for (int k = 0; k < m->nkey; k++) {
    const mjcf::KeySpec& key = spec.keys[k];
    if (!key.src.name.empty() && FindName(m->key_names, key.src.name) >= 0) {
      ThrowAt(key.src, "repeated key name '" + key.src.name + "'");
    }
    m->key_names[k] = key.src.name;
    m->key_time[k] = key.time;
    FillRow(key, "qpos", key.qpos, m->nq, true, m->qpos0.data(), &m->key_qpos[k * m->nq]);
    FillRow(key, "qvel", key.qvel, m->nv, true, nullptr, &m->key_qvel[k * m->nv]);
    FillRow(key, "act", key.act, m->na, true, nullptr, &m->key_act[k * m->na]);
    FillRow(key, "ctrl", key.ctrl, m->nu, true, nullptr, &m->key_ctrl[k * m->nu]);
    FillRow(key, "mpos", key.mpos, 3 * m->nmocap, true, mpos.data(), &m->key_mpos[k * 3 * m->nmocap]);
    FillRow(key, "mquat", key.mquat, 4 * m->nmocap, true, mquat.data(),
            &m->key_mquat[k * 4 * m->nmocap]);
    NormalizeQuats(*m, &m->key_qpos[k * m->nq]);
  }
}

}  // namespace simlab::compiler
