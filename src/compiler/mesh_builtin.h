// Builtin mesh shapes (mesh_builtin.cc).
#ifndef SIMLAB_COMPILER_MESH_BUILTIN_H_
#define SIMLAB_COMPILER_MESH_BUILTIN_H_

#include "compiler/mesh_io.h"
#include "mjcf/spec.h"

namespace simlab::compiler {

// The vertices (and triangles, for shapes that have them) of s.builtin made from
// s.params as MuJoCo 3.5 does; bad parameters throw at s.src.
MeshData BuiltinMesh(const mjcf::MeshSpec& s);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_MESH_BUILTIN_H_
