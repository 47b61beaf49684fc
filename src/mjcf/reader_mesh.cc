// MJCF reader: <mesh> assets and the mesh settings of default classes. Files are only
// located here (against the model's folder and <compiler meshdir/assetdir>); the
// compiler reads and processes them (src/compiler/mesh.cc).
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <algorithm>
#include <filesystem>
#include <cstdlib>
#include <optional>
#include <string>

#include "mjcf/error.h"
#include "mjcf/limits.h"
#include "mjcf/reader.h"

namespace simlab::mjcf {

namespace {

bool IsAbsolute(const std::string& path) { return !path.empty() && path[0] == '/'; }

// `dir` + `rel`, unless `rel` is absolute.
std::string JoinPath(const std::string& dir, const std::string& rel) {
  if (dir.empty() || IsAbsolute(rel)) return rel;
  return dir.back() == '/' ? dir + rel : dir + "/" + rel;
}

// The folder part of a path ("" for a bare file name).
std::string FolderOf(const std::string& path) {
  size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "" : path.substr(0, slash + 1);
}


}  // namespace

// ---------------------------------------------------------------- <mesh>

void Reader::ReadMesh(const XmlElement& e, MeshSpec* mesh, bool in_default) const {
  if (in_default) {
    e.CheckAttributes({"scale", "maxhullvert", "inertia"});
  } else {
    e.CheckAttributes({"name", "class", "content_type", "file", "vertex", "normal", "texcoord",
                       "face", "refpos", "refquat", "scale", "smoothnormal", "maxhullvert",
                       "inertia", "builtin", "params", "material"});
    mesh->src = e.src();
  }

  // Settings a default class can carry.
  e.Numbers("scale", mesh->scale);
  e.Enum("inertia", &mesh->inertia, {{"convex", kMeshConvex}, {"exact", kMeshExact},
                                     {"legacy", kMeshLegacy}, {"shell", kMeshShell}});
  if (e.Int("maxhullvert", &mesh->maxhullvert) && mesh->maxhullvert != -1 &&
      mesh->maxhullvert < 4) {
    e.Fail("maxhullvert must be larger than 3");
  }
  if (in_default) return;

  // Geometry: a file or inline data (and normals, texture coordinates).
  if (e.Has("file")) {
    e.RequiredText("file", &mesh->file);
    mesh->path = AssetPath(mesh->file, spec_->compiler.meshdir, e);
  }
  e.Text("content_type", &mesh->content_type);
  mesh->vertex = ReadList(e, "vertex", ParseFloat);
  mesh->face = ReadList(e, "face", ParseInt);
  mesh->normal = ReadList(e, "normal", ParseFloat);
  mesh->texcoord = ReadList(e, "texcoord", ParseFloat);
  e.Bool("smoothnormal", &mesh->smoothnormal);
  e.Numbers("refpos", mesh->refpos);
  e.Numbers("refquat", mesh->refquat);
  ReadBuiltin(e, mesh);
  if (mesh->src.name.empty()) mesh->src.name = StemOf(mesh->file);
}

// A builtin shape (the compiler makes its vertices): not with a file or vertex data.
void Reader::ReadBuiltin(const XmlElement& e, MeshSpec* mesh) const {
  if (!e.Enum("builtin", &mesh->builtin,
              {{"none", kMeshBuiltinNone}, {"sphere", kMeshBuiltinSphere},
               {"hemisphere", kMeshBuiltinHemisphere}, {"cone", kMeshBuiltinCone},
               {"supersphere", kMeshBuiltinSupersphere}, {"supertorus", kMeshBuiltinSupertorus},
               {"wedge", kMeshBuiltinWedge}, {"plate", kMeshBuiltinPlate}}) ||
      mesh->builtin == kMeshBuiltinNone) {
    return;
  }
  std::optional<std::vector<double>> params = e.Vector("params");
  if (!params) e.Fail("a builtin mesh needs 'params'");
  mesh->params = *params;
  if (e.Has("file")) e.Fail("builtin cannot be used with a mesh file");
  if (!mesh->vertex.empty()) e.Fail("builtin mesh cannot be used with user vertex data");
  // A plate is flat: MuJoCo gives it shell inertia whatever the element says.
  if (mesh->builtin == kMeshBuiltinPlate) mesh->inertia = kMeshShell;
}

// A file name without folders and extension: the name of an
// unnamed mesh or texture.
std::string StemOf(const std::string& path) {
  std::string base = path.substr(path.find_last_of('/') + 1);
  size_t dot = base.find_last_of('.');
  return dot == std::string::npos ? base : base.substr(0, dot);
}

// A file an asset names, found against the model's folder and `dir` (the asset kind's
// folder, else assetdir), without its folders under strippath. An asset written in an
// included file from another folder is looked for there too when the model's folder
// has no such file (as MuJoCo 3.5 finds it: the model's folder first).
std::string Reader::AssetPath(const std::string& written, const std::string& dir,
                              const XmlElement& e) const {
  const std::string& folder = dir.empty() ? spec_->compiler.assetdir : dir;
  std::string file = spec_->compiler.strippath ? written.substr(written.find_last_of('/') + 1)
                                               : written;
  std::string path = JoinPath(JoinPath(FolderOf(file_), folder), file);
  if (e.src().file == file_ || FolderOf(e.src().file) == FolderOf(file_)) return path;
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) return path;
  std::string beside = JoinPath(JoinPath(FolderOf(e.src().file), folder), file);
  return std::filesystem::exists(beside, ec) ? beside : path;
}

