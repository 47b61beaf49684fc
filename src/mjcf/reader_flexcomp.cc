// MJCF reader: a <flexcomp> expanded as MuJoCo's parser expands it (mjCFlexcomp::Make):
// the shape's points, pinned points and the flex's rigidity, the bodies with slider
// joints that carry the points that move (or the nodes that interpolate them: one cell's,
// or with MuJoCo 3.12's cells a lattice of them), the flex itself, and the edge or vertex
// equality it asks for, or the strain equalities of its elements.
#include <algorithm>
#include <string>

#include "compiler/flex_cells.h"
#include "mjcf/flexcomp.h"
#include "mjcf/limits.h"
#include "mjcf/reader.h"
#include "compiler/orientation.h"
#include "math/math.h"
#include "simlab/model.h"

namespace simlab::mjcf {

namespace {

bool IsDirect(int type) { return type == kFcompDirect || type == kFcompMesh || type == kFcompGmsh; }
bool IsInterpolated(int dof) { return dof == kFcompDofTrilinear || dof == kFcompDofQuadratic; }
int InterpolationOrder(int dof) { return dof == kFcompDofTrilinear ? 1 : dof == kFcompDofQuadratic ? 2 : 0; }

// The lattice of an interpolated flexcomp's nodes (one cell unless cellcount says).
FlexLattice NodeLattice(const FlexcompSpec& fc) {
  FlexLattice g;
  g.order = InterpolationOrder(fc.dof);
  if (fc.cellcount[0] >= 0) {
    for (int k = 0; k < 3; k++) g.cells[k] = fc.cellcount[k];
  }
  g.shell = fc.flex.elastic2d != kElastic2DNone;
  return g;
}

// cellcount: positive numbers of cells for an interpolated flexcomp, within the budget
// of its node bodies and its element stiffness.
void CheckCellcount(const XmlElement& e, const FlexcompSpec& fc) {
  if (!e.Has("cellcount")) return;
  if (!IsInterpolated(fc.dof)) e.Fail("cellcount requires dof=\"trilinear\" or \"quadratic\"");
  for (int c : fc.cellcount) {
    if (c == 0) e.Fail("cellcount cannot be 0 in any dimension when interpolation order > 0");
    if (c < 0) e.Fail("cellcount must be positive");
  }
  FlexLattice g = NodeLattice(fc);
  uint64_t nodes = 1, cells = 1;
  for (int c : fc.cellcount) {
    nodes = MulBytes(nodes, static_cast<uint64_t>(c) * g.order + 1);
    cells = MulBytes(cells, static_cast<uint64_t>(c));
  }
  uint64_t bytes = MulBytes(nodes, sizeof(BodySpec) + 3 * sizeof(JointSpec));
  uint64_t ndof = 3 * static_cast<uint64_t>(g.NodesPerCell());
  uint64_t stiffness = MulBytes(MulBytes(cells, ndof * ndof), sizeof(double));
  std::string request = AttrText("cellcount", e.node().attribute("cellcount").value());
  if (bytes > kMaxArrayBytes) e.Fail(OverBudget(request, bytes, "flexcomp node bodies", kMaxArrayBytes));
  if (stiffness > kMaxArrayBytes) {
    e.Fail(OverBudget(request, stiffness, "flex cell stiffness", kMaxArrayBytes));
  }
}

// The checks MuJoCo makes before building: name, dim, counts, spacing, scale, mass.
void CheckFlexcomp(const XmlElement& e, const FlexcompSpec& fc, bool named_parent) {
  const FlexSpec& flex = fc.flex;
  if (!named_parent) e.Fail("Parent body must have name");
  if (flex.dim < 1 || flex.dim > 3) e.Fail("Invalid dim, must be between 1 and 3");
  for (int i = 0; i < 3; i++) {
    if (fc.count[i] < 1 || (fc.dof == kFcompDofRadial && fc.count[i] < 2 && flex.dim == 3)) {
      e.Fail("Count too small");
    }
  }
  // (MuJoCo would loop forever on a box side of one point; simlab refuses it.)
  bool box = fc.type == kFcompBox || fc.type == kFcompCylinder || fc.type == kFcompEllipsoid;
  if (box && std::min({fc.count[0], fc.count[1], fc.count[2]}) < 2) {
    e.Fail("Count too small: a box, cylinder or ellipsoid needs 2 points on each side");
  }
  double minspace = 2 * flex.radius + flex.margin;
  if (!IsDirect(fc.type) && std::min({fc.spacing[0], fc.spacing[1], fc.spacing[2]}) < minspace) {
    e.Fail("Spacing must be larger than geometry size");
  }
  if (std::min({fc.scale[0], fc.scale[1], fc.scale[2]}) < kMinVal) {
    e.Fail("Scale must be larger than mjMINVAL");
  }
  if (fc.mass < kMinVal || fc.inertiabox < kMinVal) {
    e.Fail("Mass and inertiabox must be larger than mjMINVAL");
  }
  uint64_t npoint = MulBytes(MulBytes(fc.count[0], fc.count[1]), fc.count[2]);
  uint64_t bytes = MulBytes(npoint, sizeof(BodySpec) + 3 * sizeof(JointSpec));
  if (!IsDirect(fc.type) && bytes > kMaxArrayBytes) {
    e.Fail(OverBudget(AttrText("count", e.node().attribute("count").value()), bytes,
                      "flexcomp bodies", kMaxArrayBytes));
  }
  CheckCellcount(e, fc);
}

// The shape's points and elements, by type (a file's loader makes MuJoCo's checks).
void MakeShape(const XmlElement& e, FlexcompSpec* fc, const AssetFiles* assets) {
  std::string error;
  if (fc->type == kFcompMesh || fc->type == kFcompGmsh) {
    error = fc->type == kFcompMesh
                ? LoadFlexcompMesh(fc->src, fc->file, assets, fc->flex.dim, fc->origin, &fc->shape)
                : LoadFlexcompGmsh(fc->file, assets, &fc->shape);
    if (fc->type == kFcompGmsh) fc->flex.dim = fc->shape.dim;
  } else if (fc->type != kFcompDirect) {
    FlexcompShapeInput in;
    in.type = fc->type;
    in.dim = fc->flex.dim;
    in.count = fc->count;
    in.spacing = fc->spacing;
    in.has_material = !fc->flex.material.empty();
    in.texcoord_given = !fc->shape.texcoord.empty();
    error = MakeFlexcompShape(in, &fc->shape);
    fc->flex.dim = fc->shape.dim;
  }
  if (!error.empty()) e.Fail(error);
}

// The points and elements must fit together: counts and point ids.
void CheckShape(const XmlElement& e, const FlexcompSpec& fc) {
  const FlexcompPoints& s = fc.shape;
  int dim = fc.flex.dim;
  if (fc.pinrange.size() % 2) e.Fail("Pin range number must be multiple of 2");
  if (fc.pingrid.size() % dim) e.Fail("Pin grid number must be multiple of dim");
  if (fc.pingridrange.size() % (2 * dim)) e.Fail("Pin grid range number of must be multiple of 2*dim");
  bool any_grid_pin = !fc.pingrid.empty() || !fc.pingridrange.empty();
  if (fc.type != kFcompGrid && any_grid_pin && !IsInterpolated(fc.dof)) {
    e.Fail("Pin grid(range) can only be used with grid or interpolated");
  }
  if (dim == 1 && any_grid_pin) e.Fail("Pin grid(range) cannot be used with dim=1");
  if (s.point.empty() || s.element.empty()) e.Fail("Point and element required");
  if (s.point.size() % 3) e.Fail("Point size must be a multiple of 3");
  if (s.element.size() % (dim + 1)) e.Fail("Element size must be a multiple of dim+1");
  int npoint = static_cast<int>(s.point.size() / 3);
  for (size_t i = 0; i < s.element.size(); i++) {
    if (s.element[i] < 0 || s.element[i] >= npoint) {
      e.Fail("element " + std::to_string(i) + " has point id " + std::to_string(s.element[i]) +
             ", number of points is " + std::to_string(npoint));
    }
  }
}

// Scale (direct types), then the flexcomp's pose, applied to every point.
void PlacePoints(const FlexcompSpec& fc, std::vector<double>* point) {
  bool scale = fc.scale[0] != 1 || fc.scale[1] != 1 || fc.scale[2] != 1;
  for (size_t i = 0; i + 2 < point->size(); i += 3) {
    double* p = point->data() + i;
    if (IsDirect(fc.type) && scale) {
      for (int k = 0; k < 3; k++) p[k] *= fc.scale[k];
    }
    double rotated[3];
    math::RotVecQuat(rotated, p, fc.quat.data());
    for (int k = 0; k < 3; k++) p[k] = rotated[k] + fc.pos[k];
  }
}

// Marks the pinned points (<pin> id, range, grid, gridrange; the centre of a radial
// flexcomp), then decides rigid (all pinned) or centered (none pinned).
void PinPoints(const XmlElement& e, FlexcompSpec* fc, int npoint, int nnode, bool* centered) {
  fc->pinned.assign(std::max(npoint, nnode), fc->rigid);
  *centered = false;
  if (fc->rigid) return;
  int dim = fc->flex.dim;
  auto& pinned = fc->pinned;
  for (int id : fc->pinid) {
    if (id < 0 || id >= npoint) e.Fail("pinid out of range");
    pinned[id] = true;
  }
  for (size_t i = 0; i < fc->pinrange.size(); i += 2) {
    int a = fc->pinrange[i], b = fc->pinrange[i + 1];
    if (a < 0 || a >= npoint || b < 0 || b >= npoint) e.Fail("pinrange out of range");
    for (int k = a; k <= b; k++) pinned[k] = true;
  }
  // Grid coordinates: the grid's counts, or the node lattice of an interpolated shape.
  // Either pins the point at its place in a grid of `count` points, which for a shape
  // that is not a grid can lie past its points and nodes (MuJoCo writes past its array
  // there; simlab refuses the pin).
  std::array<int, 3> limit = fc->count;
  if (fc->type != kFcompGrid && IsInterpolated(fc->dof)) {
    limit.fill(fc->dof == kFcompDofTrilinear ? 2 : 3);
  }
  auto pin_grid_point = [&](const int* at, const char* what) {
    // (the place grows along the axes; past the array it stops growing, in 64 bits)
    int64_t id = 0;
    for (int k = 0; k < dim && id < static_cast<int64_t>(pinned.size()); k++) {
      id = id * fc->count[k] + at[k];
    }
    if (id >= static_cast<int64_t>(pinned.size())) {
      std::string place = std::to_string(at[0]);
      for (int k = 1; k < dim; k++) place.append(" ").append(std::to_string(at[k]));
      e.Fail(std::string(what) + " out of range: grid point (" + place + ") of count lies past " +
             "the flexcomp's " + std::to_string(pinned.size()) + " points and nodes");
    }
    pinned[id] = true;
  };
  for (size_t i = 0; i < fc->pingrid.size(); i += dim) {
    for (int k = 0; k < dim; k++) {
      if (fc->pingrid[i + k] < 0 || fc->pingrid[i + k] >= limit[k]) e.Fail("pingrid out of range");
    }
    pin_grid_point(fc->pingrid.data() + i, "pingrid");
  }
  for (size_t i = 0; i < fc->pingridrange.size(); i += 2 * dim) {
    const int* r = fc->pingridrange.data() + i;
    for (int k = 0; k < 2 * dim; k++) {
      if (r[k] < 0 || r[k] >= fc->count[k % dim]) e.Fail("pingridrange out of range");
    }
    for (int ix = r[0]; ix <= r[dim]; ix++) {
      for (int iy = r[1]; iy <= r[dim + 1]; iy++) {
        for (int iz = dim == 2 ? 0 : r[2]; iz <= (dim == 2 ? 0 : r[5]); iz++) {
          int at[3] = {ix, iy, iz};
          pin_grid_point(at, "pingridrange");
        }
      }
    }
  }
  if (fc->dof == kFcompDofRadial) pinned[0] = true;

  // All pinned: the flex moves with the parent. None: vertices at the bodies' origins.
  int npinned = static_cast<int>(std::count(pinned.begin(), pinned.begin() + npoint, true));
  if (npinned == npoint) fc->rigid = true;
  if (npinned == 0) *centered = true;
}

// Drops the points no element uses (direct, mesh and GMSH shapes), renumbering the rest.
void DropUnusedPoints(FlexcompSpec* fc, int nnode) {
  FlexcompPoints& s = fc->shape;
  int npoint = static_cast<int>(s.point.size() / 3);
  std::vector<bool> used(npoint, false);
  for (int id : s.element) used[id] = true;
  std::vector<int> newid(npoint, -1);
  int n = 0;
  for (int i = 0; i < npoint; i++) {
    if (!used[i]) continue;
    newid[i] = n;
    for (int k = 0; k < 3; k++) s.point[3 * n + k] = s.point[3 * i + k];
    if (!s.texcoord.empty()) {
      for (int k = 0; k < 2; k++) s.texcoord[2 * n + k] = s.texcoord[2 * i + k];
    }
    fc->pinned[n] = fc->pinned[i];
    n++;
  }
  if (n == npoint) return;
  for (int& id : s.element) id = newid[id];
  s.point.resize(3 * n);
  if (!s.texcoord.empty()) s.texcoord.resize(2 * n);
  fc->pinned.resize(std::max(n, nnode));
}

// A body for a point or node: at `pos` in the parent, with the flexcomp's mass share
// and box inertia, and sliders by `dof`: three orthogonal ones (full), one radial
// (radial) or two along the parent's x and y (2d).
BodySpec* AddPointBody(BodySpec* parent, const FlexcompSpec& fc, const DefaultClass* def,
                       const std::string& name, const double pos[3], double mass, int dof) {
  auto body = std::make_unique<BodySpec>();
  body->src = fc.src;
  body->src.tag = "body";
  body->src.name = name;
  for (int k = 0; k < 3; k++) body->pos[k] = pos[k];
  body->explicit_inertial = true;
  body->inertial_src = fc.src;
  body->ipos = {0, 0, 0};
  body->mass = mass;
  double inertia = mass * (2.0 * fc.inertiabox * fc.inertiabox) / 3.0;
  body->inertia = {inertia, inertia, inertia};
  bool radial = dof == kFcompDofRadial;
  int nslider = radial ? 1 : dof == kFcompDof2D ? 2 : 3;
  for (int j = 0; j < nslider; j++) {
    JointSpec joint = def->joint;
    joint.src = fc.src;
    joint.src.tag = "joint";
    joint.src.name.clear();
    joint.type = kJointSlide;
    joint.pos = {0, 0, 0};
    joint.axis = {0, 0, 0};
    if (radial) {
      joint.axis = body->pos;
      compiler::NormalizeVec(joint.axis.data(), 3);
    } else {
      joint.axis[j] = 1;
    }
    body->joints.push_back(std::move(joint));
  }
  BodySpec* raw = body.get();
  parent->bodies.push_back(std::move(body));
  return raw;
}

// A collision sphere of the flex's radius on a point body (contact vertcollide).
void AddVertexSphere(BodySpec* body, const FlexcompSpec& fc, const DefaultClass* def, int group) {
  GeomSpec geom = def->geom;
  geom.src = fc.src;
  geom.src.tag = "geom";
  geom.src.name.clear();
  geom.type = kGeomSphere;
  geom.size[0] = fc.flex.radius;
  if (group >= 0) geom.group = group;
  body->geoms.push_back(std::move(geom));
}

// The bodies of the points that move: one per unpinned point, named NAME_i, unless
// the flex is interpolated (then every vertex is in the parent).
void AddVertexBodies(FlexcompSpec* fc, BodySpec* body, const DefaultClass* def, bool centered,
                     const std::string& parent) {
  FlexSpec& flex = fc->flex;
  int npoint = static_cast<int>(fc->shape.point.size() / 3);
  double mass = fc->mass / npoint;
  for (int i = 0; i < npoint; i++) {
    double* p = fc->shape.point.data() + 3 * i;
    if (fc->pinned[i] || IsInterpolated(fc->dof)) {
      flex.vertbody.push_back(parent);
      continue;
    }
    std::string name = fc->name + "_" + std::to_string(i);
    BodySpec* pb = AddPointBody(body, *fc, def, name, p, mass, fc->dof);
    if (flex.vertcollide) AddVertexSphere(pb, *fc, def, 4);
    flex.vertbody.push_back(name);
    if (!centered) p[0] = p[1] = p[2] = 0;
  }
}

// The node lattice of an interpolated flexcomp over the points' bounding box: bodies
// NAME_i_j_k (pinned nodes stay in the parent), order 1 (2^3 nodes) or 2 (3^3).
void AddNodeBodies(FlexcompSpec* fc, BodySpec* body, const DefaultClass* def,
                   const double minmax[6], const std::string& parent) {
  FlexSpec& flex = fc->flex;
  int order = fc->dof == kFcompDofTrilinear ? 1 : 2;
  flex.order = order;
  std::vector<double> node(3 * (order + 1) * (order + 1) * (order + 1), 0);
  const double quadratic_mass[3] = {1. / 6., 2. / 3., 1. / 6.};
  double step = 1.0 / order;
  int idx = 0;
  for (int i = 0; i <= order; i++) {
    for (int j = 0; j <= order; j++) {
      for (int k = 0; k <= order; k++, idx++) {
        double pos[3] = {minmax[0] + i * step * (minmax[3] - minmax[0]),
                         minmax[1] + j * step * (minmax[4] - minmax[1]),
                         minmax[2] + k * step * (minmax[5] - minmax[2])};
        if (fc->pinned[idx]) {
          for (int c = 0; c < 3; c++) node[3 * idx + c] = pos[c];
          flex.nodebody.push_back(parent);
          continue;
        }
        double mass = order == 1 ? fc->mass / 8
                                 : fc->mass * quadratic_mass[i] * quadratic_mass[j] * quadratic_mass[k];
        std::string name = fc->name + "_" + std::to_string(i) + "_" + std::to_string(j) + "_" +
                           std::to_string(k);
        BodySpec* pb = AddPointBody(body, *fc, def, name, pos, mass, kFcompDofFull);
        if (flex.vertcollide) {
          // (MuJoCo adds the node's sphere before its joints, in the default group.)
          AddVertexSphere(pb, *fc, def, -1);
        }
        flex.nodebody.push_back(name);
      }
    }
  }
  flex.node = std::move(node);
}

// The equalities a flexcomp asks for (<edge equality>): one on its edges (1) or its
// vertices (2); for strain (3) one per element of its node lattice, in MuJoCo's order:
// a shell's faces (data[0] the face, data[1-2] -1), else the cells that hold elements
// (data[0-2] the cell's indices along x, y, z).
void AddFlexcompEqualities(const FlexcompSpec& fc, const FlexSpec& flex,
                           std::vector<EqualitySpec>* out) {
  EqualitySpec eq = fc.eq;  // MuJoCo's defaults, with the edge's solref and solimp
  eq.src = fc.src;
  eq.src.tag = "equality";
  eq.src.name.clear();
  eq.active = true;
  eq.name1 = fc.name;
  if (fc.equality != 3) {
    eq.type = fc.equality == 1 ? kEqFlex : kEqFlexVert;
    out->push_back(std::move(eq));
    return;
  }
  eq.type = kEqFlexStrain;
  const std::array<int, 3>& c = flex.cellcount;
  if (flex.elastic2d != kElastic2DNone) {
    int nface = 2 * (c[1] * c[2] + c[0] * c[2] + c[0] * c[1]);
    for (int face = 0; face < nface; face++) {
      eq.data[0] = face;
      eq.data[1] = eq.data[2] = -1;
      out->push_back(eq);
    }
    return;
  }
  for (int i = 0; i < c[0]; i++) {
    for (int j = 0; j < c[1]; j++) {
      for (int k = 0; k < c[2]; k++) {
        size_t cell = (static_cast<size_t>(i) * c[1] + j) * c[2] + k;
        if (!flex.cell_empty.empty() && flex.cell_empty[cell]) continue;
        eq.data[0] = i;
        eq.data[1] = j;
        eq.data[2] = k;
        out->push_back(eq);
      }
    }
  }
}

// The nodes of a flexcomp made of cells that nothing moves: in MuJoCo 3.12, those in
// empty cells only (a volume), or off the lattice's boundary (a shell, whose interior
// follows the boundary). pinned is indexed by node.
void PinCellNodes(const FlexLattice& g, FlexcompSpec* fc, const double minmax[6]) {
  FlexSpec& flex = fc->flex;
  int nx = g.Nodes(0), ny = g.Nodes(1), nz = g.Nodes(2);
  if (g.shell) {
    for (int i = 0; i < nx; i++) {
      for (int j = 0; j < ny; j++) {
        for (int k = 0; k < nz; k++) {
          bool boundary = i == 0 || i == nx - 1 || j == 0 || j == ny - 1 || k == 0 || k == nz - 1;
          if (!boundary) fc->pinned[g.Node(i, j, k)] = true;
        }
      }
    }
    return;
  }
  flex.cell_empty = compiler::EmptyFlexCells(g.cells, fc->shape.point, flex.elem, flex.dim, minmax);
  auto cell_range = [&](int node, int axis, int* lo, int* hi) {
    *lo = std::max(0, node == 0 ? 0 : (node - 1) / g.order);
    *hi = std::min(g.cells[axis] - 1, node / g.order);
  };
  for (int i = 0; i < nx; i++) {
    for (int j = 0; j < ny; j++) {
      for (int k = 0; k < nz; k++) {
        // Every cell holding the node is empty.
        int lo[3], hi[3];
        cell_range(i, 0, &lo[0], &hi[0]);
        cell_range(j, 1, &lo[1], &hi[1]);
        cell_range(k, 2, &lo[2], &hi[2]);
        bool all_empty = true;
        for (int ci = lo[0]; ci <= hi[0] && all_empty; ci++) {
          for (int cj = lo[1]; cj <= hi[1] && all_empty; cj++) {
            for (int ck = lo[2]; ck <= hi[2] && all_empty; ck++) {
              all_empty = flex.cell_empty[(ci * g.cells[1] + cj) * g.cells[2] + ck];
            }
          }
        }
        if (all_empty) fc->pinned[g.Node(i, j, k)] = true;
      }
    }
  }
}

// The node lattice of a flexcomp made of cells over the points' bounding box: bodies
// NAME_i_j_k with three sliders for the nodes that move, their masses (one per node
// trilinear, Simpson's weights quadratic, a node shared by two cells along an axis
// counting twice) scaled to the flexcomp's mass (MuJoCo 3.12's Make).
void AddCellNodeBodies(FlexcompSpec* fc, BodySpec* body, const DefaultClass* def,
                       const double minmax[6], const std::string& parent) {
  FlexSpec& flex = fc->flex;
  FlexLattice g = NodeLattice(*fc);
  flex.order = g.order;
  flex.cellcount = g.cells;
  PinCellNodes(g, fc, minmax);
  int nx = g.Nodes(0), ny = g.Nodes(1), nz = g.Nodes(2);
  std::vector<double> node(3 * static_cast<size_t>(nx) * ny * nz, 0);
  std::vector<std::pair<BodySpec*, double>> bodies;  // and their unscaled masses
  const double simpson[2] = {1. / 6., 2. / 3.};
  int idx = 0;
  for (int i = 0; i < nx; i++) {
    for (int j = 0; j < ny; j++) {
      for (int k = 0; k < nz; k++, idx++) {
        int at[3] = {i, j, k};
        double pos[3];
        for (int a = 0; a < 3; a++) {
          double s = static_cast<double>(at[a]) / (g.cells[a] * g.order);
          pos[a] = minmax[a] + s * (minmax[a + 3] - minmax[a]);
        }
        if (fc->pinned[idx]) {
          for (int a = 0; a < 3; a++) node[3 * idx + a] = pos[a];
          flex.nodebody.push_back(parent);
          continue;
        }
        double mass = 1.0;
        if (g.order == 2) {
          for (int a = 0; a < 3; a++) mass *= simpson[at[a] % 2];
          for (int a = 0; a < 3; a++) {
            bool shared = at[a] > 0 && at[a] < g.Nodes(a) - 1 && at[a] % 2 == 0;
            mass *= shared ? 2 : 1;
          }
        }
        std::string name = fc->name + "_" + std::to_string(i) + "_" + std::to_string(j) + "_" +
                           std::to_string(k);
        BodySpec* pb = AddPointBody(body, *fc, def, name, pos, mass, kFcompDofFull);
        if (flex.vertcollide) AddVertexSphere(pb, *fc, def, -1);
        bodies.push_back({pb, mass});
        flex.nodebody.push_back(name);
      }
    }
  }

  // The masses (and inertias) scaled to the flexcomp's.
  double total = 0;
  for (const auto& b : bodies) total += b.second;
  if (total > 0) {
    double scale = fc->mass / total;
    for (auto& b : bodies) {
      b.first->mass *= scale;
      for (double& inertia : b.first->inertia) inertia *= scale;
    }
  }
  flex.node = std::move(node);
}

}  // namespace

void Reader::MakeFlexcomp(const XmlElement& e, FlexcompSpec* fc, BodySpec* body,
                          const DefaultClass* def) {
  CheckFlexcomp(e, *fc, !body->src.name.empty() || IsWorld(body));
  MakeShape(e, fc, spec_->assets.get());
  FlexSpec& flex = fc->flex;
  if (fc->type == kFcompBox || fc->type == kFcompCylinder ||
      (fc->type == kFcompGrid && flex.dim == 3)) {
    flex.flatskin = true;
  }
  CheckShape(e, *fc);
  PlacePoints(*fc, &fc->shape.point);

  // The points' bounding box (for the node lattice).
  int npoint = static_cast<int>(fc->shape.point.size() / 3);
  double minmax[6] = {1e10, 1e10, 1e10, -1e10, -1e10, -1e10};
  for (int i = 0; i < npoint; i++) {
    for (int k = 0; k < 3; k++) {
      minmax[k] = std::min(minmax[k], fc->shape.point[3 * i + k]);
      minmax[k + 3] = std::max(minmax[k + 3], fc->shape.point[3 * i + k]);
    }
  }
  // (a model that follows MuJoCo 3.12 lays out every interpolated flexcomp's nodes as 3.12
  // does, masses shared by the nodes that move; a flexcomp with cells, a shell or strain
  // equality always makes the model follow 3.12: Reader::FindNewerConstruct)
  bool cell_nodes = IsInterpolated(fc->dof) && !spec_->newer_construct.tag.empty();
  int nnode = 0;
  if (IsInterpolated(fc->dof)) {
    FlexLattice g = NodeLattice(*fc);
    nnode = cell_nodes ? g.Nodes(0) * g.Nodes(1) * g.Nodes(2) : g.NodesPerCell();
  }
  bool centered = false;
  PinPoints(e, fc, npoint, nnode, &centered);
  if (IsDirect(fc->type)) DropUnusedPoints(fc, nnode);

  // The flex: the flexcomp's settings, its elements and texture coordinates.
  flex.src = fc->src;
  flex.src.tag = "flex";
  flex.src.name = fc->name;
  // (the flexcomp is dropped once expanded: its shape moves into the flex)
  flex.elem = std::move(fc->shape.element);
  flex.texcoord = std::move(fc->shape.texcoord);
  flex.elemtexcoord = std::move(fc->shape.elemtexcoord);
  std::string parent = IsWorld(body) ? "world" : body->src.name;
  if (fc->rigid) {
    flex.vert = std::move(fc->shape.point);
    flex.vertbody = {parent};
    spec_->flexes.push_back(std::move(flex));
    return;
  }
  AddVertexBodies(fc, body, def, centered, parent);
  if (cell_nodes) {
    AddCellNodeBodies(fc, body, def, minmax, parent);
  } else if (IsInterpolated(fc->dof)) {
    AddNodeBodies(fc, body, def, minmax, parent);
  }
  if (!centered || IsInterpolated(fc->dof)) flex.vert = std::move(fc->shape.point);
  spec_->flexes.push_back(std::move(flex));

  // The equality that keeps the edges (or the vertices' metric) at their lengths, or
  // the strain equalities of the flex's elements.
  if (fc->equality) AddFlexcompEqualities(*fc, spec_->flexes.back(), &spec_->equalities);
}

}  // namespace simlab::mjcf
