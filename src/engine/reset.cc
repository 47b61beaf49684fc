// Resetting Data to the model's default state or to a keyframe
// (MuJoCo mj_resetData, mj_resetDataKeyframe).
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "engine/engine.h"
#include "engine/rows.h"
#include "engine/sleep.h"
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

// Row `key` of a keyframe array with n numbers per key into `state` (rows of arrays
// that may be empty: no actuators, activations or mocap bodies).
void CopyKeyRow(const std::vector<double>& array, int key, int n, std::vector<double>& state) {
  std::copy_n(RowOf(array, key, n), n, state.begin());
}

}  // namespace

void ResetData(const Model& m, Data& d) {
  // (plugins keep their state numbers for their reset to set)
  std::vector<double> plugin_state = d.plugin_state;
  // Everything computed or applied goes to zero...
#define SIMLAB_X(type, name, rows, cols) std::fill(d.name.begin(), d.name.end(), type{});
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  // actuator_moment and ten_J are zero: no row has a nonzero anywhere
  std::fill(d.moment_rownnz.begin(), d.moment_rownnz.end(), 0);
  std::fill(d.ten_J_rownnz.begin(), d.ten_J_rownnz.end(), 0);
  d.nJ = d.nA = 0;
  d.time = 0;
  d.energy[0] = d.energy[1] = 0;
  d.flg_energypos = d.flg_energyvel = d.flg_subtreevel = d.flg_rnepost = false;
  d.ncon = d.nefc = d.solver_niter = 0;
  d.ne = d.nf = d.nl = d.nisland = 0;
  for (auto& w : d.warning) w = WarningStat{};
  for (auto& t : d.timer) t = TimerStat{};
  // ...except the configuration and the mocap poses, which come from the model, and a
  // quaternion command, which starts at the identity.
  for (int i = 0; i < m.nactuator; i++) {
    if (m.actuator_gaintype[i] == kGainSo3 && m.actuator_ctrlspec[i] == kChartQuat) {
      d.ctrl[m.actuator_ctrladr[i]] = 1;
    }
  }
  d.qpos = m.qpos0;
  ResetMocap(m, d);
  // Equality constraints start as the model declares them (active or not).
  d.eq_active = m.eq_active0;
  // Delay and sampling buffers: zero samples before time 0.
  ResetHistory(m, d);
  // Scratch memory for the stages of the model's integrator (MakeData checked its size),
  // or the peak a step has needed.
  size_t need = std::max(static_cast<size_t>(StackDoubles(m)), d.stack_peak);
  if (d.stack.size() < need) d.stack.assign(need, 0.0);
  d.stack_top = 0;
  d.stack_blocks.clear();
  d.plugin_state = std::move(plugin_state);
  ResetPlugins(m, d);
  // Every tree awake, or those marked sleep="init" asleep.
  ResetSleep(m, d);
}

void ResetDataKeyframe(const Model& m, Data& d, int key) {
  if (key < 0 || key >= m.nkey) {
    throw Error("keyframe " + std::to_string(key) + " does not exist (the model has " +
                std::to_string(m.nkey) + ")");
  }
  ResetData(m, d);
  d.time = m.key_time[key];
  CopyKeyRow(m.key_qpos, key, m.nq, d.qpos);
  CopyKeyRow(m.key_qvel, key, m.nv, d.qvel);
  CopyKeyRow(m.key_act, key, m.na, d.act);
  CopyKeyRow(m.key_ctrl, key, m.nu, d.ctrl);
  CopyKeyRow(m.key_mpos, key, 3 * m.nmocap, d.mocap_pos);
  CopyKeyRow(m.key_mquat, key, 4 * m.nmocap, d.mocap_quat);
}

}  // namespace simlab
