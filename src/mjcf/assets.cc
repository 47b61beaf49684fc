// Files given in memory, found by base name before the disk (see assets.h).
#include "mjcf/assets.h"

#include <cctype>
#include <fstream>
#include <sstream>

#include "simlab/simlab.h"

namespace simlab::mjcf {

std::string AssetKey(const std::string& path) {
  size_t slash = path.find_last_of("/\\");
  std::string key = slash == std::string::npos ? path : path.substr(slash + 1);
  for (char& c : key) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return key;
}

AssetFiles::AssetFiles(const std::map<std::string, std::string>& files) {
  // Each asset under its key; a folder-only name or a second file with the same key
  // is refused, as MuJoCo's Python binding refuses "path/a.xml" next to "a.xml".
  std::map<std::string, const std::string*> names;  // key -> the name that took it
  for (const auto& [name, bytes] : files) {
    std::string key = AssetKey(name);
    if (key.empty()) throw Error("asset '" + name + "' has no file name");
    auto [it, added] = names.emplace(key, &name);
    if (!added) {
      throw Error("Repeated file name in assets: '" + *it->second + "' and '" + name +
                  "' (assets are found by file name, whatever their folders and case)");
    }
    files_.emplace(key, bytes);
  }
}

const std::string* AssetFiles::Find(const std::string& path) const {
  auto it = files_.find(AssetKey(path));
  return it == files_.end() ? nullptr : &it->second;
}

bool ReadFileOrAsset(const std::string& path, const AssetFiles* assets, std::string* bytes) {
  // An asset with the file's name shadows the disk.
  if (assets) {
    if (const std::string* found = assets->Find(path)) {
      *bytes = *found;
      return true;
    }
  }

  // Else the file itself.
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  *bytes = buffer.str();
  return !in.bad();
}

std::string NotAmongAssets(const AssetFiles* assets) {
  if (!assets || assets->empty()) return "";
  return " (no asset has that file name, and it is not on disk)";
}

}  // namespace simlab::mjcf
