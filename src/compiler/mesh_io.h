// Mesh files as MuJoCo reads them: binary STL (repeated vertices merged), Wavefront OBJ
// (polygons cut into triangles the way MuJoCo's OBJ loader does), MuJoCo's binary MSH,
// and ASCII STL, which simlab reads as well (MuJoCo 3.5 refuses it).
#ifndef SIMLAB_COMPILER_MESH_IO_H_
#define SIMLAB_COMPILER_MESH_IO_H_

#include <cstdint>
#include <string>
#include <vector>

#include "mjcf/spec.h"

namespace simlab::compiler {

// Vertices (single precision, x y z per vertex), triangles (vertex indices) and the
// normals a file or builtin shape gives (x y z each; empty when it gives none).
struct MeshData {
  std::vector<float> vert;
  std::vector<int> face;
  std::vector<float> normal;
  std::vector<float> texcoord;   // u v per coordinate
  std::vector<int> facetexcoord; // a coordinate per face corner (empty: the face's vertex)
};

// Reads mesh.path, from `assets` (may be null) when one has its file name, else from
// disk; the file type comes from content_type or the extension. A negative scale
// product reverses the triangles' winding, as in MuJoCo. Throws at mesh.src.
MeshData ReadMeshFile(const mjcf::MeshSpec& mesh, const mjcf::AssetFiles* assets = nullptr);

// ReadMeshFile for the bytes of mesh.path, read already: the file type is checked (an
// unknown one throws at mesh.src) and the bytes parsed.
MeshData ReadMeshBytes(const mjcf::MeshSpec& mesh, const std::string& bytes);

// The face count of a binary STL file (an 80-byte header, the count, then 50 bytes per
// face), or -1 when the file's size does not fit one (an ASCII STL file, say).
int64_t BinaryStlFaceCount(const std::string& bytes);

// Merges exactly equal vertices (the first occurrence kept, in order; 0 and -0 are
// equal) and renumbers the faces (MuJoCo's remove_repeated; STL files come merged).
void MergeRepeatedVertices(MeshData* data);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_MESH_IO_H_
