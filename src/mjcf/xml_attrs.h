// Typed, checked access to the attributes of one XML element.
//
// Every reader reports problems as "file:line: <tag name=...>: what", the way the rest
// of the loader does, and never leaves a half-read value behind.
#ifndef SIMLAB_MJCF_XML_ATTRS_H_
#define SIMLAB_MJCF_XML_ATTRS_H_

#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pugixml.hpp>

#include "mjcf/spec.h"

namespace simlab::mjcf {

// Maps byte offsets of the XML text to 1-based line numbers.
class LineIndex {
 public:
  explicit LineIndex(const std::string& text);
  int Line(ptrdiff_t offset) const;

 private:
  std::vector<ptrdiff_t> starts_;
};

// A keyword and its value, for enumerated attributes.
using Keyword = std::pair<const char*, int>;

class XmlElement {
 public:
  XmlElement(pugi::xml_node node, const std::string& file, const LineIndex& lines);
  // An element whose place is known already (one copied in from an included file).
  XmlElement(pugi::xml_node node, const std::string& file, int line);

  pugi::xml_node node() const { return node_; }
  const std::string& tag() const { return src_.tag; }
  const Source& src() const { return src_; }

  // Throws for the element, e.g. Fail("kp must be positive").
  [[noreturn]] void Fail(const std::string& what) const;

  // Throws if the element has an attribute not in `allowed`.
  void CheckAttributes(const std::vector<const char*>& allowed) const;

  bool Has(const char* name) const;

  // Reads up to n numbers (exactly n if `exact`); returns how many were read, or 0
  // if absent. Throws for non-numbers and wrong counts.
  int Numbers(const char* name, double* out, int n, bool exact = true) const;
  template <size_t N>
  int Numbers(const char* name, std::array<double, N>& out, bool exact = true) const {
    return Numbers(name, out.data(), static_cast<int>(N), exact);
  }
  bool Number(const char* name, double* out) const { return Numbers(name, out, 1) == 1; }
  void RequiredNumber(const char* name, double* out) const;
  // A list of any length.
  std::optional<std::vector<double>> Vector(const char* name) const;
  bool Int(const char* name, int* out) const;
  int Ints(const char* name, int* out, int n, bool exact = true) const;
  bool Text(const char* name, std::string* out) const;
  void RequiredText(const char* name, std::string* out) const;
  bool Enum(const char* name, int* out, std::initializer_list<Keyword> keywords) const;
  bool Bool(const char* name, bool* out) const;
  // false / true / auto
  bool Tri(const char* name, int* out) const;
  // A quaternion that is not all zeros.
  bool Quat(const char* name, std::array<double, 4>& out) const;
  // The alternative orientations (axisangle, xyaxes, zaxis, euler); at most one, and
  // not together with quat.
  void Orient(Orientation* alt) const;
  // The whitespace-separated tokens of an attribute (none when it is absent).
  std::vector<std::string> Tokens(const char* name) const;

 private:
  // The shared reader behind Numbers and Ints.
  template <typename T>
  int List(const char* name, T* out, int n, bool exact, const char* kind,
           bool (*parse)(const std::string&, T*)) const;

  pugi::xml_node node_;
  Source src_;
};

// Parses a whole token as a double; false if anything is left over (a value out of
// range reads as strtod gives it: infinity, or a denormal or zero).
bool ParseDouble(const std::string& token, double* out);

// Parses a whole token as an int; false if it is not one or out of range.
bool ParseInt(const std::string& token, int* out);

// Parses a whole token as a float (rounded once, as MuJoCo reads float data); false if
// it is not one.
bool ParseFloat(const std::string& token, float* out);

// A list of any length (empty when the attribute is absent); a bad token fails at e.
template <typename T>
std::vector<T> ReadList(const XmlElement& e, const char* name,
                        bool (*parse)(const std::string&, T*)) {
  std::vector<T> out;
  for (const std::string& t : e.Tokens(name)) {
    T value;
    if (!parse(t, &value)) e.Fail("bad number '" + t + "' in '" + name + "'");
    out.push_back(value);
  }
  return out;
}

// Parses the XML text of `file` into `doc` and returns its root element (empty if there
// is none). A syntax error, or elements nested deeper than MuJoCo's parser allows (see
// mjcf/limits.h), throw simlab::Error naming the file and line.
pugi::xml_node ParseXml(const std::string& text, const std::string& file,
                        const LineIndex& lines, pugi::xml_document* doc);

}  // namespace simlab::mjcf

#endif  // SIMLAB_MJCF_XML_ATTRS_H_
