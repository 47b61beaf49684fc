// The mesh of a signed distance field plugin (<mesh><plugin instance=.../></mesh>): the
// field's zero level set, by marching cubes on a grid over the plugin's box, as MuJoCo's
// compiler makes it (mjCMesh::LoadSDF): about 300 cells along the box's three sides
// together, the field sampled in single precision, each vertex where an edge of the grid
// changes sign (linear in the two values), shared by the cubes around that edge, and
// vertex normals the normalized sums of the adjacent triangles' cross products.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "compiler/compiler.h"
#include "compiler/mesh_io.h"
#include "mjcf/error.h"
#include "simlab/plugin.h"

namespace simlab::compiler {

using mjcf::ThrowAt;

namespace {

// The triangles of each of the 256 sign configurations of a cube's corners (bit c set:
// corner c is inside), three edge numbers (hexadecimal digits) per triangle. Corner c is
// at (x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)); edges 0-3 run along x from
// corners 0, 2, 4, 6; edges 4-7 along y from corners 0, 1, 4, 5; edges 8-11 along z from
// corners 0, 1, 2, 3. This is the triangulation of MarchingCubeCpp (MIT licence), the
// library MuJoCo's compiler uses, so that the meshes are MuJoCo's to the vertex.
const char* const kCaseTriangles[256] = {
    "", "048", "509", "495489", "1a4", "1801a8", "1a4950", "51a5a99a8",
    "b15", "5b1804", "0b109b", "14818bb89", "a5ba45", "05b0b88ba", "40949aa9b", "8ba89b",
    "286", "062046", "950628", "295256654", "41a286", "a62a21120", "0958621a4", "61a621251295",
    "28615b", "604620b15", "b09b10628", "46162916919b", "5a45ba286", "2a625a5ba052", "286a9ba49409", "2a629a9ba",
    "927", "048792", "250275", "827874475", "1a4279", "1801a8792", "250275a41", "827871175a81",
    "b15279", "0485b1279", "7b1712210", "48242112717b", "a5ba45279", "7928ba80b05b", "ba7a407a0702", "7827b8ba8",
    "879867", "904947746", "086065567", "467475", "7867981a4", "79661a916901", "a41567506086", "a51a65675",
    "87986715b", "15b746794904", "08606bb6710b", "17b147467", "4ba45b698679", "670ba0a605b0790", "ba06707b0860a40", "67b6ba",
    "36a", "a36048", "36a095", "94895436a", "341364", "680603301", "341364950", "958836538513",
    "36a5b1", "15b48036a", "0b109b6a3", "6a3b89b18148", "b36b65564", "8368030b305b", "6b360b09b406", "6b368b89b",
    "2a328a", "4a3430032", "a28a32509", "34a394954293", "841812213", "013032", "509213281841", "529512132",
    "2a328a5b1", "b150320434a3", "38a32819b109", "9b4324294a34b14", "5b4428b24b32", "b05b30320", "3249b4b34094284", "32939b",
    "792a36", "2796a3048", "527502a36", "36a475487827", "436413927", "927301360680", "164136075027", "138758518278368",
    "36a79215b", "0486a379215b", "a362102717b1", "36ab17127142482", "2795645b6b36", "2798060360535b3", "02b64b40b36b27b", "6838b387b827",
    "37939aa98", "a04a30390379", "8a0a370a7075", "34a374754", "184178798371", "937903013", "758138378418508", "137175",
    "5b1a98a39379", "15ba34304370790", "8a7107087b17a37", "37a74a7147b1", "4539838437935b3", "9070370b305b", "08437b", "7b3",
    "73b", "0483b7", "5093b7", "4954893b7", "b7341a", "81a80173b", "1a4b73095", "3b79a895a51a",
    "173157", "715731804", "973930031", "148187789317", "3a4347745", "80aa7307a057", "a40a03309397", "3973a9a89",
    "286b73", "062046b73", "2869503b7", "b73654625295", "3b7a41286", "73b1201a2a62", "1a48629503b7", "3b762a21a291951",
    "173157862", "246204357315", "628031093973", "469319149739629", "8627457343a4", "57a20a05a62a73a", "2867393093a0a40", "2969a693a973",
    "3923b9", "3923b9480", "b50b03302", "54b482b42b23", "93b92341a", "0a801a2b923b", "41a3023b0b50", "235a858251a53b5",
    "592521123", "804123152592", "031023", "814821231", "3a4349945239", "a852353a5925805", "43a403023", "23a2a8",
    "63b6b88b9", "63b6b00b9460", "86383003b0b5", "b63b56546", "1a48b986b63b", "016b969063b61a6", "1a450b03b083863", "a616516b563b",
    "985863583531", "319469639049159", "608630310", "314346", "983453593a43863", "3a6059", "6383083403a4", "3a6",
    "6b76ab", "b6ab76048", "6b76ab095", "854895a76ab7", "1b7174476", "0680b6b761b0", "9504764171b7", "891761681b71951",
    "a15a56657", "0486576a5a15", "7696a1961910", "7618919714816a1", "476457", "068056576", "940974764", "897876",
    "72878bb8a", "b7aa0470a720", "095b8ab78728", "ab25424a2952b72", "4284121721b7", "71b721201", "0954181281b2b72", "5191291721b7",
    "872817157a18", "20a57a72a15a04a", "1078a7a17287097", "14a297", "872847457", "205257", "842472497409", "972",
    "26a2a99ab", "4809ab92a26a", "26a2a55ab025", "542ab2b526a2482", "4166921961b9", "b960161b6806926", "64b02b26b50b41b", "2681b5",
    "6a1612215259", "0489252152616a1", "a26a12102", "a16126182148", "259265645", "058568526592", "026064", "268",
    "8ab8b9", "4904a9ab9", "0b508b8ab", "ab5a54", "1841b8b98", "01b0b9", "1b4b84b08b50", "b51",
    "5a159a98a", "4a0a90a59a15", "10818a", "14a", "459498", "590", "084", "",
};

// The corner each edge starts from, and its axis (edge / 4).
constexpr int kEdgeCorner[12] = {0, 2, 4, 6, 0, 1, 4, 5, 0, 1, 2, 3};

// A number in single precision; beyond its range, an infinity (as x86 converts it).
float SingleOf(double v) {
  const double most = std::numeric_limits<float>::max();
  if (v > most) return std::numeric_limits<float>::infinity();
  if (v < -most) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(v);
}

// A mesh in grid units, single precision as MuJoCo's marching cubes computes it.
struct GridMesh {
  std::vector<float> vert, normal;
  std::vector<int> face;
};

// The field on a grid of size[0] * size[1] * size[2] points, x fastest.
struct Grid {
  std::vector<float> value;
  int size[3] = {0, 0, 0};
  size_t Index(int x, int y, int z) const {
    return (static_cast<size_t>(z) * size[1] + y) * size[0] + x;
  }
  float At(int x, int y, int z) const { return value[Index(x, y, z)]; }
};

// Vertex ids of the edges from the grid points of two z layers (z % 2), per axis.
class EdgeVertices {
 public:
  EdgeVertices(int nx, int ny) : nx_(nx), ny_(ny), id_(static_cast<size_t>(nx) * ny * 2 * 3, -1) {}
  int& operator()(int x, int y, int z, int axis) {
    return id_[((static_cast<size_t>(z % 2) * ny_ + y) * nx_ + x) * 3 + axis];
  }

