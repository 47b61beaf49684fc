// geom_fluid: the per-geom numbers of MuJoCo's ellipsoid fluid model (user_objects.cc,
// mjCGeom::SetFluidCoefs; doc/computation/fluid.rst). A row of kNFluid numbers:
//
//   [0]     1 when the geom uses the ellipsoid model (fluidshape="ellipsoid"), else 0
//   [1..5]  fluidcoef: blunt drag, slender drag, angular drag, Kutta lift, Magnus lift
//   [6..8]  virtual (added) mass per unit fluid density, along the ellipsoid axes
//   [9..11] virtual moment of inertia per unit fluid density
//
// The ellipsoid has the geom's semi-axes (sphere r r r, capsule r r r+h, cylinder r r h,
// otherwise size). With kappa_i = integral over l in [0, inf) of
//   d_x d_y d_z / sqrt((d_i^2 + l)^3 (d_j^2 + l) (d_k^2 + l)),
// the added mass is V kappa_i / (2 - kappa_i) and the added inertia about x is
//   V/5 (d_y^2 - d_z^2)^2 |k_z - k_y| / |2 (d_y^2 - d_z^2) + (d_y^2 + d_z^2)(k_y - k_z)|.
// kappa comes from the same 15-point Gauss-Kronrod rule MuJoCo uses, after the change of
// variables l = x^3 / (1 - x)^2, so the numbers agree to the last bit.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "compiler/compiler.h"
#include "engine/engine.h"

namespace simlab::compiler {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = 1e-14;  // the compiler's mjEPS: smallest denominator here

// Quadrature weights, abscissae l(x) and dl/dx at the 15 Kronrod points of [0, 1].
constexpr double kKronrodWeight[15] = {
    0.01146766, 0.03154605, 0.05239501, 0.07032663, 0.08450236,
    0.09517529, 0.10221647, 0.10474107, 0.10221647, 0.09517529,
    0.08450236, 0.07032663, 0.05239501, 0.03154605, 0.01146766};
constexpr double kKronrodLambda[15] = {
    7.865151709349917e-08, 1.7347976913907274e-05, 0.0003548008144506193,
    0.002846636252924549, 0.014094260903596077, 0.053063261727396636,
    0.17041978741317773, 0.5, 1.4036301548686991, 3.9353484827022642,
    11.644841677041734, 39.53187807410903, 177.5711362220801,
    1429.4772912937397, 54087.416549217705};
constexpr double kKronrodSlope[15] = {
    5.538677720489877e-05, 0.002080868285293228, 0.016514126520723166,
    0.07261900344370877, 0.23985243401862602, 0.6868318249020725,
    1.8551129519182894, 5.0, 14.060031152313941, 43.28941239611009,
    156.58546376397112, 747.9826085305024, 5827.4042950027115,
    116754.0197944512, 25482945.327264845};

double Square(double x) { return x * x; }

// kappa along the first axis (symmetric in the last two).
double AddedMassKappa(double dx, double dy, double dz) {
  double inv_x2 = 1.0 / (dx * dx), inv_y2 = 1.0 / (dy * dy), inv_z2 = 1.0 / (dz * dz);

  // l is measured in units of d^2 (scale), which keeps the sum well conditioned.
  double scale = std::pow(dx * dx * dx * dy * dz, 0.4);
  double kappa = 0;
  for (int i = 0; i < 15; i++) {
    double lambda = scale * kKronrodLambda[i];
    double fx = 1 + lambda * inv_x2;
    double denom = fx * std::sqrt(fx * (1 + lambda * inv_y2) * (1 + lambda * inv_z2));
    kappa += scale * kKronrodSlope[i] / denom * kKronrodWeight[i];
  }
  return kappa * inv_x2;
}

// Added inertia factor about the axis whose other two semi-axes are a, b (kappas ka, kb).
double AddedInertiaFactor(double a, double b, double ka, double kb) {
  double diff = a * a - b * b;
  return Square(diff) * std::abs(kb - ka) /
         std::max(kEps, std::abs(2 * diff + (a * a + b * b) * (ka - kb)));
}

}  // namespace

void GeomFluid(const GeomState& g, double* fluid) {
  std::fill(fluid, fluid + kNFluid, 0.0);
  const mjcf::GeomSpec& s = *g.spec;
  if (!s.fluid_ellipsoid) return;
  fluid[0] = 1;
  for (int k = 0; k < 5; k++) fluid[1 + k] = s.fluidcoef[k];

  // The equivalent ellipsoid and its kappas.
  double d[3];
  GeomSemiAxes(s.type, g.size, d);
  double volume = 4.0 / 3.0 * kPi * d[0] * d[1] * d[2];
  double kx = AddedMassKappa(d[0], d[1], d[2]);
  double ky = AddedMassKappa(d[1], d[2], d[0]);
  double kz = AddedMassKappa(d[2], d[0], d[1]);

  // Added mass along each axis, then added inertia about each axis.
  fluid[6] = volume * kx / std::max(kEps, 2 - kx);
  fluid[7] = volume * ky / std::max(kEps, 2 - ky);
  fluid[8] = volume * kz / std::max(kEps, 2 - kz);
  fluid[9] = volume * AddedInertiaFactor(d[1], d[2], ky, kz) / 5;
  fluid[10] = volume * AddedInertiaFactor(d[2], d[0], kz, kx) / 5;
  fluid[11] = volume * AddedInertiaFactor(d[0], d[1], kx, ky) / 5;
}

}  // namespace simlab::compiler
