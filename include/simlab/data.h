// simlab::Data: everything about a simulation that changes.
//
// The state and inputs (time, qpos, qvel, act, ctrl, applied forces, mocap poses) and
// every quantity the pipeline computes from them, with MuJoCo's mjData names and
// shapes. Like Model, one table (SIMLAB_DATA_FIELDS) drives allocation and name lookup.
#ifndef SIMLAB_DATA_H_
#define SIMLAB_DATA_H_

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "simlab/model.h"

namespace simlab {

// Kinds of warning the engine counts: MuJoCo's mjtWarning, in its order, then simlab's
// own two: the line search met a non-convex objective (MuJoCo prints that without
// counting it), and an engine error inside Forward or a Step, such as an option set to a
// value that does not exist (MuJoCo stops with an error; simlab resets the data, as for a
// state that diverged, and keeps the message in Data::error).
enum Warning : int {
  kWarnInertia = 0, kWarnContactFull, kWarnConstraintFull, kWarnVGeomFull, kWarnBadQpos,
  kWarnBadQvel, kWarnBadQacc, kWarnBadCtrl, kWarnLineSearch, kWarnEngineError, kNumWarnings
};
// MuJoCo's kinds are the first ones (its mjNWARNING).
inline constexpr int kNumMujocoWarnings = kWarnLineSearch;

// Kinds of constraint row (mjtConstraint) and states of a row in the solution
// (mjtConstraintState), with MuJoCo's values.
enum ConstraintType : int {
  kCnstrEquality = 0, kCnstrFrictionDof = 1, kCnstrFrictionTendon = 2, kCnstrLimitJoint = 3,
  kCnstrLimitTendon = 4, kCnstrContactFrictionless = 5, kCnstrContactPyramidal = 6,
  kCnstrContactElliptic = 7
};
enum ConstraintState : int {
  kStateSatisfied = 0, kStateQuadratic = 1, kStateLinearNeg = 2, kStateLinearPos = 3,
  kStateCone = 4
};

// One contact between two geoms (MuJoCo's mjContact). frame's first row is the normal,
// pointing from geom[0] to geom[1]; rows 2 and 3 span the tangent plane.
struct Contact {
  double dist = 0;            // signed distance: negative when penetrating
  double pos[3] = {0, 0, 0};  // position, midway between the two surfaces
  double frame[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  double includemargin = 0;   // rows are made when dist < includemargin (margin - gap)
  double friction[5] = {0, 0, 0, 0, 0};  // tangent1, tangent2, spin, roll1, roll2
  double solref[kNRef] = {0, 0};          // reference acceleration, normal direction
  double solreffriction[kNRef] = {0, 0};  // reference acceleration, frictional directions
  double solimp[kNImp] = {0, 0, 0, 0, 0};
  double mu = 0;              // friction of the regularized cone (set by the rows)
  double H[36] = {};          // cone Hessian (set by the Newton solver)
  int dim = 0;                // contact space dimension: 1, 3, 4 or 6
  int geom1 = -1, geom2 = -1; // the two geoms (deprecated MuJoCo names of geom[])
  int geom[2] = {-1, -1};
  int flex[2] = {-1, -1};     // always -1: flexes are not modelled
  int elem[2] = {-1, -1};
  int vert[2] = {-1, -1};
  int exclude = 0;            // 1: within the gap, no rows made
  int efc_address = -1;       // first constraint row of this contact, or -1
};

// Scratch of the collision stage's broad phase, kept between steps so that it does not
// allocate: candidate body pairs as signatures (b1 << 16) + b2, the collidable bodies,
// and the sweep's sorted interval ends (SweepKey: value, then 2 i + 1 for interval i's
// upper end) and open intervals. Each flex's self-collision sweep has its own ends
// (flex_ends[f]); both start the next step's sort from this one's order. A flex's open
// elements keep their bounds on the two other axes beside their ids (open_bounds, 4 each).
struct BroadPhaseScratch {
  std::vector<int> pairs;
  std::vector<int> bodies;
  std::vector<uint64_t> ends;
  std::vector<int> open;
  std::vector<std::vector<uint64_t>> flex_ends;
  std::vector<double> open_bounds;
};

// Arrays the constraint solvers take each step (engine/constraint.h, SolverFrame), kept
// between steps so that they only grow and a steady simulation does not allocate.
struct SolverScratch {
  std::vector<std::vector<double>> reals;
  std::vector<std::vector<int>> ints;
  size_t nreal = 0, nint = 0;  // arrays in use
};

struct WarningStat {
  int lastinfo = 0;  // info from the last time the warning was raised
  int number = 0;    // how many times it was raised
};

// The profiler's timers (mjtTimer, MuJoCo's order and meaning): the whole step and
// forward pass, the stages, the parts of the position stage and of collision.
enum Timer : int {
  kTimerStep = 0, kTimerForward, kTimerInverse, kTimerPosition, kTimerVelocity,
  kTimerActuation, kTimerConstraint, kTimerAdvance, kTimerPosKinematics, kTimerPosInertia,
  kTimerPosCollision, kTimerPosMake, kTimerPosProject, kTimerColBroad, kTimerColNarrow,
  kNumTimers
};

struct TimerStat {
  double duration = 0;  // total time, in the unit of Data::timer_clock
  int number = 0;       // how many times it ran
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
  X(int, tree_asleep, ntree, 1)  /* < 0 awake (-1: ready to sleep); >= 0 asleep, the next tree of its cycle */ \
  /* sleep (sleep.cc UpdateSleep, from tree_asleep) */ \
  X(int, tree_awake, ntree, 1)                  \
  X(int, body_awake, nbody, 1)  /* SleepState */ \
  X(int, body_awake_ind, nbody, 1)  /* awake and static bodies */ \
  X(int, parent_awake_ind, nbody, 1)  /* bodies whose parent is awake or static */ \
  X(int, dof_awake_ind, nv, 1)                  \
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
  X(double, cam_xpos, ncam, 3)                  \
  X(double, cam_xmat, ncam, 9)                  \
  X(double, light_xpos, nlight, 3)              \
  X(double, light_xdir, nlight, 3)              \
  X(double, subtree_com, nbody, 3)              \
  X(double, cdof, nv, 6)                        \
  X(double, cinert, nbody, 10)                  \
  X(double, ten_length, ntendon, 1)             \
  X(double, ten_J, ntendon, nv)                 \
  X(int, ten_wrapadr, ntendon, 1)               \
  X(int, ten_wrapnum, ntendon, 1)               \
  X(int, wrap_obj, nwrap, 2)                    \
  X(double, wrap_xpos, nwrap, 6)                \
  X(double, flexvert_xpos, nflexvert, 3)        \
  X(double, flexelem_aabb, nflexelem, 6)        \
  X(double, bvh_aabb_dyn, nbvhdynamic, 6)  /* flex tree boxes: centre, half sizes */ \
  X(double, flexedge_J, nJfe, 1)                \
  X(double, flexedge_length, nflexedge, 1)      \
  X(double, flexvert_J, nJfv, 2)                \
  X(double, flexvert_length, nflexvert, 2)      \
  X(double, actuator_length, nout, 1)             \
  X(double, actuator_moment, nout, nv)            \
  X(double, crb, nbody, 10)                     \
  X(double, M, nM, 1)                           \
  X(double, qM, nM, 1)                          \
  X(double, qLD, nM, 1)                         \
  X(double, qLDiagInv, nv, 1)                   \
  /* velocity-dependent */                      \
  X(double, ten_velocity, ntendon, 1)           \
  X(double, flexedge_velocity, nflexedge, 1)    \
  X(double, actuator_velocity, nout, 1)           \
  X(double, cvel, nbody, 6)                     \
  X(double, cdof_dot, nv, 6)                    \
  X(double, qfrc_bias, nv, 1)                   \
  X(double, qfrc_spring, nv, 1)                 \
  X(double, qfrc_damper, nv, 1)                 \
  X(double, qfrc_fluid, nv, 1)                  \
  X(double, qfrc_gravcomp, nv, 1)               \
  X(double, qfrc_passive, nv, 1)                \
  X(double, subtree_linvel, nbody, 3)  /* on demand: SubtreeVel */ \
  X(double, subtree_angmom, nbody, 3)  /* about each subtree's com */ \
  /* acceleration-dependent */                  \
  X(double, actuator_force, nout, 1)              \
  X(double, qfrc_actuator, nv, 1)               \
  X(double, qfrc_smooth, nv, 1)                 \
  X(double, qacc_smooth, nv, 1)                 \
  X(double, qfrc_constraint, nv, 1)             \
  X(int, dof_island, nv, 1)     /* island of each dof, -1 outside every island */ \
  X(int, tree_island, ntree, 1)  /* island of each tree, -1 outside every island */ \
  X(int, island_ntree, ntree, 1)  /* trees of each island (nisland used) */ \
  X(int, island_itreeadr, ntree, 1)  /* its first entry in map_itree2tree */ \
  X(int, map_itree2tree, ntree, 1)  /* trees by island; trees in none last */ \
  X(double, qfrc_inverse, nv, 1)                \
  X(double, cacc, nbody, 6)                     \
  X(double, cfrc_int, nbody, 6)                 \
  X(double, cfrc_ext, nbody, 6)                 \
  X(double, sensordata, nsensordata, 1)         \
  X(double, plugin_state, npluginstate, 1)      \
  X(double, history, nhistory, 1)  /* delayed actuators' and sensors' samples */ \
  /* implicit integration */                    \
  X(double, qDeriv, nD, 1)  /* in the dof-dof pattern D (D_rowadr...) */ \
  X(double, qLU, nD, 1)  /* M - h qDeriv factored (U + I) L, pattern D */ \
  X(double, qH, nM, 1)                          \
  X(double, qHDiagInv, nv, 1)

// Constraint rows: X(type, name, cols), nefc rows each.
#define SIMLAB_DATA_EFC_FIELDS(X)                                                   \
  X(int, efc_type, 1)           /* mjtConstraint: equality, friction, limit, contact */ \
  X(int, efc_id, 1)             /* id of the element that made the row */             \
  X(int, efc_J_rownnz, 1)       /* entries of the row in efc_J */                     \
  X(int, efc_J_rowadr, 1)       /* where the row starts in efc_J and efc_J_colind */  \
  X(double, efc_pos, 1)         /* position (distance or error) */                    \
  X(double, efc_margin, 1)      /* inclusion margin */                                \
  X(double, efc_frictionloss, 1)/* friction loss of friction rows */                 \
  X(double, efc_diagApprox, 1)  /* approximation of diag(J M^-1 J^T) */              \
  X(double, efc_KBIP, 4)        /* stiffness, damping, impedance, impedance slope */  \
  X(double, efc_D, 1)           /* constraint mass 1/R */                             \
  X(double, efc_R, 1)           /* regularizer */                                     \
  X(double, efc_vel, 1)         /* J qvel */                                          \
  X(double, efc_aref, 1)        /* reference acceleration */                          \
  X(double, efc_b, 1)           /* J qacc_smooth - aref */                            \
  X(double, efc_force, 1)       /* constraint force in constraint space */            \
  X(int, efc_state, 1)          /* mjtConstraintState of the solution */             \
  X(int, efc_island, 1)         /* island of the row */

// What a plugin instance keeps beside its numbers in plugin_state (MuJoCo's plugin_data):
// made by the plugin's init, copied with the Data through Clone.
class PluginInstanceData {
 public:
  virtual ~PluginInstanceData() = default;
  virtual std::unique_ptr<PluginInstanceData> Clone() const = 0;
};

// Owns one instance's data; copies clone it (so a Data stays copyable).
struct PluginDataSlot {
  std::unique_ptr<PluginInstanceData> data;
  PluginDataSlot() = default;
  PluginDataSlot(const PluginDataSlot& o) : data(o.data ? o.data->Clone() : nullptr) {}
  PluginDataSlot& operator=(const PluginDataSlot& o) {
    data = o.data ? o.data->Clone() : nullptr;
    return *this;
  }
  PluginDataSlot(PluginDataSlot&&) = default;
  PluginDataSlot& operator=(PluginDataSlot&&) = default;
};

struct Data {
  double time = 0;
  double energy[2] = {0, 0};  // potential, kinetic (when the energy flag is enabled)
  int ncon = 0;               // contacts
  int nefc = 0;               // constraint rows
  int solver_niter = 0;       // iterations of the last constraint solve (all islands)
  int ne = 0;                 // equality rows (first in the efc arrays)
  int nf = 0;                 // friction rows (after the equalities)
  int nl = 0;                 // limit rows (after the friction rows; contacts follow)
  int nisland = 0;            // constraint islands of the last solve
  // Sleep (sleep.cc): counts of the *_awake_ind lists, from tree_asleep.
  int ntree_awake = 0;
  int nbody_awake = 0;
  int nparent_awake = 0;
  int nv_awake = 0;
  WarningStat warning[kNumWarnings];
  // The profiler (MuJoCo's d->timer with mjcb_time, here per Data): when timer_clock is
  // set, each timed part of the pipeline adds its time to timer[kind]; ResetData clears
  // them. simlab bench sets a thread CPU clock in microseconds.
  TimerStat timer[kNumTimers];
  double (*timer_clock)() = nullptr;
  int nreset = 0;             // resets after a divergence (bad qpos, qvel or qacc)
  // Quantities computed on demand, once per step (MuJoCo's lazy-evaluation flags):
  // energy[0], energy[1], subtree_linvel/angmom, cacc/cfrc_int/cfrc_ext.
  bool flg_energypos = false;
  bool flg_energyvel = false;
  bool flg_subtreevel = false;
  bool flg_rnepost = false;
  // The one warning channel. Every warning is counted in `warning` (number, lastinfo)
  // and, if this is set, passed here as it is raised, with its text; the engine itself
  // prints nothing (MuJoCo's mju_user_warning, here per Data).
  std::function<void(const Data& d, Warning w, int info, const std::string& text)>
      warning_callback;
  // The message of the last engine error (kWarnEngineError), or "".
  std::string error;
  // User sensors' callback (MuJoCo's mjcb_sensor, here per Data): called with the stage
  // (kStagePos/Vel/Acc) once per stage that has user sensors, after their outputs were
  // zeroed; it writes d.sensordata at their sensor_adr.
  std::function<void(const Model& m, Data& d, int stage)> sensor_callback;

#define SIMLAB_X(type, name, rows, cols) std::vector<type> name;
  SIMLAB_DATA_FIELDS(SIMLAB_X)
#undef SIMLAB_X

