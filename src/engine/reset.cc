// Resetting Data to the model's default state or to a keyframe
// (MuJoCo mj_resetData, mj_resetDataKeyframe).
#include <algorithm>
#include <string>

#include "engine/engine.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

// Mocap bodies start at their model pose.
void ResetMocap(const Model& m, Data& d) {
  for (int b = 0; b < m.nbody; b++) {
    int id = m.body_mocapid[b];
    if (id < 0) continue;
    std::copy_n(&m.body_pos[3 * b], 3, &d.mocap_pos[3 * id]);
    std::copy_n(&m.body_quat[4 * b], 4, &d.mocap_quat[4 * id]);
  }
}

}  // namespace

void ResetData(const Model& m, Data& d) {
  // Everything computed or applied goes to zero...
#define SIMLAB_X(type, name, rows, cols) std::fill(d.name.begin(), d.name.end(), type{});
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  d.time = 0;
  d.energy[0] = d.energy[1] = 0;
  d.flg_energypos = d.flg_energyvel = d.flg_subtreevel = d.flg_rnepost = false;
  d.ncon = d.nefc = d.solver_niter = 0;
  d.ne = d.nf = d.nl = d.nisland = 0;
  for (auto& w : d.warning) w = WarningStat{};
  // ...except the configuration and the mocap poses, which come from the model.
  d.qpos = m.qpos0;
  ResetMocap(m, d);
  // Equality constraints start as the model declares them (active or not).
  d.eq_active = m.eq_active0;
  // Delay and sampling buffers: zero samples before time 0.
  ResetHistory(m, d);
  // Scratch memory for the stages: enough for the largest (the RNE derivative).
  size_t block = static_cast<size_t>(6) * m.nv;
  size_t need = 3 * m.nbody * block + m.nv * block + block + 16 * (m.nq + m.nv + m.na + m.nbody + m.nu) + 64;
  if (d.stack.size() < need) d.stack.assign(need, 0.0);
  d.stack_top = 0;
}

void ResetDataKeyframe(const Model& m, Data& d, int key) {
  if (key < 0 || key >= m.nkey) {
    throw Error("keyframe " + std::to_string(key) + " does not exist (the model has " +
                std::to_string(m.nkey) + ")");
  }
  ResetData(m, d);
  d.time = m.key_time[key];
  std::copy_n(&m.key_qpos[static_cast<size_t>(key) * m.nq], m.nq, d.qpos.begin());
  std::copy_n(&m.key_qvel[static_cast<size_t>(key) * m.nv], m.nv, d.qvel.begin());
  std::copy_n(&m.key_act[static_cast<size_t>(key) * m.na], m.na, d.act.begin());
  std::copy_n(&m.key_ctrl[static_cast<size_t>(key) * m.nu], m.nu, d.ctrl.begin());
  std::copy_n(&m.key_mpos[static_cast<size_t>(key) * 3 * m.nmocap], 3 * m.nmocap, d.mocap_pos.begin());
  std::copy_n(&m.key_mquat[static_cast<size_t>(key) * 4 * m.nmocap], 4 * m.nmocap, d.mocap_quat.begin());
}

}  // namespace simlab
