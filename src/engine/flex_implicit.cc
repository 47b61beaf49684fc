// Interpolated flexes in the implicit integrators (MuJoCo's mj_implicitSkip with
// mjd_flexInterp_addH and mjd_flexInterp_mulKD). An interpolated flex's elasticity is a
// constant stiffness matrix K on its nodes in the corotated frame; the implicit step
// takes it into the dofs that move the nodes:
//
//   (H_nodes + (h^2 + h b) J' K J) qacc_nodes = qfrc_nodes - H_coupling qacc_rest + ...
//
// a small dense system, factored by Cholesky, whose solution replaces those dofs'
// accelerations from the ordinary sparse solve (the rest of the system sees the flex
// one way only). K is stored negated in flex_stiffness, so "adding" it subtracts.
#include "engine/flex_implicit.h"

#include <algorithm>
#include <cmath>

#include "engine/engine.h"
#include "engine/flex_cells.h"
#include "engine/flex_elasticity.h"
#include "engine/stack.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

namespace {

// The rotated, scaled stiffness of flex f (3 nnode square): block (i, j) is
// scale R' K_ij R with R the rotation of `quat` (world to corotated).
void RotatedStiffness(const Model& m, int f, const double quat[4], double scale, double* krot) {
  int nnode = m.flex_nodenum[f], dim = 3 * nnode;
  const double* k = &m.flex_stiffness[m.flex_stiffnessadr[f]];
  double rot[9], rot_t[9];
  math::QuatToMat(rot, quat);
  for (int r = 0; r < 3; r++) {
    for (int c = 0; c < 3; c++) rot_t[3 * r + c] = rot[3 * c + r];
  }
  for (int i = 0; i < nnode; i++) {
    for (int j = 0; j < nnode; j++) {
      // Block (i, j): K_ij R, then R' times it.
      int adr = 3 * i * dim + 3 * j;
      double block[9], right[9];
      for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) block[3 * r + c] = k[adr + r * dim + c];
      }
      math::MulMat3(right, block, rot);
      math::MulMat3(block, rot_t, right);
      for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) krot[adr + r * dim + c] = scale * block[3 * r + c];
      }
    }
  }
}

// The translation Jacobians of flex f's nodes at their corotated positions (as MuJoCo
// takes them), each on its body's dof chain: node i's chain at chain + i nv (nchain[i]
// long), its 3 rows at jac + 3 i nv. Also returns the rotation into `quat`.
void NodeJacobians(const Model& m, const Data& d, int f, double* xpos, double quat[4],
                   int* chain, int* nchain, double* jac) {
  FlexInterpState(m, d, f, xpos, nullptr, quat);
  const int* bodyid = &m.flex_nodebodyid[m.flex_nodeadr[f]];
  for (int i = 0; i < m.flex_nodenum[f]; i++) {
    int* ch = chain + static_cast<size_t>(i) * m.nv;
    nchain[i] = MergedDofChain(m, bodyid[i], bodyid[i], ch);
    JacobianOnDofs(m, d, ch, nchain[i], jac + 3 * static_cast<size_t>(i) * m.nv, nullptr,
                   xpos + 3 * i, bodyid[i]);
  }
}

// Does flex f's stiffness enter the step: an interpolated flex of MuJoCo 3.5.1's kind
// (one made of cells, flex_cells.h, is MuJoCo 3.12's, whose implicit integrators take
// its elasticity explicitly outside the CG solver's effective metric)?
bool TakesImplicitStiffness(const Model& m, int f) {
  return m.flex_interp[f] != 0 && !FlexHasCells(m, f);
}

// The scale at which flex f's stiffness enters, h^2 + h damping; 0 when it does not
// (not interpolated, rigid, or without stiffness).
double StiffnessScale(const Model& m, int f, double h) {
  if (!TakesImplicitStiffness(m, f) || m.flex_rigid[f]) return 0;
  if (m.flex_stiffness[m.flex_stiffnessadr[f]] == 0) return 0;
  return h * h + h * m.flex_damping[f];
}

