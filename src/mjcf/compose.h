// Model composition: <include> (a DOM-level paste of another file, done before
// reading) and <attach> (a copy of a body subtree of a model declared with
// <asset><model>, with its referencing elements and keyframes, done while reading).
#ifndef SIMLAB_MJCF_COMPOSE_H_
#define SIMLAB_MJCF_COMPOSE_H_

#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <pugixml.hpp>

#include "mjcf/spec.h"
#include "mjcf/xml_attrs.h"

namespace simlab::mjcf {

// Where the elements pasted in by <include> came from (file and line), keyed by node.
// Elements not listed come from the main file.
class NodeOrigins {
 public:
  struct Origin {
    std::string file;
    int line = 0;
  };
  void Record(pugi::xml_node node, const std::string& file, int line);
  void Forget(pugi::xml_node node) { map_.erase(node.internal_object()); }
  const Origin* Find(pugi::xml_node node) const;

 private:
  std::unordered_map<const void*, Origin> map_;
};

// Replaces every <include file="..."/> below `root` (the document of `file`) by the
// elements under the root of the included file, recursively. A file is found relative
// to the main file's folder, else to the including file's folder, each time among
// `assets` (may be null) before the disk; each file can be included once (which also
// stops recursion). Returns how deep the composed document nests (the root is level 1),
// at most kMaxTreeDepth (mjcf/limits.h).
int ExpandIncludes(pugi::xml_node root, const std::string& file, const LineIndex& lines,
                   NodeOrigins* origins, const AssetFiles* assets);

// The folder part of a path, with its trailing '/' ("" for a bare file name).
std::string DirectoryOf(const std::string& path);

// A model as read from its file, with its default classes (a model declared with
// <asset><model> is kept this way, ready to be attached).
struct ParsedModel {
  ModelSpec spec;
  std::map<std::string, std::unique_ptr<DefaultClass>> classes;
  int own_keys = 0;  // spec.keys before the <size nkey> blanks
  int depth = 1;     // levels of its composed document, attached models in place
};

// What one <attach> copied: child elements and their copies (compose.cc).
struct Attachment;

// Values that elements of a child model hold for keyframes, by keyframe name. MuJoCo
// keeps an attached model's keyframes on its elements: when <attach> copies an
// element, the copy takes the values along and the original forgets them; an element
// left behind keeps them, and a later attachment that copies it brings them too.
using KeyValues = std::map<std::string, std::vector<double>>;
struct HeldValues {
  KeyValues qpos, qvel, act, ctrl, mpos, mquat;
};

// A keyframe of an attached model, as the elements of this model hold it. The
// compiler starts from the whole model's compiled defaults (qpos0, zeros, mocap body
// poses) and writes these values into the places of their elements.
struct AttachedKey {
  std::vector<std::pair<const JointSpec*, std::vector<double>>> qpos, qvel;
  std::vector<std::pair<int, std::vector<double>>> act, ctrl;  // by actuator index
  std::vector<std::pair<const BodySpec*, std::vector<double>>> mpos, mquat;
};

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_COMPOSE_H_
