// The flexstrain equality's rows (see flex_strain.h), in MuJoCo 3.12's order of
// operations so that residuals and Jacobians agree to the last bit.
#include "engine/flex_strain.h"

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/flex_cells.h"
#include "engine/flex_elasticity.h"
#include "math/math.h"

namespace simlab {

namespace {

// The most nodes of an element (a quadratic cell).
constexpr int kMaxElementNodes = 27;

// One element of an interpolated flex: a cell (eq_data the cell's x, y, z indices) or a
// shell's face (eq_data[0] the face), its index among the flex's elements, its nodes'
// lattice ids and, for a face, its normal axis.
struct StrainElement {
  int flex = -1;
  FlexLattice lattice;
  int index = 0;
  int nnode = 0;
  int normal = -1;
  int node[kMaxElementNodes];

  int Dofs() const { return 3 * nnode; }
};

// Equality eq's element; false when its flex has no nodes (it then makes no rows).
bool ElementOf(const Model& m, int eq, StrainElement* el) {
  int f = m.eq_obj1id[eq];
  if (m.flex_interp[f] == 0 || m.flex_nodenum[f] == 0) return false;
  el->flex = f;
  el->lattice = FlexLatticeOf(m, f);
  const FlexLattice& g = el->lattice;
  const double* data = &m.eq_data[static_cast<size_t>(kNEqData) * eq];
  el->nnode = g.NodesPerElement();
  int cell[3] = {static_cast<int>(data[0]), static_cast<int>(data[1]), static_cast<int>(data[2])};
  el->index = g.shell ? cell[0] : (cell[0] * g.cells[1] + cell[1]) * g.cells[2] + cell[2];
  el->normal = FlexElementNodes(g, el->index, el->node);
  return true;
}

// The element's modes in flex_stiffness: their count, then each mode's 3 nnode numbers;
// null when the flex stores no stiffness.
const double* ElementModes(const Model& m, const StrainElement& el) {
  int adr = m.flex_stiffnessadr[el.flex];
  if (adr < 0) return nullptr;
  size_t size = static_cast<size_t>(el.Dofs()) * el.Dofs();
  return m.flex_stiffness.data() + adr + size * el.index;
}

// The element's nodes in the world, and its corotated frame q.
void ElementState(const Model& m, const Data& d, const StrainElement& el, double* xpos,
                  double quat[4]) {
  int nodeadr = m.flex_nodeadr[el.flex];
  for (int n = 0; n < el.nnode; n++) {
    FlexNodeXpos(m, d, el.flex, nodeadr + el.node[n], xpos + 3 * n);
  }
  if (el.lattice.shell) {
    FlexFaceRotation(el.lattice.order, el.normal, xpos, quat);
  } else {
    FlexCellRotation(el.lattice.order, xpos, quat);
  }
}

// The translation Jacobians (3 rows each, on the element's n dofs) of its nodes.
void NodeJacobians(const Model& m, const Data& d, const StrainElement& el, const double* xpos,
                   const int* dofs, int n, double* jac) {
  int nodeadr = m.flex_nodeadr[el.flex];
  for (int k = 0; k < el.nnode; k++) {
    int body = m.flex_nodebodyid[nodeadr + el.node[k]];
    JacobianOnDofs(m, d, dofs, n, jac + 3 * static_cast<size_t>(n) * k, nullptr, xpos + 3 * k,
                   body);
  }
}

// One mode's row: sum over nodes and axes (zero weights skipped) of the mode turned back
// to the world times the node's Jacobian row.
void ModeRow(const double* world_mode, const double* node_jac, int ndof, int n, double* row) {
  for (int k = 0; k < n; k++) row[k] = 0;
  for (int j = 0; j < ndof; j++) {
    double w = world_mode[j];
    if (w == 0) continue;
    const double* jac = node_jac + static_cast<size_t>(n) * j;
    for (int k = 0; k < n; k++) row[k] += w * jac[k];
  }
}

}  // namespace

double FlexStrainInvWeight(const Model& m, int eq) {
  StrainElement el;
  if (!ElementOf(m, eq, &el)) return 0;
  int nodeadr = m.flex_nodeadr[el.flex];
  double sum = 0;
  for (int n = 0; n < el.nnode; n++) {
    sum += m.body_invweight0[2 * m.flex_nodebodyid[nodeadr + el.node[n]]];
  }
  return sum / el.nnode;
}

void FlexStrainRows(const Model& m, Data& d, int eq, FlexStrainRowSink row) {
  StrainElement el;
  if (!ElementOf(m, eq, &el)) return;
  const double* modes = ElementModes(m, el);
  int nmode = modes ? static_cast<int>(modes[0]) : 0;
  int ndof = el.Dofs(), nodeadr = m.flex_nodeadr[el.flex];

  // The nodes, the element's frame, and the displacement from rest in that frame.
  SolverFrame frame(d.solver_scratch);
  double* xpos = frame.RealsToWrite(ndof);
  double* displacement = frame.RealsToWrite(ndof);
  double quat[4], inverse[4];
  ElementState(m, d, el, xpos, quat);
  for (int n = 0; n < el.nnode; n++) {
    double turned[3];
    math::RotVecQuat(turned, xpos + 3 * n, quat);
    const double* rest = &m.flex_node0[3 * (nodeadr + el.node[n])];
    for (int k = 0; k < 3; k++) displacement[3 * n + k] = turned[k] - rest[k];
  }
  math::NegQuat(inverse, quat);

  // The dofs that move any node, and each node's Jacobian on them.
  int bodies[kMaxElementNodes];
  for (int n = 0; n < el.nnode; n++) bodies[n] = m.flex_nodebodyid[nodeadr + el.node[n]];
  int* dofs = frame.IntsToWrite(m.nv);
  int ncol = MergedDofChains(m, bodies, el.nnode, dofs);
  double* node_jac = frame.RealsToWrite(static_cast<size_t>(ndof) * ncol);
  NodeJacobians(m, d, el, xpos, dofs, ncol, node_jac);

  // One row per mode: its residual, and its Jacobian through the mode turned back.
  double* world_mode = frame.RealsToWrite(ndof);
  double* jac = frame.RealsToWrite(ncol);
  for (int i = 0; i < nmode; i++) {
    const double* mode = modes + 1 + static_cast<size_t>(i) * ndof;
    double residual = 0;
    for (int j = 0; j < ndof; j++) residual += mode[j] * displacement[j];
    for (int n = 0; n < el.nnode; n++) math::RotVecQuat(world_mode + 3 * n, mode + 3 * n, inverse);
    ModeRow(world_mode, node_jac, ndof, ncol, jac);
    row(jac, dofs, ncol, residual);
  }
}

int FlexStrainRneStep(const Model& m, int eq) {
  int f = m.eq_obj1id[eq];
  int interp = m.flex_interp[f];
  int order = interp < 0 ? -interp : interp;
  if (order == 0 || m.flex_nodenum[f] == 0) return 0;
  int ngauss = (order + 1) * (order + 1) * (order + 1);
  const int* c = &m.flex_cellnum[3 * f];
  return c[0] * c[1] * c[2] * (order == 1 ? 2 + 3 * ngauss : 6 * ngauss);
}

}  // namespace simlab