// One flex's stiffness in the world, in arrays of a SolverFrame: the rotated, scaled
// stiffness (dim = 3 nnode square) and the node Jacobians (rows of 3 per node).
struct WorldStiffness {
  int dim = 0;
  double* krot = nullptr;
  double* jac = nullptr;
  int* chain = nullptr;
  int* nchain = nullptr;

  // Row r's values and columns (node r / 3, axis r % 3), and its length.
  // (node i's Jacobian is 3 x nchain[i], at jac + 3 i nv)
  const double* Row(int nv, int r) const {
    return jac + 3 * static_cast<size_t>(r / 3) * nv + (r % 3) * nchain[r / 3];
  }
  const int* Cols(int nv, int r) const { return chain + static_cast<size_t>(r / 3) * nv; }
  int Count(int r) const { return nchain[r / 3]; }
};

WorldStiffness MakeWorldStiffness(const Model& m, const Data& d, int f, double scale,
                                  SolverFrame& frame) {
  WorldStiffness w;
  int nnode = m.flex_nodenum[f];
  w.dim = 3 * nnode;
  size_t dim = w.dim;
  double* xpos = frame.RealsToWrite(dim);
  w.krot = frame.RealsToWrite(dim * dim);
  w.jac = frame.RealsToWrite(dim * m.nv);
  w.chain = frame.IntsToWrite(static_cast<size_t>(nnode) * m.nv);
  w.nchain = frame.IntsToWrite(nnode);
  double quat[4] = {1, 0, 0, 0};
  NodeJacobians(m, d, f, xpos, quat, w.chain, w.nchain, w.jac);
  RotatedStiffness(m, f, quat, scale, w.krot);
  return w;
}

// Calls use(w, scratch) for each flex whose stiffness enters the step, in order, with
// its stiffness in the world at scale h^2 + h damping, in a frame of scratch of its own.
template <typename Use>
void ForEachWorldStiffness(const Model& m, Data& d, Use use) {
  double h = m.opt.timestep;
  for (int f = 0; f < m.nflex; f++) {
    double scale = StiffnessScale(m, f, h);
    if (scale == 0) continue;
    SolverFrame scratch(d.solver_scratch);
    use(MakeWorldStiffness(m, d, f, scale, scratch), scratch);
  }
}

// res += J' Krot J vec for one flex (MuJoCo's order: J vec row by row, Krot times it as
// long dot products, then J' back row by row).
void AddStiffnessTimesVec(const Model& m, const WorldStiffness& w, const double* vec,
                          double* res, SolverFrame& frame) {
  double* jv = frame.Reals(w.dim);
  double* kjv = frame.RealsToWrite(w.dim);
  for (int r = 0; r < w.dim; r++) {
    const double* row = w.Row(m.nv, r);
    const int* cols = w.Cols(m.nv, r);
    for (int k = 0; k < w.Count(r); k++) jv[r] += row[k] * vec[cols[k]];
  }
  math::MulMatVec(kjv, w.krot, jv, w.dim, w.dim);
  for (int r = 0; r < w.dim; r++) {
    const double* row = w.Row(m.nv, r);
    const int* cols = w.Cols(m.nv, r);
    for (int k = 0; k < w.Count(r); k++) res[cols[k]] += row[k] * kjv[r];
  }
}