 private:
  int nx_, ny_;
  std::vector<int> id_;
};

// Adds the vertex where the edge from (x, y, z) along `axis` crosses zero, if it does.
void EdgeVertex(float va, float vb, int axis, int x, int y, int z, EdgeVertices* ids, GridMesh* mesh) {
  if ((va < 0.0) == (vb < 0.0)) return;
  float v[3] = {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
  v[axis] += va / (va - vb);
  (*ids)(x, y, z, axis) = static_cast<int>(mesh->vert.size() / 3);
  mesh->vert.insert(mesh->vert.end(), v, v + 3);
  mesh->normal.insert(mesh->normal.end(), {0.0f, 0.0f, 0.0f});
}

// Adds triangle (a, b, c)'s cross product (c - b) x (a - b) to its vertices' normals.
void AccumulateNormal(GridMesh* mesh, int a, int b, int c) {
  const float* va = &mesh->vert[3 * a];
  const float* vb = &mesh->vert[3 * b];
  const float* vc = &mesh->vert[3 * c];
  float ab[3] = {va[0] - vb[0], va[1] - vb[1], va[2] - vb[2]};
  float cb[3] = {vc[0] - vb[0], vc[1] - vb[1], vc[2] - vb[2]};
  float n[3] = {cb[1] * ab[2] - cb[2] * ab[1], cb[2] * ab[0] - cb[0] * ab[2],
                cb[0] * ab[1] - cb[1] * ab[0]};
  for (int v : {a, b, c}) {
    for (int k = 0; k < 3; k++) mesh->normal[3 * v + k] += n[k];
  }
}

// One cube, its lowest corner at (x, y, z): the vertices on its edges that no earlier
// cube made (an edge is new when the cube is first along each axis the edge is not on
// and does not start at the far side of), then its triangles.
void MarchCube(const Grid& g, int x, int y, int z, EdgeVertices* ids, GridMesh* mesh) {
  float vs[8];
  int config = 0;
  for (int c = 0; c < 8; c++) {
    vs[c] = g.At(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1));
    config |= (vs[c] < 0) << c;
  }
  if (config == 0 || config == 255) return;
  const int at[3] = {x, y, z};
  int edge_vertex[12];
  for (int e = 0; e < 12; e++) {
    int axis = e / 4, c = kEdgeCorner[e];
    int p[3] = {x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)};
    bool fresh = true;
    for (int b = 0; b < 3; b++) {
      if (b != axis && p[b] == at[b] && at[b] != 0) fresh = false;
    }
    if (fresh) EdgeVertex(vs[c], vs[c | 1 << axis], axis, p[0], p[1], p[2], ids, mesh);
    edge_vertex[e] = (*ids)(p[0], p[1], p[2], axis);
  }
  size_t first = mesh->face.size();
  for (const char* t = kCaseTriangles[config]; *t; t++) {
    int e = *t <= '9' ? *t - '0' : *t - 'a' + 10;
    mesh->face.push_back(edge_vertex[e]);
  }
  for (size_t f = first; f < mesh->face.size(); f += 3) {
    AccumulateNormal(mesh, mesh->face[f], mesh->face[f + 1], mesh->face[f + 2]);
  }
}

GridMesh MarchingCubes(const Grid& g) {
  GridMesh mesh;
  EdgeVertices ids(g.size[0], g.size[1]);
  for (int z = 0; z + 1 < g.size[2]; z++) {
    for (int y = 0; y + 1 < g.size[1]; y++) {
      for (int x = 0; x + 1 < g.size[0]; x++) MarchCube(g, x, y, z, &ids, &mesh);
    }
  }
  for (size_t i = 0; i < mesh.normal.size(); i += 3) {
    float* n = &mesh.normal[i];
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) n[k] = n[k] / len;
  }
  return mesh;
}

}  // namespace

