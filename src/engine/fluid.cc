// Fluid forces (MuJoCo engine_passive.c mj_fluid; doc/computation/fluid.rst), part of
// the passive forces, and their velocity derivative for the implicit integrators
// (engine_derivative.c mjd_inertiaBoxFluid, mjd_ellipsoidFluid).
//
// A body moves through a medium of density rho and viscosity beta that itself moves
// with the uniform velocity `wind`. Every body with mass feels, in a frame attached to
// it, a force f and torque t from its velocity relative to the medium (w, v), applied
// at that frame's origin and mapped to joint space (qfrc_fluid) by the Jacobian there.
// Two models:
//
// Inertia box (default): the body is the box with its inertia, sides b = sqrt(6 (I_j +
// I_k - I_i) / mass), frame at the centre of mass, principal axes:
//   f_i = -3 pi d beta v_i - rho/2 b_j b_k |v_i| v_i                 d = mean of b
//   t_i = -pi d^3 beta w_i - rho/64 b_i (b_j^4 + b_k^4) |w_i| w_i
//
// Ellipsoid (any geom of the body with fluidshape="ellipsoid"): each such geom is an
// ellipsoid with semi-axes s, frame at the geom; with the coefficients of geom_fluid
// (compiler/fluid.cc) the force sums added mass (the momentum of the entrained fluid,
// rho m_a v and rho I_a w, crossed with the velocities), Magnus lift
// c_M rho V (w x v), Kutta-Joukowski lift, and linear (Stokes) plus quadratic drag
// whose area is the ellipsoid's projection along v; the torque has linear and
// quadratic angular drag.
//
// Derivatives: qDeriv += J^T B J with J the 6 x nv Jacobian (rotation, then
// translation) in the local frame and B = d(t, f) / d(w, v), a 6x6 matrix; diagonal for
// the box, full for the ellipsoid (symmetrized under implicitfast, as MuJoCo does).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "engine/constraint.h"
#include "engine/engine.h"
#include "engine/free_body_implicit.h"
#include "engine/stack.h"
#include "math/math.h"

