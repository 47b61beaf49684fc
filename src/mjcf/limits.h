// What one model may ask of a load: how deep its elements nest, and how many bytes the
// arrays that its attributes size may take. Each limit is checked before the recursion
// or the allocation it bounds; a model beyond one gets a simlab::Error naming the file,
// line, element and attribute, never a crash, a stack overflow or a huge allocation.
//
// Depth. MuJoCo's XML parser (tinyxml2, TINYXML2_MAX_ELEMENT_DEPTH) refuses a file whose
// elements nest 500 deep ("XML_ELEMENT_DEPTH_EXCEEDED: Element nesting is too deep"):
// the root is level 1, and an element on level 499 may only be written self-closed
// (`<geom/>`), since the parser counts the content of each open element as one more
// level. Every file simlab reads is held to the same rule when it is parsed. Files put
// together (<include> pastes, <attach> copies) can nest deeper than any one of them;
// the composed model is capped at kMaxTreeDepth levels, so that every recursive walk of
// the reader and the compiler stays within a known stack (about 0.5 kB per level).
//
// Bytes. A fixed budget, independent of the machine's free memory: one array sized by
// an attribute (keyframes, sensordata, user numbers, a height field, a builtin mesh,
// the copies of a <replicate>, a file) may take at most kMaxArrayBytes, all arrays of
// the Model at most kMaxModelBytes, and all arrays of one Data at most kMaxDataBytes
// (simlab/data.h, checked by the compiler and again by MakeData). The sizes are computed
// in 64 bits, saturating, before anything is allocated.
#ifndef SIMLAB_MJCF_LIMITS_H_
#define SIMLAB_MJCF_LIMITS_H_

#include <cstdint>
#include <string>

namespace simlab::mjcf {

inline constexpr int kMaxXmlDepth = 500;    // nesting levels of one file (MuJoCo's)
inline constexpr int kMaxTreeDepth = 1000;  // nesting levels of the composed model

inline constexpr uint64_t kMaxArrayBytes = uint64_t{1} << 30;  // 1 GiB: one array
inline constexpr uint64_t kMaxModelBytes = uint64_t{4} << 30;  // 4 GiB: the whole Model

// count * each, or UINT64_MAX if that does not fit.
uint64_t MulBytes(uint64_t count, uint64_t each);
// a + b, or UINT64_MAX if that does not fit.
uint64_t AddBytes(uint64_t a, uint64_t b);

// "16.0 GB" (binary units: KB, MB, GB, TB), for messages.
std::string ByteSize(uint64_t bytes);

// `name="value"`, the way an attribute is written.
std::string AttrText(const std::string& name, const std::string& value);

// The message for a request (attributes as written, see AttrText) of more than `budget`
// bytes: `nkey="1000000000" asks for 253.3 GB of keyframes, over the 1.0 GB budget of
// one array`.
std::string OverBudget(const std::string& request, uint64_t bytes, const std::string& what,
                       uint64_t budget, const char* budget_of = "one array");

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_LIMITS_H_
