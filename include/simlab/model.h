// simlab::Model: the compiled, immutable description of a simulated system.
//
// Field names, shapes and enum values follow MuJoCo's mjModel on purpose, so that
// `model.body_mass[i]` or `model.actuator_gainprm[10*i]` mean the same thing here, in
// the Python bindings and in the browser lab. Arrays are flat and row-major: a field
// listed as (nbody x 3) stores body i's three numbers at [3*i, 3*i+3).
//
// One table (SIMLAB_MODEL_FIELDS) lists every array with its element type, row count
// (the name of a size member) and column count; allocation, name lookup, copying and
// dumping are all generated from it.
#ifndef SIMLAB_MODEL_H_
#define SIMLAB_MODEL_H_

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace simlab {

// ---------------------------------------------------------------- enums (MuJoCo values)

enum JointType : int { kJointFree = 0, kJointBall = 1, kJointSlide = 2, kJointHinge = 3 };

enum GeomType : int {
  kGeomPlane = 0, kGeomHfield = 1, kGeomSphere = 2, kGeomCapsule = 3, kGeomEllipsoid = 4,
  kGeomCylinder = 5, kGeomBox = 6, kGeomMesh = 7, kGeomSdf = 8
};

enum Integrator : int {
  kIntegratorEuler = 0, kIntegratorRK4 = 1, kIntegratorImplicit = 2,
  kIntegratorImplicitFast = 3
};

enum ConeType : int { kConePyramidal = 0, kConeElliptic = 1 };
enum JacobianType : int { kJacobianDense = 0, kJacobianSparse = 1, kJacobianAuto = 2 };
enum SolverType : int { kSolverPGS = 0, kSolverCG = 1, kSolverNewton = 2 };

// Bits of Option::disableflags (MuJoCo's mjtDisableBit).
enum DisableBit : int {
  kDisableConstraint = 1 << 0, kDisableEquality = 1 << 1, kDisableFrictionloss = 1 << 2,
  kDisableLimit = 1 << 3, kDisableContact = 1 << 4, kDisableSpring = 1 << 5,
  kDisableDamper = 1 << 6, kDisableGravity = 1 << 7, kDisableClampctrl = 1 << 8,
  kDisableWarmstart = 1 << 9, kDisableFilterparent = 1 << 10, kDisableActuation = 1 << 11,
  kDisableRefsafe = 1 << 12, kDisableSensor = 1 << 13, kDisableMidphase = 1 << 14,
  kDisableEulerdamp = 1 << 15, kDisableAutoreset = 1 << 16, kDisableNativeccd = 1 << 17,
  kDisableIsland = 1 << 18
};

// Bits of Option::enableflags (MuJoCo's mjtEnableBit).
enum EnableBit : int {
  kEnableOverride = 1 << 0, kEnableEnergy = 1 << 1, kEnableFwdinv = 1 << 2,
  kEnableInvdiscrete = 1 << 3, kEnableMulticcd = 1 << 4, kEnableSleep = 1 << 5
};

// A tree's sleep policy (MuJoCo's mjtSleepPolicy): the compiler turns kSleepAuto into
// kSleepAutoNever (actuated, or coupled by a springy tendon) or kSleepAutoAllowed; the
// others come from the root body's sleep attribute.
enum SleepPolicy : int {
  kSleepAuto = 0, kSleepAutoNever, kSleepAutoAllowed, kSleepNever, kSleepAllowed, kSleepInit
};
// Steps a tree must stay below the sleep tolerance before it may sleep (mjMINAWAKE).
inline constexpr int kMinAwake = 10;

// Actuator transmission, dynamics, gain and bias types (mjtTrn, mjtDyn, mjtGain, mjtBias),
// numbered as MuJoCo 3.12 (which inserted dcmotor, so3 and pid before the user types).
enum TrnType : int {
  kTrnJoint = 0, kTrnJointInParent = 1, kTrnSliderCrank = 2, kTrnTendon = 3, kTrnSite = 4,
  kTrnBody = 5, kTrnSo3 = 6, kTrnUndefined = 1000
};
enum DynType : int {
  kDynNone = 0, kDynIntegrator = 1, kDynFilter = 2, kDynFilterExact = 3, kDynMuscle = 4,
  kDynDcmotor = 5, kDynPid = 6, kDynUser = 7
};
enum GainType : int {
  kGainFixed = 0, kGainAffine = 1, kGainMuscle = 2, kGainDcmotor = 3, kGainSo3 = 4, kGainPid = 5,
  kGainUser = 6
};
enum BiasType : int {
  kBiasNone = 0, kBiasAffine = 1, kBiasMuscle = 2, kBiasDcmotor = 3, kBiasSo3 = 4, kBiasUser = 5
};

// An actuator's input signature (actuator_ctrlspec), read by its gain type: for pid and
// dcmotor the inputs present (mjtCtrlInput bits, packed in ctrl in this order), for so3
// the chart of the orientation command (mjtCtrlChart).
enum CtrlInput : int {
  kInputPos = 1, kInputVel = 2, kInputFf = 4, kInputVoltage = 8, kInputNone = 16
};
enum CtrlChart : int { kChartExpmap = 1, kChartQuat = 2 };

// Equality constraint types (mjtEq).
enum EqType : int {
  kEqConnect = 0, kEqWeld = 1, kEqJoint = 2, kEqTendon = 3, kEqFlex = 4, kEqFlexVert = 5,
  kEqFlexStrain = 6  // one cell (or shell face) of an interpolated flex: its stiff modes
};

// Self-collision modes of a flex (mjtFlexSelf).
enum FlexSelf : int {
  kFlexSelfNone = 0, kFlexSelfNarrow, kFlexSelfBvh, kFlexSelfSap, kFlexSelfAuto
};

// Object types (mjtObj), used by name lookup.
enum ObjType : int {
  kObjUnknown = 0, kObjBody = 1, kObjXBody = 2, kObjJoint = 3, kObjDof = 4, kObjGeom = 5,
  kObjSite = 6, kObjCamera = 7, kObjLight = 8, kObjFlex = 9, kObjMesh = 10, kObjSkin = 11,
  kObjHfield = 12, kObjTexture = 13, kObjMaterial = 14, kObjPair = 15, kObjExclude = 16,
  kObjEquality = 17, kObjTendon = 18, kObjActuator = 19, kObjSensor = 20, kObjNumeric = 21,
  kObjText = 22, kObjTuple = 23, kObjKey = 24, kObjPlugin = 25
};

// Numbers per solref, solimp, gain/bias/dyn parameter rows (mjNREF, mjNIMP, mjNGAIN...).
inline constexpr int kNRef = 2;
inline constexpr int kNImp = 5;
inline constexpr int kNDyn = 10;
inline constexpr int kNGain = 10;
inline constexpr int kNBias = 10;
// Numbers per row of eq_data (mjNEQDATA): connect anchors (0-5), weld anchors, relative
// quaternion and torquescale (0-10), joint/tendon polynomial coefficients (0-4).
inline constexpr int kNEqData = 11;
inline constexpr int kNTexRole = 10;  // texture roles of a material (mjNTEXROLE)
inline constexpr int kNPoly = 2;  // higher-order damping terms (MuJoCo 3.7+ mjNPOLY)
inline constexpr int kNFluid = 12;  // geom_fluid row (mjNFLUID): flag, 5 coefs, added mass, inertia

// Sensor types (mjtSensor), computation stages (mjtStage) and sensor data types
// (mjtDataType), with MuJoCo's values.
enum SensorType : int {
  kSensTouch = 0, kSensAccelerometer, kSensVelocimeter, kSensGyro, kSensForce, kSensTorque,
  kSensMagnetometer, kSensRangefinder, kSensCamProjection, kSensJointPos, kSensJointVel,
  kSensTendonPos, kSensTendonVel, kSensActuatorPos, kSensActuatorVel, kSensActuatorFrc,
  kSensJointActFrc, kSensTendonActFrc, kSensBallQuat, kSensBallAngVel, kSensJointLimitPos,
  kSensJointLimitVel, kSensJointLimitFrc, kSensTendonLimitPos, kSensTendonLimitVel,
  kSensTendonLimitFrc, kSensFramePos, kSensFrameQuat, kSensFrameXAxis, kSensFrameYAxis,
  kSensFrameZAxis, kSensFrameLinVel, kSensFrameAngVel, kSensFrameLinAcc, kSensFrameAngAcc,
  kSensSubtreeCom, kSensSubtreeLinVel, kSensSubtreeAngMom, kSensInsideSite, kSensGeomDist,
  kSensGeomNormal, kSensGeomFromTo, kSensContact, kSensEPotential, kSensEKinetic, kSensClock,
  kSensTactile, kSensPlugin, kSensUser
};
enum Stage : int { kStageNone = 0, kStagePos = 1, kStageVel = 2, kStageAcc = 3 };
enum DataType : int {
  kDataReal = 0, kDataPositive = 1, kDataAxis = 2, kDataQuaternion = 3
};
// Integer parameters per sensor (mjNSENS): the data mask, reduction and count of
// contact and rangefinder sensors.
inline constexpr int kNSens = 3;
// Fields a contact sensor can report (mjtConDataField), and a rangefinder (mjtRayDataField).
enum ConDataField : int {
  kConDataFound = 0, kConDataForce, kConDataTorque, kConDataDist, kConDataPos,
  kConDataNormal, kConDataTangent, kNConData
};
enum RayDataField : int {
  kRayDataDist = 0, kRayDataDir, kRayDataOrigin, kRayDataPoint, kRayDataNormal,
  kRayDataDepth, kNRayData
};

// Tendon path element types (mjtWrap).
enum WrapType : int {
  kWrapNone = 0, kWrapJoint = 1, kWrapPulley = 2, kWrapSite = 3, kWrapSphere = 4,
  kWrapCylinder = 5
};

// Smallest value treated as nonzero (mjMINVAL) and the largest acceptable value in
// state and accelerations before a simulation is declared divergent (mjMAXVAL).
inline constexpr double kMinVal = 1e-15;
inline constexpr double kMaxVal = 1e10;
// Smallest friction coefficient a contact gets (mjMINMU).
inline constexpr double kMinMu = 1e-5;

// ---------------------------------------------------------------- options

// Physics options: MuJoCo's mjOption, with its defaults.
struct Option {
  double timestep = 0.002;
  double impratio = 1;
  double tolerance = 1e-8;
  double ls_tolerance = 0.01;
  double noslip_tolerance = 1e-6;
  double ccd_tolerance = 1e-6;
  double sleep_tolerance = 1e-4;  // velocity below which a tree may sleep
  std::array<double, 3> gravity = {0, 0, -9.81};
  std::array<double, 3> wind = {0, 0, 0};
  std::array<double, 3> magnetic = {0, -0.5, 0};
  double density = 0;
  double viscosity = 0;
  double o_margin = 0;
  std::array<double, kNRef> o_solref = {0.02, 1};
  std::array<double, kNImp> o_solimp = {0.9, 0.95, 0.001, 0.5, 2};
  std::array<double, 5> o_friction = {1, 1, 0.005, 0.0001, 0.0001};
  int integrator = kIntegratorEuler;
  int cone = kConePyramidal;
  int jacobian = kJacobianAuto;
  int solver = kSolverNewton;
  int iterations = 100;
  int ls_iterations = 50;
  int noslip_iterations = 0;
  int ccd_iterations = 35;
  int sdf_initpoints = 40;  // starting points of the sdf collider's descents
  int sdf_iterations = 10;  // gradient steps of each
  int disableflags = 0;
  int enableflags = 0;
  int disableactuator = 0;
};

// The model's statistics (MuJoCo's mjStatistic, defaults of mj_defaultStatistic), computed
// at qpos0 unless <statistic> gives them: meaninertia scales the constraint solver's
// tolerance, the others the viewer's scale and free camera.
struct Statistic {
  double meaninertia = 1;  // mean diagonal of M at qpos0
  double meanmass = 1;     // mean body mass
  double meansize = 0.2;   // mean body size
  double extent = 2;       // largest side of the box around the model
  std::array<double, 3> center = {0, 0, 0};  // centre of that box
};

// What a viewer needs of <visual> (MuJoCo's mjVisual, its defaults): the free camera's
// start and field of view, the mouse perturbation's springs, clipping, the headlight and
// the haze colour.
struct Visual {
  struct Global {
    double fovy = 45;        // degrees
    double azimuth = 90;     // degrees
    double elevation = -45;  // degrees (negative: looking down)
  } global;
  struct Map {
    double stiffness = 100;     // translational perturbation spring (per unit mass)
    double stiffnessrot = 500;  // rotational perturbation spring (per unit inertia)
    double znear = 0.01;        // clipping planes, in units of the model's extent
    double zfar = 50;
  } map;
  // The light that moves with the free camera.
  struct Headlight {
    std::array<double, 3> ambient = {0.1, 0.1, 0.1};
    std::array<double, 3> diffuse = {0.4, 0.4, 0.4};
    std::array<double, 3> specular = {0.5, 0.5, 0.5};
    int active = 1;
  } headlight;
  struct Rgba {
    std::array<double, 4> haze = {0.15, 0.25, 0.35, 1};  // the horizon's colour
  } rgba;
};

// ---------------------------------------------------------------- the field table
//
// X(type, name, rows, cols): an array of rows*cols elements, rows being a size member.

#define SIMLAB_MODEL_FIELDS(X)                     \
  /* state layout */                               \
  X(double, qpos0, nq, 1)                          \
  X(double, qpos_spring, nq, 1)                    \
  /* bodies */                                     \
  X(int, body_parentid, nbody, 1)                  \
  X(int, body_rootid, nbody, 1)                    \
  X(int, body_weldid, nbody, 1)                    \
  X(int, body_mocapid, nbody, 1)                   \
  X(int, body_jntnum, nbody, 1)                    \
  X(int, body_jntadr, nbody, 1)                    \
  X(int, body_dofnum, nbody, 1)                    \
  X(int, body_dofadr, nbody, 1)                    \
  X(int, body_treeid, nbody, 1)                    \
  X(int, body_geomnum, nbody, 1)                   \
  X(int, body_geomadr, nbody, 1)                   \
  X(int, body_sameframe, nbody, 1)                 \
  X(double, body_pos, nbody, 3)                    \
  X(double, body_quat, nbody, 4)                   \
  X(double, body_ipos, nbody, 3)                   \
  X(double, body_iquat, nbody, 4)                  \
  X(double, body_mass, nbody, 1)                   \
  X(double, body_subtreemass, nbody, 1)            \
  X(double, body_inertia, nbody, 3)                \
  X(double, body_gravcomp, nbody, 1)               \
  X(int, body_simple, nbody, 1)                    \
  X(double, body_invweight0, nbody, 2)             \
  X(int, body_contype, nbody, 1)                   \
  X(int, body_conaffinity, nbody, 1)               \
  X(int, body_plugin, nbody, 1) /* plugin instance, or -1 */ \
  X(double, body_margin, nbody, 1) /* widest geom margin */ \
  X(int, body_bvhadr, nbody, 1) /* first node of its tree, or -1 */ \
  X(int, body_bvhnum, nbody, 1)                    \
  /* bounding volume hierarchies of the bodies'     \
     colliding geoms (midphase); MuJoCo's arrays     \
     also hold its meshes' face trees after them */  \
  X(int, bvh_depth, nbvh, 1)                       \
  X(int, bvh_child, nbvh, 2) /* within the body's tree, -1: none */ \
  X(int, bvh_nodeid, nbvh, 1) /* a leaf's geom (flexes: element), else -1 */ \
  X(double, bvh_aabb, nbvhstatic, 6) /* centre, half sizes; inertial frame (bodies' trees) */ \
  /* joints */                                     \
  X(int, jnt_type, njnt, 1)                        \
  X(int, jnt_qposadr, njnt, 1)                     \
  X(int, jnt_dofadr, njnt, 1)                      \
  X(int, jnt_bodyid, njnt, 1)                      \
  X(int, jnt_group, njnt, 1)                       \
  X(int, jnt_limited, njnt, 1)                     \
  X(int, jnt_actfrclimited, njnt, 1)               \
  X(int, jnt_actgravcomp, njnt, 1)                 \
  X(double, jnt_solref, njnt, kNRef)               \
  X(double, jnt_solimp, njnt, kNImp)               \
  X(double, jnt_pos, njnt, 3)                      \
  X(double, jnt_axis, njnt, 3)                     \
  X(double, jnt_stiffness, njnt, 1)                \
  X(double, jnt_range, njnt, 2)                    \
  X(double, jnt_actfrcrange, njnt, 2)              \
  X(double, jnt_margin, njnt, 1)                   \
  X(int, jnt_actuatorid, njnt, 1)                  \
  /* degrees of freedom */                         \
  X(int, dof_bodyid, nv, 1)                        \
  X(int, dof_jntid, nv, 1)                         \
  X(int, dof_parentid, nv, 1)                      \
  X(int, dof_treeid, nv, 1)                        \
  X(int, dof_Madr, nv, 1)                          \
  X(double, dof_solref, nv, kNRef)                 \
  X(double, dof_solimp, nv, kNImp)                 \
  X(double, dof_frictionloss, nv, 1)               \
  X(double, dof_armature, nv, 1)                   \
  X(double, dof_damping, nv, 1)                    \
  X(double, dof_invweight0, nv, 1)                 \
  X(int, dof_simplenum, nv, 1)                     \
  X(double, dof_M0, nv, 1)                         \
  X(double, dof_length, nv, 1) /* 1 for sliding dofs; rotating: the body's size */ \
  /* kinematic trees (ntree: roots of the dof forest) */ \
  X(int, tree_bodyadr, ntree, 1)                   \
  X(int, tree_bodynum, ntree, 1)                   \
  X(int, tree_dofadr, ntree, 1)                    \
  X(int, tree_dofnum, ntree, 1)                    \
  X(int, tree_sleep_policy, ntree, 1) /* SleepPolicy */ \
  /* inertia matrix sparsity: row i of the lower     \
     triangle holds i's ancestor dofs, then i */     \
  X(int, M_rownnz, nv, 1)                          \
  X(int, M_rowadr, nv, 1)                          \
  X(int, M_colind, nM, 1)                          \
  /* the symmetric dof-dof pattern (qDeriv): row i  \
     holds i's ancestors, i, then its descendants */ \
  X(int, D_rownnz, nv, 1)                          \
  X(int, D_rowadr, nv, 1)                          \
  X(int, D_diag, nv, 1) /* diagonal's place in the row */ \
  X(int, D_colind, nD, 1)                          \
  /* the body-dof pattern B: row b holds the dofs of \
     b's ancestors, then of its subtree (ascending) */ \
  X(int, B_rownnz, nbody, 1)                       \
  X(int, B_rowadr, nbody, 1)                       \
  X(int, B_colind, nB, 1)                          \
  /* geoms */                                      \
  X(int, geom_type, ngeom, 1)                      \
  X(int, geom_contype, ngeom, 1)                   \
  X(int, geom_conaffinity, ngeom, 1)               \
  X(int, geom_condim, ngeom, 1)                    \
  X(int, geom_bodyid, ngeom, 1)                    \
  X(int, geom_group, ngeom, 1)                     \
  X(int, geom_priority, ngeom, 1)                  \
  X(int, geom_sameframe, ngeom, 1)                 \
  X(double, geom_solmix, ngeom, 1)                 \
  X(double, geom_solref, ngeom, kNRef)             \
  X(double, geom_solimp, ngeom, kNImp)             \
  X(double, geom_size, ngeom, 3)                   \
  X(double, geom_rbound, ngeom, 1)                 \
  X(double, geom_aabb, ngeom, 6)                   \
  X(double, geom_pos, ngeom, 3)                    \
  X(double, geom_quat, ngeom, 4)                   \
  X(double, geom_friction, ngeom, 3)               \
  X(double, geom_margin, ngeom, 1)                 \
  X(double, geom_gap, ngeom, 1)                    \
  X(double, geom_rgba, ngeom, 4)                   \
  X(double, geom_fluid, ngeom, kNFluid)            \
  X(int, geom_dataid, ngeom, 1)                    \
  X(int, geom_matid, ngeom, 1) /* material, or -1 */ \
  X(int, geom_plugin, ngeom, 1) /* sdf plugin instance, or -1 */ \
  /* meshes (vertices hold float-rounded values, as MuJoCo stores floats) */ \
  X(int, mesh_vertadr, nmesh, 1)                   \
  X(int, mesh_vertnum, nmesh, 1)                   \
  X(int, mesh_faceadr, nmesh, 1)                   \
  X(int, mesh_facenum, nmesh, 1)                   \
  X(int, mesh_graphadr, nmesh, 1)                  \
  X(double, mesh_scale, nmesh, 3)                  \
  X(double, mesh_pos, nmesh, 3)                    \
  X(double, mesh_quat, nmesh, 4)                   \
  X(double, mesh_vert, nmeshvert, 3)               \
  X(int, mesh_face, nmeshface, 3)                  \
  X(int, mesh_graph, nmeshgraph, 1)                \
  /* the hull's flat sides (multiccd): polygons of \
     mesh vertices, and each vertex's polygons */   \
  X(int, mesh_polynum, nmesh, 1)                   \
  X(int, mesh_polyadr, nmesh, 1)                   \
  X(double, mesh_polynormal, nmeshpoly, 3)         \
  X(int, mesh_polyvertadr, nmeshpoly, 1)           \
  X(int, mesh_polyvertnum, nmeshpoly, 1)           \
  X(int, mesh_polyvert, nmeshpolyvert, 1)          \
  X(int, mesh_polymapadr, nmeshvert, 1)            \
  X(int, mesh_polymapnum, nmeshvert, 1)            \
  X(int, mesh_polymap, nmeshpolymap, 1)            \
  /* signed distance octrees of meshes sdf geoms use (-1: none) */ \
  X(int, mesh_octadr, nmesh, 1)                    \
  X(int, mesh_octnum, nmesh, 1)                    \
  X(int, oct_depth, noct, 1)                       \
  X(int, oct_child, noct, 8) /* -1: a leaf */      \
  X(double, oct_aabb, noct, 6) /* centre, half sizes */ \
  X(double, oct_coeff, noct, 8) /* corner values */ \
  /* mesh normals, float-rounded (wedges and plates: normal and 2 tangents per vertex) */ \
  X(int, mesh_normaladr, nmesh, 1)                 \
  X(int, mesh_normalnum, nmesh, 1)                 \
  X(double, mesh_normal, nmeshnormal, 3)           \
  /* texture coordinates (float-rounded; v flipped as MuJoCo's OBJ reader does), and the \
     coordinate of each face corner (all 0 for meshes without coordinates) */ \
  X(int, mesh_texcoordadr, nmesh, 1)  /* first row in mesh_texcoord, or -1 */ \
  X(int, mesh_texcoordnum, nmesh, 1)               \
  X(double, mesh_texcoord, nmeshtexcoord, 2)       \
  X(int, mesh_facetexcoord, nmeshface, 3)          \
  /* height fields (elevation normalized to [0, 1], float-rounded as MuJoCo's) */ \
  X(double, hfield_size, nhfield, 4)  /* x, y, top z, base depth */ \
  X(int, hfield_nrow, nhfield, 1)                  \
  X(int, hfield_ncol, nhfield, 1)                  \
  X(int, hfield_adr, nhfield, 1)                   \
  X(double, hfield_data, nhfielddata, 1)           \
  /* skins (float-rounded, as MuJoCo's): triangle meshes drawn over bodies, each vertex \
     carried by its bones (a body, the pose it was bound in, a weight per vertex) */ \
  X(int, skin_matid, nskin, 1)                     \
  X(int, skin_group, nskin, 1)                     \
  X(double, skin_rgba, nskin, 4)                   \
  X(double, skin_inflate, nskin, 1)                \
  X(int, skin_vertadr, nskin, 1)                   \
  X(int, skin_vertnum, nskin, 1)                   \
  X(int, skin_texcoordadr, nskin, 1)  /* first row in skin_texcoord, or -1 */ \
  X(int, skin_faceadr, nskin, 1)                   \
  X(int, skin_facenum, nskin, 1)                   \
  X(int, skin_boneadr, nskin, 1)                   \
  X(int, skin_bonenum, nskin, 1)                   \
  X(double, skin_vert, nskinvert, 3)               \
  X(double, skin_texcoord, nskintexvert, 2)        \
  X(int, skin_face, nskinface, 3)                  \
  X(int, skin_bonevertadr, nskinbone, 1)           \
  X(int, skin_bonevertnum, nskinbone, 1)           \
  X(double, skin_bonebindpos, nskinbone, 3)        \
  X(double, skin_bonebindquat, nskinbone, 4)       \
  X(int, skin_bonebodyid, nskinbone, 1)            \
  X(int, skin_bonevertid, nskinbonevert, 1)        \
  X(double, skin_bonevertweight, nskinbonevert, 1) \
  /* flexes (MuJoCo's deformables): vertices on bodies joined by elements of dimension \
     1, 2 or 3 (lines, triangles, tetrahedra), their edges, collision and elasticity */ \
  X(int, flex_contype, nflex, 1)                   \
  X(int, flex_conaffinity, nflex, 1)               \
  X(int, flex_condim, nflex, 1)                    \
  X(int, flex_priority, nflex, 1)                  \
  X(double, flex_solmix, nflex, 1)                 \
  X(double, flex_solref, nflex, kNRef)             \
  X(double, flex_solimp, nflex, kNImp)             \
  X(double, flex_friction, nflex, 3)               \
  X(double, flex_margin, nflex, 1)                 \
  X(double, flex_gap, nflex, 1)                    \
  X(int, flex_internal, nflex, 1)                  \
  X(int, flex_selfcollide, nflex, 1) /* FlexSelf */ \
  X(int, flex_activelayers, nflex, 1)              \
  X(int, flex_passive, nflex, 1)                   \
  X(int, flex_dim, nflex, 1)                       \
  X(int, flex_matid, nflex, 1)                     \
  X(int, flex_group, nflex, 1)                     \
  X(int, flex_interp, nflex, 1) /* 0: vertices; 1, 2: order of the nodes; -1, -2: a shell */ \
  X(int, flex_cellnum, nflex, 3) /* cells of the node lattice along x, y, z */ \
  X(int, flex_nodeadr, nflex, 1)                   \
  X(int, flex_nodenum, nflex, 1)                   \
  X(int, flex_vertadr, nflex, 1)                   \
  X(int, flex_vertnum, nflex, 1)                   \
  X(int, flex_edgeadr, nflex, 1)                   \
  X(int, flex_edgenum, nflex, 1)                   \
  X(int, flex_elemadr, nflex, 1)                   \
  X(int, flex_elemnum, nflex, 1)                   \
  X(int, flex_elemdataadr, nflex, 1)               \
  X(int, flex_stiffnessadr, nflex, 1) /* -1: none */ \
  X(int, flex_elemedgeadr, nflex, 1)               \
  X(int, flex_bendingadr, nflex, 1)   /* -1: none */ \
  X(int, flex_shellnum, nflex, 1)                  \
  X(int, flex_shelldataadr, nflex, 1) /* -1: none */ \
  X(int, flex_evpairadr, nflex, 1)    /* -1: none */ \
  X(int, flex_evpairnum, nflex, 1)                 \
  X(int, flex_texcoordadr, nflex, 1)  /* -1: none */ \
  X(int, flex_nodebodyid, nflexnode, 1)            \
  X(int, flex_vertbodyid, nflexvert, 1)            \
  X(int, flex_vertedgeadr, nflexvert, 1)           \
  X(int, flex_vertedgenum, nflexvert, 1)           \
  X(int, flex_vertedge, nflexedge, 2)              \
  X(int, flex_edge, nflexedge, 2)                  \
  X(int, flex_edgeflap, nflexedge, 2) /* the flap's other two vertices (dim 2), else -1 */ \
  X(int, flex_elem, nflexelemdata, 1)              \
  X(int, flex_elemtexcoord, nflexelemdata, 1)      \
  X(int, flex_elemedge, nflexelemedge, 1)          \
  X(int, flex_elemlayer, nflexelem, 1)             \
  X(int, flex_shell, nflexshelldata, 1)            \
  X(int, flex_evpair, nflexevpair, 2)              \
  X(double, flex_vert, nflexvert, 3)               \
  X(double, flex_vert0, nflexvert, 3)              \
  X(double, flex_vertmetric, nflexvert, 4)         \
  X(double, flex_node, nflexnode, 3)               \
  X(double, flex_node0, nflexnode, 3)              \
  X(double, flexedge_length0, nflexedge, 1)        \
  X(double, flexedge_invweight0, nflexedge, 1)     \
  X(double, flex_radius, nflex, 1)                 \
  X(double, flex_size, nflex, 3)                   \
  X(double, flex_stiffness, nflexstiffness, 1) /* per flex: 21 per element, or see flex_cells.h */ \
  X(double, flex_bending, nflexbending, 1)     /* per flex: 17 per edge, or see flex_cells.h */ \
  X(double, flex_damping, nflex, 1)                \
  X(double, flex_edgestiffness, nflex, 1)          \
  X(double, flex_edgedamping, nflex, 1)            \
  X(int, flex_edgeequality, nflex, 1) /* 0: none, 1: edges, 2: vertices, 3: strain */ \
  X(int, flex_rigid, nflex, 1)                     \
  X(int, flexedge_rigid, nflexedge, 1)             \
  X(int, flex_centered, nflex, 1)                  \
  X(int, flex_flatskin, nflex, 1)                  \
  X(int, flex_bvhadr, nflex, 1)                    \
  X(int, flex_bvhnum, nflex, 1)                    \
  X(int, flexedge_J_rownnz, nflexedge, 1)          \
  X(int, flexedge_J_rowadr, nflexedge, 1)          \
  X(int, flexedge_J_colind, nJfe, 1)               \
  X(int, flexvert_J_rownnz, nflexvert, 2)          \
  X(int, flexvert_J_rowadr, nflexvert, 2)          \
  X(int, flexvert_J_colind, nJfv, 2)               \
  X(double, flex_rgba, nflex, 4)                   \
  X(double, flex_texcoord, nflextexcoord, 2)       \
  /* explicit contact pairs and excluded body pairs */ \
  X(int, pair_dim, npair, 1)                       \
  X(int, pair_geom1, npair, 1)                     \
  X(int, pair_geom2, npair, 1)                     \
  X(int, pair_signature, npair, 1)                 \
  X(double, pair_solref, npair, kNRef)             \
  X(double, pair_solreffriction, npair, kNRef)     \
  X(double, pair_solimp, npair, kNImp)             \
  X(double, pair_margin, npair, 1)                 \
  X(double, pair_gap, npair, 1)                    \
  X(double, pair_friction, npair, 5)               \
  X(int, exclude_signature, nexclude, 1)           \
  /* sites */                                      \
  X(int, site_type, nsite, 1)                      \
  X(int, site_bodyid, nsite, 1)                    \
  X(int, site_group, nsite, 1)                     \
  X(int, site_sameframe, nsite, 1)                 \
  X(double, site_size, nsite, 3)                   \
  X(double, site_pos, nsite, 3)                    \
  X(double, site_quat, nsite, 4)                   \
  X(double, site_rgba, nsite, 4)                   \
  X(int, site_matid, nsite, 1)                     \
  /* cameras (sensorsize and intrinsic hold float-rounded values, as MuJoCo) */ \
  X(int, cam_mode, ncam, 1)                        \
  X(int, cam_bodyid, ncam, 1)                      \
  X(int, cam_targetbodyid, ncam, 1)                \
  X(double, cam_pos, ncam, 3)                      \
  X(double, cam_quat, ncam, 4)                     \
  X(double, cam_poscom0, ncam, 3)                  \
  X(double, cam_pos0, ncam, 3)                     \
  X(double, cam_mat0, ncam, 9)                     \
  X(int, cam_projection, ncam, 1)                  \
  X(double, cam_fovy, ncam, 1)                     \
  X(double, cam_ipd, ncam, 1)                      \
  X(int, cam_resolution, ncam, 2)                  \
  X(int, cam_output, ncam, 1)                      \
  X(double, cam_sensorsize, ncam, 2)               \
  X(double, cam_intrinsic, ncam, 4)                \
  /* lights (colours and intensities float-rounded, as MuJoCo's) */ \
  X(int, light_mode, nlight, 1)   /* mjtCamLight, as cam_mode */ \
  X(int, light_bodyid, nlight, 1)                  \
  X(int, light_targetbodyid, nlight, 1)            \
  X(int, light_type, nlight, 1)   /* mjtLightType: spot, directional, point, image */ \
  X(int, light_texid, nlight, 1)                   \
  X(int, light_castshadow, nlight, 1)              \
  X(double, light_bulbradius, nlight, 1)           \
  X(double, light_intensity, nlight, 1)            \
  X(double, light_range, nlight, 1)                \
  X(int, light_active, nlight, 1)                  \
  X(double, light_pos, nlight, 3)                  \
  X(double, light_dir, nlight, 3)                  \
  X(double, light_poscom0, nlight, 3)              \
  X(double, light_pos0, nlight, 3)                 \
  X(double, light_dir0, nlight, 3)                 \
  X(double, light_attenuation, nlight, 3)          \
  X(double, light_cutoff, nlight, 1)               \
  X(double, light_exponent, nlight, 1)             \
  X(double, light_ambient, nlight, 3)              \
  X(double, light_diffuse, nlight, 3)              \
  X(double, light_specular, nlight, 3)             \
  /* textures: tex_data holds bytes (0-255), row by row, nchannel per pixel; cube and \
     skybox textures are 6 square faces stacked (height = 6 width) */ \
  X(int, tex_type, ntex, 1)       /* mjtTexture: 2d, cube, skybox */ \
  X(int, tex_colorspace, ntex, 1)                  \
  X(int, tex_height, ntex, 1)                      \
  X(int, tex_width, ntex, 1)                       \
  X(int, tex_nchannel, ntex, 1)                    \
  X(int, tex_adr, ntex, 1)                         \
  X(int, tex_data, ntexdata, 1)                    \
  /* materials (float-rounded, as MuJoCo's); mat_texid: a texture per mjtTextureRole */ \
  X(int, mat_texid, nmat, kNTexRole)               \
  X(int, mat_texuniform, nmat, 1)                  \
  X(double, mat_texrepeat, nmat, 2)                \
  X(double, mat_emission, nmat, 1)                 \
  X(double, mat_specular, nmat, 1)                 \
  X(double, mat_shininess, nmat, 1)                \
  X(double, mat_reflectance, nmat, 1)              \
  X(double, mat_metallic, nmat, 1)                 \
  X(double, mat_roughness, nmat, 1)                \
  X(double, mat_rgba, nmat, 4)                     \
  /* equality constraints */                       \
  X(int, eq_type, neq, 1)                          \
  X(int, eq_obj1id, neq, 1)                        \
  X(int, eq_obj2id, neq, 1)                        \
  X(int, eq_objtype, neq, 1)                       \
  X(int, eq_active0, neq, 1)                       \
  X(double, eq_solref, neq, kNRef)                 \
  X(double, eq_solimp, neq, kNImp)                 \
  X(double, eq_data, neq, kNEqData)                \
  /* fixed and spatial tendons */                  \
  X(int, tendon_adr, ntendon, 1)                   \
  X(int, tendon_num, ntendon, 1)                   \
  X(int, tendon_limited, ntendon, 1)               \
  X(int, tendon_actfrclimited, ntendon, 1)         \
  X(double, tendon_solref_lim, ntendon, kNRef)     \
  X(double, tendon_solimp_lim, ntendon, kNImp)     \
  X(double, tendon_solref_fri, ntendon, kNRef)     \
  X(double, tendon_solimp_fri, ntendon, kNImp)     \
  X(double, tendon_range, ntendon, 2)              \
  X(double, tendon_actfrcrange, ntendon, 2)        \
  X(double, tendon_margin, ntendon, 1)             \
  X(double, tendon_stiffness, ntendon, 1)          \
  X(double, tendon_damping, ntendon, 1)            \
  X(double, tendon_armature, ntendon, 1)           \
  X(double, tendon_frictionloss, ntendon, 1)       \
  X(double, tendon_lengthspring, ntendon, 2)       \
  X(double, tendon_length0, ntendon, 1)            \
  X(double, tendon_invweight0, ntendon, 1)         \
  X(int, tendon_actuatorid, ntendon, 1)            \
  X(int, tendon_treenum, ntendon, 1) /* trees along the path */ \
  X(int, tendon_treeid, ntendon, 2) /* its first two trees, -1: none */ \
  X(int, wrap_type, nwrap, 1)                      \
  X(int, wrap_objid, nwrap, 1)                     \
  X(double, wrap_prm, nwrap, 1)                    \
  /* actuators */                                  \
  X(int, actuator_trntype, nactuator, 1)           \
  X(int, actuator_dyntype, nactuator, 1)           \
  X(int, actuator_gaintype, nactuator, 1)          \
  X(int, actuator_biastype, nactuator, 1)          \
  X(int, actuator_ctrladr, nactuator, 1)  /* first control in ctrl */ \
  X(int, actuator_ctrlnum, nactuator, 1)  /* controls it reads */     \
  X(int, actuator_ctrlspec, nactuator, 1) /* input signature */       \
  X(int, actuator_outadr, nactuator, 1)   /* first force output */    \
  X(int, actuator_outnum, nactuator, 1)   /* force outputs */         \
  X(int, actuator_trnid, nactuator, 2)             \
  X(int, actuator_actadr, nactuator, 1)            \
  X(int, actuator_actnum, nactuator, 1)            \
  X(int, actuator_group, nactuator, 1)             \
  X(int, actuator_ctrllimited, nu, 1)              \
  X(int, actuator_forcelimited, nactuator, 1)      \
  X(int, actuator_actlimited, nactuator, 1)        \
  X(int, actuator_actearly, nactuator, 1)          \
  X(double, actuator_dynprm, nactuator, kNDyn)     \
  X(double, actuator_gainprm, nactuator, kNGain)   \
  X(double, actuator_biasprm, nactuator, kNBias)   \
  X(double, actuator_ctrlrange, nu, 2)             \
  X(double, actuator_forcerange, nactuator, 2)     \
  X(double, actuator_actrange, nactuator, 2)       \
  X(double, actuator_gear, nout, 6)                \
  X(double, actuator_cranklength, nactuator, 1)    \
  X(double, actuator_acc0, nout, 1)                \
  X(double, actuator_length0, nout, 1)             \
  X(double, actuator_lengthrange, nout, 2)         \
  X(double, actuator_damping, nactuator, 1)        \
  X(double, actuator_dampingpoly, nactuator, kNPoly) \
  X(double, actuator_armature, nactuator, 1)       \
  X(int, actuator_history, nactuator, 2)  /* nsample, interp */      \
  X(int, actuator_historyadr, nactuator, 1) /* -1: none */         \
  X(double, actuator_delay, nactuator, 1)          \
  X(int, actuator_plugin, nactuator, 1) /* plugin instance, or -1 */ \
  /* sensors */                                    \
  X(int, sensor_type, nsensor, 1)                  \
  X(int, sensor_datatype, nsensor, 1)              \
  X(int, sensor_needstage, nsensor, 1)             \
  X(int, sensor_objtype, nsensor, 1)               \
  X(int, sensor_objid, nsensor, 1)                 \
  X(int, sensor_reftype, nsensor, 1)               \
  X(int, sensor_refid, nsensor, 1)                 \
  X(int, sensor_intprm, nsensor, kNSens)           \
  X(int, sensor_dim, nsensor, 1)                   \
  X(int, sensor_adr, nsensor, 1)                   \
  X(double, sensor_cutoff, nsensor, 1)             \
  X(double, sensor_noise, nsensor, 1)              \
  X(int, sensor_history, nsensor, 2)   /* nsample, interp */ \
  X(int, sensor_historyadr, nsensor, 1) /* -1: none */       \
  X(double, sensor_delay, nsensor, 1)              \
  X(double, sensor_interval, nsensor, 2) /* period, phase */ \
  X(double, sensor_user, nsensor, nuser_sensor)    \
  X(int, sensor_plugin, nsensor, 1) /* plugin instance, or -1 */ \
  /* plugin instances */                           \
  X(int, plugin, nplugin, 1)        /* registry slot */ \
  X(int, plugin_stateadr, nplugin, 1)              \
  X(int, plugin_statenum, nplugin, 1)              \
  X(int, plugin_attradr, nplugin, 1) /* in plugin_attr */ \
  /* keyframes */                                  \
  X(double, key_time, nkey, 1)                     \
  X(double, key_qpos, nkey, nq)                    \
  X(double, key_qvel, nkey, nv)                    \
  X(double, key_act, nkey, na)                     \
  X(double, key_mpos, nkey, nmocap3)               \
  X(double, key_mquat, nkey, nmocap4)              \
  X(double, key_ctrl, nkey, nu)

// The names of the object kinds that carry names, with their count member.
#define SIMLAB_MODEL_NAMED(X) \
  X(body, nbody)              \
  X(jnt, njnt)                \
  X(geom, ngeom)              \
  X(site, nsite)              \
  X(cam, ncam)                \
  X(mesh, nmesh)              \
  X(hfield, nhfield)          \
  X(skin, nskin)              \
  X(flex, nflex)              \
  X(light, nlight)            \
  X(tex, ntex)                \
  X(mat, nmat)                \
  X(pair, npair)              \
  X(exclude, nexclude)        \
  X(eq, neq)                  \
  X(tendon, ntendon)          \
  X(actuator, nactuator)      \
  X(sensor, nsensor)          \
  X(key, nkey)

// The size members, which give the array shapes in the field tables.
#define SIMLAB_MODEL_SIZES(X)                                              \
  X(nq)          /* generalized coordinates */                             \
  X(nv)          /* degrees of freedom */                                  \
  X(nactuator)   /* actuators */                                           \
  X(nu)          /* scalar controls, the length of ctrl */                 \
  X(nout)        /* actuator force outputs (actuator_force rows) */        \
  X(na)          /* activation states */                                   \
  X(nbody)       /* bodies, including the world body 0 */                  \
  X(ntree)       /* kinematic trees: roots of the dof forest */            \
  X(njnt)        /* joints */                                              \
  X(ngeom)       /* geoms */                                               \
  X(nsite)       /* sites */                                               \
  X(ncam)        /* cameras */                                             \
  X(nmesh)       /* meshes */                                              \
  X(nmeshvert)   /* vertices of all meshes */                              \
  X(nmeshface)   /* triangles of all meshes */                             \
  X(nmeshgraph)  /* ints of all convex-hull graphs (mesh_graph) */         \
  X(nmeshpoly)   /* polygons of the meshes' hulls */                       \
  X(nmeshpolyvert) /* vertices of all polygons */                          \
  X(nmeshpolymap) /* vertex-to-polygon entries */                          \
  X(noct)        /* cells of the meshes' signed distance octrees */        \
  X(nmeshnormal) /* normals of all meshes (mesh_normal rows) */           \
  X(nmeshtexcoord) /* texture coordinates of all meshes */                \
  X(nhfield)     /* height fields */                                       \
  X(nhfielddata) /* elevation numbers of all height fields */              \
  X(nskin)       /* skins */                                               \
  X(nskinvert)   /* vertices of all skins */                               \
  X(nskintexvert) /* texture coordinates of all skins */                   \
  X(nskinface)   /* triangles of all skins */                              \
  X(nskinbone)   /* bones of all skins */                                  \
  X(nskinbonevert) /* vertex weights of all bones */                       \
  X(nflex)       /* flexes */                                              \
  X(nflexnode)   /* nodes of all interpolated flexes */                    \
  X(nflexvert)   /* vertices of all flexes */                              \
  X(nflexedge)   /* edges of all flexes */                                 \
  X(nflexelem)   /* elements of all flexes */                              \
  X(nflexelemdata) /* element vertex ids of all flexes */                  \
  X(nflexstiffness) /* stiffness numbers of all flexes */                  \
  X(nflexbending) /* bending numbers of all flexes */                      \
  X(nflexelemedge) /* element edge ids of all flexes */                    \
  X(nflexshelldata) /* shell fragment vertex ids of all flexes */          \
  X(nflexevpair) /* element-vertex collision pairs of all flexes */        \
  X(nflextexcoord) /* texture coordinates of all flexes */                 \
  X(nJfe)        /* nonzeros of the sparse flex edge Jacobian */           \
  X(nJfv)        /* nonzeros of the sparse flex vertex Jacobian */         \
  X(nlight)      /* lights */                                              \
  X(ntex)        /* textures */                                            \
  X(ntexdata)    /* bytes of all textures */                               \
  X(nmat)        /* materials */                                           \
  X(npair)       /* explicit geom pairs (<contact><pair>) */               \
  X(nexclude)    /* excluded body pairs (<contact><exclude>) */            \
  X(ntendon)     /* tendons */                                             \
  X(nwrap)       /* tendon path elements */                                \
  X(neq)         /* equality constraints */                                \
  X(nsensor)     /* sensors */                                             \
  X(nsensordata) /* numbers of sensor output */                            \
  X(nuser_sensor) /* user numbers per sensor */                            \
  X(nhistory)    /* numbers in the actuator and sensor history buffer */   \
  X(nkey)        /* keyframes */                                           \
  X(nmocap)      /* mocap bodies */                                        \
  X(nmocap3)     /* 3 * nmocap (row width of key_mpos) */                  \
  X(nmocap4)     /* 4 * nmocap (row width of key_mquat) */                 \
  X(nbvh)        /* bounding volumes: the bodies' geom trees, then the flexes' */ \
  X(nbvhstatic)  /* those of the bodies (boxes in bvh_aabb) */             \
  X(nbvhdynamic) /* those of the flexes (boxes in Data::bvh_aabb_dyn) */    \
  X(nD)          /* nonzeros of the dof-dof pattern D, 2 nM - nv */        \
  X(nB)          /* nonzeros of the body-dof pattern B */                  \
  X(nM)          /* nonzeros of the inertia matrix in tree layout */       \
  X(ngravcomp)   /* bodies with positive gravcomp */                       \
  X(nplugin)     /* plugin instances (<extension>, or implicit ones) */    \
  X(npluginstate) /* numbers in plugin_state, all instances */

// A view of one array of a Model or Data by its MuJoCo name (for bindings and the lab).
struct FieldView {
  const char* name = nullptr;
  const char* rows_name = "";  // the size member that counts its rows ("nbody")
  const char* cols_name = "";  // its column count as the table writes it ("1", "kNGain", "nq")
  bool is_int = false;
  double* doubles = nullptr;
  int* ints = nullptr;
  int rows = 0;
  int cols = 0;

  // MuJoCo's shape: (rows,) when the table's column count is the literal 1, else
  // (rows, cols) (so key_qpos stays (nkey, nq) even when nq is 1).
  bool one_dimensional() const { return cols_name[0] == '1' && cols_name[1] == '\0'; }
};

// ---------------------------------------------------------------- Model

// The MuJoCo release whose behaviour a model follows where releases differ.
enum class Release : int {
  k3_5_1,  // the conformance oracle's (npm mujoco 3.5.1): every model it can load
  k3_12,   // MuJoCo 3.12: a model that uses a construct 3.5.1 does not define
};

struct Model {
#define SIMLAB_X(size) int size = 0;
  SIMLAB_MODEL_SIZES(SIMLAB_X)
#undef SIMLAB_X

  // 3.12 when the model uses a construct only MuJoCo 3.12 defines (a flex's cellcount or
  // node dof, a flexcomp's cells, shell, strain equality or dof="2d", a flexstrain
  // equality): 3.5.1 cannot run it, so 3.12 is its only reference, and the engine
  // follows 3.12 where the two differ (flex contacts thinned per collision pair; flexes
  // held by equalities may sleep). Set by the compiler.
  Release release = Release::k3_5_1;

  Option opt;
  Statistic stat;
  Visual vis;
  std::string model_name;

  // arrays, from the table
#define SIMLAB_X(type, name, rows, cols) std::vector<type> name;
  SIMLAB_MODEL_FIELDS(SIMLAB_X)
#undef SIMLAB_X

  // Plugin instances' configuration: for each, its plugin's attributes in declared order,
  // each a string ended by '\0' ("" when not given), from plugin_attradr on.
  std::string plugin_attr;

  // names of objects, one vector per named kind (body_names[i] is body i's name, or "")
#define SIMLAB_X(kind, count) std::vector<std::string> kind##_names;
  SIMLAB_MODEL_NAMED(SIMLAB_X)
#undef SIMLAB_X

  // Resizes every array to the sizes above (values are zero-filled).
  void Allocate();

  // The names of the objects of a kind (body_names for kObjBody and kObjXBody...), or
  // null for a kind without names.
  const std::vector<std::string>* Names(ObjType type) const;

  // Id of the named object of the given kind, or -1 (by hash once IndexNames ran, which
  // the compiler does; by a scan of the names otherwise).
  int NameToId(ObjType type, const std::string& name) const;

  // Builds the name -> id tables NameToId uses; call again after renaming objects.
  void IndexNames();

  // Every array of the model, in table order.
  std::vector<FieldView> Fields();

  // name -> id per object kind (indexed by ObjType), filled by IndexNames. The first of
  // equal names wins, as in MuJoCo; unnamed objects are not listed.
  std::vector<std::unordered_map<std::string, int>> name_index;
};


}  // namespace simlab

#endif  // SIMLAB_MODEL_H_
