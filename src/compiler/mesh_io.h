// Mesh files as MuJoCo reads them: binary STL (repeated vertices merged), Wavefront OBJ
// (polygons cut into triangles the way MuJoCo's OBJ loader does), MuJoCo's binary MSH,
// and ASCII STL, which simlab reads as well (MuJoCo 3.5 refuses it).
#ifndef SIMLAB_COMPILER_MESH_IO_H_
#define SIMLAB_COMPILER_MESH_IO_H_

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

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_MESH_IO_H_