// H -= Jr' Krot Jr for one flex, Jr the node Jacobians on the system's n dofs (`local`
// maps a dof to its place, -1 off the system). Krot Jr is summed as MuJoCo's
// mju_mulMatMat (skipping zeros of Krot), each entry of H as one running sum.
void SubtractStiffness(const Model& m, const WorldStiffness& w, const int* local, int n,
                       double* H, SolverFrame& frame) {
  size_t size = static_cast<size_t>(w.dim) * n;
  double* jr = frame.Reals(size);
  double* kj = frame.Reals(size);
  for (int r = 0; r < w.dim; r++) {
    const double* row = w.Row(m.nv, r);
    const int* cols = w.Cols(m.nv, r);
    for (int k = 0; k < w.Count(r); k++) {
      if (local[cols[k]] >= 0) jr[static_cast<size_t>(r) * n + local[cols[k]]] = row[k];
    }
  }
  for (int i = 0; i < w.dim; i++) {
    for (int k = 0; k < w.dim; k++) {
      double scale = w.krot[static_cast<size_t>(i) * w.dim + k];
      if (scale == 0) continue;
      double* out = kj + static_cast<size_t>(i) * n;
      const double* in = jr + static_cast<size_t>(k) * n;
      for (int j = 0; j < n; j++) out[j] += in[j] * scale;
    }
  }
  for (int i = 0; i < n; i++) {
    for (int j = 0; j < n; j++) {
      double sum = 0;
      for (int r = 0; r < w.dim; r++) sum += jr[static_cast<size_t>(r) * n + i] * kj[static_cast<size_t>(r) * n + j];
      H[static_cast<size_t>(i) * n + j] -= sum;
    }
  }
}

// The dofs that move the interpolated flexes' nodes, each once in order of first
// appearance: a node body's own dofs, or for a pinned node (a body without dofs) those
// of the chain that carries it. local[dof] is its place (-1 for other dofs).
int FlexNodeDofs(const Model& m, int* dofs, int* local, int* chain) {
  std::fill(local, local + m.nv, -1);
  int n = 0;
  for (int f = 0; f < m.nflex; f++) {
    if (!TakesImplicitStiffness(m, f)) continue;
    for (int i = 0; i < m.flex_nodenum[f]; i++) {
      int b = m.flex_nodebodyid[m.flex_nodeadr[f] + i], count = m.body_dofnum[b];
      if (count == 0) {
        count = MergedDofChain(m, b, b, chain);
      } else {
        for (int j = 0; j < count; j++) chain[j] = m.body_dofadr[b] + j;
      }
      for (int j = 0; j < count; j++) {
        if (local[chain[j]] >= 0) continue;
        local[chain[j]] = n;
        dofs[n++] = chain[j];
      }
    }
  }
  return n;
}

// Dense Cholesky in place on the lower triangle (MuJoCo's mju_cholFactor: a pivot below
// `mindiag` is raised to it).
void CholeskyFactor(double* a, int n, double mindiag) {
  for (int j = 0; j < n; j++) {
    double* rowj = a + static_cast<size_t>(j) * n;
    double pivot = rowj[j];
    if (j) pivot -= math::Dot(rowj, rowj, j);
    rowj[j] = std::sqrt(pivot < mindiag ? mindiag : pivot);
    double inverse = 1 / rowj[j];
    for (int i = j + 1; i < n; i++) {
      double* rowi = a + static_cast<size_t>(i) * n;
      rowi[j] = (rowi[j] - math::Dot(rowi, rowj, j)) * inverse;
    }
  }
}

// x = (L L')^-1 x for a factor of CholeskyFactor.
void CholeskySolve(const double* a, int n, double* x) {
  for (int i = 0; i < n; i++) {
    const double* row = a + static_cast<size_t>(i) * n;
    if (i) x[i] -= math::Dot(row, x, i);
    x[i] /= row[i];
  }
  for (int i = n - 1; i >= 0; i--) {
    for (int j = i + 1; j < n; j++) x[i] -= a[static_cast<size_t>(j) * n + i] * x[j];
    x[i] /= a[static_cast<size_t>(i) * n + i];
  }
}

}  // namespace

