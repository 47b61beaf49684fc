// Constraint rows (MuJoCo mj_makeConstraint, engine_core_constraint.c): one row per scalar
// condition, in MuJoCo's order: equalities, friction losses, limits (contacts come with
// the collision stage). Each row has a Jacobian J (dense, nv columns), a position error
// efc_pos, a margin and a type/id naming the element that made it.
//
// The rows are then given their softness: diagApprox (an estimate of J M^-1 J^T from the
// inverse weights the compiler stores), the impedance from solimp, the regularizer
// R = (1 - imp) / imp * diagApprox and the spring-damper numbers of solref (efc_KBIP).
#include <algorithm>
#include <cmath>

#include "engine/constraint.h"
#include "engine/contact_bodies.h"
#include "engine/engine.h"
#include "engine/flex_strain.h"
#include "engine/rows.h"
#include "engine/sleep.h"
#include "engine/stack.h"
#include "math/dot.h"
#include "math/math.h"

namespace simlab {

namespace {

constexpr double kMinImp = 0.0001;  // mjMINIMP
constexpr double kMaxImp = 0.9999;  // mjMAXIMP

// ---------------------------------------------------------------- adding rows

// Room in every efc array for `size` more rows of `width` Jacobian entries each. The
// arrays keep their size from step to step (nefc and nJ say how much is in use) and grow
// by half again when short, all per-row arrays to the same number of rows (efc_type's
// size), so that steady steps neither allocate nor clear what the rows overwrite.
void GrowRows(Data& d, int size, int width) {
  size_t rows = static_cast<size_t>(d.nefc + size);
  size_t capacity = d.efc_type.size();
  if (rows > capacity) {
    capacity = std::max(rows, capacity + capacity / 2);
#define SIMLAB_X(type, name, cols) d.name.resize(capacity * (cols));
    SIMLAB_DATA_EFC_FIELDS(SIMLAB_X)
#undef SIMLAB_X
  }
  size_t entries = static_cast<size_t>(d.nJ) + static_cast<size_t>(size) * width;
  if (entries > d.efc_J.size()) {
    size_t grown = std::max(entries, d.efc_J.size() + d.efc_J.size() / 2);
    d.efc_J.resize(grown);
    d.efc_J_colind.resize(grown);
  }
}

// The columns of a group of rows: the dofs `dof` (ascending), `n` of them.
struct Columns {
  const int* dof;
  int n;
};

// Appends `size` rows whose Jacobian `jac` (size x cols.n) holds the columns `cols`
// (every other column is zero): stored as they are with a sparse Jacobian, spread over
// all nv dofs with a dense one. Rows other than contacts whose Jacobian is all zero are
// skipped: they cannot act on anything (MuJoCo does the same).
void AddRows(const Model& m, Data& d, const double* jac, Columns cols, const double* pos,
             double margin, double frictionloss, int size, ConstraintType type, int id) {
  bool contact = type >= kCnstrContactFrictionless;
  const double* end = jac + static_cast<size_t>(size) * cols.n;
  if (!contact && std::all_of(jac, end, [](double x) { return x == 0; })) return;

  int first = d.nefc;
  bool dense = !SparseJacobian(m);
  int width = dense ? m.nv : cols.n;
  GrowRows(d, size, width);
  for (int r = 0; r < size; r++) {
    d.efc_J_rownnz[first + r] = width;
    d.efc_J_rowadr[first + r] = d.nJ;
    double* values = d.efc_J.data() + d.nJ;
    int* colind = d.efc_J_colind.data() + d.nJ;
    const double* row = jac + static_cast<size_t>(r) * cols.n;
    if (dense) {
      std::fill_n(values, width, 0.0);
      for (int k = 0; k < cols.n; k++) values[cols.dof[k]] = row[k];
      for (int v = 0; v < width; v++) colind[v] = v;
    } else {
      std::copy_n(row, width, values);
      std::copy_n(cols.dof, width, colind);
    }
    d.nJ += width;
    d.efc_pos[first + r] = pos ? pos[r] : 0;
    d.efc_margin[first + r] = margin;
    d.efc_frictionloss[first + r] = frictionloss;
    d.efc_type[first + r] = type;
    d.efc_id[first + r] = id;
  }
  d.nefc += size;
  if (type == kCnstrEquality) d.ne += size;
  if (type == kCnstrFrictionDof || type == kCnstrFrictionTendon) d.nf += size;
  if (type == kCnstrLimitJoint || type == kCnstrLimitTendon) d.nl += size;
}

// Appends rows given as dense size x nv Jacobians, by the columns that are nonzero in
// some row (compacted in place: `jac` is overwritten); `index` has room for nv dofs.
void AddDenseRows(const Model& m, Data& d, double* jac, int* index, const double* pos,
                  double margin, double frictionloss, int size, ConstraintType type, int id) {
  int nv = m.nv, n = 0;
  for (int v = 0; v < nv; v++) {
    bool used = false;
    for (int r = 0; r < size && !used; r++) used = jac[r * nv + v] != 0;
    if (used) index[n++] = v;
  }
  for (int r = 0; r < size; r++) {
    for (int k = 0; k < n; k++) jac[r * n + k] = jac[r * nv + index[k]];
  }
  AddRows(m, d, jac, Columns{index, n}, pos, margin, frictionloss, size, type, id);
}

// The columns of rows that move bodies b0 and b1: the dofs of both bodies' chains (MuJoCo
// mj_mergeChain); `index` has room for nv.
Columns BodyPairColumns(const Model& m, int b0, int b1, int* index) {
  return Columns{index, MergedDofChain(m, b0, b1, index)};
}

// ---------------------------------------------------------------- equality rows

// The body and world point of side j of a connect or weld (site or body-anchor form).
// `anchor` is the body-frame anchor used in the body form.
int EqualityPoint(const Model& m, const Data& d, int eq, int j, const double* anchor,
                  double* point) {
  int obj = j == 0 ? m.eq_obj1id[eq] : m.eq_obj2id[eq];
  if (m.eq_objtype[eq] == kObjSite) {
    math::Copy3(point, &d.site_xpos[3 * obj]);
    return m.site_bodyid[obj];
  }
  math::MulMatVec3(point, &d.xmat[9 * obj], anchor);
  math::AddScaled3(point, &d.xpos[3 * obj], 1);
  return obj;
}

// Connect: the two anchor points coincide (3 rows).
void ConnectRows(const Model& m, Data& d, int eq, double* jac, double* jac1, int* index) {
  const double* data = &m.eq_data[kNEqData * eq];
  double pos[2][3];
  int body0 = EqualityPoint(m, d, eq, 0, data, pos[0]);
  int body1 = EqualityPoint(m, d, eq, 1, data + 3, pos[1]);
  double err[3];
  math::Sub3(err, pos[0], pos[1]);

  // J = J(body0 at point0) - J(body1 at point1)
  Columns cols = BodyPairColumns(m, body0, body1, index);
  JacobianOnDofs(m, d, cols.dof, cols.n, jac, nullptr, pos[0], body0);
  JacobianOnDofs(m, d, cols.dof, cols.n, jac1, nullptr, pos[1], body1);
  for (int k = 0; k < 3 * cols.n; k++) jac[k] -= jac1[k];
  AddRows(m, d, jac, cols, err, 0, 0, 3, kCnstrEquality, eq);
}

// Weld: the two frames coincide, up to relpose (3 translation + 3 rotation rows).
void WeldRows(const Model& m, Data& d, int eq, double* jac, double* jac1, int* index) {
  const double* data = &m.eq_data[kNEqData * eq];
  double pos[2][3];
  int body0 = EqualityPoint(m, d, eq, 0, data + 3, pos[0]);
  int body1 = EqualityPoint(m, d, eq, 1, data, pos[1]);
  double err[6];
  math::Sub3(err, pos[0], pos[1]);

  // Translation and rotation Jacobian differences, rows 0-2 and 3-5.
  Columns cols = BodyPairColumns(m, body0, body1, index);
  int nv = cols.n;
  JacobianOnDofs(m, d, cols.dof, nv, jac, jac + 3 * nv, pos[0], body0);
  JacobianOnDofs(m, d, cols.dof, nv, jac1, jac1 + 3 * nv, pos[1], body1);
  for (int k = 0; k < 6 * nv; k++) jac[k] -= jac1[k];

  // Orientation error: the vector part of conj(q1) * q0 (* relpose in the body form).
  double q0[4], q1[4], q1neg[4], qerr[4];
  if (m.eq_objtype[eq] == kObjSite) {
    math::MulQuat(q0, &d.xquat[4 * body0], &m.site_quat[4 * m.eq_obj1id[eq]]);
    math::MulQuat(q1, &d.xquat[4 * body1], &m.site_quat[4 * m.eq_obj2id[eq]]);
  } else {
    math::MulQuat(q0, &d.xquat[4 * body0], data + 6);
    math::CopyQuat(q1, &d.xquat[4 * body1]);
  }
  math::NegQuat(q1neg, q1);
  math::MulQuat(qerr, q1neg, q0);
  double torquescale = data[10];
  math::Scale3(err + 3, qerr + 1, torquescale);

  // Rotation rows: 0.5 * conj(q1) * (omega0 - omega1) * q0, per dof, times torquescale.
  for (int v = 0; v < nv; v++) {
    double axis[3] = {jac[3 * nv + v], jac[4 * nv + v], jac[5 * nv + v]};
    double tmp[4], rot[4];
    math::MulQuatAxis(tmp, q1neg, axis);
    math::MulQuat(rot, tmp, q0);
    for (int k = 0; k < 3; k++) jac[(3 + k) * nv + v] = 0.5 * rot[1 + k] * torquescale;
  }
  AddRows(m, d, jac, cols, err, 0, 0, 6, kCnstrEquality, eq);
}

// Joint or tendon coupling: x1 - x1_0 = poly(x2 - x2_0), or x1 = x1_0 + data[0] alone.
void CouplingRow(const Model& m, Data& d, int eq, double* jac, double* jac1, int* index) {
  int nv = m.nv;
  const double* data = &m.eq_data[kNEqData * eq];
  bool joint = m.eq_type[eq] == kEqJoint;
  int ids[2] = {m.eq_obj1id[eq], m.eq_obj2id[eq]};
  double value[2] = {0, 0}, ref[2] = {0, 0};
  double* jacs[2] = {jac, jac1};
  for (int j = 0; j < (ids[1] >= 0 ? 2 : 1); j++) {
    std::fill(jacs[j], jacs[j] + nv, 0.0);
    if (joint) {
      int qadr = m.jnt_qposadr[ids[j]];
      value[j] = d.qpos[qadr];
      ref[j] = m.qpos0[qadr];
      jacs[j][m.jnt_dofadr[ids[j]]] = 1;
    } else {
      value[j] = d.ten_length[ids[j]];
      ref[j] = m.tendon_length0[ids[j]];
      std::copy_n(RowOf(d.ten_J, ids[j], nv), nv, jacs[j]);
    }
  }
  double err = value[0] - ref[0] - data[0];
  if (ids[1] >= 0) {
    double x = value[1] - ref[1];
    err -= x * (data[1] + x * (data[2] + x * (data[3] + x * data[4])));
    double slope = data[1] + x * (2 * data[2] + x * (3 * data[3] + x * 4 * data[4]));
    for (int v = 0; v < nv; v++) jac[v] -= slope * jac1[v];
  }
  AddDenseRows(m, d, jac, index, &err, 0, 0, 1, kCnstrEquality, eq);
}

// One equality row of eq at violation `pos`, on row r of a flex's sparse Jacobian
// (values J, rows at rowadr, rownnz long, columns colind).
void SparseEqualityRow(const Model& m, Data& d, int eq, double pos, const std::vector<double>& J,
                       const std::vector<int>& rowadr, const std::vector<int>& rownnz,
                       const std::vector<int>& colind, int r) {
  int adr = rowadr[r];
  AddRows(m, d, J.data() + adr, Columns{colind.data() + adr, rownnz[r]}, &pos, 0, 0, 1,
          kCnstrEquality, eq);
}

// A flex's edge equality: one row per edge whose ends can move apart, its length's
// stretch from its length at qpos0, on the edge's sparse Jacobian.
void FlexEdgeRows(const Model& m, Data& d, int eq) {
  int f = m.eq_obj1id[eq];
  int begin = m.flex_edgeadr[f], end = begin + m.flex_edgenum[f];
  for (int e = begin; e < end; e++) {
    if (m.flexedge_rigid[e]) continue;
    double pos = d.flexedge_length[e] - m.flexedge_length0[e];
    SparseEqualityRow(m, d, eq, pos, d.flexedge_J, m.flexedge_J_rowadr, m.flexedge_J_rownnz,
                      m.flexedge_J_colind, e);
  }
}

// A cloth's vertex equality: two rows per vertex, its strain invariants (zero at rest),
// on the vertex's sparse Jacobian rows.
void FlexVertexRows(const Model& m, Data& d, int eq) {
  int f = m.eq_obj1id[eq];
  int begin = m.flex_vertadr[f], end = begin + m.flex_vertnum[f];
  for (int row = 2 * begin; row < 2 * end; row++) {
    SparseEqualityRow(m, d, eq, d.flexvert_length[row], d.flexvert_J, m.flexvert_J_rowadr,
                      m.flexvert_J_rownnz, m.flexvert_J_colind, row);
  }
}

// One element of an interpolated flex held near its rest shape: a row per stiff mode
// (flex_strain.h).
void FlexStrainEqualityRows(const Model& m, Data& d, int eq) {
  FlexStrainRows(m, d, eq, [&](const double* jac, const int* dofs, int n, double pos) {
    AddRows(m, d, jac, Columns{dofs, n}, &pos, 0, 0, 1, kCnstrEquality, eq);
  });
}

void EqualityRows(const Model& m, Data& d) {
  if ((m.opt.disableflags & kDisableEquality) || m.neq == 0) return;
  StackFrame frame(d);
  double* jac = frame.Alloc(6 * m.nv);
  double* jac1 = frame.Alloc(6 * m.nv);
  SolverFrame ints(d.solver_scratch);
  int* index = ints.Ints(m.nv);
  bool any_asleep = AnyAsleep(m, d);
  for (int eq = 0; eq < m.neq; eq++) {
    if (!d.eq_active[eq]) continue;
    // (an equality neither of whose sides is awake makes no row)
    if (any_asleep && ElementSleepState(m, d, kObjEquality, eq) == kAsleep) continue;
    switch (m.eq_type[eq]) {
      case kEqConnect: ConnectRows(m, d, eq, jac, jac1, index); break;
      case kEqWeld: WeldRows(m, d, eq, jac, jac1, index); break;
      case kEqFlex: FlexEdgeRows(m, d, eq); break;
      case kEqFlexVert: FlexVertexRows(m, d, eq); break;
      case kEqFlexStrain: FlexStrainEqualityRows(m, d, eq); break;
      default: CouplingRow(m, d, eq, jac, jac1, index); break;
    }
  }
}

// ---------------------------------------------------------------- friction and limits

// The nonzero columns of tendon t's Jacobian (ascending: those of its pattern that are
// not zero), their values into `values`.
Columns TendonColumns(const Model& m, const Data& d, int t, int* index, double* values) {
  const double* row = RowOf(d.ten_J, t, m.nv);
  const int* cols = RowOf(d.ten_J_colind, t, m.nv);
  int n = 0;
  for (int k = 0; k < d.ten_J_rownnz[t]; k++) {
    if (row[cols[k]] == 0) continue;
    index[n] = cols[k];
    values[n++] = row[cols[k]];
  }
  return Columns{index, n};
}

// One row per dof and per tendon with a friction loss.
void FrictionRows(const Model& m, Data& d) {
  if (m.opt.disableflags & kDisableFrictionloss) return;
  StackFrame frame(d);
  double* jac = frame.Alloc(m.nv);
  SolverFrame ints(d.solver_scratch);
  int* index = ints.Ints(m.nv);
  bool any_asleep = AnyAsleep(m, d);
  for (int v = 0; v < m.nv; v++) {
    if (m.dof_frictionloss[v] == 0) continue;
    if (any_asleep && !d.tree_awake[m.dof_treeid[v]]) continue;  // (asleep: no row)
    const double one = 1;
    AddRows(m, d, &one, Columns{&v, 1}, nullptr, 0, m.dof_frictionloss[v], 1,
            kCnstrFrictionDof, v);
  }
  for (int t = 0; t < m.ntendon; t++) {
    if (m.tendon_frictionloss[t] <= 0) continue;
    Columns cols = TendonColumns(m, d, t, index, jac);
    AddRows(m, d, jac, cols, nullptr, 0, m.tendon_frictionloss[t], 1, kCnstrFrictionTendon, t);
  }
}

// Lower and upper limit of a scalar quantity with Jacobian `grad` on the columns `cols`:
// a row for each side closer than the margin, pointing into the allowed range.
void ScalarLimitRows(const Model& m, Data& d, double value, const double* range, double margin,
                     const double* grad, Columns cols, double* jac, ConstraintType type, int id) {
  for (int side = -1; side <= 1; side += 2) {
    double dist = LimitDistance(range, value, side);
    if (dist >= margin) continue;
    for (int k = 0; k < cols.n; k++) jac[k] = -side * grad[k];
    AddRows(m, d, jac, cols, &dist, margin, 0, 1, type, id);
  }
}

// Ball joint limit: the rotation angle stays below the larger range value.
void BallLimitRow(const Model& m, Data& d, int j) {
  int adr = m.jnt_qposadr[j];
  double quat[4];
  math::CopyQuat(quat, &d.qpos[adr]);
  math::NormalizeQuat(quat);
  double axis[3];
  math::QuatToVel(axis, quat, 1);
  double angle = math::Normalize3(axis);
  double dist = std::max(m.jnt_range[2 * j], m.jnt_range[2 * j + 1]) - angle;
  double margin = m.jnt_margin[j];
  if (dist >= margin) return;
  // The joint's three dofs, along minus the rotation axis.
  const int dofs[3] = {m.jnt_dofadr[j], m.jnt_dofadr[j] + 1, m.jnt_dofadr[j] + 2};
  double jac[3];
  math::Scale3(jac, axis, -1);
  AddRows(m, d, jac, Columns{dofs, 3}, &dist, margin, 0, 1, kCnstrLimitJoint, j);
}

void LimitRows(const Model& m, Data& d) {
  if (m.opt.disableflags & kDisableLimit) return;
  StackFrame frame(d);
  double* jac = frame.Alloc(m.nv);
  double* grad = frame.Alloc(m.nv);
  SolverFrame ints(d.solver_scratch);
  int* index = ints.Ints(m.nv);
  bool any_asleep = AnyAsleep(m, d);
  for (int j = 0; j < m.njnt; j++) {
    if (!m.jnt_limited[j]) continue;
    if (any_asleep && !d.tree_awake[m.dof_treeid[m.jnt_dofadr[j]]]) continue;  // (asleep: no row)
    int type = m.jnt_type[j];
    if (type == kJointBall) BallLimitRow(m, d, j);
    if (type != kJointSlide && type != kJointHinge) continue;
    // The joint's own dof, with slope 1.
    int dof = m.jnt_dofadr[j];
    const double one = 1;
    ScalarLimitRows(m, d, d.qpos[m.jnt_qposadr[j]], &m.jnt_range[2 * j], m.jnt_margin[j], &one,
                    Columns{&dof, 1}, jac, kCnstrLimitJoint, j);
  }
  for (int t = 0; t < m.ntendon; t++) {
    if (!m.tendon_limited[t]) continue;
    Columns cols = TendonColumns(m, d, t, index, grad);
    ScalarLimitRows(m, d, d.ten_length[t], &m.tendon_range[2 * t], m.tendon_margin[t], grad, cols,
                    jac, kCnstrLimitTendon, t);
  }
}

// ---------------------------------------------------------------- contact rows

// The Jacobian at the contact point of side 1's bodies minus side 0's, weighted (a flex
// element's vertices), into jac1p, jac1r (3 x n each; jac1r with rotation rows only): the
// first body's Jacobian scaled, the others added scaled, as MuJoCo's mj_jacSum. `work`
// holds 6 n.
void WeightedContactJacobian(const Model& m, Data& d, const Contact& c, Columns cols,
                             const ContactSide* sides, double* jac1p, double* jac1r,
                             double* work) {
  int n = cols.n;
  double* jac2p = work;
  double* jac2r = work + 3 * n;
  bool rotation = c.dim > 3, first = true;
  for (int k = 0; k < 2; k++) {
    for (int i = 0; i < sides[k].n; i++) {
      double w = sides[k].weight[i];  // (signed: side 0 negative)
      JacobianOnDofs(m, d, cols.dof, n, jac2p, rotation ? jac2r : nullptr, c.pos,
                     sides[k].body[i]);
      for (int j = 0; j < 3 * n; j++) {
        jac1p[j] = first ? jac2p[j] * w : jac1p[j] + w * jac2p[j];
        if (rotation) jac1r[j] = first ? jac2r[j] * w : jac1r[j] + w * jac2r[j];
      }
      first = false;
    }
  }
}

// Contact rows in the contact frame: the normal (and tangents for dim > 1) from the
// translation Jacobian difference at the contact point, torsion and rolling (dim > 3)
// from the rotation difference. `jac` receives dim x cols.n.
void ContactJacobian(const Model& m, Data& d, const Contact& c, Columns cols, double* jac,
                     double* scratch, const ContactSide* sides) {
  int n = cols.n;
  if (ContactOnTwoBodies(m, c)) {
    FrameJacobianDifference(m, d, cols.dof, n, c.pos, sides[0].body[0], sides[1].body[0],
                            c.frame, c.dim, jac);
    return;
  }
  double* dif_p = scratch;
  double* dif_r = scratch + 3 * n;
  WeightedContactJacobian(m, d, c, cols, sides, dif_p, dif_r, scratch + 6 * n);
  // Rotate the differences into the contact frame.
  for (int r = 0; r < c.dim; r++) {
    bool rotation_row;
    const double* axis = ContactRowAxis(c.frame, c.dim, r, &rotation_row);
    const double* dif = rotation_row ? dif_r : dif_p;
    double* row = jac + r * n;
    for (int v = 0; v < n; v++) row[v] = 0;
    for (int k = 0; k < 3; k++) {
      for (int v = 0; v < n; v++) row[v] += axis[k] * dif[k * n + v];
    }
  }
}

// The columns of a contact's rows: the dofs of both sides' bodies, ascending (for one
// body a side, the body pair's merged chain); `index` has room for nv.
Columns ContactColumns(const Model& m, const ContactSide* sides, int* index) {
  static_assert(2 * ContactSide::kMax <= kMaxMergedChains);
  int bodies[2 * ContactSide::kMax];
  int n = 0;
  for (int k = 0; k < 2; k++) {
    for (int i = 0; i < sides[k].n; i++) bodies[n++] = sides[k].body[i];
  }
  return Columns{index, MergedDofChains(m, bodies, n, index)};
}

// The bodies of contact c's sides and the columns of its rows. False, the contact marked
// excluded (3), when a side is not on bodies (as an interpolated flex's can be) or, with
// a sparse Jacobian, when no dof moves either side.
bool ContactColumnsOf(const Model& m, const Data& d, Contact& c, bool sparse, int* index,
                      ContactSide* sides, Columns* cols) {
  if (!ContactSideBodies(m, d, c, 0, true, &sides[0]) ||
      !ContactSideBodies(m, d, c, 1, true, &sides[1])) {
    c.exclude = 3;
    return false;
  }
  *cols = ContactColumns(m, sides, index);
  if (sparse && cols->n == 0) {
    c.exclude = 3;
    return false;
  }
  return true;
}

// One contact's rows: frictionless (1 row), a pyramid (a pair of opposing edges per
// friction direction: normal +- mu_k tangent_k) or an elliptic cone (dim rows).
void ContactRowsOf(const Model& m, Data& d, int i, double* jac, double* edges, double* scratch,
                   const ContactSide* sides, Columns cols) {
  Contact& c = d.contact[i];
  int n = cols.n;
  ContactJacobian(m, d, c, cols, jac, scratch, sides);
  if (c.dim == 1) {
    AddRows(m, d, jac, cols, &c.dist, c.includemargin, 0, 1, kCnstrContactFrictionless, i);
  } else if (m.opt.cone == kConePyramidal) {
    double pos[2] = {c.dist, c.dist};
    for (int k = 1; k < c.dim; k++) {
      double mu = c.friction[k - 1];
      for (int v = 0; v < n; v++) {
        edges[v] = jac[v] + mu * jac[k * n + v];
        edges[n + v] = jac[v] - mu * jac[k * n + v];
      }
      AddRows(m, d, edges, cols, pos, c.includemargin, 0, 2, kCnstrContactPyramidal, i);
    }
  } else {
    // Only the normal row has a distance and a margin.
    double pos[6] = {c.dist, 0, 0, 0, 0, 0};
    int first = d.nefc;
    AddRows(m, d, jac, cols, pos, 0, 0, c.dim, kCnstrContactElliptic, i);
    d.efc_margin[first] = c.includemargin;
  }
}

// Rows of every contact not excluded by its gap (MuJoCo mj_instantiateContact).
void ContactRows(const Model& m, Data& d) {
  if ((m.opt.disableflags & kDisableContact) || d.ncon == 0) return;
  // Contacts of passive flexes make no rows (MuJoCo marks them while counting rows).
  for (int i = 0; i < d.ncon && m.nflex > 0; i++) {
    Contact& c = d.contact[i];
    if (ContactOnPassiveFlex(m, c)) {
      c.efc_address = -1;
      c.exclude = 4;
    }
  }
  if (m.nv == 0) return;
  // (each contact writes the parts of these it reads: ContactJacobian)
  StackFrame frame(d);
  double* jac = frame.AllocToWrite(6 * static_cast<size_t>(m.nv));
  double* edges = frame.AllocToWrite(2 * static_cast<size_t>(m.nv));
  double* scratch = frame.AllocToWrite(12 * static_cast<size_t>(m.nv));
  SolverFrame ints(d.solver_scratch);
  int* index = ints.Ints(m.nv);
  bool sparse = SparseJacobian(m);
  for (int i = 0; i < d.ncon; i++) {
    Contact& c = d.contact[i];
    if (c.exclude) continue;
    // (a side not on bodies, or no dofs under a sparse Jacobian: no rows)
    ContactSide sides[2];
    Columns cols{nullptr, 0};
    if (!ContactColumnsOf(m, d, c, sparse, index, sides, &cols)) {
      c.efc_address = -1;
      continue;
    }
    c.efc_address = d.nefc;
    ContactRowsOf(m, d, i, jac, edges, scratch, sides, cols);
  }
}

// ---------------------------------------------------------------- softness

// Inverse weight of one side of a joint or tendon coupling.
double CouplingWeight(const Model& m, int eq, int obj) {
  return m.eq_type[eq] == kEqJoint ? m.dof_invweight0[m.jnt_dofadr[obj]]
                                   : m.tendon_invweight0[obj];
}

// diagApprox of the rows of the contact starting at row i, from the translational and
// rotational inverse weights of both bodies; returns its number of rows.
int ContactDiagApprox(const Model& m, Data& d, int i) {
  const Contact& c = d.contact[d.efc_id[i]];
  // Both sides' bodies' inverse weights, weighted (a flex element's vertices).
  double tran = 0, rot = 0;
  for (int k = 0; k < 2; k++) {
    ContactSide side;
    ContactSideBodies(m, d, c, k, false, &side);
    for (int j = 0; j < side.n; j++) {
      tran += m.body_invweight0[2 * side.body[j]] * side.weight[j];
      rot += m.body_invweight0[2 * side.body[j] + 1] * side.weight[j];
    }
  }
  double* diag = &d.efc_diagApprox[i];
  if (d.efc_type[i] == kCnstrContactFrictionless) {
    diag[0] = tran;
    return 1;
  }
  if (d.efc_type[i] == kCnstrContactElliptic) {
    for (int j = 0; j < c.dim; j++) diag[j] = j < 3 ? tran : rot;
    return c.dim;
  }
  // Pyramid edge pairs: the normal plus the friction-scaled tangential weight.
  for (int j = 0; j < c.dim - 1; j++) {
    double mu = c.friction[j];
    diag[2 * j] = diag[2 * j + 1] = tran + mu * mu * (j < 2 ? tran : rot);
  }
  return 2 * (c.dim - 1);
}

// efc_diagApprox: the inverse weights of what each row moves (MuJoCo mj_diagApprox).
void DiagApprox(const Model& m, Data& d) {
  for (int i = 0; i < d.nefc; i++) {
    int id = d.efc_id[i];
    double& diag = d.efc_diagApprox[i];
    switch (d.efc_type[i]) {
      case kCnstrEquality: {
        if (m.eq_type[id] == kEqConnect || m.eq_type[id] == kEqWeld) {
          // Rows 0-2 translate, rows 3-5 of a weld rotate.
          int rows = m.eq_type[id] == kEqWeld ? 6 : 3;
          int b0 = EqualityBody(m, id, 0), b1 = EqualityBody(m, id, 1);
          for (int r = 0; r < rows; r++) {
            int rot = r >= 3;
            d.efc_diagApprox[i + r] =
                m.body_invweight0[2 * b0 + rot] + m.body_invweight0[2 * b1 + rot];
          }
          i += rows - 1;
        } else if (m.eq_type[id] == kEqFlexVert) {
          // Two rows per vertex, weighed by the vertex body's translational weight.
          int f = m.eq_obj1id[id];
          for (int v = m.flex_vertadr[f]; v < m.flex_vertadr[f] + m.flex_vertnum[f]; v++) {
            double w = m.body_invweight0[2 * m.flex_vertbodyid[v]];
            d.efc_diagApprox[i++] = w;
            d.efc_diagApprox[i++] = w;
          }
          i--;
        } else if (m.eq_type[id] == kEqFlexStrain) {
          // One row per mode, each weighed by the element's nodes' mean weight.
          double w = FlexStrainInvWeight(m, id);
          int last = i;
          while (last + 1 < d.nefc && d.efc_type[last + 1] == kCnstrEquality &&
                 d.efc_id[last + 1] == id) {
            last++;
          }
          for (int r = i; r <= last; r++) d.efc_diagApprox[r] = w;
          i = last;
        } else if (m.eq_type[id] == kEqFlex) {
          // One row per movable edge, weighed by the edge's inverse weight.
          int f = m.eq_obj1id[id];
          for (int e = m.flex_edgeadr[f]; e < m.flex_edgeadr[f] + m.flex_edgenum[f]; e++) {
            if (!m.flexedge_rigid[e]) d.efc_diagApprox[i++] = m.flexedge_invweight0[e];
          }
          i--;
        } else {
          diag = CouplingWeight(m, id, m.eq_obj1id[id]);
          if (m.eq_obj2id[id] >= 0) diag += CouplingWeight(m, id, m.eq_obj2id[id]);
        }
        break;
      }
      case kCnstrFrictionDof: diag = m.dof_invweight0[id]; break;
      case kCnstrLimitJoint: diag = m.dof_invweight0[m.jnt_dofadr[id]]; break;
      case kCnstrFrictionTendon:
      case kCnstrLimitTendon: diag = m.tendon_invweight0[id]; break;
      default: i += ContactDiagApprox(m, d, i) - 1; break;
    }
  }
}

// A solref made safe: mixed standard/direct form falls back to `fallback`; a time
// constant is kept at least two time steps unless refsafe is disabled.
void SafeSolref(const Model& m, double* solref, const double* fallback) {
  if ((solref[0] > 0) != (solref[1] > 0)) std::copy_n(fallback, kNRef, solref);
  if (!(m.opt.disableflags & kDisableRefsafe) && solref[0] > 0) {
    solref[0] = std::max(solref[0], 2 * m.opt.timestep);
  }
}

// solref, solreffriction (contacts only, else zero) and solimp of row i, made safe as
// MuJoCo does (getsolparam).
void SolverParams(const Model& m, const Data& d, int i, double* solref, double* solreffriction,
                  double* solimp) {
  int id = d.efc_id[i];
  const double* ref = nullptr;
  const double* imp = nullptr;
  std::fill_n(solreffriction, kNRef, 0.0);
  switch (d.efc_type[i]) {
    case kCnstrEquality: ref = &m.eq_solref[kNRef * id]; imp = &m.eq_solimp[kNImp * id]; break;
    case kCnstrLimitJoint: ref = &m.jnt_solref[kNRef * id]; imp = &m.jnt_solimp[kNImp * id]; break;
    case kCnstrFrictionDof: ref = &m.dof_solref[kNRef * id]; imp = &m.dof_solimp[kNImp * id]; break;
    case kCnstrLimitTendon:
      ref = &m.tendon_solref_lim[kNRef * id];
      imp = &m.tendon_solimp_lim[kNImp * id];
      break;
    case kCnstrFrictionTendon:
      ref = &m.tendon_solref_fri[kNRef * id];
      imp = &m.tendon_solimp_fri[kNImp * id];
      break;
    default:
      ref = d.contact[id].solref;
      imp = d.contact[id].solimp;
      std::copy_n(d.contact[id].solreffriction, kNRef, solreffriction);
      break;
  }
  std::copy_n(ref, kNRef, solref);
  std::copy_n(imp, kNImp, solimp);

  const double kDefaultSolref[kNRef] = {0.02, 1};
  const double kZeroSolref[kNRef] = {0, 0};
  SafeSolref(m, solref, kDefaultSolref);
  SafeSolref(m, solreffriction, kZeroSolref);
  solimp[0] = std::clamp(solimp[0], kMinImp, kMaxImp);
  solimp[1] = std::clamp(solimp[1], kMinImp, kMaxImp);
  solimp[2] = std::max(0.0, solimp[2]);
  solimp[3] = std::clamp(solimp[3], kMinImp, kMaxImp);
  solimp[4] = std::max(1.0, solimp[4]);
}

// a^b, exact for the common powers 1 and 2.
double Power(double a, double b) {
  if (b == 1) return a;
  if (b == 2) return a * a;
  return std::pow(a, b);
}

}  // namespace

int EqualityBody(const Model& m, int eq, int j) {
  int obj = j == 0 ? m.eq_obj1id[eq] : m.eq_obj2id[eq];
  return m.eq_objtype[eq] == kObjSite ? m.site_bodyid[obj] : obj;
}

// The impedance d(r) of solimp at violation r = pos - margin, and its slope.
void Impedance(const double* solimp, double pos, double margin, double* imp, double* slope) {
  double dmin = solimp[0], dmax = solimp[1], width = solimp[2];
  double mid = solimp[3], power = solimp[4];
  *slope = 0;
  if (dmin == dmax || width <= kMinVal) {
    *imp = 0.5 * (dmin + dmax);
    return;
  }
  double x = (pos - margin) / width;
  double sign = x < 0 ? -1 : 1;
  x = std::abs(x);
  if (x >= 1 || x <= 0) {
    *imp = x >= 1 ? dmax : dmin;
    return;
  }

  // The sigmoid: linear, or two power curves meeting at the midpoint.
  double y, dy;
  if (power == 1) {
    y = x;
    dy = 1;
  } else if (x <= mid) {
    double a = 1 / Power(mid, power - 1);
    y = a * Power(x, power);
    dy = power * a * Power(x, power - 1);
  } else {
    double b = 1 / Power(1 - mid, power - 1);
    y = 1 - b * Power(1 - x, power);
    dy = power * b * Power(1 - x, power - 1);
  }
  *imp = dmin + y * (dmax - dmin);
  *slope = dy * sign * (dmax - dmin) / width;
}

namespace {

// Position and dimension of the constraint starting at row i: connect and weld use the
// norm of their error vector for the impedance of all their rows.
int RowGroup(const Model& m, const Data& d, int i, double* pos) {
  *pos = d.efc_pos[i];
  if (d.efc_type[i] == kCnstrContactElliptic) return d.contact[d.efc_id[i]].dim;
  if (d.efc_type[i] == kCnstrContactPyramidal) return 2 * (d.contact[d.efc_id[i]].dim - 1);
  if (d.efc_type[i] != kCnstrEquality) return 1;
  int type = m.eq_type[d.efc_id[i]];
  int dim = type == kEqWeld ? 6 : type == kEqConnect ? 3 : 1;
  if (dim > 1) {
    double s = 0;
    for (int r = 0; r < dim; r++) s += d.efc_pos[i + r] * d.efc_pos[i + r];
    *pos = std::sqrt(s);
  }
  return dim;
}

// efc_KBIP of row r: stiffness K and damping B from solref (standard form: time
// constant and damping ratio; direct form: -stiffness, -damping), impedance and slope.
// Friction-loss rows and the frictional rows of elliptic contacts have no stiffness.
void SetKBIP(Data& d, int r, bool no_stiffness, const double* ref, const double* solimp,
             double imp, double slope) {
  double* kbip = &d.efc_KBIP[4 * r];
  double dmax = solimp[1];
  if (no_stiffness) {
    kbip[0] = 0;
  } else if (ref[0] > 0) {
    kbip[0] = 1 / std::max(kMinVal, dmax * dmax * ref[0] * ref[0] * ref[1] * ref[1]);
  } else {
    kbip[0] = -ref[0] / std::max(kMinVal, dmax * dmax);
  }
  kbip[1] = ref[1] > 0 ? 2 / std::max(kMinVal, dmax * ref[0]) : -ref[1] / std::max(kMinVal, dmax);
  kbip[2] = imp;
  kbip[3] = slope;
}

// Frictional contact rows: R of the first friction direction is the normal's divided
// by impratio, which sets the regularized cone's mu; elliptic rows scale the other
// directions by their friction, pyramid edges all share one R (MuJoCo's match of the
// two cone models). Returns the contact's number of rows.
int ContactFrictionR(const Model& m, Data& d, int i) {
  Contact& c = d.contact[d.efc_id[i]];
  double* R = &d.efc_R[i];
  R[1] = R[0] / std::max(kMinVal, m.opt.impratio);
  c.mu = c.friction[0] * std::sqrt(R[1] / R[0]);
  if (d.efc_type[i] == kCnstrContactElliptic) {
    for (int j = 1; j < c.dim - 1; j++) {
      R[j + 1] = R[1] * c.friction[0] * c.friction[0] / (c.friction[j] * c.friction[j]);
    }
    return c.dim;
  }
  double r_pyramid = 2 * c.mu * c.mu * R[0];
  for (int j = 0; j < 2 * (c.dim - 1); j++) R[j] = r_pyramid;
  return 2 * (c.dim - 1);
}

// efc_R, efc_D, efc_KBIP from solref/solimp; diagApprox then matches R (mj_makeImpedance).
void MakeImpedance(const Model& m, Data& d) {
  for (int i = 0; i < d.nefc;) {
    double solref[kNRef], solreffriction[kNRef], solimp[kNImp], pos, imp, slope;
    SolverParams(m, d, i, solref, solreffriction, solimp);
    int dim = RowGroup(m, d, i, &pos);
    Impedance(solimp, pos, d.efc_margin[i], &imp, &slope);
    bool use_friction_ref = solreffriction[0] != 0 || solreffriction[1] != 0;
    for (int r = i; r < i + dim; r++) {
      d.efc_R[r] = std::max(kMinVal, (1 - imp) * d.efc_diagApprox[r] / imp);
      int type = d.efc_type[r];
      bool elliptic_friction = type == kCnstrContactElliptic && r > i;
      bool friction = type == kCnstrFrictionDof || type == kCnstrFrictionTendon;
      const double* ref = elliptic_friction && use_friction_ref ? solreffriction : solref;
      SetKBIP(d, r, friction || elliptic_friction, ref, solimp, imp, slope);
    }
    i += dim;
  }
  for (int i = d.ne + d.nf; i < d.nefc; i++) {
    int type = d.efc_type[i];
    if (type == kCnstrContactPyramidal || type == kCnstrContactElliptic) {
      i += ContactFrictionR(m, d, i) - 1;
    }
  }
  for (int i = 0; i < d.nefc; i++) {
    d.efc_D[i] = 1 / d.efc_R[i];
    double imp = d.efc_KBIP[4 * i + 2];
    d.efc_diagApprox[i] = d.efc_R[i] * imp / (1 - imp);
  }
}

}  // namespace

void MakeConstraint(const Model& m, Data& d) {
  d.ne = d.nf = d.nl = d.nefc = d.nJ = 0;
  if (m.opt.disableflags & kDisableConstraint) return;
  EqualityRows(m, d);
  FrictionRows(m, d);
  LimitRows(m, d);
  ContactRows(m, d);
  if (d.nefc == 0) return;
  DiagApprox(m, d);
  MakeImpedance(m, d);
}

void PassiveContactForces(const Model& m, Data& d) {
  if ((m.opt.disableflags & kDisableContact) || d.ncon == 0 || m.nv == 0) return;
  constexpr double kContactStiffness = 1e4;
  StackFrame frame(d);
  double* jac = nullptr;
  double* scratch = nullptr;
  int* index = nullptr;
  SolverFrame ints(d.solver_scratch);
  bool sparse = SparseJacobian(m);
  for (int i = 0; i < d.ncon; i++) {
    Contact& c = d.contact[i];
    if (c.exclude != 4) continue;
    if (!jac) {
      jac = frame.AllocToWrite(6 * static_cast<size_t>(m.nv));
      scratch = frame.AllocToWrite(12 * static_cast<size_t>(m.nv));
      index = ints.Ints(m.nv);
    }
    c.efc_address = -1;
    ContactSide sides[2];
    Columns cols{nullptr, 0};
    if (!ContactColumnsOf(m, d, c, sparse, index, sides, &cols)) continue;
    // The normal row only: a spring pushing the sides apart.
    ContactJacobian(m, d, c, cols, jac, scratch, sides);
    double scale = -kContactStiffness * c.dist;
    for (int k = 0; k < cols.n; k++) d.qfrc_spring[cols.dof[k]] += jac[k] * scale;
  }
}

void ReferenceConstraint(const Model& m, Data& d) {
  for (int i = 0; i < d.nefc; i++) {
    double vel = EfcRowDot(m, d, i, d.qvel.data());
    d.efc_vel[i] = vel;
    const double* kbip = &d.efc_KBIP[4 * i];
    d.efc_aref[i] = -kbip[1] * vel - kbip[0] * kbip[2] * (d.efc_pos[i] - d.efc_margin[i]);
  }
}

}  // namespace simlab