namespace simlab {

using namespace math;

namespace {

constexpr double kPi = std::numbers::pi;

double Square(double x) { return x * x; }
double Pow4(double x) { return (x * x) * (x * x); }

// ------------------------------------------------------------ shared pieces

// True when body i feels the fluid (it has mass).
bool InFluid(const Model& m, int i) { return m.body_mass[i] >= kMinVal; }

// True when some geom of body i asks for the ellipsoid model.
bool UsesEllipsoid(const Model& m, int i) {
  for (int g = m.body_geomadr[i]; g < m.body_geomadr[i] + m.body_geomnum[i]; g++) {
    if (m.geom_fluid[kNFluid * g] > 0) return true;
  }
  return false;
}

// The 6D velocity (w, v) of a frame at `pos` with orientation `rot` that moves with
// `body`, in that frame's coordinates, relative to the wind (MuJoCo mj_objectVelocity,
// local).
void RelativeVelocity(const Model& m, const Data& d, int body, const double* pos,
                      const double* rot, double* lvel) {
  if (m.body_weldid[body] == 0) {
    std::fill(lvel, lvel + 6, 0.0);
  } else {
    const double* com = &d.subtree_com[3 * m.body_rootid[body]];
    TransformSpatial(lvel, &d.cvel[6 * body], false, pos, com, rot);
  }
  double lwind[3];
  MulMatTVec3(lwind, rot, m.opt.wind.data());
  for (int k = 0; k < 3; k++) lvel[3 + k] -= lwind[k];
}

// qfrc_fluid += J^T (force, torque) for a local (torque, force) pair in frame `rot`
// at `point` on `body` (MuJoCo mj_applyFT).
void ApplyLocalWrench(const Model& m, Data& d, const double* lfrc, const double* rot,
                      const double* point, int body) {
  double torque[3], force[3];
  MulMatVec3(torque, rot, lfrc);
  MulMatVec3(force, rot, lfrc + 3);
  ApplyForceTorque(m, d, force, torque, point, body, d.qfrc_fluid.data());
}

// Sides of body i's equivalent inertia box.
void InertiaBox(const Model& m, int i, double* box) {
  const double* inertia = &m.body_inertia[3 * i];
  for (int k = 0; k < 3; k++) {
    double sum = inertia[(k + 1) % 3] + inertia[(k + 2) % 3] - inertia[k];
    box[k] = std::sqrt(std::max(kMinVal, sum) / m.body_mass[i] * 6.0);
  }
}

// The two axes other than k, in increasing order.
int LowerOther(int k) { return k == 0 ? 1 : 0; }
int UpperOther(int k) { return k == 2 ? 1 : 2; }

// Quadratic drag coefficients of the box, torque then force: lfrc -= coef |vel| vel
// (the torque's coefficient is further divided by 64).
void BoxQuadraticCoefs(const Model& m, const double* box, double* coef) {
  double rho = m.opt.density;
  for (int k = 0; k < 3; k++) {
    double lo = box[LowerOther(k)], hi = box[UpperOther(k)];
    coef[k] = rho * box[k] * (lo * lo * lo * lo + hi * hi * hi * hi);
    coef[3 + k] = 0.5 * rho * lo * hi;
  }
}

// Stokes drag coefficients of the box's sphere (diameter: the mean side), torque then
// force: lfrc = coef vel.
void BoxStokesCoefs(const Model& m, const double* box, double* coef) {
  double diam = (box[0] + box[1] + box[2]) / 3.0;
  for (int k = 0; k < 3; k++) coef[k] = -kPi * diam * diam * diam * m.opt.viscosity;
  for (int k = 0; k < 3; k++) coef[3 + k] = -3.0 * kPi * diam * m.opt.viscosity;
}

// The local (torque, force) the box model puts on body i.
void InertiaBoxWrench(const Model& m, const double* box, const double* lvel, double* lfrc) {
  std::fill(lfrc, lfrc + 6, 0.0);

  // Stokes drag of the sphere with the box's mean side.
  if (m.opt.viscosity > 0) {
    double coef[6];
    BoxStokesCoefs(m, box, coef);
    for (int k = 0; k < 6; k++) lfrc[k] = lvel[k] * coef[k];
  }

  // Quadratic drag of the box faces.
  if (m.opt.density > 0) {
    double coef[6];
    BoxQuadraticCoefs(m, box, coef);
    for (int k = 0; k < 3; k++) lfrc[3 + k] -= coef[3 + k] * std::abs(lvel[3 + k]) * lvel[3 + k];
    for (int k = 0; k < 3; k++) lfrc[k] -= coef[k] * std::abs(lvel[k]) * lvel[k] / 64.0;
  }
}

void InertiaBoxForce(const Model& m, Data& d, int i) {
  double box[3], lvel[6], lfrc[6];
  InertiaBox(m, i, box);
  RelativeVelocity(m, d, i, &d.xipos[3 * i], &d.ximat[9 * i], lvel);
  InertiaBoxWrench(m, box, lvel, lfrc);
  ApplyLocalWrench(m, d, lfrc, &d.ximat[9 * i], &d.xipos[3 * i], i);
}

// ------------------------------------------------------------ ellipsoid model

// A geom's row of geom_fluid, by name.
struct EllipsoidCoefs {
  double scale, blunt, slender, angular, kutta, magnus;
  const double* added_mass;     // 3
  const double* added_inertia;  // 3
};

EllipsoidCoefs ReadCoefs(const Model& m, int g) {
  const double* f = &m.geom_fluid[kNFluid * g];
  return {f[0], f[1], f[2], f[3], f[4], f[5], f + 6, f + 9};
}

// Shape numbers of an ellipsoid with semi-axes s, shared by the force and derivative.
struct EllipsoidShape {
  double volume, area_max, stokes_force, stokes_torque, moment_max;
  double moment[3];  // largest moment of the ellipsoid about each axis
};

EllipsoidShape Shape(const double* s) {
  EllipsoidShape e;
  double d_max = std::max(std::max(s[0], s[1]), s[2]);
  double d_min = std::min(std::min(s[0], s[1]), s[2]);
  double d_mid = s[0] + s[1] + s[2] - d_max - d_min;
  double sphere_diam = 2.0 / 3.0 * (s[0] + s[1] + s[2]);
  e.volume = 4.0 / 3.0 * kPi * s[0] * s[1] * s[2];
  e.area_max = kPi * d_max * d_mid;
  e.stokes_force = 3.0 * kPi * sphere_diam;
  e.stokes_torque = kPi * sphere_diam * sphere_diam * sphere_diam;
  e.moment_max = 8.0 / 15.0 * kPi * d_mid * Pow4(d_max);
  for (int k = 0; k < 3; k++) {
    double other = std::max(s[(k + 1) % 3], s[(k + 2) % 3]);
    e.moment[k] = 8.0 / 15.0 * kPi * s[k] * Pow4(other);
  }
  return e;
}

// Angular drag coefficient per axis: blends the angular and slender coefficients.
void AngularDragCoefs(const EllipsoidShape& e, const EllipsoidCoefs& c, double* coef) {
  for (int k = 0; k < 3; k++) {
    coef[k] = c.angular * e.moment[k] + c.slender * (e.moment_max - e.moment[k]);
  }
}

// The entrained fluid's momentum crossed with the velocities (MuJoCo mj_addedMassForces
// without the acceleration term).
void AddedMassWrench(const double* lvel, double rho, const EllipsoidCoefs& c, double* lfrc) {
  const double* w = lvel;
  const double* v = lvel + 3;
  double lin_mom[3], ang_mom[3];
  for (int k = 0; k < 3; k++) {
    lin_mom[k] = rho * c.added_mass[k] * v[k];
    ang_mom[k] = rho * c.added_inertia[k] * w[k];
  }
  double force[3], torque_lin[3], torque_ang[3];
  Cross3(force, lin_mom, w);
  Cross3(torque_lin, lin_mom, v);
  Cross3(torque_ang, ang_mom, w);
  for (int k = 0; k < 3; k++) lfrc[k] += torque_lin[k];
  for (int k = 0; k < 3; k++) lfrc[k] += torque_ang[k];
  for (int k = 0; k < 3; k++) lfrc[3 + k] += force[k];
}

// Projection of the ellipsoid along v: a_i = (s_j s_k)^2, num = sum a_i v_i^2,
// den = sum a_i^2 v_i^2; projected area pi sqrt(den / num).
struct Projection {
  double a[3], num, den, area;
};

// The force squares s_j s_k v_i in num; the derivatives, written in a_i, take a_i v_i^2
// (MuJoCo rounds them so; so do we).
Projection Project(const double* s, const double* v, bool derivative_form = false) {
  Projection p;
  for (int k = 0; k < 3; k++) p.a[k] = Square(s[(k + 1) % 3] * s[(k + 2) % 3]);
  p.den = Pow4(s[1] * s[2]) * Square(v[0]) + Pow4(s[2] * s[0]) * Square(v[1]) +
          Pow4(s[0] * s[1]) * Square(v[2]);
  if (derivative_form) {
    p.num = p.a[0] * Square(v[0]) + p.a[1] * Square(v[1]) + p.a[2] * Square(v[2]);
  } else {
    p.num = Square(s[1] * s[2] * v[0]) + Square(s[2] * s[0] * v[1]) + Square(s[0] * s[1] * v[2]);
  }
  p.area = kPi * std::sqrt(p.den / std::max(kMinVal, p.num));
  return p;
}

// Lift and drag of the moving ellipsoid (MuJoCo mj_viscousForces).
void ViscousWrench(const Model& m, const double* lvel, const double* s, const EllipsoidCoefs& c,
                   double* lfrc) {
  double rho = m.opt.density, beta = m.opt.viscosity;
  const double* w = lvel;
  const double* v = lvel + 3;
  EllipsoidShape e = Shape(s);

  // Magnus lift: c_M rho V (w x v).
  double magnus[3];
  Cross3(magnus, w, v);
  for (int k = 0; k < 3; k++) magnus[k] *= c.magnus * rho * e.volume;

  // Kutta lift: circulation (n x v) over the projected area, crossed with v.
  Projection p = Project(s, v);
  double normal[3] = {p.a[0] * v[0], p.a[1] * v[1], p.a[2] * v[2]};
  double cos_alpha = p.num / std::max(kMinVal, Norm3(v) * p.den);
  double circulation[3], kutta[3];
  Cross3(circulation, normal, v);
  for (int k = 0; k < 3; k++) circulation[k] *= c.kutta * rho * cos_alpha * p.area;
  Cross3(kutta, circulation, v);

  // Linear (Stokes) plus quadratic drag, of translation and of rotation.
  double ang_coef[3], mom_visc[3];
  AngularDragCoefs(e, c, ang_coef);
  for (int k = 0; k < 3; k++) mom_visc[k] = w[k] * ang_coef[k];
  double drag_lin = beta * e.stokes_force +
                    rho * Norm3(v) * (p.area * c.blunt + c.slender * (e.area_max - p.area));
  double drag_ang = beta * e.stokes_torque + rho * Norm3(mom_visc);
  for (int k = 0; k < 3; k++) lfrc[k] -= drag_ang * w[k];
  for (int k = 0; k < 3; k++) lfrc[3 + k] += magnus[k] + kutta[k] - drag_lin * v[k];
}

void EllipsoidForce(const Model& m, Data& d, int body) {
  for (int g = m.body_geomadr[body]; g < m.body_geomadr[body] + m.body_geomnum[body]; g++) {
    EllipsoidCoefs c = ReadCoefs(m, g);
    if (c.scale == 0) continue;
    double s[3], lvel[6], lfrc[6] = {0, 0, 0, 0, 0, 0};
    GeomSemiAxes(m.geom_type[g], &m.geom_size[3 * g], s);
    const double* rot = &d.geom_xmat[9 * g];
    RelativeVelocity(m, d, body, &d.geom_xpos[3 * g], rot, lvel);
    AddedMassWrench(lvel, m.opt.density, c, lfrc);
    ViscousWrench(m, lvel, s, c, lfrc);
    for (int k = 0; k < 6; k++) lfrc[k] *= c.scale;
    ApplyLocalWrench(m, d, lfrc, rot, &d.geom_xpos[3 * g], body);
  }
}

// ------------------------------------------------------------ derivatives

// The 6 x n Jacobian (rotation rows, then translation rows) of a frame at `point` on
// `body`, expressed in the frame's axes `rot`, on the n dofs that move the body (the
// other columns are zero), with where each (dof, dof) pair of the chain sits in qDeriv.
struct ChainJacobian {
  int n = 0;
  int* dofs = nullptr;    // ascending dof indices, n of them
  double* jac = nullptr;  // 6 x n, row-major
  int* deriv = nullptr;   // n x n: qDeriv address of (dofs[c], dofs[p])
};

// The qDeriv addresses of the chain's pairs: row dofs[c] of D holds every dof of the
// chain (ascending, as `dofs`), found by one walk along the row.
void ChainDerivAddresses(const Model& m, ChainJacobian& chain) {
  int n = chain.n;
  for (int c = 0; c < n; c++) {
    int adr = m.D_rowadr[chain.dofs[c]];
    for (int p = 0; p < n; p++) {
      while (m.D_colind[adr] < chain.dofs[p]) adr++;
      chain.deriv[c * n + p] = adr;
    }
  }
}

ChainJacobian LocalJacobian(const Model& m, Data& d, StackFrame& frame, SolverFrame& ints,
                            const double* point, const double* rot, int body) {
  ChainJacobian chain;
  chain.dofs = ints.IntsToWrite(m.nv);
  chain.n = MergedDofChain(m, body, body, chain.dofs);
  int n = chain.n;
  chain.deriv = ints.IntsToWrite(static_cast<size_t>(n) * n);
  ChainDerivAddresses(m, chain);
  chain.jac = frame.Alloc(6 * n);
  StackFrame scratch(d);
  double* world = scratch.Alloc(6 * n);
  JacobianOnDofs(m, d, chain.dofs, n, world + 3 * n, world, point, body);
  for (int half = 0; half < 2; half++) {
    const double* src = world + 3 * half * n;
    double* dst = chain.jac + 3 * half * n;
    for (int r = 0; r < 3; r++) {
      for (int c = 0; c < n; c++) {
        dst[r * n + c] = rot[r] * src[c] + rot[3 + r] * src[n + c] + rot[6 + r] * src[2 * n + c];
      }
    }
  }
  return chain;
}

// qDeriv += J^T B J for B (k x k) and the rows [row0, row0 + k) of a chain Jacobian.
void AddJacTBJac(Data& d, const ChainJacobian& chain, int row0, const double* b,
                 int k) {
  int n = chain.n;
  const double* jac = chain.jac + row0 * n;
  for (int i = 0; i < k; i++) {
    for (int j = 0; j < k; j++) {
      if (b[i * k + j] == 0) continue;
      for (int c = 0; c < n; c++) {
        if (jac[i * n + c] == 0) continue;
        double scale = jac[i * n + c] * b[i * k + j];
        const int* deriv = chain.deriv + c * n;
        for (int p = 0; p < n; p++) d.qDeriv[deriv[p]] += jac[j * n + p] * scale;
      }
    }
  }
}

// B (6x6, row-major): block (row_block, col_block) += D (3x3).
void AddBlock(double* b, const double* dmat, int row_block, int col_block) {
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) b[6 * (3 * row_block + i) + 3 * col_block + j] += dmat[3 * i + j];
  }
}

