// The spec tree: an MJCF file after parsing, with default classes applied and
// orientation alternatives kept as written (they are resolved by the compiler).
//
// Every element keeps its Source (file, line, tag, name) so that compile errors can
// point at the XML that caused them. Values start at MuJoCo's defaults (mjs_default*),
// then the class defaults, then the attributes written on the element.
#ifndef SIMLAB_MJCF_SPEC_H_
#define SIMLAB_MJCF_SPEC_H_

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mjcf/assets.h"
#include "simlab/model.h"

namespace simlab::mjcf {

inline constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

// Where an element came from, for error messages.
struct Source {
  std::string file;
  int line = 0;
  std::string tag;
  std::string name;
};

// Three-valued flags such as limited="false|true|auto".
enum TriState : int { kFalse = 0, kTrue = 1, kAuto = 2 };

// Orientation alternatives (MuJoCo's mjsOrientation): which one was written.
enum class OrientKind { kQuat, kAxisAngle, kXYAxes, kZAxis, kEuler };

struct Orientation {
  OrientKind kind = OrientKind::kQuat;
  std::array<double, 4> axisangle = {0, 0, 0, 0};
  std::array<double, 6> xyaxes = {0, 0, 0, 0, 0, 0};
  std::array<double, 3> zaxis = {0, 0, 0};
  std::array<double, 3> euler = {0, 0, 0};
};

// The <compiler> settings an element was written under when they are not this model's:
// an attached model's elements keep their own model's (MuJoCo compiles each element with
// its origin's settings). Null: this model's (SettingsOf resolves it).
struct CompilerSpec;
using CompilerPtr = std::shared_ptr<const CompilerSpec>;

// A <frame> element as written; frames nest through `parent`. Elements inside a
// frame point at it, and the compiler composes the chain into their poses.
struct FrameSpec {
  Source src;
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 4> quat = {1, 0, 0, 0};
  Orientation alt;
  std::shared_ptr<const FrameSpec> parent;
  CompilerPtr compiler;
};
using FramePtr = std::shared_ptr<const FrameSpec>;

// ---------------------------------------------------------------- tree elements

struct JointSpec {
  Source src;
  int type = kJointHinge;
  int group = 0;
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 3> axis = {0, 0, 1};
  std::array<double, 2> springdamper = {0, 0};
  int limited = kAuto;
  int actfrclimited = kAuto;
  std::array<double, kNRef> solref_limit = {0.02, 1};
  std::array<double, kNImp> solimp_limit = {0.9, 0.95, 0.001, 0.5, 2};
  std::array<double, kNRef> solref_friction = {0.02, 1};
  std::array<double, kNImp> solimp_friction = {0.9, 0.95, 0.001, 0.5, 2};
  double stiffness = 0;
  std::array<double, 2> range = {0, 0};
  std::array<double, 2> actfrcrange = {0, 0};
  bool actgravcomp = false;
  double margin = 0;
  double ref = 0;
  double springref = 0;
  double armature = 0;
  double damping = 0;
  double frictionloss = 0;
  int align = kAuto;
  FramePtr frame;
  CompilerPtr compiler;
};

// The plugin instance an element uses (<actuator><plugin>, <sensor><plugin>, a body's,
// geom's or mesh's <plugin>): the plugin and/or a named instance of it, or its own
// (implicit) instance, ModelSpec::implicit_instances[implicit_instance], which its
// <config> children configure.
struct PluginUse {
  bool active = false;
  std::string plugin, instance;
  int implicit_instance = -1;
};

struct GeomSpec {
  Source src;
  int type = kGeomSphere;
  std::array<double, 3> size = {0, 0, 0};
  int contype = 1;
  int conaffinity = 1;
  int condim = 3;
  int group = 0;
  int priority = 0;
  std::array<double, 3> friction = {1, 0.005, 0.0001};
  double solmix = 1;
  std::array<double, kNRef> solref = {0.02, 1};
  std::array<double, kNImp> solimp = {0.9, 0.95, 0.001, 0.5, 2};
  double margin = 0;
  double gap = 0;
  double mass = kUndefined;
  double density = 1000;
  bool shellinertia = false;
  std::array<double, 6> fromto = {kUndefined, 0, 0, 0, 0, 0};
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 4> quat = {1, 0, 0, 0};
  Orientation alt;
  std::array<double, 4> rgba = {0.5, 0.5, 0.5, 1};
  // Ellipsoid fluid model: on/off, then blunt drag, slender drag, angular drag, Kutta
  // lift and Magnus lift coefficients.
  bool fluid_ellipsoid = false;
  std::array<double, 5> fluidcoef = {0.5, 0.25, 1.5, 1.0, 1.0};
  std::string mesh;
  std::string hfield;
  std::string material;
  double fitscale = 1;  // scale of a primitive fitted to a mesh
  PluginUse plugin;     // an sdf geom's signed distance field plugin
  FramePtr frame;
  CompilerPtr compiler;
};

struct SiteSpec {
  Source src;
  int type = kGeomSphere;
  int group = 0;
  std::array<double, 3> size = {0.005, 0.005, 0.005};
  std::array<double, 6> fromto = {kUndefined, 0, 0, 0, 0, 0};
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 4> quat = {1, 0, 0, 0};
  Orientation alt;
  std::array<double, 4> rgba = {0.5, 0.5, 0.5, 1};
  std::string material;
  FramePtr frame;
  CompilerPtr compiler;
};

// A light (MuJoCo's mjsLight): where it sits in its body, where it points, and its colours.
struct LightSpec {
  Source src;
  int mode = 0;                // mjtCamLight, as cameras
  std::string target;          // target body of the targetbody modes
  int type = 0;                // mjtLightType: spot, directional, point, image
  bool castshadow = true;
  bool active = true;
  double bulbradius = 0.02, intensity = 0, range = 10;
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 3> dir = {0, 0, -1};
  std::array<double, 3> attenuation = {1, 0, 0};
  double cutoff = 45, exponent = 10;
  std::array<double, 3> ambient = {0, 0, 0};
  std::array<double, 3> diffuse = {0.7, 0.7, 0.7};
  std::array<double, 3> specular = {0.3, 0.3, 0.3};
  std::string texture;
  FramePtr frame;
  CompilerPtr compiler;
};

// A camera (MuJoCo's mjsCamera). Lengths of the sensor model (sensorsize, focal,
// principal) are single precision, as MuJoCo keeps them.
struct CameraSpec {
  Source src;
  int mode = 0;                // mjtCamLight: fixed, track, trackcom, targetbody(com)
  std::string target;          // target body of the tracking modes
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 4> quat = {1, 0, 0, 0};
  Orientation alt;
  int projection = 0;          // mjtProjection: perspective, orthographic
  std::array<int, 2> resolution = {1, 1};
  int output = 1;              // mjtCamOut bit flags (rgb)
  double fovy = 45;
  double ipd = 0.068;
  std::array<double, 2> sensorsize = {0, 0};
  std::array<double, 2> focal = {0, 0};
  std::array<double, 2> focalpixel = {0, 0};
  std::array<double, 2> principal = {0, 0};
  std::array<double, 2> principalpixel = {0, 0};
  FramePtr frame;
  CompilerPtr compiler;
};

struct BodySpec;

// A body's child bodies. They are owned, and copying the list copies the subtrees
// (an attached model's bodies are copies of the child model's).
struct BodyList : std::vector<std::unique_ptr<BodySpec>> {
  BodyList() = default;
  BodyList(BodyList&&) = default;
  BodyList& operator=(BodyList&&) = default;
  BodyList(const BodyList& other);
  BodyList& operator=(const BodyList& other);
};

struct BodySpec {
  Source src;
  std::array<double, 3> pos = {0, 0, 0};
  std::array<double, 4> quat = {1, 0, 0, 0};
  Orientation alt;
  bool mocap = false;
  double gravcomp = 0;
  int sleep = 0;  // SleepPolicy: auto, never, allowed or init
  FramePtr frame;
  CompilerPtr compiler;

