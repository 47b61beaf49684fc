// The acceleration-stage quantities computed on demand (RnePostConstraint, SubtreeVel,
// EnergyPos, EnergyVel) against MuJoCo 3.5.1's mj_rnePostConstraint, mj_subtreeVel,
// mj_energyPos and mj_energyVel: the humanoid in contact (pyramidal cones, one case with
// an applied force), contact scenes with pyramidal and elliptic cones, body and
// site-semantic connect/weld constraints with xfrc_applied and springs of every kind.
// Cases: tests/rne_post/cases.txt; goldens: tests/rne_post/make_goldens.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/engine.h"
#include "simlab/simlab.h"
#include "test_files.h"

namespace simlab {
namespace {

using test_util::ReadControlRows;
constexpr auto Path = test_util::SourcePath;

struct RnePostCase {
  std::string model, ctrl, golden;
  int key = -1;
  std::string xfrc;  // BODY:fx,fy,fz,tx,ty,tz;... or -
};

std::vector<RnePostCase> ReadCases() {
  std::vector<RnePostCase> cases;
  std::ifstream in(Path("tests/rne_post/cases.txt"));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream fields(line);
    RnePostCase c;
    std::string at;
    fields >> c.model >> c.key >> c.ctrl >> at >> c.xfrc;
    std::string base = c.model.substr(c.model.rfind('/') + 1);
    c.golden = "tests/rne_post/goldens/" + base.substr(0, base.size() - 4) + ".json";
    cases.push_back(c);
  }
  return cases;
}

// xfrc_applied from "BODY:fx,fy,fz,tx,ty,tz;BODY:...".
void ApplyForces(const Model& m, Data& d, const std::string& spec) {
  if (spec == "-") return;
  std::stringstream entries(spec);
  std::string entry;
  while (std::getline(entries, entry, ';')) {
    size_t colon = entry.find(':');
    int body = m.NameToId(kObjBody, entry.substr(0, colon));
    ASSERT_GE(body, 0) << entry;
    std::stringstream values(entry.substr(colon + 1));
    std::string value;
    for (int k = 0; k < 6 && std::getline(values, value, ','); k++) {
      d.xfrc_applied[6 * body + k] = std::stod(value);
    }
  }
}

// Worst |ours - ref| / max(1, |ref|) over one field.
double WorstError(const std::vector<double>& ours, const nlohmann::json& ref) {
  EXPECT_EQ(ours.size(), ref.size());
  double worst = 0;
  for (size_t i = 0; i < ours.size() && i < ref.size(); i++) {
    double r = ref[i].get<double>();
    worst = std::max(worst, std::abs(ours[i] - r) / std::max(1.0, std::abs(r)));
  }
  return worst;
}

// Runs a case to each dumped step and compares every field; returns the worst error.
double CheckCase(const RnePostCase& c) {
  std::ifstream in(Path(c.golden));
  nlohmann::json golden = nlohmann::json::parse(in);
  Model m = LoadXml(Path(c.model));
  Data d = MakeData(m);
  if (c.key >= 0) ResetDataKeyframe(m, d, c.key);
  ApplyForces(m, d, c.xfrc);
  std::vector<std::vector<double>> controls = ReadControlRows(c.ctrl);
  int step = 0;
  double worst = 0;
  for (const nlohmann::json& dump : golden["dumps"]) {
    for (; step < dump["step"].get<int>(); step++) {
      // the step's control row, the last one held (a case without controls has none)
      if (!controls.empty()) {
        const std::vector<double>& row = controls[std::min<size_t>(step, controls.size() - 1)];
        for (int u = 0; u < m.nu; u++) d.ctrl[u] = row[u];
      }
      Step(m, d);
    }
    Forward(m, d);
    RnePostConstraint(m, d);
    SubtreeVel(m, d);
    EnergyPos(m, d);
    EnergyVel(m, d);
    EXPECT_EQ(d.ncon, dump["ncon"].get<int>()) << c.model << " step " << step;
    const std::pair<const char*, const std::vector<double>*> fields[] = {
        {"cacc", &d.cacc}, {"cfrc_int", &d.cfrc_int}, {"cfrc_ext", &d.cfrc_ext},
        {"subtree_linvel", &d.subtree_linvel}, {"subtree_angmom", &d.subtree_angmom}};
    for (const auto& [name, ours] : fields) {
      double e = WorstError(*ours, dump[name]);
      EXPECT_LT(e, 1e-9) << c.model << " step " << step << " " << name;
      worst = std::max(worst, e);
    }
    double e = WorstError({d.energy[0], d.energy[1]}, dump["energy"]);
    EXPECT_LT(e, 1e-9) << c.model << " step " << step << " energy";
    worst = std::max(worst, e);
  }
  return worst;
}

TEST(RnePost, AgreesWithMuJoCo) {
  std::vector<RnePostCase> cases = ReadCases();
  ASSERT_GE(cases.size(), 6u);
  for (const RnePostCase& c : cases) {
    double worst = CheckCase(c);
    std::printf("%-70s worst relative error %.2e\n", c.model.c_str(), worst);
  }
}

// The flags tell the sensors what is already computed this step: each function sets
// its own, and Forward clears them so that the next step recomputes.
TEST(RnePost, FlagsMarkWhatIsComputed) {
  Model m = LoadXml(Path("tests/rne_post/models/equality_sites.xml"));
  Data d = MakeData(m);
  Forward(m, d);
  RnePostConstraint(m, d);
  SubtreeVel(m, d);
  EnergyPos(m, d);
  EnergyVel(m, d);
  EXPECT_TRUE(d.flg_rnepost && d.flg_subtreevel && d.flg_energypos && d.flg_energyvel);
  Step(m, d);
  Forward(m, d);
  EXPECT_FALSE(d.flg_rnepost || d.flg_subtreevel || d.flg_energypos || d.flg_energyvel);
}

// Forward computes cacc/cfrc and the subtree momenta only for models whose sensors read
// them (MuJoCo's mj_sensorAcc/Vel triggers), and the sensors read this step's values.
TEST(RnePost, ComputedOnlyForSensorsThatNeedIt) {
  Model plain = LoadXml(Path("tests/rne_post/models/equality_sites.xml"));
  Data d = MakeData(plain);
  Forward(plain, d);
  EXPECT_FALSE(d.flg_rnepost || d.flg_subtreevel);
  EXPECT_EQ(d.cfrc_int[6 * 1 + 5], 0.0);  // never computed

  Model sensed = LoadXml(Path("tests/sensors/acc_force_sensors.xml"));
  Data s = MakeData(sensed);
  Step(sensed, s);
  Forward(sensed, s);
  EXPECT_TRUE(s.flg_rnepost && s.flg_subtreevel);
  std::vector<double> from_sensors = s.cfrc_int;
  RnePostConstraint(sensed, s);
  EXPECT_EQ(from_sensors, s.cfrc_int);
}

// Split stepping recomputes the acceleration-stage sensors in Step2 (MuJoCo 3.5.1 clears
// its rnepost flag there too), so Step1 + Step2 reads what Step reads, step after step.
TEST(RnePost, SplitStepReadsFreshForces) {
  Model m = LoadXml(Path("tests/sensors/acc_force_sensors.xml"));
  Data whole = MakeData(m), split = MakeData(m);
  for (int step = 0; step < 20; step++) {
    for (Data* d : {&whole, &split}) d->ctrl[0] = 0.1 * step;
    Step(m, whole);
    Step1(m, split);
    Step2(m, split);
    ASSERT_EQ(whole.sensordata, split.sensordata) << "step " << step;
  }
  EXPECT_NE(whole.sensordata[2], 0.0);  // the wrist force carries the arm's weight
}

}  // namespace
}  // namespace simlab