// Derivatives of a x b: da = d/da (= -[b]x), db = d/db (= [a]x).
void CrossDerivatives(const double* a, const double* b, double* da, double* db) {
  const double rows_a[9] = {0, b[2], -b[1], -b[2], 0, b[0], b[1], -b[0], 0};
  const double rows_b[9] = {0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0};
  std::copy(rows_a, rows_a + 9, da);
  std::copy(rows_b, rows_b + 9, db);
}

void InertiaBoxDerivative(const Model& m, Data& d, int i) {
  double box[3], lvel[6];
  InertiaBox(m, i, box);
  RelativeVelocity(m, d, i, &d.xipos[3 * i], &d.ximat[9 * i], lvel);
  StackFrame frame(d);
  SolverFrame ints(d.solver_scratch);
  ChainJacobian chain = LocalJacobian(m, d, frame, ints, &d.xipos[3 * i], &d.ximat[9 * i], i);

  // Each local component is damped on its own: B is diagonal, one row of J at a time.
  double slope[6] = {0, 0, 0, 0, 0, 0};
  if (m.opt.viscosity > 0) {
    BoxStokesCoefs(m, box, slope);
    for (int k = 0; k < 6; k++) AddJacTBJac(d, chain, k, &slope[k], 1);
  }
  if (m.opt.density > 0) {
    double coef[6];
    BoxQuadraticCoefs(m, box, coef);
    for (int k = 0; k < 3; k++) slope[k] = -coef[k] * 2 * std::abs(lvel[k]) / 64.0;
    for (int k = 0; k < 3; k++) slope[3 + k] = -coef[3 + k] * 2 * std::abs(lvel[3 + k]);
    for (int k = 0; k < 6; k++) AddJacTBJac(d, chain, k, &slope[k], 1);
  }
}