  // Constraint rows, nefc of them, in MuJoCo's efc_* layout (resized by the position stage).
#define SIMLAB_X(type, name, cols) std::vector<type> name;
  SIMLAB_DATA_EFC_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  // The dofs where each actuator's row of actuator_moment may be nonzero (set by the
  // transmission stage): moment_rownnz[i] of them, ascending, from moment_colind[i * nv] on.
  std::vector<int> moment_rownnz;
  std::vector<int> moment_colind;
  // The same for each tendon's row of ten_J (set by the tendon stage).
  std::vector<int> ten_J_rownnz;
  std::vector<int> ten_J_colind;

  // The constraint Jacobian in compressed rows, nJ entries: row r has efc_J_rownnz[r]
  // entries from efc_J_rowadr[r] on, in the dofs efc_J_colind (ascending). As MuJoCo's
  // (mj_isSparse): with jacobian="sparse", or "auto" and 60 dofs or more, a row holds the
  // dofs that can move what it constrains; otherwise every row holds all nv dofs, so
  // efc_J is the dense nefc x nv matrix.
  int nJ = 0;
  std::vector<double> efc_J;
  std::vector<int> efc_J_colind;
  // AR = J M^-1 J^T + diag(R), for the dual solvers (PGS, noslip), nA entries: the dense
  // nefc x nefc matrix, or, when efc_J is sparse, in compressed rows as MuJoCo's (row r:
  // efc_AR_rownnz[r] entries from efc_AR_rowadr[r] on, at the rows efc_AR_colind that
  // share a dof with r, ascending).
  int nA = 0;
  std::vector<double> efc_AR;
  std::vector<int> efc_AR_rownnz;
  std::vector<int> efc_AR_rowadr;
  std::vector<int> efc_AR_colind;

