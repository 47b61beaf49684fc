// mujoco.sensor.touch_grid, MuJoCo's first-party tactile grid (plugin/sensor there): a
// sensor on a site that bins the contact forces of the site's weld body over a grid of
// directions seen from the site (looking down its -z axis), `size` = columns x rows over a
// field of view `fov` (degrees, horizontal x vertical), the bin edges bent towards the
// centre by `gamma` (0: even). Channel c of each cell sums force component c of the
// contacts whose direction falls in it, components in the site's frame permuted to
// (normal z, x, y), torques after forces: nchannel of these (1 to 6) per cell. Forces
// point away from the body with the larger id, as MuJoCo's contact forces do.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "engine/engine.h"
#include "engine/stack.h"
#include "math/elementary.h"
#include "math/math.h"
#include "simlab/plugin.h"
#include "simlab/simlab.h"

namespace simlab {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The grid of one instance: its channels, columns and rows, their bin edges (azimuth,
// elevation), and its sensor (-1: none uses it).
struct TouchGridData : PluginInstanceData {
  int nchannel = 1;
  int size[2] = {0, 0};
  std::vector<double> xedges, yedges;
  int sensor = -1;
  std::unique_ptr<PluginInstanceData> Clone() const override {
    return std::make_unique<TouchGridData>(*this);
  }
};

[[noreturn]] void Refuse(int instance, const std::string& what) {
  throw Error("mujoco.sensor.touch_grid instance " + std::to_string(instance) + ": " + what);
}

// The numbers of a config value separated by single spaces (as MuJoCo reads them: an
// empty item between two spaces is a 0).
std::vector<double> Numbers(const Model& m, int instance, const char* key) {
  std::string text = PluginConfig(m, instance, key);
  std::vector<double> numbers;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find(' ', at);
    if (end == std::string::npos) end = text.size();
    std::string item = text.substr(at, end - at);
    numbers.push_back(std::strtod(item.c_str(), nullptr));
    at = end + 1;
  }
  return numbers;
}

// One number; "" is 0 and anything but a number (blanks aside) an error.
double Scalar(const Model& m, int instance, const char* key) {
  std::string text;
  for (char c : PluginConfig(m, instance, key)) {
    if (!std::isspace(static_cast<unsigned char>(c))) text += c;
  }
  char* end = nullptr;
  double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) Refuse(instance, std::string("'") + key + "' is not a number");
  return value;
}

// Channels (0 means 1) and the grid's columns and rows, checked.
int Channels(const Model& m, int instance) {
  double n = Scalar(m, instance, "nchannel");
  if (!(n > -1e9 && n < 1e9)) Refuse(instance, "nchannel must be between 1 and 6");
  int channels = static_cast<int>(n);  // (truncated, as MuJoCo reads it)
  if (channels == 0) return 1;
  if (channels < 1 || channels > 6) Refuse(instance, "nchannel must be between 1 and 6");
  return channels;
}

void GridSize(const Model& m, int instance, int size[2]) {
  std::vector<double> s = Numbers(m, instance, "size");
  if (s.size() != 2) Refuse(instance, "both horizontal and vertical resolutions must be specified");
  if (!(s[0] >= 1 && s[1] >= 1 && s[0] * s[1] <= 1e6)) {
    Refuse(instance, "horizontal and vertical resolutions must be positive (and at most 10^6 cells)");
  }
  size[0] = static_cast<int>(s[0]);
  size[1] = static_cast<int>(s[1]);
}

// ---------------------------------------------------------------- binning

// Bin edges along one axis: n + 1 even steps over [-1, 1] (accumulated, as MuJoCo's
// LinSpace), bent by gamma g into g x^5 + (1 - g) x, scaled to fov degrees.
std::vector<double> BinEdges(int n, double fov, double gamma) {
  std::vector<double> edges(n + 1);
  double step = (1.0 - -1.0) / n, x = -1;
  for (double& e : edges) {
    e = x;
    x += step;
  }
  if (gamma != 0) {
    double g = gamma < 1 ? (gamma > 0 ? gamma : 0) : 1;
    for (double& e : edges) e = g * std::pow(e, 5) + (1 - g) * e;
  }
  double scale = fov * kPi / 180;
  for (double& e : edges) e *= scale;
  return edges;
}

// The first edge >= x (binary search).
int LowerBound(const std::vector<double>& edges, double x) {
  int lo = 0, hi = static_cast<int>(edges.size());
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    if (x <= edges[mid]) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  return lo;
}

// The cell (row-major, rows along y) of direction (azimuth, elevation), or -1 outside.
int CellOf(const std::vector<double>& xe, const std::vector<double>& ye, double a, double e) {
  int xi = LowerBound(xe, a);
  if (xi == 0 || xi == static_cast<int>(xe.size())) return -1;
  int yi = LowerBound(ye, e);
  if (yi == 0 || yi == static_cast<int>(ye.size())) return -1;
  return (yi - 1) * (static_cast<int>(xe.size()) - 1) + (xi - 1);
}

// ---------------------------------------------------------------- the instance