// ---------------------------------------------------------------- <hfield>

void Reader::ReadHField(const XmlElement& e, HFieldSpec* hfield) const {
  e.CheckAttributes({"name", "content_type", "file", "nrow", "ncol", "size", "elevation"});
  hfield->src = e.src();
  // From a file (PNG, or MuJoCo's binary format), read by the compiler: the grid's size
  // comes from there, so none may be given here.
  if (e.Text("file", &hfield->file)) {
    if (e.Has("nrow") || e.Has("ncol") || e.Has("elevation")) {
      e.Fail("hfield specified from file and manually");
    }
    e.Text("content_type", &hfield->content_type);
    if (e.Numbers("size", hfield->size) != 4) e.Fail("'size' needs 4 numbers");
    hfield->path = AssetPath(hfield->file, spec_->compiler.meshdir, e);
    if (hfield->src.name.empty()) hfield->src.name = StemOf(hfield->file);
    return;
  }
  e.Int("nrow", &hfield->nrow);
  e.Int("ncol", &hfield->ncol);
  if (e.Numbers("size", hfield->size) != 4) e.Fail("'size' needs 4 numbers");
  if (hfield->nrow < 1 || hfield->ncol < 1) e.Fail("hfield needs positive nrow and ncol");
  size_t n = static_cast<size_t>(hfield->nrow) * hfield->ncol;
  uint64_t bytes = MulBytes(n, sizeof(double));  // the Model's hfield_data
  if (bytes > kMaxArrayBytes) {
    e.Fail(OverBudget(AttrText("nrow", std::to_string(hfield->nrow)) + " x " +
                          AttrText("ncol", std::to_string(hfield->ncol)),
                      bytes, "height field data", kMaxArrayBytes));
  }

  // Elevation rows are written from +y down to -y; they are stored from -y up.
  std::vector<float> rows = ReadList(e, "elevation", ParseFloat);
  if (rows.empty()) rows.assign(n, 0.0f);
  if (rows.size() != n) e.Fail("elevation data length must match nrow*ncol");
  hfield->elevation.resize(n);
  for (int r = 0; r < hfield->nrow; r++) {
    std::copy_n(rows.begin() + static_cast<size_t>(r) * hfield->ncol, hfield->ncol,
                hfield->elevation.begin() + static_cast<size_t>(hfield->nrow - 1 - r) * hfield->ncol);
  }
}

// ---------------------------------------------------------------- <skin>

void Reader::ReadSkin(const XmlElement& e, SkinSpec* skin) const {
  e.CheckAttributes({"name", "file", "material", "rgba", "inflate", "vertex", "texcoord", "face",
                     "group"});
  skin->src = e.src();
  if (e.Text("file", &skin->file)) skin->path = AssetPath(skin->file, spec_->compiler.meshdir, e);
  e.Text("material", &skin->material);
  if (e.Int("group", &skin->group) && (skin->group < 0 || skin->group > 5)) {
    e.Fail("skin group must be between 0 and 5");
  }
  std::array<double, 4> rgba;
  if (e.Numbers("rgba", rgba)) {
    for (int k = 0; k < 4; k++) skin->rgba[k] = static_cast<float>(rgba[k]);
  }
  double inflate;
  if (e.Number("inflate", &inflate)) skin->inflate = static_cast<float>(inflate);
  skin->vertex = ReadList(e, "vertex", ParseFloat);
  skin->texcoord = ReadList(e, "texcoord", ParseFloat);
  skin->face = ReadList(e, "face", ParseInt);

  // Bones: each names its body, bind pose and the vertices it carries.
  for (pugi::xml_node n : e.node().children()) {
    if (n.type() != pugi::node_element) continue;
    XmlElement b = Element(n);
    if (b.tag() != "bone") Unknown(b);
    b.CheckAttributes({"body", "bindpos", "bindquat", "vertid", "vertweight"});
    SkinBoneSpec bone;
    bone.src = b.src();
    b.RequiredText("body", &bone.body);
    std::array<double, 3> pos;
    std::array<double, 4> quat;
    if (!b.Numbers("bindpos", pos)) b.Fail("missing attribute 'bindpos'");
    if (!b.Numbers("bindquat", quat)) b.Fail("missing attribute 'bindquat'");
    for (int k = 0; k < 3; k++) bone.bindpos[k] = static_cast<float>(pos[k]);
    for (int k = 0; k < 4; k++) bone.bindquat[k] = static_cast<float>(quat[k]);
    if (!b.Has("vertid")) b.Fail("missing attribute 'vertid'");
    if (!b.Has("vertweight")) b.Fail("missing attribute 'vertweight'");
    bone.vertid = ReadList(b, "vertid", ParseInt);
    bone.vertweight = ReadList(b, "vertweight", ParseFloat);
    skin->bones.push_back(std::move(bone));
  }
}

}  // namespace simlab::mjcf