// d(added-mass wrench) / d(w, v) into B.
void AddedMassDerivative(const double* lvel, double rho, const EllipsoidCoefs& c, double* b) {
  const double* w = lvel;
  const double* v = lvel + 3;
  double lin_mom[3], ang_mom[3], da[9], db[9];
  for (int k = 0; k < 3; k++) {
    lin_mom[k] = rho * c.added_mass[k] * v[k];
    ang_mom[k] = rho * c.added_inertia[k] * w[k];
  }

  // Torque ang_mom x w: through w directly and through ang_mom.
  CrossDerivatives(ang_mom, w, da, db);
  AddBlock(b, db, 0, 0);
  for (int k = 0; k < 9; k++) da[k] *= rho * c.added_inertia[k % 3];
  AddBlock(b, da, 0, 0);

  // Torque lin_mom x v: through v directly and through lin_mom.
  CrossDerivatives(lin_mom, v, da, db);
  AddBlock(b, db, 0, 1);
  for (int k = 0; k < 9; k++) da[k] *= rho * c.added_mass[k % 3];
  AddBlock(b, da, 0, 1);

  // Force lin_mom x w: through w, and through lin_mom (that is, v).
  CrossDerivatives(lin_mom, w, da, db);
  AddBlock(b, db, 1, 0);
  for (int k = 0; k < 9; k++) da[k] *= rho * c.added_mass[k % 3];
  AddBlock(b, da, 1, 1);
}

