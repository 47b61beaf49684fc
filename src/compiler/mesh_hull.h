// The convex hull of a mesh as MuJoCo's mesh_graph (see mesh_hull.cc for the layout).
#ifndef SIMLAB_COMPILER_MESH_HULL_H_
#define SIMLAB_COMPILER_MESH_HULL_H_

#include <string>
#include <vector>

namespace simlab::compiler {

enum class HullResult { kOk, kQhullError, kBadGraph, kUnavailable };

// Fills `graph` from the vertices (x y z each); leaves it empty for fewer than 4
// vertices or on failure (then `message` holds qhull's error line). maxhullvert -1
// means no limit.
HullResult ConvexHullGraph(const std::vector<double>& vert, int maxhullvert,
                           std::vector<int>* graph, std::string* message);

}  // namespace simlab::compiler

#endif  // SIMLAB_COMPILER_MESH_HULL_H_
