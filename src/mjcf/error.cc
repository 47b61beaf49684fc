// Formatting of parse and compile errors.
#include "mjcf/error.h"

namespace simlab::mjcf {

std::string DescribeElement(const std::string& tag, const std::string& name) {
  if (name.empty()) return "<" + tag + ">";
  return "<" + tag + " name=\"" + name + "\">";
}

std::string FormatError(const Source& src, const std::string& what) {
  std::string msg = src.file;
  if (src.line > 0) msg += ":" + std::to_string(src.line);
  msg += ": ";
  if (!src.tag.empty()) msg += DescribeElement(src.tag, src.name) + ": ";
  return msg + what;
}

void ThrowAt(const Source& src, const std::string& what) {
  throw Error(FormatError(src, what));
}

}  // namespace simlab::mjcf
