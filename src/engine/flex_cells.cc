// The lattice of interpolated flexes made of cells (see flex_cells.h), in MuJoCo 3.12's
// order of operations.
#include "engine/flex_cells.h"

#include <algorithm>
#include <cmath>

#include "engine/flex_elasticity.h"
#include "engine/sensor.h"
#include "math/math.h"

namespace simlab {

namespace {

// The sides of a shell's lattice: normal axis and count along the fast in-plane axis.
constexpr int kSideNormal[6] = {0, 0, 1, 1, 2, 2};

// The face elements on each side, in side order.
void SideSizes(const FlexLattice& g, int sizes[6]) {
  const int* c = g.cells.data();
  int per_axis[3] = {c[1] * c[2], c[0] * c[2], c[0] * c[1]};
  for (int s = 0; s < 6; s++) sizes[s] = per_axis[s / 2];
}

}  // namespace

FlexLattice FlexLatticeOf(const Model& m, int f) {
  FlexLattice g;
  int interp = m.flex_interp[f];
  g.order = interp < 0 ? -interp : interp;
  g.shell = interp < 0;
  for (int k = 0; k < 3; k++) g.cells[k] = m.flex_cellnum[3 * f + k];
  return g;
}

bool FlexHasCells(const Model& m, int f) {
  int interp = m.flex_interp[f];
  if (interp == 0) return false;
  const int* c = &m.flex_cellnum[3 * f];
  return interp < 0 || c[0] * c[1] * c[2] > 1 || m.flex_edgeequality[f] == kFlexEdgeStrain;
}

void FlexCellNodes(const FlexLattice& g, int ci, int cj, int ck, int* ids) {
  int n = 0;
  for (int li = 0; li <= g.order; li++) {
    for (int lj = 0; lj <= g.order; lj++) {
      for (int lk = 0; lk <= g.order; lk++) {
        ids[n++] = g.Node(ci * g.order + li, cj * g.order + lj, ck * g.order + lk);
      }
    }
  }
}

int FlexFaceNodes(const FlexLattice& g, int fe, int* ids) {
  // The side holding fe, and fe's place on it.
  int sizes[6];
  SideSizes(g, sizes);
  int side = 0, within = fe, first = 0;
  for (int s = 0; s < 6; s++) {
    if (fe < first + sizes[s]) {
      side = s;
      within = fe - first;
      break;
    }
    first += sizes[s];
  }

  // Its nodes: the side's lattice plane, in-plane axes a0 (slow) and a1 (fast).
  int normal = kSideNormal[side];
  int a0 = (normal + 1) % 3, a1 = (normal + 2) % 3;
  int fixed = side % 2 ? g.cells[normal] * g.order : 0;
  int q0 = within / g.cells[a1], q1 = within % g.cells[a1];
  int n = 0;
  for (int l0 = 0; l0 <= g.order; l0++) {
    for (int l1 = 0; l1 <= g.order; l1++) {
      int at[3];
      at[normal] = fixed;
      at[a0] = q0 * g.order + l0;
      at[a1] = q1 * g.order + l1;
      ids[n++] = g.Node(at[0], at[1], at[2]);
    }
  }
  return normal;
}

int FlexElementNodes(const FlexLattice& g, int fe, int* ids) {
  if (g.shell) return FlexFaceNodes(g, fe, ids);
  int cy = g.cells[1], cz = g.cells[2];
  FlexCellNodes(g, fe / (cy * cz), (fe / cz) % cy, fe % cz, ids);
  return -1;
}

void FlexCellLookup(const double coord[3], const int cells[3], int order, double local[3],
                    int* ids) {
  int cell[3];
  for (int k = 0; k < 3; k++) {
    cell[k] = static_cast<int>(std::floor(coord[k] * cells[k]));
    cell[k] = std::max(std::min(cell[k], cells[k] - 1), 0);
    local[k] = std::min(std::max(coord[k] * cells[k] - cell[k], 0.0), 1.0);
  }
  if (!ids) return;
  FlexLattice g;
  g.cells = {cells[0], cells[1], cells[2]};
  g.order = order;
  FlexCellNodes(g, cell[0], cell[1], cell[2], ids);
}

void FlexCellWeights(const double local[3], int order, double* weight) {
  double shape[3][3];
  for (int axis = 0; axis < 3; axis++) {
    for (int i = 0; i <= order; i++) shape[axis][i] = FlexShape(local[axis], i, order);
  }
  int n = 0;
  for (int i0 = 0; i0 <= order; i0++) {
    for (int i1 = 0; i1 <= order; i1++) {
      double w01 = shape[0][i0] * shape[1][i1];
      for (int i2 = 0; i2 <= order; i2++) weight[n++] = w01 * shape[2][i2];
    }
  }
}

void FlexShellInterior(const FlexLattice& g, double* xpos) {
  int nx = g.Nodes(0), ny = g.Nodes(1), nz = g.Nodes(2);
  if (nx < 3 || ny < 3 || nz < 3) return;
  auto at = [&](int i, int j, int k) { return xpos + 3 * g.Node(i, j, k); };
  for (int i = 1; i < nx - 1; i++) {
    for (int j = 1; j < ny - 1; j++) {
      for (int k = 1; k < nz - 1; k++) {
        double s = static_cast<double>(i) / (nx - 1);
        double t = static_cast<double>(j) / (ny - 1);
        double u = static_cast<double>(k) / (nz - 1);
        double r[3] = {0, 0, 0};
        // Each pair of opposite faces, interpolated across.
        for (int d = 0; d < 3; d++) r[d] += (1 - s) * at(0, j, k)[d] + s * at(nx - 1, j, k)[d];
        for (int d = 0; d < 3; d++) r[d] += (1 - t) * at(i, 0, k)[d] + t * at(i, ny - 1, k)[d];
        for (int d = 0; d < 3; d++) r[d] += (1 - u) * at(i, j, 0)[d] + u * at(i, j, nz - 1)[d];
        // The twelve edges, counted twice by the faces, taken off.
        for (int d = 0; d < 3; d++) {
          r[d] -= (1 - t) * (1 - u) * at(i, 0, 0)[d];
          r[d] -= (1 - t) * u * at(i, 0, nz - 1)[d];
          r[d] -= t * (1 - u) * at(i, ny - 1, 0)[d];
          r[d] -= t * u * at(i, ny - 1, nz - 1)[d];
        }
        for (int d = 0; d < 3; d++) {
          r[d] -= (1 - s) * (1 - u) * at(0, j, 0)[d];
          r[d] -= (1 - s) * u * at(0, j, nz - 1)[d];
          r[d] -= s * (1 - u) * at(nx - 1, j, 0)[d];
          r[d] -= s * u * at(nx - 1, j, nz - 1)[d];
        }
        for (int d = 0; d < 3; d++) {
          r[d] -= (1 - s) * (1 - t) * at(0, 0, k)[d];
          r[d] -= (1 - s) * t * at(0, ny - 1, k)[d];
          r[d] -= s * (1 - t) * at(nx - 1, 0, k)[d];
          r[d] -= s * t * at(nx - 1, ny - 1, k)[d];
        }
        // The eight corners, put back.
        for (int d = 0; d < 3; d++) {
          for (int a = 0; a < 2; a++) {
            for (int b = 0; b < 2; b++) {
              for (int c = 0; c < 2; c++) {
                double ws = a ? s : 1 - s, wt = b ? t : 1 - t, wu = c ? u : 1 - u;
                r[d] += ws * wt * wu * at(a * (nx - 1), b * (ny - 1), c * (nz - 1))[d];
              }
            }
          }
        }
        math::Copy3(at(i, j, k), r);
      }
    }
  }
}

void FlexCellNodeState(const Model& m, const Data& d, int f, double* xpos, double* vel) {
  int nnode = m.flex_nodenum[f], nodeadr = m.flex_nodeadr[f];
  for (int i = 0; i < nnode; i++) {
    FlexNodeXpos(m, d, f, nodeadr + i, xpos + 3 * i);
    if (!vel) continue;

    // The velocity of the node's point of its body: at the centre of mass, plus the
    // angular velocity across to the node.
    int body = m.flex_nodebodyid[nodeadr + i];
    double screw[6], arm[3], cross[3];
    ObjectVelocity(m, d, kObjBody, body, screw, false);
    math::Copy3(vel + 3 * i, screw + 3);
    math::Sub3(arm, xpos + 3 * i, &d.xipos[3 * body]);
    math::Cross3(cross, screw, arm);
    math::Add3(vel + 3 * i, vel + 3 * i, cross);
  }
  FlexLattice g = FlexLatticeOf(m, f);
  if (!g.shell) return;
  FlexShellInterior(g, xpos);
  if (vel) FlexShellInterior(g, vel);
}

void FlexCellRotation(int order, const double* xpos, double quat[4]) {
  const double centre[3] = {0.5, 0.5, 0.5};
  double mat[9];
  FlexDeformationGradient(mat, centre, xpos, order);
  math::SetIdentityQuat(quat);
  FlexNearestRotation(quat, mat);
  math::NegQuat(quat, quat);
}

void FlexFaceNormal(int order, const double* xpos, const double local[2], double normal[3],
                    double t1[3], double t2[3]) {
  math::Zero3(t1);
  math::Zero3(t2);
  int n = 0;
  for (int l0 = 0; l0 <= order; l0++) {
    for (int l1 = 0; l1 <= order; l1++, n++) {
      double g0 = FlexShapeSlope(local[0], l0, order) * FlexShape(local[1], l1, order);
      double g1 = FlexShape(local[0], l0, order) * FlexShapeSlope(local[1], l1, order);
      for (int k = 0; k < 3; k++) {
        t1[k] += xpos[3 * n + k] * g0;
        t2[k] += xpos[3 * n + k] * g1;
      }
    }
  }
  math::Cross3(normal, t1, t2);
}

void FlexFaceRotation(int order, int normal_axis, const double* xpos, double quat[4]) {
  // The face's tangents and normal at its centre, as the columns of its in-plane axes
  // and its normal axis (so a face of an axis-aligned lattice has the identity).
  const double centre[2] = {0.5, 0.5};
  double t1[3], t2[3], normal[3];
  FlexFaceNormal(order, xpos, centre, normal, t1, t2);
  const double* column[3];
  column[(normal_axis + 1) % 3] = t1;
  column[(normal_axis + 2) % 3] = t2;
  column[normal_axis] = normal;
  double mat[9];
  for (int c = 0; c < 3; c++) {
    for (int r = 0; r < 3; r++) mat[3 * r + c] = column[c][r];
  }
  math::SetIdentityQuat(quat);
  FlexNearestRotation(quat, mat);
  math::NegQuat(quat, quat);
}

}  // namespace simlab
