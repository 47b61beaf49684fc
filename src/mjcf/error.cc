// Formatting of parse and compile errors.
#include "mjcf/error.h"

namespace simlab::mjcf {

std::string DescribeElement(const std::string& tag, const std::string& name) {
  std::string s = "<";
  s.append(tag);
  if (!name.empty()) s.append(" name=\"").append(name).append("\"");
  s.append(">");
  return s;
}

std::string FormatError(const Source& src, const std::string& what) {
  std::string msg = src.file;
  if (src.line > 0) msg.append(":").append(std::to_string(src.line));
  msg.append(": ");
  if (!src.tag.empty()) msg.append(DescribeElement(src.tag, src.name)).append(": ");
  msg.append(what);
  return msg;
}

void ThrowAt(const Source& src, const std::string& what) {
  throw Error(FormatError(src, what));
}

}  // namespace simlab::mjcf