// d(Magnus force) / d(w, v) into B.
void MagnusDerivative(const double* lvel, double rho, const EllipsoidShape& e,
                      const EllipsoidCoefs& c, double* b) {
  double coef = c.magnus * rho * e.volume;
  double w[3], v[3], dw[9], dv[9];
  for (int k = 0; k < 3; k++) {
    w[k] = coef * lvel[k];
    v[k] = coef * lvel[3 + k];
  }
  CrossDerivatives(w, v, dw, dv);
  AddBlock(b, dw, 1, 0);
  AddBlock(b, dv, 1, 1);
}

// d(Kutta lift) / dv (3x3), from the closed form of MuJoCo's derivation.
void KuttaDerivative(const double* v, double rho, const double* s, const EllipsoidCoefs& c,
                     double* dmat) {
  Projection p = Project(s, v, true);
  double norm2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  double scale = kPi * c.kutta * rho / std::max(kMinVal, std::sqrt(p.den * p.num * norm2));
  double proj_term = p.num / std::max(kMinVal, p.den);
  double cos_term = p.num / std::max(kMinVal, norm2);
  double row_coef[3], inner[3];
  for (int i = 0; i < 3; i++) {
    int lo = LowerOther(i), hi = UpperOther(i);
    row_coef[i] = v[lo] * v[lo] * (p.a[i] - p.a[lo]) + v[hi] * v[hi] * (p.a[i] - p.a[hi]);
    inner[i] = p.a[i] * p.a[i] * proj_term - p.a[i] + cos_term;
  }
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      double entry = (p.a[j] - p.a[i]) * (2 * p.num);
      entry += inner[j] * row_coef[i];
      entry *= v[i] * v[j];
      if (i == j) entry -= row_coef[i] * p.num;
      dmat[3 * i + j] = entry * scale;
    }
  }
}

