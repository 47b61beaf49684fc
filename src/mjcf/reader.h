// MJCF text -> spec tree (src/mjcf/spec.h).
//
// The reader validates the XML against the subset of MuJoCo's schema that simlab
// supports, applies default classes and childclass, records frames, and keeps every
// value as written. Elements that MuJoCo knows but simlab does not implement yet are
// rejected with "<element> is not supported yet" and their line.
#ifndef SIMLAB_MJCF_READER_H_
#define SIMLAB_MJCF_READER_H_

#include <cstdint>
#include <map>
#include <set>
#include <memory>
#include <string>

#include <pugixml.hpp>

#include "mjcf/compose.h"
#include "mjcf/spec.h"
#include "mjcf/xml_attrs.h"

namespace simlab::mjcf {

// Parses MJCF text; `file` names it in error messages and its folder is where
// included and attached files are found: among `assets` first (may be null), then on
// disk. The spec keeps `assets` for the compiler, which reads the mesh files.
ModelSpec ReadMjcf(const std::string& text, const std::string& file,
                   const AssetFilesPtr& assets = nullptr);

// The same for the file at `path`, read through the loader's one reader of files (a
// regular file within the budget); an unreadable file throws Error ("path: why").
ModelSpec ReadMjcfFile(const std::string& path);

// The same, keeping the default classes (for models that get attached).
void ReadModel(const std::string& text, const std::string& file, ParsedModel* out,
               const AssetFilesPtr& assets = nullptr);

// Is `tag` one of the <actuator> section's elements (general, motor, ..., pid)?
bool IsActuatorElement(const std::string& tag);
// A file name without folders and extension (reader_mesh.cc).
std::string StemOf(const std::string& path);
// The modes of cameras and lights, mjtCamLight (reader_sections.cc).
extern const std::initializer_list<Keyword> kCamLightModes;

// The reader's state while walking one document.
class Reader {
 public:
  Reader(const std::string& file, const LineIndex& lines, ModelSpec* spec,
         const NodeOrigins* origins = nullptr);
  void Root(pugi::xml_node root);

 private:
  friend void ReadModel(const std::string& text, const std::string& file, ParsedModel* out,
                        const AssetFilesPtr& assets);
  // The element with its file and line (from `origins_` if it was included).
  XmlElement Element(pugi::xml_node node) const;
  [[noreturn]] void NotSupported(const XmlElement& e, const std::string& what = "") const;
  // A geom's or mesh's <plugin> child (its signed distance field), the only child allowed.
  void ChildPlugin(const XmlElement& e, PluginUse* use);
  [[noreturn]] void Unknown(const XmlElement& e) const;

  // sections (reader_sections.cc)
  void Compiler(const XmlElement& e);
  void Option(const XmlElement& e);
  void Flags(const XmlElement& e);
  void Size(const XmlElement& e);
  void Visual(const XmlElement& e);
  void Statistic(const XmlElement& e);
  void Custom(const XmlElement& e);
  void Asset(const XmlElement& e);
  void Contact(const XmlElement& e);
  void Tendon(const XmlElement& e);
  void Actuator(const XmlElement& e);
  void Keyframe(const XmlElement& e);
  // sensors (reader_sensor.cc)
  void Sensor(const XmlElement& e);
  // equality constraints (reader_equality.cc)
  void Equality(const XmlElement& e);
  void ReadEquality(const XmlElement& e, EqualitySpec* eq, bool in_default) const;
  void ReadPair(const XmlElement& e, PairSpec* pair, bool in_default) const;
  // mesh assets (reader_mesh.cc)
  void ReadMesh(const XmlElement& e, MeshSpec* mesh, bool in_default) const;
  void ReadBuiltin(const XmlElement& e, MeshSpec* mesh) const;
  std::string AssetPath(const std::string& written, const std::string& dir,
                        const XmlElement& e) const;
  void ReadHField(const XmlElement& e, HFieldSpec* hfield) const;
  void ReadSkin(const XmlElement& e, SkinSpec* skin) const;
  // the <deformable> section: skins and flexes
  void Deformable(const XmlElement& e);
  // flexes (reader_flex.cc) and flexcomps (reader_flex.cc, expanded in reader_flexcomp.cc)
  void ReadFlex(const XmlElement& e, FlexSpec* flex);
  // The document's first element that only MuJoCo 3.12 defines (a <flexstrain>, a <flex>
  // with dof or cellcount, a <flexcomp> with cellcount, dof="2d", or interpolated with
  // a shell or strain equality), into newer_construct before anything is read: a model
  // that follows 3.12 is read by 3.12's rules where they differ.
  void FindNewerConstruct(pugi::xml_node root);
  void Flexcomp(const XmlElement& e, BodySpec* body, const DefaultClass* def);
  void FlexcompChildren(const XmlElement& e, struct FlexcompSpec* fc);
  void MakeFlexcomp(const XmlElement& e, struct FlexcompSpec* fc, BodySpec* body,
                    const DefaultClass* def);
  void ReadCamera(const XmlElement& e, CameraSpec* cam, bool in_default) const;
  // textures, materials and lights (reader_visual.cc)
  void ReadTexture(const XmlElement& e, TextureSpec* tex) const;
  void ReadMaterial(const XmlElement& e, MaterialSpec* mat, bool in_default) const;
  void ReadLight(const XmlElement& e, LightSpec* light, bool in_default) const;

