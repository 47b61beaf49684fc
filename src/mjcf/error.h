// Error messages that point at the XML: "file.xml:42: <joint name="hip">: problem".
#ifndef SIMLAB_MJCF_ERROR_H_
#define SIMLAB_MJCF_ERROR_H_

#include <string>

#include "mjcf/spec.h"
#include "simlab/simlab.h"

namespace simlab::mjcf {

// `<tag name="x">` or `<tag>` when the element has no name.
std::string DescribeElement(const std::string& tag, const std::string& name);

// The full message for a problem with the element at `src`.
std::string FormatError(const Source& src, const std::string& what);

// Throw simlab::Error for the element at `src`.
[[noreturn]] void ThrowAt(const Source& src, const std::string& what);

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_ERROR_H_