// d(translational drag) / dv (3x3).
void DragDerivative(const Model& m, const double* v, const double* s, const EllipsoidShape& e,
                    const EllipsoidCoefs& c, double* dmat) {
  double rho = m.opt.density;
  Projection p = Project(s, v, true);
  const double* a = p.a;
  double area_slope = kPi / std::max(kMinVal, std::sqrt(p.num * p.num * p.num * p.den));
  double norm = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double inv_norm = 1.0 / std::max(kMinVal, norm);
  double lin_coef = m.opt.viscosity * 3.0 * kPi * (2.0 / 3.0 * (s[0] + s[1] + s[2]));
  double quad_coef = rho * (p.area * c.blunt + c.slender * (e.area_max - p.area));
  double area_coef = rho * norm * (c.blunt - c.slender);

  // d(projected area)/dv, times the quadratic drag's weight.
  double darea[3];
  for (int i = 0; i < 3; i++) {
    int l = LowerOther(i), h = UpperOther(i);
    darea[i] = area_coef * area_slope * a[i] * v[i] *
               (a[l] * (v[l] * v[l]) * (a[i] - a[l]) + a[h] * (v[h] * v[h]) * (a[i] - a[h]));
  }

  // -quad (v v^T + |v|^2 I) / |v| - v darea^T - lin I.
  double inner = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) {
      double entry = v[i] * v[j] + (i == j ? inner : 0);
      entry *= -quad_coef * inv_norm;
      entry += darea[j] * -v[i];
      if (i == j) entry -= lin_coef;
      dmat[3 * i + j] = entry;
    }
  }
}

// d(angular drag torque) / dw (3x3).
void AngularDragDerivative(const Model& m, const double* w, const EllipsoidShape& e,
                           const EllipsoidCoefs& c, double* dmat) {
  double coef[3], mom_visc[3], mom_sq[3];
  AngularDragCoefs(e, c, coef);
  for (int k = 0; k < 3; k++) mom_visc[k] = w[k] * coef[k];
  double density = m.opt.density / std::max(kMinVal, Norm3(mom_visc));
  for (int k = 0; k < 3; k++) mom_sq[k] = -density * w[k] * coef[k] * coef[k];
  double lin_coef = m.opt.viscosity * e.stokes_torque;
  double diag = w[0] * mom_sq[0] + w[1] * mom_sq[1] + w[2] * mom_sq[2] - lin_coef;
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) dmat[3 * i + j] = (i == j ? diag : 0) + mom_sq[j] * w[i];
  }
}