  // defaults and the body tree (reader.cc)
  void Default(const XmlElement& e, const DefaultClass* parent);
  const DefaultClass* FindClass(const XmlElement& e, const char* attr) const;
  // The classes no element used (after the document is read): spec_->unused_classes.
  void NoteUnusedClasses();
  void Body(const XmlElement& e, BodySpec* body, const FramePtr& frame,
            const DefaultClass* def);
  void BodyChild(const XmlElement& e, BodySpec* body, const FramePtr& frame,
                 const DefaultClass* def);
  void ChildBody(const XmlElement& e, BodySpec* parent, const FramePtr& frame,
                 const DefaultClass* def);
  void Frame(const XmlElement& e, BodySpec* body, const FramePtr& frame,
             const DefaultClass* def);
  void Inertial(const XmlElement& e, BodySpec* body);
  void FreeJoint(const XmlElement& e, BodySpec* body, const FramePtr& frame);
  // The world, or a replicate's scratch body standing in for it.
  bool IsWorld(const BodySpec* body) const;

  // <replicate> (reader_replicate.cc)
  // Keyframe values that elements of a replicate's template carry (an attached model's
  // keyframes) go to the first replica's copies, as MuJoCo's first copy takes them.
  void MoveCarriedKeys(const struct ReplicaMap& first);
  void Replicate(const XmlElement& e, BodySpec* body, const FramePtr& frame,
                 const DefaultClass* def);

  // one element of each kind, in a body or a default class (reader_elements.cc)
  void ReadJoint(const XmlElement& e, JointSpec* joint, bool in_default) const;
  void ReadGeom(const XmlElement& e, GeomSpec* geom, bool in_default) const;
  void ReadSite(const XmlElement& e, SiteSpec* site, bool in_default) const;
  void ReadTendon(const XmlElement& e, TendonSpec* tendon, bool in_default) const;
  WrapSpec ReadWrap(const XmlElement& e, bool spatial) const;
  void ReadActuator(const XmlElement& e, ActuatorSpec* act, bool in_default) const;
  // <extension>: the plugins used and their named instances; an element's <config>
  // children (key/value pairs).
  void Extension(const XmlElement& e);
  std::vector<std::pair<std::string, std::string>> ReadConfigs(const XmlElement& e) const;
  // The instance a plugin element uses (`user` names its kind in messages): a named one,
  // or its own, configured by its <config> children.
  void ReadPluginUse(const XmlElement& e, const std::string& user, PluginUse* use);
  // The <plugin> child of a body, geom or mesh (`owner`), which has at most one.
  void ReadOwnPlugin(const XmlElement& e, const std::string& owner, PluginUse* use);
  // <actuator><plugin>: an actuator computed by a plugin.
  void ReadPluginActuator(const XmlElement& e, ActuatorSpec* act);
  // <sensor><plugin>: a sensor computed by a plugin.
  void ReadPluginSensor(const XmlElement& e, SensorSpec* s);
  void ReadTransmission(const XmlElement& e, ActuatorSpec* act) const;
  void ReadShortcut(const XmlElement& e, ActuatorSpec* act) const;

  // composition: <asset><model> and <attach> (compose.cc)
  void AssetModel(const XmlElement& e);
  void Attach(const XmlElement& e, BodySpec* body, const FramePtr& frame);
  void CheckAttachDepth(const XmlElement& e, const ParsedModel& child);
  void AttachClasses(const ParsedModel& child, const std::string& prefix);
  void HoldKeys(const XmlElement& e, const ParsedModel& child, const std::string& prefix);
  void CarryKeys(const Attachment& att);
  // Keyframes in MuJoCo's order: the file's own, blanks up to <size nkey>, attached ones.
  void FinishKeys();

  std::string file_;
  const LineIndex& lines_;
  ModelSpec* spec_;
  std::map<std::string, std::unique_ptr<DefaultClass>> classes_;
  std::set<std::string> own_classes_;           // defined by this document's <default>s
  mutable std::set<std::string> used_classes_;  // named by class= or childclass=
  const NodeOrigins* origins_ = nullptr;
  std::map<std::string, std::shared_ptr<const ParsedModel>> models_;
  std::vector<KeySpec> attached_keys_;
  std::map<const void*, HeldValues> held_;        // by element of a child model
  std::map<std::string, AttachedKey> carried_;    // by keyframe name
  int own_keys_ = 0;
  std::vector<const BodySpec*> world_standins_;  // scratch bodies of replicates in the world
  int depth_ = 1;  // levels of the composed document, attached models in place
  // The product of the counts of the <replicate> elements being read (each copies
  // what is read inside it that many times).
  uint64_t replicate_factor_ = 1;
};

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_READER_H_
