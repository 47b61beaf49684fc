// Keyframes: missing values take the model's defaults (qpos0, zeros, mocap body
// poses); short values are padded as MuJoCo pads them, from the values as written.
#include <string>

#include "compiler/compiler.h"
#include "math/math.h"
#include "mjcf/error.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

// Copies `given` into a row of width n. An absent value takes `full` (the compiled
// default); a short one is padded from `pad`, which MuJoCo takes from the values as
// written (raw ref in degrees, quat attributes), before compilation.
void FillRow(const mjcf::KeySpec& key, const char* what, const std::vector<double>& given,
             int n, const double* full, const double* pad, double* row) {
  int count = static_cast<int>(given.size());
  if (count > n) {
    ThrowAt(key.src, std::string("invalid ") + what + " size, expected " + std::to_string(n) +
                         ", got " + std::to_string(count));
  }
  for (int i = 0; i < n; i++) {
    if (i < count) {
      row[i] = given[i];
    } else if (count == 0) {
      row[i] = full ? full[i] : 0;
    } else {
      row[i] = pad ? pad[i] : 0;
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

// The padding values: qpos0 and mocap poses from the spec as written.
struct RawReference {
  std::vector<double> qpos, mpos, mquat;
};

RawReference MakeRawReference(const CompileState& state, const Model& m) {
  RawReference raw;
  for (const JointState& j : state.joints) {
    const mjcf::BodySpec& body = *state.bodies[j.body].spec;
    switch (j.spec->type) {
      case kJointFree:
        raw.qpos.insert(raw.qpos.end(), body.pos.begin(), body.pos.end());
        raw.qpos.insert(raw.qpos.end(), body.quat.begin(), body.quat.end());
        break;
      case kJointBall: raw.qpos.insert(raw.qpos.end(), {1, 0, 0, 0}); break;
      default: raw.qpos.push_back(j.spec->ref); break;
    }
  }
  raw.mpos.resize(3 * m.nmocap);
  raw.mquat.resize(4 * m.nmocap);
  for (const BodyState& b : state.bodies) {
    int id = m.body_mocapid[b.id];
    if (id < 0) continue;
    for (int k = 0; k < 3; k++) raw.mpos[3 * id + k] = b.spec->pos[k];
    for (int k = 0; k < 4; k++) raw.mquat[4 * id + k] = b.spec->quat[k];
  }
  return raw;
}

}  // namespace

void CompileKeyframes(const mjcf::ModelSpec& spec, const CompileState& state, Model* m) {
  // Mocap bodies' compiled poses, the default mpos and mquat.
  std::vector<double> mpos(3 * m->nmocap), mquat(4 * m->nmocap);
  for (int b = 0; b < m->nbody; b++) {
    int id = m->body_mocapid[b];
    if (id < 0) continue;
    for (int k = 0; k < 3; k++) mpos[3 * id + k] = m->body_pos[3 * b + k];
    for (int k = 0; k < 4; k++) mquat[4 * id + k] = m->body_quat[4 * b + k];
  }
  RawReference raw = MakeRawReference(state, *m);
  int nm = m->nmocap;
  for (int k = 0; k < m->nkey; k++) {
    const mjcf::KeySpec& key = spec.keys[k];
    if (!key.src.name.empty() && FindName(m->key_names, key.src.name) >= 0) {
      ThrowAt(key.src, "repeated key name '" + key.src.name + "'");
    }
    m->key_names[k] = key.src.name;
    m->key_time[k] = key.time;
    FillRow(key, "qpos", key.qpos, m->nq, m->qpos0.data(), raw.qpos.data(), &m->key_qpos[k * m->nq]);
    FillRow(key, "qvel", key.qvel, m->nv, nullptr, nullptr, &m->key_qvel[k * m->nv]);
    FillRow(key, "act", key.act, m->na, nullptr, nullptr, &m->key_act[k * m->na]);
    FillRow(key, "ctrl", key.ctrl, m->nu, nullptr, nullptr, &m->key_ctrl[k * m->nu]);
    FillRow(key, "mpos", key.mpos, 3 * nm, mpos.data(), raw.mpos.data(), &m->key_mpos[k * 3 * nm]);
    FillRow(key, "mquat", key.mquat, 4 * nm, mquat.data(), raw.mquat.data(), &m->key_mquat[k * 4 * nm]);
    NormalizeQuats(*m, &m->key_qpos[k * m->nq]);
  }
}

}  // namespace simlab::compiler
