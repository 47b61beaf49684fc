// spec tree -> simlab::Model, the way MuJoCo's compiler (mjCModel::Compile) lays out
// and computes mjModel. One file per section:
//
//   body.cc      the tree: bodies, joints, dofs, geoms, sites, in depth-first order
//   inertia.cc   geom volumes and inertias, body inertia from geoms, mass bounds
//   fluid.cc     geom_fluid: the ellipsoid fluid model's added mass and inertia
//   camera.cc    cameras: poses, target bodies, intrinsics, tracking offsets
//   tendon.cc    fixed tendons
//   actuator.cc  actuators: transmission targets, limits, activation layout
//   equality.cc  equality constraints: objects, parameters, eq_data at qpos0
//   keyframe.cc  keyframes, padded as MuJoCo does
//   sensor.cc    sensors: objects, output sizes, sensordata and history layout
//   option.cc    physics options
//   constants.cc quantities computed at qpos0 (subtree mass, lengths, acc0)
#ifndef SIMLAB_COMPILER_COMPILER_H_
#define SIMLAB_COMPILER_COMPILER_H_

#include <cstdint>
#include <array>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "engine/flex_cells.h"
#include "mjcf/spec.h"
#include "simlab/data.h"
#include "simlab/model.h"
#include "simlab/plugin.h"