bool UsesFlexImplicitSystem(const Model& m, const Data& d) {
  if ((m.opt.enableflags & kEnableSleep) && d.nv_awake < m.nv) return false;
  for (int f = 0; f < m.nflex; f++) {
    if (TakesImplicitStiffness(m, f)) return true;
  }
  return false;
}

FlexImplicitSystem BuildFlexImplicitSystem(const Model& m, Data& d, const StepMatrix& step,
                                           SolverFrame& frame) {
  FlexImplicitSystem s;
  s.local = frame.IntsToWrite(m.nv);
  int* dofs = frame.IntsToWrite(m.nv);
  {
    SolverFrame chain(d.solver_scratch);
    s.n = FlexNodeDofs(m, dofs, s.local, chain.IntsToWrite(m.nv));
  }
  s.dofs = dofs;
  if (s.n == 0) return s;

  // The step matrix's rows of those dofs: entries on them into H, the rest couplings.
  s.H = frame.Reals(static_cast<size_t>(s.n) * s.n);
  int ncoupling = 0;
  for (int i = 0; i < s.n; i++) {
    for (int k = 0; k < step.rownnz[dofs[i]]; k++) {
      ncoupling += step.Kept(m, dofs[i], k) && s.local[step.colind[step.rowadr[dofs[i]] + k]] < 0;
    }
  }
  s.coupling_val = frame.RealsToWrite(ncoupling);
  s.coupling_row = frame.IntsToWrite(ncoupling);
  s.coupling_col = frame.IntsToWrite(ncoupling);
  for (int i = 0; i < s.n; i++) {
    int row = dofs[i];
    for (int k = 0; k < step.rownnz[row]; k++) {
      if (!step.Kept(m, row, k)) continue;
      int adr = step.rowadr[row] + k, col = step.colind[adr], j = s.local[col];
      if (j >= 0) {
        s.H[static_cast<size_t>(i) * s.n + j] = step.values[adr];
      } else {
        s.coupling_val[s.ncoupling] = step.values[adr];
        s.coupling_row[s.ncoupling] = i;
        s.coupling_col[s.ncoupling++] = col;
      }
    }
  }

  // Plus the flexes' stiffness, then factored; with each flex's stiffness in the world at
  // hand, also its velocity correction -h K v (each flex at its own h^2 + h b, divided
  // back by the first flex's, as MuJoCo does), which depends on the state only.
  double* velocity = frame.Reals(m.nv);
  ForEachWorldStiffness(m, d, [&](const WorldStiffness& w, SolverFrame& scratch) {
    SubtractStiffness(m, w, s.local, s.n, s.H, scratch);
    AddStiffnessTimesVec(m, w, d.qvel.data(), velocity, scratch);
  });
  CholeskyFactor(s.H, s.n, kMinVal);
  double h = m.opt.timestep;
  double first = h * h + h * (m.nflex > 0 ? m.flex_damping[0] : 0);
  double factor = first > kMinVal ? h / first : 0;
  s.velocity_term = frame.RealsToWrite(s.n);
  for (int i = 0; i < s.n; i++) s.velocity_term[i] = velocity[dofs[i]] * factor;
  return s;
}

void SolveFlexImplicitSystem(const Model& m, Data& d, const FlexImplicitSystem& s,
                             const double* qfrc, double* qacc) {
  if (s.n == 0) return;
  SolverFrame frame(d.solver_scratch);
  double* rhs = frame.RealsToWrite(s.n);
  for (int i = 0; i < s.n; i++) rhs[i] = qfrc[s.dofs[i]] + s.velocity_term[i];

  // Less the couplings to the other dofs' accelerations, then solved into qacc.
  for (int k = 0; k < s.ncoupling; k++) {
    rhs[s.coupling_row[k]] -= s.coupling_val[k] * qacc[s.coupling_col[k]];
  }
  CholeskySolve(s.H, s.n, rhs);
  for (int i = 0; i < s.n; i++) qacc[s.dofs[i]] = rhs[i];
}

}  // namespace simlab
