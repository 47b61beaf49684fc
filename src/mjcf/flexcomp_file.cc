// The files of <flexcomp type="mesh"> and <flexcomp type="gmsh"> (see flexcomp.h), read
// the way MuJoCo's mjCFlexcomp::MakeMesh and LoadGMSH read them.
//
// Points and elements go into what the flexcomp already holds as MuJoCo's do: a mesh
// replaces the points (and, for dim 2, the elements; dim 3 appends its tetrahedra), and
// replaces the texture coordinates only when the mesh has some; a GMSH file appends its
// nodes and elements. Every byte read from a GMSH file is bounds-checked, and room is
// made for a count the file states only once its bytes are known to hold that many
// (ascii values are appended as they are read).
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <exception>
#include <string>
#include <string_view>
#include <vector>

#include "compiler/mesh_io.h"
#include "mjcf/assets.h"
#include "mjcf/flexcomp.h"
#include "mjcf/spec.h"
#include "simlab/model.h"
#include "simlab/simlab.h"

namespace simlab::mjcf {

namespace {

// ---------------------------------------------------------------- files

// The message when `path` cannot be read (MuJoCo: "Error opening file '...'"), with why.
std::string OpenError(const std::string& path, const AssetFiles* assets,
                      const std::string& problem) {
  std::string message = "Error opening file '" + path + "'";
  return problem.empty() ? message + NotAmongAssets(assets) : message + ": " + problem;
}

// The lower-case extension of `path` with its dot, from the last dot (MuJoCo's
// mjuu_getext), or "".
std::string Extension(const std::string& path) {
  size_t dot = path.find_last_of('.');
  if (dot == std::string::npos) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// ---------------------------------------------------------------- mesh

// MuJoCo refuses a non-finite vertex, naming its first coordinate among the file's
// vertices as read (for binary STL, before repeated ones are merged).
std::string NonFiniteVertex(const std::string& ext, const std::string& bytes,
                            const compiler::MeshData& mesh) {
  auto message = [](uint64_t coordinate) {
    return "vertex coordinate " + std::to_string(coordinate) + " is not finite";
  };

  // Binary STL: each triangle's 3 corners follow its 12-byte normal.
  int64_t triangles = ext == ".stl" ? compiler::BinaryStlFaceCount(bytes) : -1;
  if (triangles >= 0) {
    for (uint64_t corner = 0; corner < 3 * uint64_t(triangles); corner++) {
      float v[3];
      std::memcpy(v, bytes.data() + 84 + 50 * (corner / 3) + 12 * (corner % 3 + 1), sizeof(v));
      if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
        return message(3 * corner);
      }
    }
    return "";
  }

  // OBJ (and simlab's ASCII STL): the vertices as the reader gave them.
  for (size_t i = 0; i < mesh.vert.size(); i++) {
    if (!std::isfinite(mesh.vert[i])) return message(i - i % 3);
  }
  return "";
}

// Reads the surface mesh at `path` with simlab's mesh reader, checked and merged as
// MuJoCo's LoadFromResource(resource, remove_repeated=true) leaves it. The reader's own
// errors throw at `src`, the flexcomp.
std::string ReadSurfaceMesh(const Source& src, const std::string& path,
                            const AssetFiles* assets, compiler::MeshData* mesh) {
  // The file must open before its type is looked at, as in MuJoCo (the reader refuses
  // every type but STL and OBJ, MSH being refused already).
  std::string bytes, problem;
  if (!ReadFileOrAsset(path, assets, &bytes, &problem)) return OpenError(path, assets, problem);
  std::string ext = Extension(path);
  if (ext == ".ply") return "unsupported mesh type: 'model/ply'";

  // Parse (STL: repeated vertices merged; OBJ: polygons cut into triangles).
  MeshSpec spec;
  spec.src = src;
  spec.path = path;
  try {
    *mesh = compiler::ReadMeshBytes(spec, bytes);
  } catch (const Error&) {
    throw;  // (it names the flexcomp already)
  } catch (const std::exception& e) {
    return e.what();
  }
  std::string bad = NonFiniteVertex(ext, bytes, *mesh);
  if (!bad.empty()) return bad;
  if (ext == ".obj") compiler::MergeRepeatedVertices(mesh);
  return "";
}

// Appends, for each face, the tetrahedron (0, face + 1) from point 0 (the origin) when
// its volume is positive (MuJoCo's test: (a x b) . c of the edges from the origin).
void AppendTetrahedra(const std::vector<int>& face, const std::array<double, 3>& origin,
                      FlexcompPoints* shape) {
  const std::vector<double>& p = shape->point;
  for (size_t i = 0; i + 2 < face.size(); i += 3) {
    int corner[3] = {face[i] + 1, face[i + 1] + 1, face[i + 2] + 1};
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
      a[k] = p[3 * corner[0] + k] - origin[k];
      b[k] = p[3 * corner[1] + k] - origin[k];
      c[k] = p[3 * corner[2] + k] - origin[k];
    }
    double normal[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                        a[0] * b[1] - a[1] * b[0]};
    if (normal[0] * c[0] + normal[1] * c[1] + normal[2] * c[2] < kMinVal) continue;
    shape->element.insert(shape->element.end(), {0, corner[0], corner[1], corner[2]});
  }
}

// ---------------------------------------------------------------- GMSH: input

// A problem with the GMSH file; LoadFlexcompGmsh returns its message.
struct GmshError {
  std::string message;
};
[[noreturn]] void Fail(const std::string& message) { throw GmshError{message}; }

// A value of type T at byte `offset`, unaligned and in the machine's byte order as MuJoCo
// reads it; fails with `truncated` when the file ends first.
template <typename T>
T ReadAt(std::string_view bytes, uint64_t offset, const char* truncated) {
  if (offset > bytes.size() || sizeof(T) > bytes.size() - offset) Fail(truncated);
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

// Where `text` first starts, or -1. Like MuJoCo's findstring, an occurrence that ends
// the file exactly is not seen.
int64_t FindText(std::string_view bytes, std::string_view text) {
  size_t at = bytes.find(text);
  if (at == std::string_view::npos || at + text.size() >= bytes.size()) return -1;
  return static_cast<int64_t>(at);
}

// mju_round: the nearest integer, halves up; 0 for what no int holds.
int RoundLikeMuJoCo(double x) {
  if (!(std::fabs(x) < 1e9)) return 0;
  double lower = std::floor(x), upper = std::ceil(x);
  return static_cast<int>(x - lower < upper - x ? lower : upper);
}

// A stream over one section's text, for ascii files. MuJoCo's checks use good(): a
// number that ends the section (no whitespace after it) counts as a failed read.
std::istringstream SectionStream(std::string_view bytes, uint64_t begin, uint64_t end) {
  return std::istringstream(std::string(bytes.substr(begin, end - begin)));
}

// The format line and where the $Nodes and $Elements sections begin and end.
struct GmshLayout {
  int version = 0;  // 100 * the version: 410 or 220
  bool binary = false;
  uint64_t node_begin = 0, node_end = 0, elem_begin = 0, elem_end = 0;
};

// Reads "$MeshFormat version binary ..." and finds the two sections (their text starts
// one byte after the keyword: its line end).
GmshLayout ReadGmshLayout(std::string_view bytes) {
  if (bytes.empty()) Fail("Empty GMSH file");
  if (bytes.size() < 11 || bytes.substr(0, 11) != "$MeshFormat") {
    Fail("GMSH file must begin with $MeshFormat");
  }
  std::string format(bytes.substr(11, 4096));
  double version = 0;
  int binary = 0;
  if (std::sscanf(format.c_str(), "%lf %d", &version, &binary) != 2) {
    Fail("Could not read GMSH file header");
  }
  GmshLayout layout;
  layout.version = RoundLikeMuJoCo(100 * version);
  layout.binary = binary != 0;
  if (layout.version != 220 && layout.version != 410) {
    Fail("Only GMSH file format versions 4.1 and 2.2 are supported");
  }

  // The sections, in order.
  int64_t nodes = FindText(bytes, "$Nodes"), end_nodes = FindText(bytes, "$EndNodes");
  int64_t elems = FindText(bytes, "$Elements"), end_elems = FindText(bytes, "$EndElements");
  if (nodes < 0) Fail("GMSH file missing $Nodes");
  if (end_nodes < nodes + 7) Fail("GMSH file missing $EndNodes after $Nodes");
  if (elems < 0) Fail("GMSH file missing $Elements");
  if (end_elems < elems + 10) Fail("GMSH file missing $EndElements after $Elements");
  layout.node_begin = nodes + 7;
  layout.node_end = end_nodes;
  layout.elem_begin = elems + 10;
  layout.elem_end = end_elems;
  return layout;
}

// ---------------------------------------------------------------- GMSH 4.1

// Version 4.1: one block of nodes (sequential tags, from minNodeTag) and one block of
// elements of the nodes' dimension: lines (type 1), triangles (2) or tetrahedra (4).
// Element node ids are the tags less minNodeTag.
struct Gmsh41Header {
  uint64_t blocks = 0, count = 0, min_tag = 0, max_tag = 0;
  int entity_dim = 0, entity_tag = 0, type_or_parametric = 0;
  uint64_t count_in_block = 0;
};
constexpr uint64_t kGmsh41HeaderBytes = 52;

// The block header of a binary section (sizes are 8 bytes, dim/tag/type 4).
Gmsh41Header ReadBinary41Header(std::string_view bytes, uint64_t begin, const char* truncated) {
  Gmsh41Header h;
  h.blocks = ReadAt<uint64_t>(bytes, begin, truncated);
  h.count = ReadAt<uint64_t>(bytes, begin + 8, truncated);
  h.min_tag = ReadAt<uint64_t>(bytes, begin + 16, truncated);
  h.max_tag = ReadAt<uint64_t>(bytes, begin + 24, truncated);
  h.entity_dim = ReadAt<int32_t>(bytes, begin + 32, truncated);
  h.entity_tag = ReadAt<int32_t>(bytes, begin + 36, truncated);
  h.type_or_parametric = ReadAt<int32_t>(bytes, begin + 40, truncated);
  h.count_in_block = ReadAt<uint64_t>(bytes, begin + 44, truncated);
  return h;
}

// The header of an ascii section; false if a number is missing.
bool ReadAscii41Header(std::istringstream& in, Gmsh41Header* h) {
  unsigned long long blocks = 0, count = 0, min_tag = 0, max_tag = 0, count_in_block = 0;
  in >> blocks >> count >> min_tag >> max_tag;
  in >> h->entity_dim >> h->entity_tag >> h->type_or_parametric >> count_in_block;
  h->blocks = blocks, h->count = count, h->min_tag = min_tag, h->max_tag = max_tag;
  h->count_in_block = count_in_block;
  return in.good();
}

void CheckNodeBlock41(const Gmsh41Header& h) {
  if (h.blocks != 1 || h.count != h.count_in_block) Fail("All nodes must be in single block");
}

void CheckNodeDim41(const Gmsh41Header& h) {
  if (h.entity_dim < 1 || h.entity_dim > 3) Fail("Entity must be 1D, 2D or 3D");
}

void CheckNodeCount41(uint64_t count) {
  if (count >= INT_MAX / 3) Fail("Invalid number of nodes.");
}

// Ascii nodes: the header, the tags (checked), then x y z of each node. Returns the
// header (its min_tag offsets the element ids) and sets the dimension.
Gmsh41Header ReadAsciiNodes41(std::string_view bytes, const GmshLayout& at, FlexcompPoints* out) {
  std::istringstream in = SectionStream(bytes, at.node_begin, at.node_end);
  Gmsh41Header h;
  if (!ReadAscii41Header(in, &h)) Fail("Error reading Nodes header");
  CheckNodeBlock41(h);
  if (h.max_tag != h.count_in_block) {
    Fail("Maximum number of nodes must be equal to number of nodes in a block");
  }
  CheckNodeDim41(h);
  out->dim = h.entity_dim;

  // Tags: minNodeTag, minNodeTag + 1, ...
  for (uint64_t i = 0; i < h.count; i++) {
    unsigned long long tag;
    in >> tag;
    if (!in.good()) Fail("Error reading node tags");
    if (tag != i + h.min_tag) Fail("Node tags must be sequential");
  }

  // Coordinates.
  CheckNodeCount41(h.count);
  for (uint64_t i = 0; i < 3 * h.count; i++) {
    double x;
    in >> x;
    if (!in.good()) Fail("Error reading node coordinates");
    out->point.push_back(x);
  }
  return h;
}

// Binary nodes: the 52-byte header, 8-byte tags, then 3 doubles per node.
Gmsh41Header ReadBinaryNodes41(std::string_view bytes, const GmshLayout& at, FlexcompPoints* out) {
  const char* truncated = "Insufficient byte size of Nodes";
  uint64_t size = at.node_end - at.node_begin;
  if (size < kGmsh41HeaderBytes) Fail("Invalid nodes header");
  Gmsh41Header h = ReadBinary41Header(bytes, at.node_begin, truncated);
  CheckNodeBlock41(h);
  CheckNodeDim41(h);
  out->dim = h.entity_dim;
  if (h.count > (size - kGmsh41HeaderBytes) / 32) Fail(truncated);

  // Tags: minNodeTag, minNodeTag + 1, ...
  uint64_t tags = at.node_begin + kGmsh41HeaderBytes;
  for (uint64_t i = 0; i < h.count; i++) {
    if (ReadAt<uint64_t>(bytes, tags + 8 * i, truncated) != i + h.min_tag) {
      Fail("Node tags must be sequential");
    }
  }

  // Coordinates.
  CheckNodeCount41(h.count);
  uint64_t coordinates = tags + 8 * h.count;
  out->point.reserve(out->point.size() + 3 * h.count);
  for (uint64_t i = 0; i < 3 * h.count; i++) {
    out->point.push_back(ReadAt<double>(bytes, coordinates + 8 * i, truncated));
  }
  return h;
}

// The element block's checks, shared by ascii and binary (in MuJoCo's order for each).
void CheckElementBlock41(const Gmsh41Header& h, int dim) {
  if (h.blocks != 1 || h.count != h.count_in_block) Fail("All elements must be in single block");
  if (h.entity_dim != dim) Fail("Inconsistent dimensionality in Elements");
}
void CheckElementType41(const Gmsh41Header& h) {
  int type = h.type_or_parametric;
  if ((h.entity_dim == 1 && type != 1) || (h.entity_dim == 2 && type != 2) ||
      (h.entity_dim == 3 && type != 4)) {
    Fail("Element type inconsistent with dimensionality");
  }
}
void CheckElementCount41(uint64_t count) {
  if (count >= INT_MAX / 4) Fail("Invalid numElements.");
}

// An element's node id: its node tag less the first node tag (wrapping as MuJoCo's int).
int NodeId41(uint64_t tag, uint64_t min_node_tag) {
  return static_cast<int>(static_cast<uint32_t>(tag - min_node_tag));
}

// Ascii elements: the header, then per element its tag and dim+1 node tags.
void ReadAsciiElements41(std::string_view bytes, const GmshLayout& at, uint64_t min_node_tag,
                         FlexcompPoints* out) {
  std::istringstream in = SectionStream(bytes, at.elem_begin, at.elem_end);
  Gmsh41Header h;
  if (!ReadAscii41Header(in, &h)) Fail("Error reading Elements header");
  CheckElementBlock41(h, out->dim);
  CheckElementCount41(h.count);
  CheckElementType41(h);
  for (uint64_t i = 0; i < h.count; i++) {
    unsigned long long tag, node;
    in >> tag;
    for (int k = 0; k <= h.entity_dim; k++) {
      in >> node;
      if (!in.good()) Fail("Error reading Elements");
      out->element.push_back(NodeId41(node, min_node_tag));
    }
  }
}

// Binary elements: the 52-byte header, then per element an 8-byte tag and dim+1
// 8-byte node tags.
void ReadBinaryElements41(std::string_view bytes, const GmshLayout& at, uint64_t min_node_tag,
                          FlexcompPoints* out) {
  const char* truncated = "Insufficient byte size of Elements";
  uint64_t size = at.elem_end - at.elem_begin;
  if (size < kGmsh41HeaderBytes) Fail("Invalid elements header");
  Gmsh41Header h = ReadBinary41Header(bytes, at.elem_begin, truncated);
  CheckElementBlock41(h, out->dim);
  CheckElementType41(h);
  CheckElementCount41(h.count);
  uint64_t element_bytes = 8 * static_cast<uint64_t>(h.entity_dim + 2);
  if (h.count > (size - kGmsh41HeaderBytes) / element_bytes) Fail(truncated);

  out->element.reserve(out->element.size() + (h.entity_dim + 1) * h.count);
  uint64_t first = at.elem_begin + kGmsh41HeaderBytes;
  for (uint64_t i = 0; i < h.count; i++) {
    for (int k = 0; k <= h.entity_dim; k++) {
      uint64_t tag = ReadAt<uint64_t>(bytes, first + i * element_bytes + 8 * (k + 1), truncated);
      out->element.push_back(NodeId41(tag, min_node_tag));
    }
  }
}

void ReadGmsh41(std::string_view bytes, const GmshLayout& at, FlexcompPoints* out) {
  Gmsh41Header nodes = at.binary ? ReadBinaryNodes41(bytes, at, out) : ReadAsciiNodes41(bytes, at, out);
  if (at.binary) {
    ReadBinaryElements41(bytes, at, nodes.min_tag, out);
  } else {
    ReadAsciiElements41(bytes, at, nodes.min_tag, out);
  }
}

// ---------------------------------------------------------------- GMSH 2.2

// Version 2.2: a node count, then tag x y z per node (tags are ignored: node ids follow
// the order), then an element count and elements, whose type is taken from the first
// one: triangles (type 2, dim 2) or tetrahedra (type 4, dim 3). Node tags count from 1.

// The nodes per element and the dimension of a 2.2 element type.
int NodesPerElement22(int type, FlexcompPoints* out) {
  if (type != 2 && type != 4) Fail("Invalid number of node tags");
  out->dim = type == 2 ? 2 : 3;
  return type == 2 ? 3 : 4;
}

// An ascii section's count line: all digits (CRLF files pass, their line being the empty
// rest of the keyword's line), then the count read from the section's start.
unsigned long long ReadAsciiCount22(std::istringstream& in, const std::string& section,
                                    const char* bad_line, const char* unreadable) {
  size_t newline = section.find('\n');
  std::string line = section.substr(0, newline);
  for (char c : line) {
    if (!std::isdigit(static_cast<unsigned char>(c))) Fail(bad_line);
  }
  // (MuJoCo steps back over the line it read, which fails when no line end follows it.)
  if (newline == std::string::npos) Fail(unreadable);
  unsigned long long count = 0;
  in >> count;
  if (!in.good()) Fail(unreadable);
  return count;
}

// Ascii nodes: the count, then a tag and x y z per node. Returns the node count.
uint64_t ReadAsciiNodes22(std::string_view bytes, const GmshLayout& at, FlexcompPoints* out) {
  std::string section(bytes.substr(at.node_begin, at.node_end - at.node_begin));
  std::istringstream in(section);
  uint64_t count = ReadAsciiCount22(in, section, "Invalid node header", "Error reading Nodes header");
  if (count >= INT_MAX / 3) Fail("Invalid number of nodes.");
  for (uint64_t i = 0; i < count; i++) {
    unsigned long long tag;
    in >> tag;
    if (!in.good()) Fail("Error reading node tags");
    for (int k = 0; k < 3; k++) {
      double x;
      in >> x;
      if (!in.good()) Fail("Error reading node coordinates");
      out->point.push_back(x);
    }
  }
  return count;
}

// Ascii elements: the count, then per element "tag type ntags [2 tags] nodes" (MuJoCo
// reads two tags whenever ntags > 0, and the type of the first element only).
void ReadAsciiElements22(std::string_view bytes, const GmshLayout& at, uint64_t node_count,
                         FlexcompPoints* out) {
  std::string section(bytes.substr(at.elem_begin, at.elem_end - at.elem_begin));
  std::istringstream in(section);
  uint64_t count = ReadAsciiCount22(in, section, "Invalid elements header",
                                    "Error reading Elements header");
  if (count >= INT_MAX / 4) Fail("Invalid number of elements.");
  int tag = 0, type = 0, ntags = 0;
  in >> tag >> type >> ntags;
  if (!in.good()) Fail("Error reading Elements");
  int nodes = NodesPerElement22(type, out);

  for (uint64_t i = 0; i < count; i++) {
    if (i != 0) {
      in >> tag >> type >> ntags;
      if (!in.good()) Fail("Error reading Elements");
    }
    if (ntags > 0) {
      int physical = 0, entity = 0;
      in >> physical >> entity;
      if (!in.good()) Fail("Error reading Elements");
    }
    for (int k = 0; k < nodes; k++) {
      int node = 0;
      in >> node;
      if (!in.good()) Fail("Error reading Elements");
      if (node < 1 || static_cast<uint64_t>(node) > node_count) Fail("Invalid node tag");
      out->element.push_back(node - 1);
    }
  }
}

// The count that starts a binary section: the first (at most 10) bytes up to a zero
// byte, read as an int, and how far its text reaches (that many bytes less one: MuJoCo
// counts the first nonzero byte of the binary data after the line end as well).
struct Count22 {
  int count = 0;
  uint64_t text_bytes = 0;
};
Count22 ReadBinaryCount22(std::string_view bytes, uint64_t begin, uint64_t end,
                          const char* out_of_range) {
  std::string_view head = bytes.substr(begin, std::min<uint64_t>(10, end - begin));
  std::string text(head.substr(0, head.find('\0')));
  // As std::stoi reads it: blanks, a sign, digits; none is MuJoCo's caught exception.
  errno = 0;
  char* stop = nullptr;
  long value = std::strtol(text.c_str(), &stop, 10);
  if (stop == text.c_str()) Fail("exception while reading GMSH file");
  if (errno == ERANGE || value < INT_MIN || value > INT_MAX) Fail(out_of_range);
  Count22 c;
  c.count = static_cast<int>(value);
  c.text_bytes = text.size() - 1;
  return c;
}

// Binary nodes: the count line, then per node a 4-byte tag and 3 doubles.
uint64_t ReadBinaryNodes22(std::string_view bytes, const GmshLayout& at, FlexcompPoints* out) {
  const char* truncated = "Insufficient byte size of Nodes";
  uint64_t size = at.node_end - at.node_begin;
  if (size < 4) Fail("Invalid nodes header");
  Count22 header = ReadBinaryCount22(bytes, at.node_begin, at.node_end, "Invalid number of nodes");
  if (header.count < 0 || static_cast<uint64_t>(header.count) > (size - 4) / 28) Fail(truncated);
  if (header.count >= INT_MAX / 3) Fail("Invalid number of nodes.");

  uint64_t first = at.node_begin + header.text_bytes;
  out->point.reserve(out->point.size() + 3 * static_cast<uint64_t>(header.count));
  for (uint64_t i = 0; i < static_cast<uint64_t>(header.count); i++) {
    for (int k = 0; k < 3; k++) {
      out->point.push_back(ReadAt<double>(bytes, first + 28 * i + 4 + 8 * k, truncated));
    }
  }
  return static_cast<uint64_t>(header.count);
}

// A node tag of a binary element, checked against `limit` (MuJoCo checks the first
// element against the node count and the others against the element count).
void AppendNodeTag22(std::string_view bytes, uint64_t offset, int64_t limit, FlexcompPoints* out) {
  int node = ReadAt<int32_t>(bytes, offset, "Insufficient byte size of Elements");
  if (node < 1 || node > limit) Fail("Invalid node tag");
  out->element.push_back(node - 1);
}

// Binary elements, in one of two layouts told apart by the first element's tag count:
// gmsh's (each element "type 1 ntags number tag tag nodes...", 4-byte ints) or fTetWild's
// ("type count 0", then "number nodes..." per element, 4 nodes wide).
void ReadBinaryElements22(std::string_view bytes, const GmshLayout& at, uint64_t node_count,
                          FlexcompPoints* out) {
  const char* truncated = "Insufficient byte size of Elements";
  uint64_t size = at.elem_end - at.elem_begin;
  if (size < 4) Fail("Invalid elements header");
  Count22 header = ReadBinaryCount22(bytes, at.elem_begin, at.elem_end, "Invalid number of elements");
  int64_t count = header.count;
  if (count < 0) Fail("Invalid number of elements");
  uint64_t first = at.elem_begin + header.text_bytes;
  int type = ReadAt<int32_t>(bytes, first, truncated);
  int ntags = ReadAt<int32_t>(bytes, first + 8, truncated);
  int nodes = NodesPerElement22(type, out);
  if (17 + 20 * static_cast<uint64_t>(count) > size) Fail(truncated);

  // gmsh: 6 + nodes ints per element, the nodes after the 6.
  if (ntags > 0) {
    uint64_t element_bytes = 4 * static_cast<uint64_t>(6 + nodes);
    if (4 + element_bytes * count > size) Fail(truncated);
    for (int64_t i = 0; i < std::max<int64_t>(count, 1); i++) {
      for (int k = 0; k < nodes; k++) {
        uint64_t offset = first + element_bytes * i + 4 * (6 + k);
        AppendNodeTag22(bytes, offset, i == 0 ? static_cast<int64_t>(node_count) : count, out);
      }
    }
    return;
  }

  // fTetWild: the first element's nodes after its 4 ints, then 5 ints per element.
  for (int k = 0; k < nodes; k++) {
    AppendNodeTag22(bytes, first + 4 * (4 + k), static_cast<int64_t>(node_count), out);
  }
  for (int64_t i = 0; i + 1 < count; i++) {
    for (int k = 0; k < nodes; k++) {
      AppendNodeTag22(bytes, first + 24 + 20 * i + 4 * (3 + k), count, out);
    }
  }
}

void ReadGmsh22(std::string_view bytes, const GmshLayout& at, FlexcompPoints* out) {
  uint64_t node_count = at.binary ? ReadBinaryNodes22(bytes, at, out) : ReadAsciiNodes22(bytes, at, out);
  if (at.binary) {
    ReadBinaryElements22(bytes, at, node_count, out);
  } else {
    ReadAsciiElements22(bytes, at, node_count, out);
  }
}

}  // namespace

// ---------------------------------------------------------------- entry points

std::string LoadFlexcompMesh(const Source& src, const std::string& path, const AssetFiles* assets,
                             int dim, const std::array<double, 3>& origin, FlexcompPoints* out) {
  // MuJoCo's checks before reading.
  if (path.empty()) return "File is required";
  if (dim < 2) return "Flex dim must be at least 2 for mesh";
  if (Extension(path) == ".msh") return "legacy MSH files are not supported in flexcomp";

  compiler::MeshData mesh;
  std::string error = ReadSurfaceMesh(src, path, assets, &mesh);
  if (!error.empty()) return error;
  if (mesh.vert.empty() || mesh.face.empty()) return "Vertex and face data required";

  // Points (double from the file's floats); texture coordinates only if the mesh has them.
  out->point.assign(mesh.vert.begin(), mesh.vert.end());
  if (!mesh.texcoord.empty()) {
    out->texcoord = mesh.texcoord;
    out->elemtexcoord = mesh.facetexcoord;
  }

  // dim 2: the triangles. dim 3: the origin first, then a tetrahedron per face.
  if (dim == 2) {
    out->element = mesh.face;
  } else {
    out->point.insert(out->point.begin(), origin.begin(), origin.end());
    AppendTetrahedra(mesh.face, origin, out);
  }
  return "";
}

std::string LoadFlexcompGmsh(const std::string& path, const AssetFiles* assets,
                             FlexcompPoints* out) {
  if (path.empty()) return "File is required";
  std::string bytes, problem;
  if (!ReadFileOrAsset(path, assets, &bytes, &problem)) return OpenError(path, assets, problem);

  // Read into a copy, so that a failure leaves `out` as it was.
  FlexcompPoints shape = *out;
  try {
    GmshLayout layout = ReadGmshLayout(bytes);
    if (layout.version == 410) {
      ReadGmsh41(bytes, layout, &shape);
    } else {
      ReadGmsh22(bytes, layout, &shape);
    }
  } catch (const GmshError& e) {
    return e.message;
  } catch (const std::exception&) {
    return "exception while reading GMSH file";
  }
  *out = std::move(shape);
  return "";
}

}  // namespace simlab::mjcf
