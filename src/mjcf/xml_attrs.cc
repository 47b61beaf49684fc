// Checked attribute reading for MJCF elements.
#include "mjcf/xml_attrs.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "mjcf/error.h"
#include "mjcf/limits.h"

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

// The whole token, or false (out untouched).
bool ParseDouble(const std::string& token, double* out) {
  errno = 0;
  char* end = nullptr;
  double v = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0') return false;
  *out = v;
  return true;
}

bool ParseFloat(const std::string& t, float* out) {
  errno = 0;
  char* end = nullptr;
  *out = std::strtof(t.c_str(), &end);
  return end != t.c_str() && *end == '\0' && !(errno == ERANGE && std::isinf(*out));
}

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

// ---------------------------------------------------------------- parsing

namespace {

// True if the start tag whose name begins at `offset` ends with "/>" (quoted attribute
// values may hold '>' and '/').
bool SelfClosed(const std::string& text, ptrdiff_t offset) {
  char quote = 0, last = 0;
  for (size_t i = static_cast<size_t>(offset); i < text.size(); i++) {
    char c = text[i];
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      return last == '/';
    }
    if (!std::isspace(static_cast<unsigned char>(c))) last = c;
  }
  return false;
}

// The first element (in document order) that MuJoCo's parser would refuse for its
// depth: one on level kMaxXmlDepth - 1 with content (it is not self-closed), the root
// being level 1. Elements deeper than that have such an ancestor, so the walk (a loop,
// not a recursion) never goes below that level.
pugi::xml_node TooDeep(pugi::xml_node root, const std::string& text) {
  const int last_level = kMaxXmlDepth - 1;
  pugi::xml_node node = root;
  int level = 1;
  while (true) {
    // This element, then its first child element if it may have one.
    if (level == last_level) {
      ptrdiff_t offset = node.offset_debug();
      bool closed = offset >= 0 ? SelfClosed(text, offset) : !node.first_child();
      if (!closed) return node;
    }
    pugi::xml_node child = node.find_child([](pugi::xml_node n) {
      return n.type() == pugi::node_element;
    });
    if (child && level < last_level) {
      node = child;
      level++;
      continue;
    }
    // Else the next element after it: a sibling of it or of its nearest ancestor.
    while (true) {
      if (node == root) return pugi::xml_node();
      pugi::xml_node next = node.next_sibling();
      while (next && next.type() != pugi::node_element) next = next.next_sibling();
      if (next) {
        node = next;
        break;
      }
      node = node.parent();
      level--;
    }
  }
}

}  // namespace

pugi::xml_node ParseXml(const std::string& text, const std::string& file,
                        const LineIndex& lines, pugi::xml_document* doc) {
  // Syntax: the line where pugixml stopped.
  pugi::xml_parse_result result =
      doc->load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!result) {
    throw Error(file + ":" + std::to_string(lines.Line(result.offset)) +
                ": malformed XML: " + result.description());
  }
  pugi::xml_node root = doc->document_element();
  if (root.empty()) return root;

  // Depth: MuJoCo's parser rule, before any recursive walk of the tree.
  if (pugi::xml_node deep = TooDeep(root, text)) {
    XmlElement(deep, file, lines)
        .Fail("element nesting is too deep: MuJoCo's XML parser allows " +
              std::to_string(kMaxXmlDepth) + " levels, the content of an element counting " +
              "as one more level (so an element on level " + std::to_string(kMaxXmlDepth - 1) +
              " must be self-closed)");
  }
  return root;
}

}  // namespace simlab::mjcf