MeshData LevelSetMesh(const Plugin& plugin, const std::vector<double>& attributes) {
  double box[6] = {0, 0, 0, 0, 0, 0};
  plugin.sdf_aabb(box, attributes.data());
  // Cells along each side in proportion to it, about 300 in all.
  const double n = 300;
  double total = box[3] + box[4] + box[5];
  double cells[3];
  for (int k = 0; k < 3; k++) cells[k] = std::floor(n / total * box[3 + k]);
  if (!(cells[0] >= 1 && cells[1] >= 1 && cells[2] >= 1 && cells[0] + cells[1] + cells[2] <= n)) {
    throw Error("plugin '" + plugin.name + "': its box is too thin for a mesh (half sizes " +
                std::to_string(box[3]) + " " + std::to_string(box[4]) + " " + std::to_string(box[5]) + ")");
  }
  Grid g;
  for (int k = 0; k < 3; k++) g.size[k] = static_cast<int>(cells[k]) + 1;
  const int* size = g.size;
  // The grid point of index i along axis k.
  auto coordinate = [&](int k, double i) {
    return box[k] - box[3 + k] + 2 * box[3 + k] * i / (size[k] - 1);
  };
  g.value.resize(static_cast<size_t>(size[0]) * size[1] * size[2]);
  for (int i = 0; i < size[0]; i++) {
    for (int j = 0; j < size[1]; j++) {
      for (int k = 0; k < size[2]; k++) {
        double p[3] = {coordinate(0, i), coordinate(1, j), coordinate(2, k)};
        g.value[g.Index(i, j, k)] = SingleOf(plugin.sdf_distance(p, attributes.data()));
      }
    }
  }
  GridMesh grid = MarchingCubes(g);
  // Grid units to the box's, rounded to single precision.
  MeshData data;
  data.vert.resize(grid.vert.size());
  for (size_t v = 0; v < grid.vert.size(); v++) {
    int k = static_cast<int>(v % 3);
    data.vert[v] = SingleOf(2 * box[3 + k] * grid.vert[v] / (size[k] - 1) + box[k] - box[3 + k]);
  }
  data.normal = std::move(grid.normal);
  data.face = std::move(grid.face);
  return data;
}

}  // namespace simlab::compiler