namespace simlab::compiler {

// A body while compiling: its spec, its place in the tree, and the values that end
// up in the model.
struct BodyState {
  const mjcf::BodySpec* spec = nullptr;
  int id = 0;
  int parent = -1;
  double pos[3] = {0, 0, 0};
  double quat[4] = {1, 0, 0, 0};
  double ipos[3] = {0, 0, 0};
  double iquat[4] = {1, 0, 0, 0};
  double mass = 0;
  double inertia[3] = {0, 0, 0};
  int weldid = 0;
  int dofnum = 0;
  // Its joints, geoms and sites: the `num` entries of the state's lists from `begin`,
  // which list each body's elements together (fusestatic adds a fused body's).
  int joint_begin = 0, geom_begin = 0, site_begin = 0;
  int joint_num = 0, geom_num = 0, site_num = 0;
  // Bodies fused into this one (fusestatic), whose cameras and lights it carries after
  // its own.
  std::vector<const mjcf::BodySpec*> fused;
  // For a body that took fused bodies, the geom ids MuJoCo 3.5.1 reports for the inner
  // nodes of its tree: it rebuilds the tree after each fusion without clearing the
  // nodes' geom pointers, so an inner node reads the geom an earlier tree had as a leaf
  // at that place (-1: none).
  std::vector<int> stale_bvh_nodeid;
  // A free body aligned with its inertial frame (joint align, compiler alignfree): the
  // transformation its geoms, sites, cameras and lights take (the inverse of the
  // inertial frame it moved onto).
  bool aligned = false;
  double align_pos[3] = {0, 0, 0};
  double align_quat[4] = {1, 0, 0, 0};
};

// Moves an element's pose (pos, quat in its body's frame) as an aligned body's elements
// move; nothing for other bodies.
void AlignedPose(const BodyState& b, double pos[3], double quat[4]);

// A compiled mesh (mesh.cc): vertices in its inertial frame, triangles, the convex
// hull graph (empty if none is needed), and the pose of that frame in the mesh file's.
struct MeshState {
  const mjcf::MeshSpec* spec = nullptr;
  std::vector<double> vert;
  std::vector<int> face;
  std::vector<int> graph;
  std::vector<float> normal;  // x y z each, single precision as MuJoCo keeps them
  std::vector<float> texcoord;    // u v each
  std::vector<int> facetexcoord;  // a texcoord per face corner, when there are texcoords
  // The hull's flat sides (mesh_polygon.cc): vertex paths, and unit normals.
  std::vector<std::vector<int>> polygons;
  std::vector<double> polynormal;
  double pos[3] = {0, 0, 0};
  double quat[4] = {1, 0, 0, 0};
  double aamm[6] = {0, 0, 0, 0, 0, 0};  // bounding box (min, max) in the inertial frame
  double boxsz[3] = {0, 0, 0};           // half-sizes of the equivalent inertia box
  double volume = 0;                     // volume, or surface area for shell inertia
  // The signed distance octree of a mesh an sdf geom uses (mesh_octree.cc): per cell its
  // level, 8 children (-1: none), box (centre, half sizes) and 8 corner values.
  std::vector<int> oct_depth, oct_child;
  std::vector<double> oct_aabb, oct_coeff;
};

// A compiled height field (hfield.cc): elevations normalized to [0, 1].
struct HFieldState {
  const mjcf::HFieldSpec* spec = nullptr;
  int nrow = 0, ncol = 0;
  std::vector<float> data;
};

// A compiled skin (skin.cc): its data (from its file, weights normalized), the body of
// each bone and its material.
struct SkinState {
  mjcf::SkinSpec data;
  std::vector<int> bodyid;
  int matid = -1;
};

// A compiled flex (flex.cc, MuJoCo's mjCFlex::Compile): its vertices' bodies (or -1
// for an interpolated flex) and world positions at qpos0, its elements (tetrahedra
// turned outward), edges, flaps, elasticity, shells, element-vertex collision pairs,
// element layers, and the box of its vertices.
struct FlexState {
  const mjcf::FlexSpec* spec = nullptr;
  int nvert = 0, nnode = 0, nelem = 0, order = 0, matid = -1;
  bool rigid = false, centered = false, interpolated = false;
  std::vector<int> vertbodyid, nodebodyid;
  std::vector<double> vertxpos, nodexpos;
  std::vector<int> elem, elemedge, elemtexcoord;
  std::vector<std::array<int, 2>> edge;
  std::vector<std::array<int, 4>> flaps;
  std::vector<double> stiffness, bending;
  std::vector<int> shell, evpair, elemlayer;
  std::vector<double> vert0;  // vertex positions in the box, on [0, 1]^3
  double size[3] = {0, 0, 0};
  // An interpolated flex made of cells (MuJoCo 3.12: more than one cell, a shell or
  // strain equality): its lattice, its empty cells, and its nodes' positions turned by
  // the lattice's rotation (flex_node0).
  bool cells = false;
  FlexLattice lattice;
  std::vector<bool> cell_empty;
  std::vector<double> nodelocal;
};

// A geom while compiling (pose in the body frame, mass properties).
struct GeomState {
  const mjcf::GeomSpec* spec = nullptr;
  int body = 0;
  const MeshState* mesh = nullptr;  // its mesh (mesh geoms, and primitives fitted to one)
  int meshid = -1;                  // geom_dataid: the mesh it names, or -1
  const HFieldState* hfield = nullptr;  // its height field (hfield geoms; meshid is its id)
  double size[3] = {0, 0, 0};
  double pos[3] = {0, 0, 0};
  double quat[4] = {1, 0, 0, 0};
  double mass = 0;
  double inertia[3] = {0, 0, 0};
};

struct JointState {
  const mjcf::JointSpec* spec = nullptr;
  int body = 0;
  double pos[3] = {0, 0, 0};
  double axis[3] = {0, 0, 1};
  double range[2] = {0, 0};
  bool limited = false;
  bool actfrclimited = false;
  double ref = 0;
  double springref = 0;
};

struct SiteState {
  const mjcf::SiteSpec* spec = nullptr;
  int body = 0;
  double size[3] = {0, 0, 0};
  double pos[3] = {0, 0, 0};
  double quat[4] = {1, 0, 0, 0};
};

// Everything the section compilers share.
struct CompileState {
  const mjcf::ModelSpec* spec = nullptr;
  // The MuJoCo release the model follows (Model::release; CompileFlexes decides).
  Release release = Release::k3_5_1;
  std::vector<BodyState> bodies;
  std::vector<JointState> joints;
  std::vector<GeomState> geoms;
  std::vector<SiteState> sites;
  std::vector<MeshState> meshes;
  std::vector<HFieldState> hfields;
  std::vector<SkinState> skins;
  std::vector<FlexState> flexes;
  // Bounding-volume nodes MuJoCo 3.5.1 counts past the bodies' trees after fusing static
  // bodies (its count grows by one for each fusion of two bodies that both had colliding
  // geoms): zero nodes at the end of bvh_*.
  int fused_bvh_padding = 0;
};

// Where each compiled element was written, by id (for messages about a compiled model
// that point at its XML: simlab lint). The world body has the model's file.
struct ElementSources {
  std::vector<mjcf::Source> body, joint, geom, site, tendon, actuator, equality, key;
};

// The whole compilation; with `sources`, also where each element came from.
Model Compile(const mjcf::ModelSpec& spec, ElementSources* sources = nullptr);

// Sections, in the order Compile runs them.
void CompileOption(const mjcf::ModelSpec& spec, Model* m);
void TreeSizes(const CompileState& state, Model* m);
// Trees' body and dof ranges, the trees along each tendon and the trees' sleep
// policies (trees.cc): after the tendons and actuators.
void CompileTrees(const CompileState& state, Model* m);
void FlattenTree(const mjcf::ModelSpec& spec, CompileState* state);
// Meshes and the geoms that use them (mesh.cc): before the bodies, which need them.
void CompileMeshes(const mjcf::ModelSpec& spec, CompileState* state);
// The zero level set of a signed distance field plugin's field, by marching cubes
// (mesh_level_set.cc).
struct MeshData;
MeshData LevelSetMesh(const Plugin& plugin, const std::vector<double>& attributes);
void MeshSizes(const CompileState& state, Model* m);
// A geom with a mesh: a primitive type is fitted to it (size), and the geom frame is
// offset by the mesh's inertial frame. A mesh geom's size is its bounding box.
void MeshGeomFrame(const mjcf::CompilerSpec& c, GeomState* g);
void MeshGeomSize(GeomState* g);
void LayoutMeshes(const CompileState& state, Model* m);
// The hull's flat sides as polygons, from the vertices as read (mesh_polygon.cc); their
// normals, from the vertices in the mesh's final frame.
void MakeMeshPolygons(MeshState* mesh);
// The triangles of a mesh's hull (the graph's face block; the graph must exist).
const int* HullFaces(const MeshState& mesh);
void MeshPolygonNormals(MeshState* mesh);
// The signed distance octree of a compiled mesh (mesh_octree.cc).
void MakeMeshOctree(MeshState* mesh);
// Skins (skin.cc): after the tree is flattened (bones name bodies).
void CompileSkins(const mjcf::ModelSpec& spec, CompileState* state);
void SkinSizes(const CompileState& state, Model* m);
void LayoutSkins(const CompileState& state, Model* m);
// MuJoCo's rules for a bounding volume's box (min x y z, max x y z), shared by the body
// and flex trees (bvh.cc): a side flatter than mjEPS grows by mjEPS each way; the split
// axis is the longest side, ties within mjEPS going to the lower axis.
void InflateFlatBox(double aamm[6]);
int LongestBoxSide(const double aamm[6]);
// Flexes (flex.cc): after the bodies (vertices need their frames at qpos0). The
// layout needs the equalities (which flexes keep their edges) and the bodies' welds;
// the constants (sparsity, rest lengths, inverse weights) need the model at qpos0.
void CompileFlexes(const mjcf::ModelSpec& spec, CompileState* state);
// The first flex bending its triangles with a vertex pinned to a static (jointless) body,
// which MuJoCo 3.5.1 refuses and 3.12 accepts (such a model follows 3.12), or null;
// joints(name) is the named body's joint count (-1: no such body).
const mjcf::FlexSpec* FlexBendingOnStaticPin(const mjcf::ModelSpec& spec,
                                             const std::function<int(const std::string&)>& joints);
// A flex's active elements (all, or a 3D flex's first activelayers layers) with their
// boxes at qpos0 (centre, half sizes grown by the radius): the leaves of its tree
// (bvh_flex.cc) and what flex_size spans.
struct FlexElementBox {
  int id = -1;
  double aabb[6] = {0, 0, 0, 0, 0, 0};
};
std::vector<FlexElementBox> ActiveFlexElements(const FlexState& flex);
void FlexSizes(const CompileState& state, Model* m);
void LayoutFlexes(const mjcf::ModelSpec& spec, const CompileState& state, Model* m);
// Height fields and the geoms that use them (hfield.cc): before the bodies.
void CompileHFields(const mjcf::ModelSpec& spec, CompileState* state);
// An hfield geom's size from its height field (MuJoCo's geom_size for hfields).
void HFieldGeomSize(GeomState* g);
// Refuses hfield geoms that could collide with a moving geom (no hfield colliders yet).
void CheckHFieldCollisions(const mjcf::ModelSpec& spec, const CompileState& state);
// Refuses hfield geoms that could collide with an sdf geom (no collider yet).
void CheckSdfCollisions(const mjcf::ModelSpec& spec, const CompileState& state);
void HFieldSizes(const CompileState& state, Model* m);
void LayoutHFields(const CompileState& state, Model* m);
void CompileBodies(CompileState* state);
// <compiler fusestatic>: static bodies merged into their parents (fuse.cc), after the
// bodies compile and before anything is laid out.
void FuseStaticBodies(const mjcf::ModelSpec& spec, CompileState* state);
// (`model`: this model's settings; an attached geom keeps its own model's)
void CompileGeom(const mjcf::CompilerSpec& model, bool infer_inertia, GeomState* g);
void InertiaFromGeoms(const mjcf::CompilerSpec& c, const std::vector<GeomState*>& geoms,
                      BodyState* body);
void BoundMassInertia(const mjcf::CompilerSpec& c, BodyState* body);
double GeomRBound(const GeomState& g);
// Its bounding box in its own frame (geom_aabb: centre, then half sizes).
void GeomAabb(const GeomState& g, double aabb[6]);
// The geom's row of geom_fluid (the ellipsoid fluid model's coefficients; fluid.cc).
void GeomFluid(const GeomState& g, double* fluid);
void CheckMovingBodies(const CompileState& state);
void LayoutTree(const CompileState& state, Model* m);
// A colour component in [0, 1] as a byte, truncated as MuJoCo converts it. Components
// outside [0, 1] (a conversion MuJoCo leaves undefined) saturate; NaN gives 0.
inline uint8_t ColourByte(double v) {
  double b = 255 * v;
  return b >= 255 ? 255 : b > 0 ? static_cast<uint8_t>(b) : 0;
}

// Textures, materials and lights (visual.cc): textures made before the sizes (their
// bytes count), the rest laid out with the tree (the lights' tracking offsets come with
// the cameras', CamLightConstants).
struct TextureImage {
  int width = 0, height = 0, nchannel = 3;
  int colorspace = 0;  // mjtColorSpace; a file's when the texture says auto
  std::vector<uint8_t> data;
};
std::vector<TextureImage> CompileTextures(const mjcf::ModelSpec& spec);
void VisualSizes(const mjcf::ModelSpec& spec, const CompileState& state,
                 const std::vector<TextureImage>& images, Model* m);
void LayoutVisual(const mjcf::ModelSpec& spec, const CompileState& state,
                  const std::vector<TextureImage>& images, Model* m);

// Cameras in body order (camera.cc); their tracking offsets at qpos0 once the
// constants are known.
int CameraCount(const CompileState& state);
void CompileCameras(const mjcf::ModelSpec& spec, const CompileState& state, Model* m);
// The tracking offsets of cameras and lights (cam_pos0, light_dir0, ...), from one pose
// of the model at qpos0.
void CamLightConstants(Model* m);
void CompileTendons(const mjcf::ModelSpec& spec, const CompileState& state, Model* m);
void CompileEqualities(const mjcf::ModelSpec& spec, Model* m);
// Stiffness and damping of joints given as springdamper (constants.cc).
void AutoSpringDamper(const CompileState& state, Model* m);
// Explicit pairs, exclusions and body_contype/conaffinity (contact.cc).
void CompileContacts(const mjcf::ModelSpec& spec, Model* m);
// body_margin and the bodies' bounding volume hierarchies (nbvh, bvh_*) (bvh.cc).
// (after fusestatic, with MuJoCo's leftovers: see BodyState::stale_bvh_nodeid and
// CompileState::fused_bvh_padding)
void CompileBodyBvh(Model* m, const CompileState& state);
// The flexes' trees over their active elements, after the bodies' (bvh_flex.cc, MuJoCo's
// mjCFlex::CreateBVH): flex_bvhadr, flex_bvhnum, nbvhdynamic; their boxes move with the
// flex and live in Data::bvh_aabb_dyn.
void CompileFlexBvh(Model* m, const CompileState& state);
// A geom in a body's tree: its id, its box (centre, half sizes) in its frame, and that
// frame's pose in the body frame.
struct BvhGeom {
  int id = -1;
  const double* aabb = nullptr;
  const double* pos = nullptr;
  const double* quat = nullptr;
};
// The nodes of the tree CompileBodyBvh builds over these geoms in the frame (ipos,
// iquat): each node's geom id if it is a leaf, else -1.
std::vector<int> BvhNodeGeoms(const std::vector<BvhGeom>& geoms, const double* ipos,
                              const double* iquat);
// eq_data computed from the body poses at qpos0 (connect and weld between bodies).
void EqualityConstants(Model* m);
// What an actuator reads and writes (checked): its input signature and control entries
// (nu adds them up), force outputs (nout) and activation states (na).
struct ActuatorShape {
  int ctrlspec = 0, ctrlnum = 1, outnum = 1, actnum = 0;
};
ActuatorShape ActuatorShapeOf(const mjcf::ActuatorSpec& a);
void CompileActuators(const mjcf::ModelSpec& spec, const CompileState& state, Model* m);
// Plugin instances, their configuration and state sizes, actuator_plugin, body_plugin
// (plugin.cc); where instance `instance` was written (for its plugin's errors at init).
void CompilePlugins(const mjcf::ModelSpec& spec, const CompileState& state, Model* m);
// The instance id an element (`kind`, written at `user`) uses, and its plugin, which
// must have `capability` (after CompilePlugins has set Model::plugin).
int PluginInstanceOf(const mjcf::ModelSpec& spec, const mjcf::Source& user,
                     const mjcf::PluginUse& use, const std::string& kind);
const Plugin& PluginWith(const Model& m, int instance, int capability, const mjcf::Source& user);
const mjcf::Source& PluginInstanceSource(const mjcf::ModelSpec& spec, int instance);
// The signed distance field plugin a mesh or geom (written at `user`) uses, and its
// instance's attribute numbers.
const Plugin& SdfPluginOf(const mjcf::ModelSpec& spec, const mjcf::Source& user,
                          const mjcf::PluginUse& use, std::vector<double>* attributes);
void CompileKeyframes(const mjcf::ModelSpec& spec, const CompileState& state, Model* m);
// Sensors (sensor.cc): user numbers per sensor (before allocation), then every sensor,
// sensordata addresses and the actuator/sensor history buffer layout.
int NUserSensor(const mjcf::ModelSpec& spec);
void CompileSensors(const mjcf::ModelSpec& spec, Model* m);
void SetTotalMass(double total, Model* m);
void ComputeConstants(Model* m);
// body_simple, body/dof/tendon_invweight0 and stat.meaninertia from a Data at qpos0
// after the smooth position stage (invweight.cc; called by ComputeConstants).
void ComputeInvWeights(Model* m, const Data& at_qpos0);
// Flex constants (flex_constants.cc): the edge and vertex Jacobians' sparsity (before anything at
// qpos0 runs the flexes), the edges' inverse weights (with the Data at qpos0), and the
// body sizes (MuJoCo's setStat) the flexes' edges or nodes lengthen.
void FlexJacobianSparsity(Model* m);
// Cloths kept by their vertices' metric (flexvert equality) turned, in flex_vert0, so that
// their first triangle faces z (MuJoCo's mj_alignFlex), after the sparsity.
void FlexAlignToPlane(Model* m);
void FlexEdgeInvWeights(Model* m, const Data& at_qpos0);
void FlexBodySizes(const Model& m, const Data& at_qpos0, std::vector<double>* size);
// body_simple, and dof_simplenum: how many simple-body dofs run from each dof on
// (invweight.cc); their rows of M are diagonal (MuJoCo's reduced M).
void SimpleBodies(Model* m);
// actuator_lengthrange where the <compiler><lengthrange> options ask for it (lengthrange.cc).
void ComputeLengthRanges(const mjcf::ModelSpec& spec, Model* m);

// Name lookup while compiling (-1 if absent), by a scan: for short lists.
int FindName(const std::vector<std::string>& names, const std::string& name);
// The id of the object named `name` (of the given kind, for the message), or an error
// at the element `src` that names it ("unknown joint 'x'").
int FindNamed(const mjcf::Source& src, const std::vector<std::string>& names,
              const std::string& name, const std::string& kind);

// Names -> the id of the first object with that name (empty names are left out), for
// lookups in constant time: models with many objects (a large <replicate>) compile in
// time linear in their size.
class NameIndex {
 public:
  NameIndex() = default;
  explicit NameIndex(const std::vector<std::string>& names);
  // Adds a name for `id`; false (and no change) if it is there already.
  bool Insert(const std::string& name, int id);
  int Find(const std::string& name) const;  // -1 if absent

 private:
  std::unordered_map<std::string, int> ids_;
};

// The bodies of the flattened tree by name (the world as "world"), and the spec's
// materials by name: what skins and flexes name.
NameIndex BodyNames(const CompileState& state);
NameIndex MaterialNames(const mjcf::ModelSpec& spec);

// FindNamed through an index.
int FindNamed(const mjcf::Source& src, const NameIndex& names, const std::string& name,
              const std::string& kind);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_COMPILER_H_