  // Contacts of the last collision stage: the first ncon entries (capacity grows as needed).
  std::vector<Contact> contact;
  // Narrow-phase output of the distance/normal/fromto sensors (kMaxContactPair, reused).
  std::vector<Contact> distance_scratch;
  BroadPhaseScratch broadphase;
  SolverScratch solver_scratch;

  // Each plugin instance's data (nplugin; see simlab/plugin.h).
  std::vector<PluginDataSlot> plugin_data;

  // Scratch memory for the stages (a stack: see engine/stack.h), sized by MakeData for
  // the model's integrator (StackDoubles). A stage that finds it short takes the rest
  // from the heap (stack_blocks, now) and the stack grows to the peak seen (stack_peak)
  // before the next public call.
  std::vector<double> stack;
  size_t stack_top = 0;
  std::vector<std::vector<double>> stack_blocks;
  size_t stack_peak = 0;
};

// Doubles of the stages' scratch stack that ResetData gives a Data for `m` (saturating):
// enough for every stage of the model's integrator, the RNE derivative included only
// for the implicit one.
uint64_t StackDoubles(const Model& m);

// A Data sized for the model and reset to its default state. Throws simlab::Error,
// allocating nothing, if its arrays would take more than kMaxDataBytes.
Data MakeData(const Model& m);

// What the arrays of a Data for `m` take, in bytes (saturating), with the largest one
// named, before any is allocated; MakeData refuses more than kMaxDataBytes (2 GiB).
inline constexpr uint64_t kMaxDataBytes = uint64_t{2} << 30;
uint64_t DataBytes(const Model& m, const char** largest = nullptr,
                   uint64_t* largest_bytes = nullptr);
// Why a Data for `m` is over kMaxDataBytes ("sensordata too large: the model's Data would
// need ..."), or "" when it is within.
std::string DataOverBudget(const Model& m);

// Every array of the data, in table order, shaped by the model.
std::vector<FieldView> DataFields(const Model& m, Data& d);

}  // namespace simlab

#endif  // SIMLAB_DATA_H_