  // <inertial>, if written (ipos[0] is NaN otherwise, as MuJoCo)
  bool explicit_inertial = false;
  Source inertial_src;
  std::array<double, 3> ipos = {kUndefined, 0, 0};
  std::array<double, 4> iquat = {1, 0, 0, 0};
  Orientation ialt;
  double mass = 0;
  std::array<double, 3> inertia = {0, 0, 0};
  std::array<double, 6> fullinertia = {kUndefined, 0, 0, 0, 0, 0};

  // children in XML order (frame contents included)
  std::vector<JointSpec> joints;
  std::vector<GeomSpec> geoms;
  std::vector<SiteSpec> sites;
  std::vector<CameraSpec> cameras;
  std::vector<LightSpec> lights;
  BodyList bodies;
  PluginUse plugin;  // a <plugin> child: the instance attached to this body
};

inline BodyList::BodyList(const BodyList& other) : std::vector<std::unique_ptr<BodySpec>>() {
  for (const auto& body : other) push_back(std::make_unique<BodySpec>(*body));
}

inline BodyList& BodyList::operator=(const BodyList& other) {
  if (this != &other) *this = BodyList(other);
  return *this;
}

// ---------------------------------------------------------------- other sections

// One element of a tendon path: a joint with its coefficient (fixed tendons), or a
// site, a wrapping geom with its optional side site, or a pulley with its divisor.
struct WrapSpec {
  Source src;
  int type = kWrapJoint;  // kWrapSphere stands for any geom until the compiler looks
  std::string target;     // joint, site or geom name
  std::string sidesite;
  double prm = 0;         // joint coefficient or pulley divisor
};

struct TendonSpec {
  Source src;
  CompilerPtr compiler;
  bool spatial = false;
  double width = 0.003;
  int group = 0;
  int limited = kAuto;
  int actfrclimited = kFalse;  // MuJoCo 3.5 leaves this one at false, not auto
  std::array<double, 2> range = {0, 0};
  std::array<double, 2> actfrcrange = {0, 0};
  std::array<double, kNRef> solref_limit = {0.02, 1};
  std::array<double, kNImp> solimp_limit = {0.9, 0.95, 0.001, 0.5, 2};
  std::array<double, kNRef> solref_friction = {0.02, 1};
  std::array<double, kNImp> solimp_friction = {0.9, 0.95, 0.001, 0.5, 2};
  double margin = 0;
  double stiffness = 0;
  double damping = 0;
  double armature = 0;
  double frictionloss = 0;
  std::array<double, 2> springlength = {-1, -1};
  std::vector<WrapSpec> wraps;
};

struct ActuatorSpec {
  Source src;
  CompilerPtr compiler;
  int group = 0;
  int ctrllimited = kAuto;
  int forcelimited = kAuto;
  int actlimited = kAuto;
  std::array<double, 2> ctrlrange = {0, 0};
  std::array<double, 2> forcerange = {0, 0};
  std::array<double, 2> actrange = {0, 0};
  std::array<double, 2> lengthrange = {0, 0};
  // ranges of a pid's velocity and feedforward inputs (limited when lo < hi)
  std::array<double, 2> velrange = {0, 0};
  std::array<double, 2> ffrange = {0, 0};
  int ctrlspec = 0;  // input signature (CtrlInput bits or CtrlChart); 0: the type's default
  std::array<double, 6> gear = {1, 0, 0, 0, 0, 0};
  double cranklength = 0;
  int trntype = kTrnUndefined;
  std::string target;
  std::string slidersite;
  std::string refsite;
  int dyntype = kDynNone;
  int gaintype = kGainFixed;
  int biastype = kBiasNone;
  std::array<double, kNDyn> dynprm = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  std::array<double, kNGain> gainprm = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  std::array<double, kNBias> biasprm = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  bool actearly = false;
  int actdim = -1;
  double inheritrange = 0;
  int nsample = 0;
  int interp = 0;  // of the delayed ctrl: 0 hold, 1 linear, 2 cubic
  double delay = 0;
  // damping at the transmission target: linear, then |v| v and v^3 terms (MuJoCo 3.7+)
  std::array<double, 1 + kNPoly> damping = {0, 0, 0};
  double armature = 0;
  // An actuator plugin (<actuator><plugin>), computed by the plugin instance it uses.
  PluginUse plugin;
};

// A plugin instance: <extension><plugin plugin=P><instance name=N> with its <config>
// key/values, or one made by an element that uses a plugin without naming an instance.
struct PluginInstanceSpec {
  Source src;
  std::string plugin, name;
  std::vector<std::pair<std::string, std::string>> config;
};

// A sensor (MuJoCo's mjsSensor): what it measures (type, object, reference object),
// and how its output is filtered, delayed and sampled.
struct SensorSpec {
  Source src;  // src.name is the sensor's name
  int type = kSensUser;
  int objtype = kObjUnknown;
  std::string objname;
  int reftype = kObjUnknown;
  std::string refname;
  std::array<int, kNSens> intprm = {0, 0, 0};
  int dim = 0;                   // user sensors only; the compiler sets the others'
  int datatype = kDataReal;      // user sensors only
  int needstage = kStageAcc;     // user sensors only
  double cutoff = 0;
  double noise = 0;
  int nsample = 0;
  int interp = 0;
  double delay = 0;
  std::array<double, 2> interval = {0, 0};
  std::vector<double> user;
  PluginUse plugin;  // a plugin sensor's instance (type kSensPlugin)
};

// An equality constraint (MuJoCo's mjsEquality). `data` starts at MuJoCo's shared
// default, which is why a weld's anchor slot reads 0 1 0 and torquescale is 1.
struct EqualitySpec {
  Source src;
  int type = kEqConnect;
  int objtype = kObjUnknown;  // body or site, for connect and weld
  std::string name1;
  std::string name2;          // empty: the world body, or no second joint/tendon
  bool active = true;
  std::array<double, kNRef> solref = {0.02, 1};
  std::array<double, kNImp> solimp = {0.9, 0.95, 0.001, 0.5, 2};
  std::array<double, kNEqData> data = {0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 1};
};

// An explicit contact pair (MuJoCo's mjsPair, with its defaults: the pair's own values
// are used, not a combination of the two geoms').
struct PairSpec {
  Source src;
  std::string geom1, geom2;
  int condim = 3;
  std::array<double, 5> friction = {1, 1, 0.005, 0.0001, 0.0001};
  std::array<double, kNRef> solref = {0.02, 1};
  std::array<double, kNRef> solreffriction = {0, 0};
  std::array<double, kNImp> solimp = {0.9, 0.95, 0.001, 0.5, 2};
  double margin = 0;
  double gap = 0;
};

// A body pair whose contacts are excluded (MuJoCo's mjsExclude).
struct ExcludeSpec {
  Source src;
  std::string body1, body2;
};

// How a mesh's mass properties are computed (mjtMeshInertia).
enum MeshInertia : int { kMeshConvex = 0, kMeshExact = 1, kMeshLegacy = 2, kMeshShell = 3 };

// A mesh asset (MuJoCo's mjsMesh): a file, or inline vertices and faces, with the
// reference frame and scale applied when compiling. Vertices are single precision as
// MuJoCo reads them.
// Builtin mesh shapes (mjtMeshBuiltin values).
enum MeshBuiltin : int {
  kMeshBuiltinNone = 0, kMeshBuiltinSphere, kMeshBuiltinHemisphere, kMeshBuiltinCone,
  kMeshBuiltinSupersphere, kMeshBuiltinSupertorus, kMeshBuiltinWedge, kMeshBuiltinPlate
};

struct MeshSpec {
  Source src;
  std::string file;          // as written (it names the mesh when `name` is absent)
  std::string path;          // file resolved against the model folder and meshdir
  std::string content_type;
  std::vector<float> vertex;
  std::vector<int> face;
  std::vector<float> normal;  // inline normals (x y z each); empty: the compiler makes them
  std::vector<float> texcoord;  // inline texture coordinates (u v per vertex)
  bool smoothnormal = false;  // keep faces at large angles in the vertex normals
  std::array<double, 3> refpos = {0, 0, 0};
  std::array<double, 4> refquat = {1, 0, 0, 0};
  std::array<double, 3> scale = {1, 1, 1};
  int inertia = kMeshLegacy;
  int maxhullvert = -1;      // -1: no limit
  int builtin = 0;           // mjtMeshBuiltin (0: none); the compiler makes its vertices
  std::vector<double> params;  // the builtin's parameters
  PluginUse plugin;  // a signed distance field plugin: the mesh is its zero level set
};

// A height field asset: a grid of elevations (rows from -y to +y, as MuJoCo stores them).
struct HFieldSpec {
  Source src;
  std::string file;          // as written (empty: the grid is given inline)
  std::string path;          // where it is read from (model folder, meshdir)
  std::string content_type;  // as written
  int nrow = 0, ncol = 0;
  std::array<double, 4> size = {0, 0, 0, 0};  // x, y half-sizes, top height, base depth
  std::vector<float> elevation;               // nrow * ncol, or empty (all zero)
};

// One bone of a skin (MuJoCo's <bone>): a body, the pose it was bound in, and the skin
// vertices it moves with their weights.
struct SkinBoneSpec {
  Source src;
  std::string body;
  std::array<float, 3> bindpos = {0, 0, 0};
  std::array<float, 4> bindquat = {0, 0, 0, 0};
  std::vector<int> vertid;
  std::vector<float> vertweight;
};

// A skin (MuJoCo's mjsSkin, in <asset> or <deformable>): a triangle mesh drawn over
// bodies, each vertex carried by its bones. Inline data or a .skn file, not both.
struct SkinSpec {
  Source src;
  std::string file;  // as written
  std::string path;  // resolved against the model folder and meshdir
  std::string material;
  std::array<float, 4> rgba = {0.5f, 0.5f, 0.5f, 1};
  float inflate = 0;
  int group = 0;
  std::vector<float> vertex, texcoord;
  std::vector<int> face;
  std::vector<SkinBoneSpec> bones;
};

// A flex (MuJoCo's mjsFlex, <deformable><flex> or made by a <flexcomp>): vertices on
// bodies (one body each, or all in one body, or interpolated from nodes on bodies), and
// elements of dim+1 vertices each, with their contact and elasticity settings.
enum FlexElastic2D : int { kElastic2DNone = 0, kElastic2DBend, kElastic2DStretch, kElastic2DBoth };

struct FlexSpec {
  Source src;
  // contact
  int contype = 1, conaffinity = 1, condim = 3, priority = 0;
  std::array<double, 3> friction = {1, 0.005, 0.0001};
  double solmix = 1;
  std::array<double, kNRef> solref = {0.02, 1};
  std::array<double, kNImp> solimp = {0.9, 0.95, 0.001, 0.5, 2};
  double margin = 0, gap = 0;
  bool internal = false;
  int selfcollide = kFlexSelfAuto;
  bool vertcollide = false;
  bool passive = false;
  int activelayers = 1;
  // shape and look
  int dim = 2;
  double radius = 0.005;
  int group = 0;
  std::string material;
  std::array<float, 4> rgba = {0.5f, 0.5f, 0.5f, 1};
  bool flatskin = false;
  // edges and elasticity
  double edgestiffness = 0, edgedamping = 0;
  double young = 0, poisson = 0, damping = 0, thickness = -1;
  int elastic2d = kElastic2DNone;
  // data: vertex bodies (one, or one per vertex), vertex positions in their bodies'
  // frames (empty: at the bodies' origins), elements, texture coordinates, and the
  // bodies and positions of interpolation nodes
  std::vector<std::string> vertbody, nodebody;
  std::vector<double> vert, node;
  std::vector<int> elem, elemtexcoord;
  std::vector<float> texcoord;
  int order = 0;  // interpolation order set by a flexcomp (0: from the node count)
  // The cells of the node grid along x, y, z (MuJoCo 3.12's cellcount): the nodes form a
  // (cx order + 1) x (cy order + 1) x (cz order + 1) lattice, x slowest; and the cells a
  // flexcomp found empty of elements (cx cy cz flags, or none: the compiler finds them).
  std::array<int, 3> cellcount = {1, 1, 1};
  std::vector<bool> cell_empty;
};

// A texture asset (MuJoCo's mjsTexture): a builtin pattern or image files.
enum TextureType : int { kTexture2D = 0, kTextureCube = 1, kTextureSkybox = 2 };
enum TextureBuiltin : int { kBuiltinNone = 0, kBuiltinGradient, kBuiltinChecker, kBuiltinFlat };
enum TextureMark : int { kMarkNone = 0, kMarkEdge, kMarkCross, kMarkRandom };

struct TextureSpec {
  Source src;
  int type = kTextureCube;
  int colorspace = 0;           // mjtColorSpace: auto, linear, sRGB
  int builtin = kBuiltinNone;
  int mark = kMarkNone;
  std::array<double, 3> rgb1 = {0.8, 0.8, 0.8};
  std::array<double, 3> rgb2 = {0.5, 0.5, 0.5};
  std::array<double, 3> markrgb = {0, 0, 0};
  double random = 0.01;
  int width = 0, height = 0;
  int nchannel = 3;
  bool hflip = false, vflip = false;
  std::string file;                  // as written
  std::string path;                  // resolved against the model folder and texturedir
  std::array<std::string, 6> cubefiles;  // right, left, up, down, front, back (resolved)
  std::array<int, 2> gridsize = {1, 1};
  std::string gridlayout = "............";
};

// A material asset (MuJoCo's mjsMaterial): a texture name per role, and its surface.
struct MaterialSpec {
  Source src;
  std::array<std::string, kNTexRole> textures;
  bool texuniform = false;
  std::array<double, 2> texrepeat = {1, 1};
  double emission = 0, specular = 0.5, shininess = 0.5, reflectance = 0;
  double metallic = -1, roughness = -1;
  std::array<double, 4> rgba = {1, 1, 1, 1};
};

// A keyframe that came with an attached model (defined in mjcf/compose.h).
struct AttachedKey;

struct KeySpec {
  Source src;
  double time = 0;
  std::vector<double> qpos, qvel, act, ctrl, mpos, mquat;
  // Set for a keyframe of an attached model: its values come from there, the rest of
  // the row from the compiled model's defaults.
  std::shared_ptr<const AttachedKey> attached;
};

// A default class: the starting values of each element kind.
struct DefaultClass {
  std::string name;
  std::string parent;
  Source src;  // the <default> element
  JointSpec joint;
  GeomSpec geom;
  SiteSpec site;
  CameraSpec camera;
  TendonSpec tendon;
  ActuatorSpec actuator;
  EqualitySpec equality;
  PairSpec pair;
  MeshSpec mesh;
  MaterialSpec material;
  LightSpec light;
};

// <compiler> settings that affect the compiled model.
// <compiler><lengthrange>: which actuators get a lengthrange computed, and how
// (MuJoCo mjLROpt; mode 0 none, 1 muscle, 2 muscle and user, 3 all).
struct LengthRangeSpec {
  int mode = 1;
  bool useexisting = true;
  bool uselimit = false;
  double accel = 20, maxforce = 0, timeconst = 1, timestep = 0.01;
  double inttotal = 10, interval = 2, tolrange = 0.05;
};

struct CompilerSpec {
  bool autolimits = true;
  double boundmass = 0;
  double boundinertia = 0;
  double settotalmass = -1;
  bool balanceinertia = false;
  bool degree = true;
  std::string eulerseq = "xyz";
  int inertiafromgeom = kAuto;
  std::array<int, 2> inertiagrouprange = {0, 5};
  bool alignfree = false;
  bool fusestatic = false;  // static bodies merged into their parents (fuse.cc)
  // Mesh files: folders (meshdir over assetdir), and whether to drop a file's folders.
  std::string meshdir;
  std::string texturedir;
  std::string assetdir;
  bool strippath = false;
  bool fitaabb = false;  // primitives fitted to a mesh's bounding box, not its inertia box
  LengthRangeSpec lengthrange;
};

// An element's settings: its own (attached) model's, else this model's.
inline const CompilerSpec& SettingsOf(const CompilerPtr& own, const CompilerSpec& model) {
  return own ? *own : model;
}

// The whole parsed model.
struct ModelSpec {
  std::string file;
  AssetFilesPtr assets;  // files given in memory (null: only the disk); see assets.h
  std::string model_name = "MuJoCo Model";
  CompilerSpec compiler;
  Option option;
  BodySpec world;
  std::vector<TendonSpec> tendons;
  std::vector<ActuatorSpec> actuators;
  std::vector<SensorSpec> sensors;
  // Plugins: those <extension> activates, its named instances, and implicit instances.
  std::vector<std::pair<std::string, Source>> active_plugins;
  std::vector<PluginInstanceSpec> plugin_instances;
  std::vector<PluginInstanceSpec> implicit_instances;
  std::vector<EqualitySpec> equalities;
  std::vector<PairSpec> pairs;
  std::vector<ExcludeSpec> excludes;
  std::vector<MeshSpec> meshes;
  std::vector<HFieldSpec> hfields;
  std::vector<SkinSpec> skins;
  std::vector<FlexSpec> flexes;
  std::vector<TextureSpec> textures;
  std::vector<MaterialSpec> materials;
  std::vector<KeySpec> keys;
  // The first construct read that only MuJoCo 3.12 defines (see Model::release); an
  // empty tag when there is none.
  Source newer_construct;
  int nkey = 0;  // <size nkey>: at least this many keyframes
  int nuser_sensor = -1;  // <size nuser_sensor>; -1: the longest sensor user data
  Source size_src;        // the <size> element, if any (for messages about its sizes)
  // <statistic>: values given by the model (undefined: computed by the compiler).
  double meaninertia = kUndefined;
  // The rest of <statistic>: replace the computed values where given.
  double meanmass = kUndefined, meansize = kUndefined, extent = kUndefined;
  std::array<double, 3> center = {kUndefined, kUndefined, kUndefined};
  double znear = 0.01;  // <visual><map znear>: default focal length of cameras
  Visual vis;           // the rest of <visual> that simlab keeps
  // <default> classes of the main document (and its includes) that no element uses, by
  // class= or childclass=, itself or through a class nested in it (for simlab lint).
  std::vector<Source> unused_classes;
};

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_SPEC_H_
