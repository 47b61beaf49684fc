// The convex hull of a mesh's vertices, by qhull (reentrant library), laid out as
// MuJoCo's mesh_graph:
//   numvert, numface, vert_edgeadr[numvert], vert_globalid[numvert],
//   edge_localid[numvert + 3*numface], face_globalid[3*numface]
// Each hull vertex lists its neighbours (hull-local ids) followed by -1; faces hold
// mesh vertex ids, wound outwards.
#include "compiler/mesh_hull.h"

#include <cstdio>
#include <string>
#include <vector>

#if __has_include(<libqhull_r/qhull_ra.h>)
#define SIMLAB_HAVE_QHULL 1
extern "C" {
#include <libqhull_r/qhull_ra.h>
}
#endif

namespace simlab::compiler {

#ifdef SIMLAB_HAVE_QHULL

namespace {

// Neighbour lists of every hull vertex (mesh ids for now), in qhull's vertex order.
// Returns false if qhull hands back something that is not a triangle or a foreign point.
bool VertexLists(qhT* qh, int nvert, int numvert, int numface, int* graph) {
  int* edgeadr = graph + 2;
  int* globalid = graph + 2 + numvert;
  int* edges = graph + 2 + 2 * numvert;
  vertexT *vertex, *vertex1, **vertex1p;
  facetT *facet, **facetp;
  int i = 0, adr = 0;
  FORALLvertices {
    int pid = qh_pointid(qh, vertex->point);
    if (pid < 0 || pid >= nvert) return false;
    edgeadr[i] = adr;
    globalid[i] = pid;
    int start = adr;

    // Every other corner of the neighbouring triangles, once.
    FOREACHfacet_(vertex->neighbors) {
      int corners = 0;
      FOREACHsetelement_(vertexT, facet->vertices, vertex1) {
        corners++;
        int other = qh_pointid(qh, vertex1->point);
        if (other < 0 || other >= nvert) return false;
        if (other == pid) continue;
        bool seen = false;
        for (int j = start; j < adr && !seen; j++) seen = edges[j] == other;
        if (!seen) edges[adr++] = other;
      }
      if (corners != 3) return false;
    }
    edges[adr++] = -1;
    i++;
  }
  return adr == numvert + 3 * numface;
}

// Triangles with mesh vertex ids; qhull's top-oriented facets get their first two
// corners swapped so that all wind outwards.
void FaceList(qhT* qh, int numvert, int numface, int* graph) {
  int* faces = graph + 2 + 3 * numvert + 3 * numface;
  facetT* facet;
  vertexT *vertex1, **vertex1p;
  int adr = 0;
  FORALLfacets {
    int slot[3] = {0, 1, 2};
    if (facet->toporient) slot[0] = 1, slot[1] = 0;
    int k = 0;
    FOREACHsetelement_(vertexT, facet->vertices, vertex1) {
      if (k < 3) faces[adr + slot[k]] = qh_pointid(qh, vertex1->point);
      k++;
    }
    adr += 3;
  }
}

// Neighbour lists hold mesh ids (below nvert) until here; make them hull-local.
void LocalEdgeIds(int nvert, int* graph) {
  int numvert = graph[0], numface = graph[1];
  const int* globalid = graph + 2 + numvert;
  int* edges = graph + 2 + 2 * numvert;
  std::vector<int> local(nvert, -1);
  for (int i = 0; i < numvert; i++) local[globalid[i]] = i;
  for (int i = 0; i < numvert + 3 * numface; i++) {
    if (edges[i] >= 0) edges[i] = local[edges[i]];
  }
}

// The first line qhull wrote to `log` (its error code and message).
std::string FirstLine(FILE* log) {
  if (!log) return "";
  std::rewind(log);
  char line[512] = {0};
  if (!std::fgets(line, sizeof(line), log)) return "";
  std::string text(line);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

// qhull's steps up to a triangulated hull whose vertices know their facets. qhull
// reports errors by longjmp back to the setjmp here, so this frame holds no C++ objects
// and is never inlined: emscripten forbids setjmp and exception handling in one function.
[[gnu::noinline]] bool TriangulatedHull(qhT* qh, char* options, coordT* points, int nvert) {
  if (setjmp(qh->errexit) != 0) return false;
  qh->NOerrexit = false;
  qh_initflags(qh, options);
  qh_init_B(qh, points, nvert, 3, False);
  qh_qhull(qh);
  qh_triangulate(qh);
  qh_vertexneighbors(qh);
  qh->NOerrexit = true;
  return true;
}

}  // namespace

HullResult ConvexHullGraph(const std::vector<double>& vert, int maxhullvert,
                           std::vector<int>* graph, std::string* message) {
  graph->clear();
  int nvert = static_cast<int>(vert.size() / 3);
  if (nvert < 4) return HullResult::kOk;

  // qhull options as MuJoCo: triangulated output; "TA" counts the vertices added after
  // the initial simplex.
  std::string options = "qhull Qt";
  if (maxhullvert > -1) options += " TA" + std::to_string(maxhullvert - 4);
  std::vector<coordT> points(vert.begin(), vert.end());

  // qhull's messages go to a scratch file, for the error text.
  FILE* log = std::tmpfile();
  FILE* errfile = log ? log : stderr;
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, errfile);
  qh_init_A(qh, stdin, stdout, errfile, 0, nullptr);
  HullResult result = HullResult::kOk;

  // The hull in mesh_graph's layout, or qhull's error line.
  if (TriangulatedHull(qh, options.data(), points.data(), nvert)) {
    int numvert = qh->num_vertices, numface = qh->num_facets;
    graph->assign(2 + 3 * numvert + 6 * numface, 0);
    (*graph)[0] = numvert;
    (*graph)[1] = numface;
    if (VertexLists(qh, nvert, numvert, numface, graph->data())) {
      FaceList(qh, numvert, numface, graph->data());
      LocalEdgeIds(nvert, graph->data());
    } else {
      graph->clear();
      result = HullResult::kBadGraph;
    }
  } else {
    result = HullResult::kQhullError;
    *message = FirstLine(log);
  }
  qh->NOerrexit = true;
  int curlong = 0, totlong = 0;
  qh_freeqhull(qh, !qh_ALL);
  qh_memfreeshort(qh, &curlong, &totlong);
  if (log) std::fclose(log);
  return result;
}

#else  // a build without qhull

HullResult ConvexHullGraph(const std::vector<double>&, int, std::vector<int>* graph,
                           std::string*) {
  graph->clear();
  return HullResult::kUnavailable;
}

#endif

}  // namespace simlab::compiler
