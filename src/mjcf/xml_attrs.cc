// Checked attribute reading for MJCF elements.
#include "mjcf/xml_attrs.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "mjcf/error.h"

namespace simlab::mjcf {

// ---------------------------------------------------------------- line numbers

LineIndex::LineIndex(const std::string& text) {
  starts_.push_back(0);
  for (size_t i = 0; i < text.size(); i++) {
    if (text[i] == '\n') starts_.push_back(static_cast<ptrdiff_t>(i + 1));
  }
}

int LineIndex::Line(ptrdiff_t offset) const {
  if (offset < 0) return 0;
  auto it = std::upper_bound(starts_.begin(), starts_.end(), offset);
  return static_cast<int>(it - starts_.begin());
}

// ---------------------------------------------------------------- element

XmlElement::XmlElement(pugi::xml_node node, const std::string& file, const LineIndex& lines)
    : node_(node) {
  src_.file = file;
  src_.line = lines.Line(node.offset_debug());
  src_.tag = node.name();
  src_.name = node.attribute("name").value();
}

XmlElement::XmlElement(pugi::xml_node node, const std::string& file, int line) : node_(node) {
  src_.file = file;
  src_.line = line;
  src_.tag = node.name();
  src_.name = node.attribute("name").value();
}

void XmlElement::Fail(const std::string& what) const { ThrowAt(src_, what); }

void XmlElement::CheckAttributes(const std::vector<const char*>& allowed) const {
  for (pugi::xml_attribute a : node_.attributes()) {
    bool known = false;
    for (const char* name : allowed) {
      if (std::strcmp(name, a.name()) == 0) {
        known = true;
        break;
      }
    }
    if (!known) Fail("unknown attribute '" + std::string(a.name()) + "'");
  }
}

bool XmlElement::Has(const char* name) const { return !node_.attribute(name).empty(); }

std::vector<std::string> XmlElement::Tokens(const char* name) const {
  std::istringstream in(node_.attribute(name).value());
  std::vector<std::string> tokens;
  std::string token;
  while (in >> token) tokens.push_back(token);
  return tokens;
}

// ---------------------------------------------------------------- numbers

namespace {

// Parses a whole token as a double; false if anything is left over.
bool ParseDouble(const std::string& token, double* out) {
  errno = 0;
  char* end = nullptr;
  double v = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0') return false;
  *out = v;
  return true;
}

}  // namespace

bool ParseInt(const std::string& token, int* out) {
  errno = 0;
  char* end = nullptr;
  long v = std::strtol(token.c_str(), &end, 10);
  if (end == token.c_str() || *end != '\0' || errno == ERANGE) return false;
  if (v < INT32_MIN || v > INT32_MAX) return false;
  *out = static_cast<int>(v);
  return true;
}

// Reads up to n (exactly n if `exact`) values of one kind; checks the count and every
// token before writing anything. `kind` names the value in messages.
template <typename T>
int XmlElement::List(const char* name, T* out, int n, bool exact, const char* kind,
                     bool (*parse)(const std::string&, T*)) const {
  if (!Has(name)) return 0;
  std::vector<std::string> tokens = Tokens(name);
  int count = static_cast<int>(tokens.size());
  if (count == 0) Fail("attribute '" + std::string(name) + "' is empty");
  if (count > n || (exact && count < n)) {
    Fail("attribute '" + std::string(name) + "' expects " + std::to_string(n) +
         (exact ? "" : " or fewer") + " " + kind + (n > 1 ? "s" : "") + ", got " +
         std::to_string(count));
  }
  std::vector<T> values(count);
  for (int i = 0; i < count; i++) {
    if (!parse(tokens[i], &values[i])) {
      Fail("attribute '" + std::string(name) + "': '" + tokens[i] + "' is not " +
           (kind[0] == 'i' ? "an " : "a ") + kind);
    }
  }
  std::copy(values.begin(), values.end(), out);
  return count;
}

int XmlElement::Numbers(const char* name, double* out, int n, bool exact) const {
  return List(name, out, n, exact, "number", ParseDouble);
}

void XmlElement::RequiredNumber(const char* name, double* out) const {
  if (!Has(name)) Fail("missing required attribute '" + std::string(name) + "'");
  Number(name, out);
}

std::optional<std::vector<double>> XmlElement::Vector(const char* name) const {
  if (!Has(name)) return std::nullopt;
  std::vector<std::string> tokens = Tokens(name);
  std::vector<double> values(tokens.size());
  for (size_t i = 0; i < tokens.size(); i++) {
    if (!ParseDouble(tokens[i], &values[i])) {
      Fail("attribute '" + std::string(name) + "': '" + tokens[i] + "' is not a number");
    }
  }
  return values;
}

int XmlElement::Ints(const char* name, int* out, int n, bool exact) const {
  return List(name, out, n, exact, "integer", ParseInt);
}

bool XmlElement::Int(const char* name, int* out) const { return Ints(name, out, 1) == 1; }

// ---------------------------------------------------------------- text and keywords

bool XmlElement::Text(const char* name, std::string* out) const {
  if (!Has(name)) return false;
  *out = node_.attribute(name).value();
  return true;
}

void XmlElement::RequiredText(const char* name, std::string* out) const {
  if (!Text(name, out) || out->empty()) {
    Fail("missing required attribute '" + std::string(name) + "'");
  }
}

bool XmlElement::Enum(const char* name, int* out, std::initializer_list<Keyword> keywords) const {
  if (!Has(name)) return false;
  std::string value = node_.attribute(name).value();
  std::string valid;
  for (const Keyword& k : keywords) {
    if (value == k.first) {
      *out = k.second;
      return true;
    }
    valid += (valid.empty() ? "" : ", ") + std::string(k.first);
  }
  Fail("attribute '" + std::string(name) + "': invalid keyword '" + value + "' (valid: " +
       valid + ")");
}

bool XmlElement::Bool(const char* name, bool* out) const {
  int v = 0;
  if (!Enum(name, &v, {{"false", 0}, {"true", 1}})) return false;
  *out = (v == 1);
  return true;
}

bool XmlElement::Tri(const char* name, int* out) const {
  return Enum(name, out, {{"false", kFalse}, {"true", kTrue}, {"auto", kAuto}});
}

// ---------------------------------------------------------------- orientation

bool XmlElement::Quat(const char* name, std::array<double, 4>& out) const {
  std::array<double, 4> q;
  if (!Numbers(name, q)) return false;
  if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0) Fail("zero quaternion is not allowed");
  out = q;
  return true;
}

void XmlElement::Orient(Orientation* alt) const {
  int count = Has("quat") ? 1 : 0;
  if (Numbers("axisangle", alt->axisangle)) {
    alt->kind = OrientKind::kAxisAngle;
    count++;
  }
  if (Numbers("xyaxes", alt->xyaxes)) {
    alt->kind = OrientKind::kXYAxes;
    count++;
  }
  if (Numbers("zaxis", alt->zaxis)) {
    alt->kind = OrientKind::kZAxis;
    count++;
  }
  if (Numbers("euler", alt->euler)) {
    alt->kind = OrientKind::kEuler;
    count++;
  }
  if (count > 1) Fail("multiple orientation specifiers are not allowed");
}

}  // namespace simlab::mjcf
