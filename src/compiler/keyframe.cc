// Keyframes: missing values take the model's defaults (qpos0, zeros, mocap body
// poses); short values are padded as MuJoCo pads them, from the values as written.
#include <functional>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/orientation.h"
#include "engine/rows.h"
#include "math/math.h"
#include "mjcf/compose.h"
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

// A quaternion as MuJoCo normalizes a keyframe's: the compiler's rule (division by the
// norm), then the engine's (multiplication by the inverse norm) when the model is made.
void KeyNormalizeQuat(double* q) {
  NormalizeVec(q, 4);
  math::NormalizeQuat(q);
}

// Unit quaternions in the ball and free joints of a keyframe's qpos.
void NormalizeQuats(const Model& m, double* qpos) {
  for (int j = 0; j < m.njnt; j++) {
    int adr = m.jnt_qposadr[j];
    if (m.jnt_type[j] == kJointBall) KeyNormalizeQuat(qpos + adr);
    if (m.jnt_type[j] == kJointFree) KeyNormalizeQuat(qpos + adr + 3);
  }
}

// The padding values: qpos0 and mocap poses from the spec as written.
struct RawReference {
  std::vector<double> qpos, mpos, mquat;
};

RawReference MakeRawReference(const CompileState& state, const Model& m) {
  RawReference raw;
  for (const JointState& j : state.joints) {
    switch (j.spec->type) {
      case kJointFree:
        // MuJoCo 3.5.1 pads a free joint with the origin and the unit quaternion,
        // not with its body's pose.
        raw.qpos.insert(raw.qpos.end(), {0, 0, 0, 1, 0, 0, 0});
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

// ---------------------------------------------------------------- attached keyframes

template <typename T>
int IndexOfSpec(const std::vector<T>& items, const void* spec) {
  for (size_t i = 0; i < items.size(); i++) {
    if (items[i].spec == spec) return static_cast<int>(i);
  }
  return -1;
}

// Writes each element's values at its address in a row.
template <typename Element>
void Overlay(const std::vector<std::pair<Element, std::vector<double>>>& values,
             const std::function<int(Element)>& address, double* row) {
  for (const auto& [element, numbers] : values) {
    int adr = address(element);
    if (adr < 0) continue;
    for (size_t i = 0; i < numbers.size(); i++) row[adr + i] = numbers[i];
  }
}

// A keyframe that came with an attached model: its rows hold the compiled defaults,
// and the elements that carry values for it write them in their places.
void OverlayAttachedKey(const mjcf::AttachedKey& key, const CompileState& state, int k,
                        Model* m) {
  using JointPtr = const mjcf::JointSpec*;
  using BodyPtr = const mjcf::BodySpec*;
  auto mocap = [&](BodyPtr b) {
    int id = IndexOfSpec(state.bodies, b);
    return id < 0 ? -1 : m->body_mocapid[id];
  };
  std::function<int(JointPtr)> qposadr = [&](JointPtr j) {
    int id = IndexOfSpec(state.joints, j);
    return id < 0 ? -1 : m->jnt_qposadr[id];
  };
  std::function<int(JointPtr)> dofadr = [&](JointPtr j) {
    int id = IndexOfSpec(state.joints, j);
    return id < 0 ? -1 : m->jnt_dofadr[id];
  };
  std::function<int(int)> actadr = [&](int a) { return m->actuator_actadr[a]; };
  std::function<int(int)> ctrladr = [&](int a) { return m->actuator_ctrladr[a]; };
  std::function<int(BodyPtr)> mposadr = [&](BodyPtr b) { return mocap(b) < 0 ? -1 : 3 * mocap(b); };
  std::function<int(BodyPtr)> mquatadr = [&](BodyPtr b) { return mocap(b) < 0 ? -1 : 4 * mocap(b); };
  Overlay(key.qpos, qposadr, RowOf(m->key_qpos, k, m->nq));
  Overlay(key.qvel, dofadr, RowOf(m->key_qvel, k, m->nv));
  Overlay(key.act, actadr, RowOf(m->key_act, k, m->na));
  Overlay(key.ctrl, ctrladr, RowOf(m->key_ctrl, k, m->nu));
  Overlay(key.mpos, mposadr, RowOf(m->key_mpos, k, 3 * m->nmocap));
  Overlay(key.mquat, mquatadr, RowOf(m->key_mquat, k, 4 * m->nmocap));
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
    FillRow(key, "qpos", key.qpos, m->nq, m->qpos0.data(), raw.qpos.data(),
            RowOf(m->key_qpos, k, m->nq));
    FillRow(key, "qvel", key.qvel, m->nv, nullptr, nullptr, RowOf(m->key_qvel, k, m->nv));
    FillRow(key, "act", key.act, m->na, nullptr, nullptr, RowOf(m->key_act, k, m->na));
    FillRow(key, "ctrl", key.ctrl, m->nu, nullptr, nullptr, RowOf(m->key_ctrl, k, m->nu));
    FillRow(key, "mpos", key.mpos, 3 * nm, mpos.data(), raw.mpos.data(),
            RowOf(m->key_mpos, k, 3 * nm));
    FillRow(key, "mquat", key.mquat, 4 * nm, mquat.data(), raw.mquat.data(),
            RowOf(m->key_mquat, k, 4 * nm));
    if (key.attached) OverlayAttachedKey(*key.attached, state, k, m);
    NormalizeQuats(*m, RowOf(m->key_qpos, k, m->nq));
  }
}

}  // namespace simlab::compiler