std::unique_ptr<PluginInstanceData> Init(const Model& m, Data&, int instance) {
  auto grid = std::make_unique<TouchGridData>();
  grid->nchannel = Channels(m, instance);
  GridSize(m, instance, grid->size);
  std::vector<double> fov = Numbers(m, instance, "fov");
  if (fov.size() != 2) Refuse(instance, "both horizontal and vertical fields of view must be specified");
  if (!(fov[0] > 0 && fov[0] <= 180)) Refuse(instance, "fov[0] must be in (0, 180] degrees");
  if (!(fov[1] > 0 && fov[1] <= 90)) Refuse(instance, "fov[1] must be in (0, 90] degrees");
  double gamma = Scalar(m, instance, "gamma");
  if (!(gamma >= 0 && gamma <= 1)) Refuse(instance, "gamma must be in [0, 1]");
  grid->xedges = BinEdges(grid->size[0], fov[0], gamma);
  grid->yedges = BinEdges(grid->size[1], fov[1], gamma);
  for (int i = m.nsensor - 1; i >= 0; i--) {
    if (m.sensor_type[i] != kSensPlugin || m.sensor_plugin[i] != instance) continue;
    if (m.sensor_objtype[i] != kObjSite) Refuse(instance, "the sensor must be attached to a site");
    grid->sensor = i;  // (the first, which MuJoCo's reads)
  }
  return grid;
}

// ---------------------------------------------------------------- the sensor

// Contact i's force and torque in the site's frame, pointing away from the body with the
// larger id, permuted to (z, x, y) each; its direction from the site as azimuth and
// elevation (looking down -z).
void SeenContact(const Model& m, const Data& d, int i, int site, int parent_body, double f[6],
                 double dir[2]) {
  const Contact& c = d.contact[i];
  const double* site_pos = &d.site_xpos[3 * site];
  const double* site_mat = &d.site_xmat[9 * site];
  double local[6], world[3], seen[6];
  ContactForce(m, d, i, local);
  for (int half = 0; half < 2; half++) {
    math::MulMatTVec3(world, c.frame, local + 3 * half);
    math::MulMatTVec3(seen + 3 * half, site_mat, world);
  }
  int b1 = m.geom_bodyid[c.geom1], b2 = m.geom_bodyid[c.geom2];
  if (parent_body < (b1 > b2 ? b1 : b2)) {
    for (double& v : seen) v *= -1;
  }
  for (int half = 0; half < 2; half++) {
    f[3 * half] = seen[3 * half + 2], f[3 * half + 1] = seen[3 * half], f[3 * half + 2] = seen[3 * half + 1];
  }
  double rel[3], p[3];
  math::Sub3(rel, c.pos, site_pos);
  math::MulMatTVec3(p, site_mat, rel);
  dir[0] = math::Atan2(p[0], -p[2]);
  dir[1] = math::Atan2(p[1], std::sqrt(p[0] * p[0] + p[2] * p[2]));
}

void Compute(const Model& m, Data& d, int instance, int) {
  const auto& grid = static_cast<const TouchGridData&>(*d.plugin_data[instance].data);
  const int id = grid.sensor;
  if (id < 0) return;
  double* out = &d.sensordata[m.sensor_adr[id]];
  for (int k = 0; k < m.sensor_dim[id]; k++) out[k] = 0;
  int site = m.sensor_objid[id];
  int parent_body = m.body_weldid[m.site_bodyid[site]];
  int parent_weld = m.body_weldid[parent_body];

  // The contacts of the site's weld body: 6 force numbers and 2 direction angles each.
  StackFrame frame(d);
  double* seen = frame.Alloc(8 * static_cast<size_t>(d.ncon));
  int n = 0;
  for (int i = 0; i < d.ncon; i++) {
    // (contacts with a flex, geom -1 on its side, are skipped: MuJoCo reads past its
    // arrays there)
    if (d.contact[i].geom1 < 0 || d.contact[i].geom2 < 0) continue;
    int w1 = m.body_weldid[m.geom_bodyid[d.contact[i].geom1]];
    int w2 = m.body_weldid[m.geom_bodyid[d.contact[i].geom2]];
    if (w1 != parent_weld && w2 != parent_weld) continue;
    SeenContact(m, d, i, site, parent_body, seen + 8 * n, seen + 8 * n + 6);
    n++;
  }

  // Each channel: the sum per cell of its component (a channel all zero adds nothing).
  int cells = grid.size[0] * grid.size[1];
  for (int c = 0; c < grid.nchannel; c++) {
    bool zero = true;
    for (int i = 0; i < n; i++) zero = zero && seen[8 * i + c] == 0;
    if (zero) continue;
    for (int i = 0; i < n; i++) {
      int cell = CellOf(grid.xedges, grid.yedges, seen[8 * i + 6], seen[8 * i + 7]);
      if (cell >= 0) out[c * cells + cell] += seen[8 * i + c];
    }
  }
}

}  // namespace

Plugin TouchGridPlugin() {
  Plugin p;
  p.name = "mujoco.sensor.touch_grid";
  p.capabilities = kPluginSensor;
  p.attributes = {"nchannel", "size", "fov", "gamma"};
  p.needstage = kStageAcc;
  p.nstate = [](const Model&, int) { return 0; };
  p.nsensordata = [](const Model& m, int instance, int) {
    int size[2];
    GridSize(m, instance, size);
    return Channels(m, instance) * size[0] * size[1];
  };
  p.init = Init;
  p.compute = Compute;
  return p;
}

}  // namespace simlab
