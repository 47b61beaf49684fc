// Files given in memory instead of on disk: the `assets` of LoadXmlString, MuJoCo's
// virtual file system (mjVFS) as its Python binding fills it for
// MjModel.from_xml_string(xml, assets).
//
// Matching follows MuJoCo 3.5: the Python binding mounts every asset under its base
// name in lower case (python/mujoco/structs_wrappers.cc LoadModelFileImpl, StripPath
// in structs.h), refusing two assets with the same base name; a file the loader opens
// (include, <model file>, mesh: the path as written, joined with meshdir/assetdir and
// the main file's folder) is then found by its own base name, ignoring case
// (src/user/user_vfs.cc VFS::FindMount, "match on just the case-insensitive
// filename"). So folders never matter, neither in asset names nor in the XML. The
// assets come before the disk: a file that is not among them is read from disk.
#ifndef SIMLAB_MJCF_ASSETS_H_
#define SIMLAB_MJCF_ASSETS_H_

#include <map>
#include <memory>
#include <string>

namespace simlab::mjcf {

// The assets of one load, read-only once made (loads on other threads have their own).
class AssetFiles {
 public:
  // Keys the files (name -> bytes) by base name in lower case. Throws simlab::Error
  // for a name without a file part and for two names with the same key.
  explicit AssetFiles(const std::map<std::string, std::string>& files);

  // The bytes of the asset for the file at `path`, or null if none has its name.
  const std::string* Find(const std::string& path) const;

  bool empty() const { return files_.empty(); }

 private:
  std::map<std::string, std::string> files_;  // by key
};

// Shared by a model's spec and the specs of the models it attaches.
using AssetFilesPtr = std::shared_ptr<const AssetFiles>;

// The key of a file name or path: its base name, in lower case.
std::string AssetKey(const std::string& path);

// The bytes of the file at `path`: the asset with its name if `assets` (may be null)
// has one, else the file on disk. False if neither can be read; then `problem` (may be
// null) says why when the file exists: only a regular file is read (a device such as
// /dev/zero, a pipe or a folder is refused before it is opened), of at most
// kMaxArrayBytes (mjcf/limits.h). This is the one place the loader reads files.
bool ReadFileOrAsset(const std::string& path, const AssetFiles* assets, std::string* bytes,
                     std::string* problem = nullptr);

// What "cannot open file 'x'" adds when assets were given: that none had its name.
std::string NotAmongAssets(const AssetFiles* assets);

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_ASSETS_H_
