// simlab::Data: everything about a simulation that changes.
//
// The state and inputs (time, qpos, qvel, act, ctrl, applied forces, mocap poses) and
// every quantity the pipeline computes from them, with MuJoCo's mjData names and
// shapes. Like Model, one table (SIMLAB_DATA_FIELDS) drives allocation and name lookup.
#ifndef SIMLAB_DATA_H_
#define SIMLAB_DATA_H_

#include <string>
#include <vector>

#include "simlab/model.h"

namespace simlab {

// Kinds of warning the engine counts (MuJoCo's mjtWarning, same order).
enum Warning : int {
  kWarnInertia = 0, kWarnContactFull, kWarnConstraintFull, kWarnVGeomFull, kWarnBadQpos,
  kWarnBadQvel, kWarnBadQacc, kWarnBadCtrl, kNumWarnings
};

struct WarningStat {
  int lastinfo = 0;  // info from the last time the warning was raised
  int number = 0;    // how many times it was raised
};

// X(type, name, rows, cols), rows and cols being members of Model (or numbers).
#define SIMLAB_DATA_FIELDS(X)                   \
  /* state and inputs */                        \
  X(double, qpos, nq, 1)                        \
  X(double, qvel, nv, 1)                        \
  X(double, act, na, 1)                         \
  X(double, qacc_warmstart, nv, 1)              \
  X(double, ctrl, nu, 1)                        \
  X(double, qfrc_applied, nv, 1)                \
  X(double, xfrc_applied, nbody, 6)             \
  X(double, mocap_pos, nmocap, 3)               \
  X(double, mocap_quat, nmocap, 4)              \
  X(int, eq_active, neq, 1)                     \
  /* accelerations */                           \
  X(double, qacc, nv, 1)                        \
  X(double, act_dot, na, 1)                     \
  /* position-dependent */                      \
  X(double, xpos, nbody, 3)                     \
  X(double, xquat, nbody, 4)                    \
  X(double, xmat, nbody, 9)                     \
  X(double, xipos, nbody, 3)                    \
  X(double, ximat, nbody, 9)                    \
  X(double, xanchor, njnt, 3)                   \
  X(double, xaxis, njnt, 3)                     \
  X(double, geom_xpos, ngeom, 3)                \
  X(double, geom_xmat, ngeom, 9)                \
  X(double, site_xpos, nsite, 3)                \
  X(double, site_xmat, nsite, 9)                \
  X(double, subtree_com, nbody, 3)              \
  X(double, cdof, nv, 6)                        \
  X(double, cinert, nbody, 10)                  \
  X(double, ten_length, ntendon, 1)             \
  X(double, ten_J, ntendon, nv)                 \
  X(double, actuator_length, nu, 1)             \
  X(double, actuator_moment, nu, nv)            \
  X(double, crb, nbody, 10)                     \
  X(double, M, nM, 1)                           \
  X(double, qM, nM, 1)                          \
  X(double, qLD, nM, 1)                         \
  X(double, qLDiagInv, nv, 1)                   \
  /* velocity-dependent */                      \
  X(double, ten_velocity, ntendon, 1)           \
  X(double, actuator_velocity, nu, 1)           \
  X(double, cvel, nbody, 6)                     \
  X(double, cdof_dot, nv, 6)                    \
  X(double, qfrc_bias, nv, 1)                   \
  X(double, qfrc_spring, nv, 1)                 \
  X(double, qfrc_damper, nv, 1)                 \
  X(double, qfrc_passive, nv, 1)                \
  /* acceleration-dependent */                  \
  X(double, actuator_force, nu, 1)              \
  X(double, qfrc_actuator, nv, 1)               \
  X(double, qfrc_smooth, nv, 1)                 \
  X(double, qacc_smooth, nv, 1)                 \
  X(double, qfrc_constraint, nv, 1)             \
  X(double, qfrc_inverse, nv, 1)                \
  X(double, cacc, nbody, 6)                     \
  X(double, cfrc_int, nbody, 6)                 \
  X(double, cfrc_ext, nbody, 6)                 \
  X(double, sensordata, nsensordata, 1)         \
  /* implicit integration */                    \
  X(double, qDeriv, nv, nv)                     \
  X(double, qLU, nv, nv)                        \
  X(double, qH, nM, 1)                          \
  X(double, qHDiagInv, nv, 1)

struct Data {
  double time = 0;
  double energy[2] = {0, 0};  // potential, kinetic (when the energy flag is enabled)
  int ncon = 0;               // contacts
  int nefc = 0;               // constraint rows
  int solver_niter = 0;       // iterations of the last constraint solve
  WarningStat warning[kNumWarnings];
  int nreset = 0;             // resets after a divergence (bad qpos, qvel or qacc)

#define SIMLAB_X(type, name, rows, cols) std::vector<type> name;
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X

  // Scratch memory for the stages (a stack: see engine/stack.h), sized by MakeData.
  std::vector<double> stack;
  size_t stack_top = 0;
};

// A Data sized for the model and reset to its default state.
Data MakeData(const Model& m);

// Every array of the data, in table order, shaped by the model.
std::vector<FieldView> DataFields(const Model& m, Data& d);

}  // namespace simlab

#endif  // SIMLAB_DATA_H_
