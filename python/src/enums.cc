// MuJoCo's enums (mjtObj, mjtGeom, ... with their mj* member names and values), as
// arithmetic Python enums: they compare equal to the integers in model arrays, combine
// with | and pass wherever an int is taken.
#include <initializer_list>
#include <utility>

#include "simlab/support.h"
#include "wrappers.h"

namespace simlab::python {

namespace {

// Camera and light tracking modes (mjtCamLight); the engine stores them as ints.
enum CamLight : int {};
// Frames the visualizer can draw (mjtFrame), for scripts that name them.
enum FrameKind : int {};
// Values MuJoCo's enums have that simlab's have no member for are cast from int.
template <typename E>
void DefineEnum(py::module_& m, const char* name,
                std::initializer_list<std::pair<const char*, int>> values) {
  py::enum_<E> e(m, name, py::arithmetic());
  for (const auto& [member, value] : values) e.value(member, static_cast<E>(value));
}

void DefineModelEnums(py::module_& m) {
  DefineEnum<ObjType>(m, "mjtObj", {
      {"mjOBJ_UNKNOWN", 0}, {"mjOBJ_BODY", 1}, {"mjOBJ_XBODY", 2}, {"mjOBJ_JOINT", 3},
      {"mjOBJ_DOF", 4}, {"mjOBJ_GEOM", 5}, {"mjOBJ_SITE", 6}, {"mjOBJ_CAMERA", 7},
      {"mjOBJ_LIGHT", 8}, {"mjOBJ_FLEX", 9}, {"mjOBJ_MESH", 10}, {"mjOBJ_SKIN", 11},
      {"mjOBJ_HFIELD", 12}, {"mjOBJ_TEXTURE", 13}, {"mjOBJ_MATERIAL", 14}, {"mjOBJ_PAIR", 15},
      {"mjOBJ_EXCLUDE", 16}, {"mjOBJ_EQUALITY", 17}, {"mjOBJ_TENDON", 18},
      {"mjOBJ_ACTUATOR", 19}, {"mjOBJ_SENSOR", 20}, {"mjOBJ_NUMERIC", 21}, {"mjOBJ_TEXT", 22},
      {"mjOBJ_TUPLE", 23}, {"mjOBJ_KEY", 24}, {"mjOBJ_PLUGIN", 25}, {"mjNOBJECT", 26},
      {"mjOBJ_FRAME", 100}, {"mjOBJ_DEFAULT", 101}, {"mjOBJ_MODEL", 102}});
  DefineEnum<GeomType>(m, "mjtGeom", {
      {"mjGEOM_PLANE", 0}, {"mjGEOM_HFIELD", 1}, {"mjGEOM_SPHERE", 2}, {"mjGEOM_CAPSULE", 3},
      {"mjGEOM_ELLIPSOID", 4}, {"mjGEOM_CYLINDER", 5}, {"mjGEOM_BOX", 6}, {"mjGEOM_MESH", 7},
      {"mjGEOM_SDF", 8}, {"mjNGEOMTYPES", 9}, {"mjGEOM_ARROW", 100}, {"mjGEOM_ARROW1", 101},
      {"mjGEOM_ARROW2", 102}, {"mjGEOM_LINE", 103}, {"mjGEOM_LINEBOX", 104},
      {"mjGEOM_FLEX", 105}, {"mjGEOM_SKIN", 106}, {"mjGEOM_LABEL", 107},
      {"mjGEOM_TRIANGLE", 108}, {"mjGEOM_NONE", 1001}});
  DefineEnum<JointType>(m, "mjtJoint", {
      {"mjJNT_FREE", 0}, {"mjJNT_BALL", 1}, {"mjJNT_SLIDE", 2}, {"mjJNT_HINGE", 3}});
  DefineEnum<CamLight>(m, "mjtCamLight", {
      {"mjCAMLIGHT_FIXED", 0}, {"mjCAMLIGHT_TRACK", 1}, {"mjCAMLIGHT_TRACKCOM", 2},
      {"mjCAMLIGHT_TARGETBODY", 3}, {"mjCAMLIGHT_TARGETBODYCOM", 4}});
  DefineEnum<EqType>(m, "mjtEq", {
      {"mjEQ_CONNECT", 0}, {"mjEQ_WELD", 1}, {"mjEQ_JOINT", 2}, {"mjEQ_TENDON", 3},
      {"mjEQ_FLEX", 4}, {"mjEQ_FLEXVERT", 5}, {"mjEQ_FLEXSTRAIN", 6}, {"mjEQ_DISTANCE", 7}});
  DefineEnum<FrameKind>(m, "mjtFrame", {
      {"mjFRAME_NONE", 0}, {"mjFRAME_BODY", 1}, {"mjFRAME_GEOM", 2}, {"mjFRAME_SITE", 3},
      {"mjFRAME_CAMERA", 4}, {"mjFRAME_LIGHT", 5}, {"mjFRAME_CONTACT", 6},
      {"mjFRAME_WORLD", 7}, {"mjNFRAME", 8}});
  DefineEnum<WrapType>(m, "mjtWrap", {
      {"mjWRAP_NONE", 0}, {"mjWRAP_JOINT", 1}, {"mjWRAP_PULLEY", 2}, {"mjWRAP_SITE", 3},
      {"mjWRAP_SPHERE", 4}, {"mjWRAP_CYLINDER", 5}});
}

void DefineActuatorEnums(py::module_& m) {
  DefineEnum<TrnType>(m, "mjtTrn", {
      {"mjTRN_JOINT", 0}, {"mjTRN_JOINTINPARENT", 1}, {"mjTRN_SLIDERCRANK", 2},
      {"mjTRN_TENDON", 3}, {"mjTRN_SITE", 4}, {"mjTRN_BODY", 5}, {"mjTRN_SO3", 6},
      {"mjTRN_UNDEFINED", 1000}});
  DefineEnum<DynType>(m, "mjtDyn", {
      {"mjDYN_NONE", 0}, {"mjDYN_INTEGRATOR", 1}, {"mjDYN_FILTER", 2},
      {"mjDYN_FILTEREXACT", 3}, {"mjDYN_MUSCLE", 4}, {"mjDYN_DCMOTOR", 5}, {"mjDYN_PID", 6},
      {"mjDYN_USER", 7}});
  DefineEnum<GainType>(m, "mjtGain", {
      {"mjGAIN_FIXED", 0}, {"mjGAIN_AFFINE", 1}, {"mjGAIN_MUSCLE", 2}, {"mjGAIN_DCMOTOR", 3},
      {"mjGAIN_SO3", 4}, {"mjGAIN_PID", 5}, {"mjGAIN_USER", 6}});
  DefineEnum<BiasType>(m, "mjtBias", {
      {"mjBIAS_NONE", 0}, {"mjBIAS_AFFINE", 1}, {"mjBIAS_MUSCLE", 2}, {"mjBIAS_DCMOTOR", 3},
      {"mjBIAS_SO3", 4}, {"mjBIAS_USER", 5}});
  DefineEnum<CtrlInput>(m, "mjtCtrlInput", {
      {"mjINPUT_POS", 1}, {"mjINPUT_VEL", 2}, {"mjINPUT_FF", 4}, {"mjINPUT_VOLTAGE", 8},
      {"mjINPUT_NONE", 16}});
  DefineEnum<CtrlChart>(m, "mjtCtrlChart", {{"mjCHART_EXPMAP", 1}, {"mjCHART_QUAT", 2}});
}

void DefineSensorEnums(py::module_& m) {
  DefineEnum<SensorType>(m, "mjtSensor", {
      {"mjSENS_TOUCH", 0}, {"mjSENS_ACCELEROMETER", 1}, {"mjSENS_VELOCIMETER", 2},
      {"mjSENS_GYRO", 3}, {"mjSENS_FORCE", 4}, {"mjSENS_TORQUE", 5},
      {"mjSENS_MAGNETOMETER", 6}, {"mjSENS_RANGEFINDER", 7}, {"mjSENS_CAMPROJECTION", 8},
      {"mjSENS_JOINTPOS", 9}, {"mjSENS_JOINTVEL", 10}, {"mjSENS_TENDONPOS", 11},
      {"mjSENS_TENDONVEL", 12}, {"mjSENS_ACTUATORPOS", 13}, {"mjSENS_ACTUATORVEL", 14},
      {"mjSENS_ACTUATORFRC", 15}, {"mjSENS_JOINTACTFRC", 16}, {"mjSENS_TENDONACTFRC", 17},
      {"mjSENS_BALLQUAT", 18}, {"mjSENS_BALLANGVEL", 19}, {"mjSENS_JOINTLIMITPOS", 20},
      {"mjSENS_JOINTLIMITVEL", 21}, {"mjSENS_JOINTLIMITFRC", 22},
      {"mjSENS_TENDONLIMITPOS", 23}, {"mjSENS_TENDONLIMITVEL", 24},
      {"mjSENS_TENDONLIMITFRC", 25}, {"mjSENS_FRAMEPOS", 26}, {"mjSENS_FRAMEQUAT", 27},
      {"mjSENS_FRAMEXAXIS", 28}, {"mjSENS_FRAMEYAXIS", 29}, {"mjSENS_FRAMEZAXIS", 30},
      {"mjSENS_FRAMELINVEL", 31}, {"mjSENS_FRAMEANGVEL", 32}, {"mjSENS_FRAMELINACC", 33},
      {"mjSENS_FRAMEANGACC", 34}, {"mjSENS_SUBTREECOM", 35}, {"mjSENS_SUBTREELINVEL", 36},
      {"mjSENS_SUBTREEANGMOM", 37}, {"mjSENS_INSIDESITE", 38}, {"mjSENS_GEOMDIST", 39},
      {"mjSENS_GEOMNORMAL", 40}, {"mjSENS_GEOMFROMTO", 41}, {"mjSENS_CONTACT", 42},
      {"mjSENS_E_POTENTIAL", 43}, {"mjSENS_E_KINETIC", 44}, {"mjSENS_CLOCK", 45},
      {"mjSENS_TACTILE", 46}, {"mjSENS_PLUGIN", 47}, {"mjSENS_USER", 48}});
  DefineEnum<Stage>(m, "mjtStage", {
      {"mjSTAGE_NONE", 0}, {"mjSTAGE_POS", 1}, {"mjSTAGE_VEL", 2}, {"mjSTAGE_ACC", 3}});
  DefineEnum<DataType>(m, "mjtDataType", {
      {"mjDATATYPE_REAL", 0}, {"mjDATATYPE_POSITIVE", 1}, {"mjDATATYPE_AXIS", 2},
      {"mjDATATYPE_QUATERNION", 3}});
  DefineEnum<ConDataField>(m, "mjtConDataField", {
      {"mjCONDATA_FOUND", 0}, {"mjCONDATA_FORCE", 1}, {"mjCONDATA_TORQUE", 2},
      {"mjCONDATA_DIST", 3}, {"mjCONDATA_POS", 4}, {"mjCONDATA_NORMAL", 5},
      {"mjCONDATA_TANGENT", 6}, {"mjNCONDATA", 7}});
  DefineEnum<RayDataField>(m, "mjtRayDataField", {
      {"mjRAYDATA_DIST", 0}, {"mjRAYDATA_DIR", 1}, {"mjRAYDATA_ORIGIN", 2},
      {"mjRAYDATA_POINT", 3}, {"mjRAYDATA_NORMAL", 4}, {"mjRAYDATA_DEPTH", 5},
      {"mjNRAYDATA", 6}});
}

void DefineOptionEnums(py::module_& m) {
  DefineEnum<Integrator>(m, "mjtIntegrator", {
      {"mjINT_EULER", 0}, {"mjINT_RK4", 1}, {"mjINT_IMPLICIT", 2}, {"mjINT_IMPLICITFAST", 3}});
  DefineEnum<ConeType>(m, "mjtCone", {{"mjCONE_PYRAMIDAL", 0}, {"mjCONE_ELLIPTIC", 1}});
  DefineEnum<JacobianType>(m, "mjtJacobian", {
      {"mjJAC_DENSE", 0}, {"mjJAC_SPARSE", 1}, {"mjJAC_AUTO", 2}});
  DefineEnum<SolverType>(m, "mjtSolver", {
      {"mjSOL_PGS", 0}, {"mjSOL_CG", 1}, {"mjSOL_NEWTON", 2}});
  DefineEnum<DisableBit>(m, "mjtDisableBit", {
      {"mjDSBL_CONSTRAINT", 1 << 0}, {"mjDSBL_EQUALITY", 1 << 1},
      {"mjDSBL_FRICTIONLOSS", 1 << 2}, {"mjDSBL_LIMIT", 1 << 3}, {"mjDSBL_CONTACT", 1 << 4},
      {"mjDSBL_SPRING", 1 << 5}, {"mjDSBL_DAMPER", 1 << 6}, {"mjDSBL_GRAVITY", 1 << 7},
      {"mjDSBL_CLAMPCTRL", 1 << 8}, {"mjDSBL_WARMSTART", 1 << 9},
      {"mjDSBL_FILTERPARENT", 1 << 10}, {"mjDSBL_ACTUATION", 1 << 11},
      {"mjDSBL_REFSAFE", 1 << 12}, {"mjDSBL_SENSOR", 1 << 13}, {"mjDSBL_MIDPHASE", 1 << 14},
      {"mjDSBL_EULERDAMP", 1 << 15}, {"mjDSBL_AUTORESET", 1 << 16},
      {"mjDSBL_NATIVECCD", 1 << 17}, {"mjDSBL_ISLAND", 1 << 18}, {"mjNDISABLE", 19}});
  DefineEnum<EnableBit>(m, "mjtEnableBit", {
      {"mjENBL_OVERRIDE", 1 << 0}, {"mjENBL_ENERGY", 1 << 1}, {"mjENBL_FWDINV", 1 << 2},
      {"mjENBL_INVDISCRETE", 1 << 3}, {"mjENBL_MULTICCD", 1 << 4}, {"mjENBL_SLEEP", 1 << 5},
      {"mjNENABLE", 6}});
}

void DefineDataEnums(py::module_& m) {
  DefineEnum<StateBit>(m, "mjtState", {
      {"mjSTATE_TIME", kStateTime}, {"mjSTATE_QPOS", kStateQpos}, {"mjSTATE_QVEL", kStateQvel},
      {"mjSTATE_ACT", kStateAct}, {"mjSTATE_HISTORY", kStateHistory},
      {"mjSTATE_WARMSTART", kStateWarmstart}, {"mjSTATE_CTRL", kStateCtrl},
      {"mjSTATE_QFRC_APPLIED", kStateQfrcApplied},
      {"mjSTATE_XFRC_APPLIED", kStateXfrcApplied}, {"mjSTATE_EQ_ACTIVE", kStateEqActive},
      {"mjSTATE_MOCAP_POS", kStateMocapPos}, {"mjSTATE_MOCAP_QUAT", kStateMocapQuat},
      {"mjSTATE_USERDATA", kStateUserdata}, {"mjSTATE_PLUGIN", kStatePlugin},
      {"mjNSTATE", kNStateBits}, {"mjSTATE_PHYSICS", kStatePhysics},
      {"mjSTATE_FULLPHYSICS", kStateFullPhysics}, {"mjSTATE_USER", kStateUser},
      {"mjSTATE_INTEGRATION", kStateIntegration}});
  DefineEnum<Warning>(m, "mjtWarning", {
      {"mjWARN_INERTIA", 0}, {"mjWARN_CONTACTFULL", 1}, {"mjWARN_CNSTRFULL", 2},
      {"mjWARN_VGEOMFULL", 3}, {"mjWARN_BADQPOS", 4}, {"mjWARN_BADQVEL", 5},
      {"mjWARN_BADQACC", 6}, {"mjWARN_BADCTRL", 7}, {"mjNWARNING", 8}});
  DefineEnum<ConstraintType>(m, "mjtConstraint", {
      {"mjCNSTR_EQUALITY", 0}, {"mjCNSTR_FRICTION_DOF", 1}, {"mjCNSTR_FRICTION_TENDON", 2},
      {"mjCNSTR_LIMIT_JOINT", 3}, {"mjCNSTR_LIMIT_TENDON", 4},
      {"mjCNSTR_CONTACT_FRICTIONLESS", 5}, {"mjCNSTR_CONTACT_PYRAMIDAL", 6},
      {"mjCNSTR_CONTACT_ELLIPTIC", 7}});
  DefineEnum<ConstraintState>(m, "mjtConstraintState", {
      {"mjCNSTRSTATE_SATISFIED", 0}, {"mjCNSTRSTATE_QUADRATIC", 1},
      {"mjCNSTRSTATE_LINEARNEG", 2}, {"mjCNSTRSTATE_LINEARPOS", 3},
      {"mjCNSTRSTATE_CONE", 4}});
}

}  // namespace

void DefineEnums(py::module_& m) {
  DefineModelEnums(m);
  DefineActuatorEnums(m);
  DefineSensorEnums(m);
  DefineOptionEnums(m);
  DefineDataEnums(m);
}

}  // namespace simlab::python
