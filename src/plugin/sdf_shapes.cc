// MuJoCo's first-party signed distance field plugins (plugin/sdf there): the shapes
// mujoco.sdf.torus, .bolt, .nut, .gear and .bowl, each a distance function of the point
// in the geom's frame and the instance's attributes, the box that holds it, and its
// gradient (the torus's analytic, the others' by forward differences of step 1e-8, as
// MuJoCo's). The formulas and their order of operations are MuJoCo's, so that the
// fields agree with it to the bit; the trigonometric functions are simlab's (musl's).
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "math/elementary.h"
#include "simlab/plugin.h"

namespace simlab {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMinVal = 1e-15;  // mjMINVAL

// Constructive solid geometry on distances (min/max as MuJoCo's mju_min/mju_max).
double Min(double a, double b) { return a < b ? a : b; }
double Max(double a, double b) { return a > b ? a : b; }
double Union(double a, double b) { return Min(a, b); }
double Intersection(double a, double b) { return Max(a, b); }
double Subtraction(double a, double b) { return Max(a, -b); }
double Fract(double x) { return x - std::floor(x); }
double Norm2(double x, double y) { return std::sqrt(x * x + y * y); }

// A shape's distance at a point of its frame, for its attributes.
using DistanceFunction = double (*)(const double point[3], const double* attributes);

// Forward-difference gradient of `distance` with MuJoCo's step.
void DifferenceGradient(DistanceFunction distance, double gradient[3], const double p[3],
                        const double* attributes) {
  const double eps = 1e-8;
  double d0 = distance(p, attributes);
  for (int k = 0; k < 3; k++) {
    double q[3] = {p[0], p[1], p[2]};
    q[k] += eps;
    gradient[k] = (distance(q, attributes) - d0) / eps;
  }
}

// ---------------------------------------------------------------- torus

// radius1: of the centre circle in the xy plane; radius2: of the tube.
double TorusDistance(const double p[3], const double* a) {
  double q = Norm2(p[0], p[1]) - a[0];
  return std::sqrt(q * q + p[2] * p[2]) - a[1];
}

void TorusGradient(double g[3], const double p[3], const double* a) {
  double len_xy = Norm2(p[0], p[1]);
  double q = len_xy - a[0];
  double dq[2] = {p[0] / len_xy, p[1] / len_xy};
  double len_qz = std::sqrt(q * q + p[2] * p[2]);
  double denominator = Max(len_qz, kMinVal);
  g[0] = q * dq[0] / denominator;
  g[1] = q * dq[1] / denominator;
  g[2] = p[2] / denominator;
}

// ---------------------------------------------------------------- bolt and nut

// The thread: a triangle wave around z whose phase turns with the azimuth (12 turns per
// unit of height), `radius` = distance from the z axis less the thread's radius.
double ThreadWave(const double p[3]) {
  const double screw = 12;
  double azimuth = math::Atan2(p[1], p[0]);
  return std::fabs(Fract(p[2] * screw - azimuth / kPi / 2.) - .5) / screw;
}

// The hexagonal head (or nut): the point turned into the nearest of six sectors, cut
// above and below and chamfered by a cone.
double HexHead(const double p[3], double radius, double sqrt12) {
  double k = 6. / kPi / 2.;
  double angle = -std::floor(math::Atan2(p[1], p[0]) * k + .5) / k;
  double s0 = math::Sin(angle), s1 = math::Sin(angle + kPi * .5);
  double x = s1 * p[0] + -s0 * p[1];
  double head = x - .5;
  head = Intersection(head, std::fabs(p[2] + .25) - .25);
  return Intersection(head, (p[2] + radius - .22) * sqrt12);
}

// radius: of the threaded rod.
double BoltDistance(const double p[3], const double* a) {
  double radius = Norm2(p[0], p[1]) - a[0];
  double sqrt12 = std::sqrt(2.) / 2.;
  double thread = (radius - ThreadWave(p)) * sqrt12;
  // the rod between z = -1 and 0, its tip chamfered by a cone
  double bolt = Subtraction(thread, .5 - std::fabs(p[2] + .5));
  double cone = (p[2] - radius) * sqrt12;
  bolt = Subtraction(bolt, cone + 1. * sqrt12);
  return Union(bolt, HexHead(p, radius, sqrt12));
}

// radius: of the threaded hole.
double NutDistance(const double p[3], const double* a) {
  double radius = Norm2(p[0], p[1]) - a[0];
  double sqrt12 = std::sqrt(2.) / 2.;
  double thread = (radius - ThreadWave(p)) * sqrt12;
  double cone = (p[2] - radius) * sqrt12;
  double hole = Subtraction(thread, cone + .5 * sqrt12);
  hole = Union(hole, -cone - .05 * sqrt12);
  return Subtraction(HexHead(p, radius, sqrt12), hole);
}

// ---------------------------------------------------------------- gear

double SmoothUnion(double a, double b, double k) {
  double h = 0.5 + 0.5 * (b - a) / k;
  h = h < 0.0 ? 0.0 : (h > 1.0 ? 1.0 : h);
  return b * (1. - h) + a * h - k * h * (1. - h);
}

double SmoothIntersection(double a, double b, double k) {
  return Subtraction(Intersection(a, b),
                     SmoothUnion(Subtraction(a, b), Subtraction(b, a), k));
}

double FloorMod(double x, double y) { return x - y * std::floor(x / y); }

// The gear's outline in the xy plane: involute teeth between the root and outside
// circles, around a hole. alpha: rotation; diameter: of the pitch circle; teeth;
// innerdiameter: of the hole (< 0: from the teeth's size).
double GearOutline(const double p[3], const double* a) {
  double D = a[1];
  double N = a[2];
  double psi = 3.096e-5 * N * N - 6.557e-3 * N + 0.551;  // pressure angle
  double alpha = a[0];
  double R = D / 2.0;
  double rho = Norm2(p[0], p[1]);
  double Pd = N / D;        // diametral pitch
  double P = kPi / Pd;      // circular pitch
  double addendum = 1.0 / Pd;
  double Ro = (D + 2.0 * addendum) / 2.0;  // outside radius
  double h = 2.2 / Pd;
  double innerR = Ro - h - 0.14 * D;
  if (a[4] >= 0.0) innerR = a[4] / 2.0;
  // inside the hole, or well outside the teeth
  if (innerR - rho > 0.0) return innerR - rho;
  if (Ro - rho < -0.2) return rho - Ro;

  // Distances to the two involutes that bound the tooth of the point's sector.
  double Rb = D * std::cos(psi) / 2.0;  // base circle
  double fi = math::Atan2(p[1], p[0]) + alpha;
  double stride = P / R;
  double inv_alpha = math::Acos(Rb / R);
  double inv_phi = std::tan(inv_alpha) - inv_alpha;
  double shift = stride / 2.0 - 2.0 * inv_phi;
  double fia = FloorMod(fi + shift / 2.0, stride) - shift / 2.0;
  double fib = FloorMod(-fi - shift + shift / 2.0, stride) - shift / 2.0;
  double dista = -1.0e6, distb = -1.0e6;
  if (Rb < rho) {
    double acos_rb_rho = math::Acos(Rb / rho);
    double ta = std::sqrt(rho * rho - Rb * Rb);
    dista = ta - Rb * (fia + acos_rb_rho);
    distb = ta - Rb * (fib + acos_rb_rho);
  }
  // Teeth cut to the outside circle, on the root circle, less the hole.
  double outer = rho - Ro;
  double root = rho - (Ro - h);
  double hole = rho - innerR;
  double cogs = Intersection(dista, distb);
  double walls = Intersection(fia - (stride - shift), fib - (stride - shift));
  cogs = Intersection(walls, cogs);
  cogs = SmoothIntersection(outer, cogs, 0.0035 * D);
  cogs = SmoothUnion(root, cogs, Rb - Ro + h);
  return Subtraction(cogs, hole);
}

// The outline extruded to thickness a[3] about z = 0.
double GearDistance(const double p[3], const double* a) {
  double w0 = GearOutline(p, a);
  double w1 = std::fabs(p[2]) - a[3] / 2.;
  double outside[2] = {Max(w0, 0), Max(w1, 0)};
  return Min(Max(w0, w1), 0.) + Norm2(outside[0], outside[1]);
}

// ---------------------------------------------------------------- bowl

// A spherical cap of `radius` cut at `height` above the centre, `thickness` thick.
double BowlDistance(const double p[3], const double* a) {
  double height = a[0], radius = a[1], thick = a[2];
  double width = std::sqrt(radius * radius - height * height);
  double q0 = Norm2(p[0], p[1]), q1 = p[2];
  double rim = Norm2(q0 - width, q1 - height);
  double shell = std::fabs(Norm2(q0, q1) - radius);
  return ((height * q0 < width * q1) ? rim : shell) - thick;
}

// ---------------------------------------------------------------- registration

Plugin SdfPlugin(const std::string& name, std::vector<std::string> attributes,
                 std::vector<double> defaults,
                 DistanceFunction distance,
                 std::function<void(double*, const double*)> aabb_half) {
  Plugin p;
  p.name = name;
  p.capabilities = kPluginSdf;
  p.attributes = std::move(attributes);
  p.sdf_defaults = std::move(defaults);
  p.sdf_distance = distance;
  p.sdf_gradient = [distance](double g[3], const double x[3], const double* a) {
    DifferenceGradient(distance, g, x, a);
  };
  p.sdf_aabb = [aabb_half](double aabb[6], const double* a) {
    aabb[0] = aabb[1] = aabb[2] = 0;
    aabb_half(aabb + 3, a);
  };
  return p;
}

}  // namespace