// B <- (B + B^T) / 2 for a 6x6 B.
void Symmetrize6(double* b) {
  for (int i = 0; i < 6; i++) {
    for (int j = 0; j < i; j++) b[6 * i + j] = b[6 * j + i] = 0.5 * (b[6 * i + j] + b[6 * j + i]);
  }
}

void EllipsoidDerivative(const Model& m, Data& d, int body) {
  double rho = m.opt.density;
  for (int g = m.body_geomadr[body]; g < m.body_geomadr[body] + m.body_geomnum[body]; g++) {
    EllipsoidCoefs c = ReadCoefs(m, g);
    if (c.scale == 0) continue;
    double s[3], lvel[6];
    GeomSemiAxes(m.geom_type[g], &m.geom_size[3 * g], s);
    const double* rot = &d.geom_xmat[9 * g];
    RelativeVelocity(m, d, body, &d.geom_xpos[3 * g], rot, lvel);
    StackFrame frame(d);
    SolverFrame ints(d.solver_scratch);
    ChainJacobian chain = LocalJacobian(m, d, frame, ints, &d.geom_xpos[3 * g], rot, m.geom_bodyid[g]);

    // B = d(torque, force) / d(w, v), term by term.
    EllipsoidShape e = Shape(s);
    double b[36] = {0}, dmat[9];
    MagnusDerivative(lvel, rho, e, c, b);
    KuttaDerivative(lvel + 3, rho, s, c, dmat);
    AddBlock(b, dmat, 1, 1);
    DragDerivative(m, lvel + 3, s, e, c, dmat);
    AddBlock(b, dmat, 1, 1);
    AngularDragDerivative(m, lvel, e, c, dmat);
    AddBlock(b, dmat, 0, 0);
    AddedMassDerivative(lvel, rho, c, b);

    // implicitfast needs a symmetric qDeriv, but for a free body MuJoCo 3.12 solves on its
    // own (SolvesFreeBodiesApart).
    bool own = SolvesFreeBodiesApart(m) && IsStandaloneFreeBody(m, body);
    if (m.opt.integrator == kIntegratorImplicitFast && !own) Symmetrize6(b);
    AddJacTBJac(d, chain, 0, b, 6);
  }
}

// False when the fluid is off: no density and no viscosity, or no passive forces.
bool FluidActive(const Model& m) {
  if ((m.opt.disableflags & kDisableSpring) && (m.opt.disableflags & kDisableDamper)) return false;
  return m.opt.viscosity != 0 || m.opt.density != 0;
}

// Runs `ellipsoid` or `box` on each body with mass, by the model its geoms ask for.
void ForEachBodyInFluid(const Model& m, Data& d, void (*ellipsoid)(const Model&, Data&, int),
                        void (*box)(const Model&, Data&, int)) {
  for (int i = 0; i < m.nbody; i++) {
    if (!InFluid(m, i)) continue;
    if (UsesEllipsoid(m, i)) {
      ellipsoid(m, d, i);
    } else {
      box(m, d, i);
    }
  }
}

}  // namespace

void GeomSemiAxes(int type, const double* size, double* semiaxes) {
  switch (type) {
    case kGeomSphere:
      semiaxes[0] = semiaxes[1] = semiaxes[2] = size[0];
      break;
    case kGeomCapsule:
      semiaxes[0] = semiaxes[1] = size[0];
      semiaxes[2] = size[1] + size[0];
      break;
    case kGeomCylinder:
      semiaxes[0] = semiaxes[1] = size[0];
      semiaxes[2] = size[1];
      break;
    default:
      for (int k = 0; k < 3; k++) semiaxes[k] = size[k];
  }
}

void FluidForces(const Model& m, Data& d) {
  std::fill(d.qfrc_fluid.begin(), d.qfrc_fluid.end(), 0.0);
  if (!FluidActive(m)) return;
  ForEachBodyInFluid(m, d, EllipsoidForce, InertiaBoxForce);
  for (int v = 0; v < m.nv; v++) d.qfrc_passive[v] += d.qfrc_fluid[v];
}

void FluidDerivative(const Model& m, Data& d) {
  if (!FluidActive(m) || !(m.opt.viscosity > 0 || m.opt.density > 0)) return;
  ForEachBodyInFluid(m, d, EllipsoidDerivative, InertiaBoxDerivative);
}

}  // namespace simlab
