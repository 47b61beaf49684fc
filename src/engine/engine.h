// The stages of the simulation pipeline, in the order they run (see forward.cc).
//
// Every stage takes (const Model&, Data&), reads what earlier stages wrote and writes
// its own outputs into Data, under MuJoCo's names. No stage keeps hidden state.
#ifndef SIMLAB_ENGINE_ENGINE_H_
#define SIMLAB_ENGINE_ENGINE_H_

#include <string>

#include "simlab/data.h"
#include "simlab/model.h"
#include "simlab/plugin.h"

namespace simlab {

// ------------------------------------------------------------ position stage

// The whole position stage, in order (forward.cc).
void FwdPosition(const Model& m, Data& d);
// The position stage without constraint rows (what the compiler needs at qpos0).
void FwdPositionSmooth(const Model& m, Data& d);

// xpos, xquat, xmat, xipos, ximat, xanchor, xaxis, geom and site poses (kinematics.cc).
void Kinematics(const Model& m, Data& d);
// subtree_com, cinert, cdof (kinematics.cc).
void ComPos(const Model& m, Data& d);
// cam_xpos, cam_xmat: every camera's pose after its tracking mode (camera.cc).
void CamLight(const Model& m, Data& d);
// World pose (xpos, xmat) of a frame given in body coordinates (pos, quat); `sameframe`
// (MuJoCo's mjtSameFrame, 0 for none) copies the body's or its inertial frame's pose
// instead (kinematics.cc).
void LocalToGlobal(const Data& d, double* xpos, double* xmat, const double* pos,
                   const double* quat, int body, int sameframe);
// Camera i's pose carried by its body alone (the fixed mode).
void CameraFixedPose(const Model& m, Data& d, int i);
// Light i's pose as if its mode were fixed (the compiler's offsets at qpos0 start here).
void LightFixedPose(const Model& m, Data& d, int i);
// flexvert_xpos, flexelem_aabb, flexedge_length and flexedge_J (flex.cc, MuJoCo mj_flex).
void FlexKinematics(const Model& m, Data& d);
// The boxes of the flexes' trees this step (d.bvh_aabb_dyn): leaves from the elements'
// boxes, inner nodes around their children (collision_flex.cc; the end of FlexKinematics,
// as of MuJoCo's mj_flex).
void FlexBoundingVolumes(const Model& m, Data& d);
// The box (centre, half sizes grown by `radius`) of an element: its dim + 1 vertex ids
// `elem` into the positions `xpos` (3 per vertex). The engine's flexelem_aabb and the
// compiler's flex trees and flex_size use it.
void FlexElementAabb(const double* xpos, const int* elem, int dim, double radius, double box[6]);
// Edge e of flex f seen from its vertex v: its rest vector in dx (flex_vert0 scaled by the
// box, flex_size), and the mass of its other end (at least mjMINVAL; 1 without a body).
// The vertex equality's metric (compiler) and invariants (FlexKinematics) weigh by it.
double FlexRestEdge(const Model& m, int f, int e, int v, double dx[3]);
// flexedge_velocity = flexedge_J qvel (flex.cc).
void FlexEdgeVelocity(const Model& m, Data& d);
// The edges' own springs and dampers into qfrc_spring and qfrc_damper (flex.cc).
void FlexEdgeSpringDamper(const Model& m, Data& d, bool spring, bool damper);
// ten_length, ten_J, ten_wrapadr, ten_wrapnum, wrap_obj, wrap_xpos (tendon.cc).
void Tendon(const Model& m, Data& d);
// ten_velocity = ten_J qvel (tendon.cc).
void TendonVelocity(const Model& m, Data& d);
// jdot (nv) = d ten_J(i) / dt; zero for fixed tendons (tendon.cc).
void TendonJacobianDot(const Model& m, Data& d, int i, double* jdot);
// qfrc += ten_J^T armature (d ten_J/dt . qvel): the bias of tendon armature (rne.cc).
void TendonBias(const Model& m, Data& d, double* qfrc);
// Armature an actuator (several: summed) adds to a joint or tendon, times gear^2 (inertia.cc).
double ActuatorArmature(const Model& m, bool tendon, int id);
// Linear damping an actuator adds to a joint or tendon, times gear^2; its |v| v and v^3
// coefficients are added to poly (passive.cc).
double ActuatorDamping(const Model& m, bool tendon, int id, double poly[kNPoly]);
// The damping force is -v (b + p0 |v| + p1 v^2); its slope in v (passive.cc).
double DampingCoefficient(double linear, const double poly[kNPoly], double v);
double DampingSlope(double linear, const double poly[kNPoly], double v);
// crb: the composite inertia of each body's subtree, in com-based coordinates (inertia.cc).
void CompositeInertia(const Model& m, Data& d);
// crb and the joint-space inertia M (CSR lower triangle) and qM (inertia.cc).
void MakeInertia(const Model& m, Data& d);
// qLD, qLDiagInv: the L^T D L factorization of M (inertia.cc).
void FactorInertia(const Model& m, Data& d);
// actuator_length, actuator_moment (transmission.cc). Body transmissions (adhesion)
// read the contacts and their constraint rows: run after MakeConstraint.
void Transmission(const Model& m, Data& d);
// For rows relative to a refsite: the last dof shared by two sites' dof chains (or -1),
// and jac -= jac_ref with the shared chain's columns cleared (transmission.cc).
int CommonAncestorDof(const Model& m, int site0, int site1);
void RelativeJacobian(const Model& m, double* jac, const double* jac_ref, int common);
// The orientation actuator (orientation.cc): its 3 lengths and moment rows, its 3 forces
// before the clamp, the clamp of their norm, and the integrator's setpoints brought back
// within a half turn after a step.
void So3Transmission(const Model& m, Data& d, int i);
void So3Force(const Model& m, const Data& d, int i, const double* ctrl, double* force);
void So3ClampForce(const Model& m, Data& d, int i);
void So3Rewind(const Model& m, Data& d);
// actuator_velocity = actuator_moment qvel, zero with actuation disabled (transmission.cc).
void ActuatorVelocity(const Model& m, Data& d);

// ------------------------------------------------------------ Jacobians (jacobian.cc)

// 3 x nv Jacobians of a world point moving with `body`: translation jacp, rotation
// jacr (either may be null), from cdof along the body's dof chain (MuJoCo mj_jac).
void Jacobian(const Model& m, const Data& d, double* jacp, double* jacr, const double* point,
              int body);
// The same Jacobians on the columns of the dofs `dofs` only (ascending, n of them; they
// hold every dof that moves `body`, as MergedDofChain gives): 3 x n each.
void JacobianOnDofs(const Model& m, const Data& d, const int* dofs, int n, double* jacp,
                    double* jacr, const double* point, int body);
// One row on the columns `dofs` (as JacobianOnDofs's): the difference of the translation
// Jacobians of point p2 on body b2 and p1 on b1 along the unit vector dir, components
// where dir is 0 left out: row[k] = sum_r (jacp2[r][k] - jacp1[r][k]) dir[r], the same
// numbers as from the two 3 x n Jacobians (a flex edge's length Jacobian, a spatial
// tendon segment's).
void JacobianDifferenceAlong(const Model& m, const Data& d, const int* dofs, int n,
                             const double* p1, int b1, const double* p2, int b2,
                             const double* dir, double* row);
// A contact's rows (dim x n, on the columns `dofs`) between bodies b1 and b2 at `point`:
// the frame's axes (rows of `frame`) times the difference of the two bodies' Jacobians
// there, J(b2) - J(b1): translation for the first row (dim 1) or three, rotation for
// rows 3 on (the first axes again). Each entry summed from 0 over the three components.
void FrameJacobianDifference(const Model& m, const Data& d, const int* dofs, int n,
                             const double* point, int b1, int b2, const double* frame, int dim,
                             double* rows);
// Row i of a contact's dim rows: its axis in the contact frame (translation rows 0-2, or
// row 0 alone for dim 1; rotation rows 3 on take the first axes again) and whether it
// is a rotation row.
inline const double* ContactRowAxis(const double* frame, int dim, int i, bool* rotation) {
  *rotation = i >= (dim > 1 ? 3 : 1);
  return frame + 3 * (*rotation ? i - 3 : i);
}
// The dofs that move body b0 or b1 (their chains to the root), ascending, into `dofs`
// (room for nv); returns their count (MuJoCo mj_mergeChain).
int MergedDofChain(const Model& m, int b0, int b1, int* dofs);
// The same for the chains of nbodies <= kMaxMergedChains bodies: the ascending union of
// the dofs that move any of them.
constexpr int kMaxMergedChains = 2 * 729;  // (two contact sides of 27 x 27 nodes)
int MergedDofChains(const Model& m, const int* bodies, int nbodies, int* dofs);
// Jacobian of site `site`'s position and rotation (MuJoCo mj_jacSite).
void JacobianSite(const Model& m, const Data& d, double* jacp, double* jacr, int site);
// Translation Jacobian of a point and the Jacobian of a unit axis turning with `body`.
void JacobianPointAxis(const Model& m, Data& d, double* jac_point, double* jac_axis,
                       const double* point, const double* axis, int body);
// qfrc (nv) += J^T force + Jr^T torque for a world force and torque acting at a world
// point moving with `body` (MuJoCo mj_applyFT).
void ApplyForceTorque(const Model& m, Data& d, const double* force, const double* torque,
                      const double* point, int body, double* qfrc);
// res (nv) = jac^T vec for a 3 x nv Jacobian.
void MulJacTVec(const Model& m, const double* jac, const double* vec, double* res);

// ------------------------------------------------------------ velocity stage

// cvel, cdof_dot (rne.cc).
void ComVel(const Model& m, Data& d);
// qfrc_spring, qfrc_damper, qfrc_gravcomp, qfrc_passive (passive.cc).
void Passive(const Model& m, Data& d);
// Whether gravity compensation acts: gravity on and some body with gravcomp > 0.
bool GravcompActive(const Model& m);
// qfrc_actuator += qfrc_gravcomp on the dofs of joints with actuatorgravcomp (passive.cc).
void AddActuatorGravcomp(const Model& m, Data& d);
// qfrc_fluid (inertia-box or ellipsoid model), added into qfrc_passive (fluid.cc).
void FluidForces(const Model& m, Data& d);
// Semi-axes of the ellipsoid that stands for a geom in the fluid model (fluid.cc).
void GeomSemiAxes(int type, const double* size, double* semiaxes);
// result = inverse dynamics without (flg_acc false) or with qacc (rne.cc).
void Rne(const Model& m, Data& d, bool flg_acc, double* result);
// One body of the RNE forward pass: cacc (nbody x 6, the parent's row already set) gets
// the body's row cacc(parent) + cdof_dot qvel [+ cdof qacc]; cfrc_body (6) the force
// that acceleration needs, cinert cacc + cvel x* (cinert cvel) (rne.cc).
void RneBodyStep(const Model& m, const Data& d, int body, bool flg_acc, double* cacc,
                 double* cfrc_body);
// subtree_linvel, subtree_angmom; sets flg_subtreevel (rne_post.cc, MuJoCo mj_subtreeVel).
void SubtreeVel(const Model& m, Data& d);
// energy[0]: gravity and joint/tendon spring potential; sets flg_energypos (energy.cc).
void EnergyPos(const Model& m, Data& d);
// energy[1] = qvel' M qvel / 2; sets flg_energyvel (energy.cc).
void EnergyVel(const Model& m, Data& d);

// ------------------------------------------------------------ acceleration stage

// The plugin instances' hooks (plugin.cc): init when a Data is made (plugin_data),
// reset, actuator act_dot and forces, passive forces, and after a step.
void InitPlugins(const Model& m, Data& d);
void ResetPlugins(const Model& m, Data& d);
void PluginActDot(const Model& m, Data& d);
void PluginActuatorForces(const Model& m, Data& d);
void PluginPassiveForces(const Model& m, Data& d);
void PluginAdvance(const Model& m, Data& d);
// The field of a signed distance field plugin's instance: its plugin and attributes.
struct SdfField {
  const Plugin* plugin = nullptr;
  const double* attributes = nullptr;
  double Distance(const double x[3]) const { return plugin->sdf_distance(x, attributes); }
  void Gradient(double g[3], const double x[3]) const { plugin->sdf_gradient(g, x, attributes); }
};
SdfField SdfFieldOf(const Data& d, int instance);
// Geom g's plugin field, or none (plugin null) for a geom without a plugin.
SdfField SdfFieldOfGeom(const Model& m, const Data& d, int g);
// act_dot, actuator_force, qfrc_actuator (actuation.cc).
void Actuation(const Model& m, Data& d);
// The activation after one step of its dynamics, clamped to actrange (actuation.cc).
double NextActivation(const Model& m, const Data& d, int actuator, int act_adr,
                      double act_dot);
// MuJoCo's muscle model (muscle.cc); prm is gainprm/biasprm (9 numbers) or dynprm.
double MuscleGainLength(double length, double lmin, double lmax);
double MuscleGain(double len, double vel, const double* lengthrange, double acc0,
                  const double* prm);
// d MuscleGain / d vel.
double MuscleGainVelocity(double len, double vel, const double* lengthrange, double acc0,
                          const double* prm);
double MuscleBias(double len, const double* lengthrange, double acc0, const double* prm);
double MuscleDynamics(double ctrl, double act, const double* prm);
// The DC motor (dcmotor.cc): act_dot of its states (the slew limit rewrites ctrl, the
// local clamped copy), its force before the clamp (ctrl[ctrladr] becomes the voltage),
// cogging and LuGre friction added after the clamp, one state's next value, and
// d force / d velocity for the implicit integrators.
void DcmotorActivation(const Model& m, Data& d, int i, double* ctrl);
double DcmotorForce(const Model& m, const Data& d, int i, double* ctrl);
void DcmotorMechanics(const Model& m, Data& d, int i);
double DcmotorNextActivation(const Model& m, const Data& d, int i, int act_adr, double act_dot);
double DcmotorDampingDerivative(const Model& m, int i);
// qfrc_smooth, qacc_smooth (acceleration.cc).
void SmoothAcceleration(const Model& m, Data& d);
// qfrc_constraint, qacc (constraint.cc).
void Constraint(const Model& m, Data& d);
// A contact's force and torque in its own frame (normal, tangents, spin, rolls), decoded
// from the pyramid's edge forces under pyramidal cones; zero without rows (rne_post.cc,
// MuJoCo mj_contactForce).
void ContactForce(const Model& m, const Data& d, int contact, double result[6]);
// After the constraint solve: cacc (with qacc), cfrc_ext (applied, contact and
// connect/weld forces) and cfrc_int (what each body's parent exerts on its subtree), all
// com-based; sets flg_rnepost (rne_post.cc, MuJoCo mj_rnePostConstraint).
void RnePostConstraint(const Model& m, Data& d);

// ------------------------------------------------------------ sparse inertia algebra

// In-place L^T D L factorization of a matrix with M's sparsity (inertia.cc).
void FactorSparse(const Model& m, double* mat, double* diag_inv);
// x <- (L^T D L)^-1 x with a factorization from FactorSparse (inertia.cc).
void SolveSparse(const Model& m, const double* ld, const double* diag_inv, double* x);
// res = mat vec for a symmetric matrix stored as its lower triangle in M's layout with nv
// rows (M itself, or an island's block of it).
void MulSymLayout(int nv, const int* rownnz, const int* rowadr, const int* colind,
                  const double* mat, const double* vec, double* res);
// The same solve for any matrix in that layout with nv rows (an island's block of M).
void SolveSparseLayout(int nv, const int* rownnz, const int* rowadr, const int* colind,
                       const double* ld, const double* diag_inv, double* x);

// ------------------------------------------------------------ history buffers (history.cc)

// The delayed actuators' and sampled sensors' buffers at their reset state (in ResetData).
void ResetHistory(const Model& m, Data& d);
// ctrl and the sampled sensors' values written at d.time, when integration starts.
void RecordHistory(const Model& m, Data& d);
// Actuator i's input before clamping: ctrl, or ctrl `delay` seconds ago if delayed.
double ActuatorInput(const Model& m, const Data& d, int i);

// ------------------------------------------------------------ integration (integrator.cc)

// qpos <- qpos (+) qvel * dt, on the configuration manifold (quaternions rotate).
void IntegratePos(const Model& m, double* qpos, const double* qvel, double dt);
// Normalizes the quaternions of ball and free joints in qpos.
void NormalizeQuat(const Model& m, double* qpos);
void Euler(const Model& m, Data& d);
void RungeKutta4(const Model& m, Data& d);
void ImplicitIntegrate(const Model& m, Data& d);

// Where each dof's 6-row block of the RNE velocity derivative starts (over its body's row
// of the body-dof pattern B), and their total size in doubles (derivative.cc).
size_t DofBlockOffsets(const Model& m, int* offset);
// qDeriv = d(qfrc_actuator + qfrc_passive [- qfrc_bias]) / d qvel (derivative.cc).
void SmoothVelocityDerivative(const Model& m, Data& d, bool with_bias);
// qDeriv += d qfrc_fluid / d qvel (fluid.cc).
void FluidDerivative(const Model& m, Data& d);

// ------------------------------------------------------------ forward (forward.cc)

// Whether the pipeline computes the sensors (MuJoCo's skipsensor).
enum class Sensors { kCompute, kSkip };

// The pipeline from the stage after `skip` on (MuJoCo mj_forwardSkip: kStageNone runs
// every stage, kStagePos reuses the position stage, kStageVel the velocity stage too).
// May throw simlab::Error; the public Forward and Step catch it.
void ForwardSkip(const Model& m, Data& d, Stage skip, Sensors sensors);

// ------------------------------------------------------------ warnings (warning.cc)

// Raises warning `w` with `info`: counts it, and passes it with its text (default:
// WarningText) to d.warning_callback. Prints nothing.
void RaiseWarning(Data& d, Warning w, int info, const std::string& text = "");
// Raises `w` when `values` (qpos, qvel or qacc) hold a NaN or a magnitude over kMaxVal,
// and then resets the data unless autoreset is disabled (the warning's count is kept);
// returns whether it raised it.
bool WarnAndResetIfBad(const Model& m, Data& d, const std::vector<double>& values, Warning w);

}  // namespace simlab

#endif  // SIMLAB_ENGINE_ENGINE_H_