std::vector<Plugin> SdfShapePlugins() {
  std::vector<Plugin> plugins;
  Plugin torus = SdfPlugin("mujoco.sdf.torus", {"radius1", "radius2"}, {.35, .15}, TorusDistance,
                           [](double* half, const double* a) {
                             half[0] = half[1] = a[0] + a[1];
                             half[2] = a[1];
                           });
  torus.sdf_gradient = TorusGradient;
  plugins.push_back(torus);
  auto screw_box = [](double* half, const double*) {
    half[0] = half[1] = .6;
    half[2] = 1;
  };
  plugins.push_back(SdfPlugin("mujoco.sdf.bolt", {"radius"}, {0.26}, BoltDistance, screw_box));
  plugins.push_back(SdfPlugin("mujoco.sdf.nut", {"radius"}, {0.26}, NutDistance, screw_box));
  plugins.push_back(SdfPlugin("mujoco.sdf.gear",
                              {"alpha", "diameter", "teeth", "thickness", "innerdiameter"},
                              {0, 2.8, 25, .2, -1}, GearDistance,
                              [](double* half, const double* a) {
                                half[0] = half[1] = a[1] / 2. * 1.25;
                                half[2] = a[3] / 2. * 1.1;
                              }));
  plugins.push_back(SdfPlugin("mujoco.sdf.bowl", {"height", "radius", "thickness"}, {.4, 1., .02},
                              BowlDistance, [](double* half, const double* a) {
                                half[0] = half[1] = half[2] = a[1] + a[2];
                              }));
  return plugins;
}

}  // namespace simlab
