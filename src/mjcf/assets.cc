// Files given in memory, found by base name before the disk (see assets.h).
#include "mjcf/assets.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "mjcf/limits.h"
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

namespace {

// Why the file at `path` cannot be read as a model file, or "" if it can (or does not
// exist, which the callers report themselves).
std::string FileProblem(const std::string& path) {
  std::error_code ec;
  std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return "";
  if (!std::filesystem::is_regular_file(status)) return "not a regular file";
  uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return "cannot read its size";
  if (size > kMaxArrayBytes) {
    return "the file has " + ByteSize(size) + ", over the " + ByteSize(kMaxArrayBytes) +
           " budget of one file";
  }
  return "";
}

}  // namespace

bool ReadFileOrAsset(const std::string& path, const AssetFiles* assets, std::string* bytes,
                     std::string* problem) {
  // An asset with the file's name shadows the disk.
  if (assets) {
    if (const std::string* found = assets->Find(path)) {
      *bytes = *found;
      return true;
    }
  }

  // Else the file itself, if it is a regular file within the budget.
  std::string why = FileProblem(path);
  if (!why.empty()) {
    if (problem) *problem = why;
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  *bytes = buffer.str();
  if (in.bad() && problem) *problem = "read error";
  return !in.bad();
}

std::string NotAmongAssets(const AssetFiles* assets) {
  if (!assets || assets->empty()) return "";
  return " (no asset has that file name, and it is not on disk)";
}

}  // namespace simlab::mjcf
