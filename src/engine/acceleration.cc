// The smooth acceleration (MuJoCo mj_fwdAcceleration): every force but the constraints',
// and the acceleration it gives, M^-1 qfrc_smooth.
#include "engine/engine.h"
#include "engine/sleep.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

// qfrc += J^T (force, torque) for every body with a Cartesian force in xfrc_applied,
// applied at the body's centre of mass (MuJoCo mj_xfrcAccumulate, mj_applyFT).
void XfrcAccumulate(const Model& m, Data& d, double* qfrc) {
  for (int b = 1; b < m.nbody; b++) {
    const double* f = &d.xfrc_applied[6 * b];
    if (f[0] == 0 && f[1] == 0 && f[2] == 0 && f[3] == 0 && f[4] == 0 && f[5] == 0) continue;
    ApplyForceTorque(m, d, f, f + 3, &d.xipos[3 * b], b, qfrc);
  }
}

}  // namespace

void SmoothAcceleration(const Model& m, Data& d) {
  // (a sleeping tree's smooth force and acceleration stay as they were)
  StackFrame frame(d);
  SleepingDofValues kept(m, d, frame, {d.qfrc_smooth.data(), d.qacc_smooth.data()});
  for (int v = 0; v < m.nv; v++) {
    d.qfrc_smooth[v] = d.qfrc_passive[v] - d.qfrc_bias[v] + d.qfrc_applied[v] + d.qfrc_actuator[v];
  }
  XfrcAccumulate(m, d, d.qfrc_smooth.data());
  d.qacc_smooth = d.qfrc_smooth;
  SolveSparse(m, d.qLD.data(), d.qLDiagInv.data(), d.qacc_smooth.data());
  kept.Restore();
}

}  // namespace simlab
