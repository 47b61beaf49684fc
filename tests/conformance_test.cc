// Conformance with MuJoCo: each case of tests/conformance/cases.txt is rolled out by
// `simlab rollout` (in process) and compared field by field with the golden that the
// real MuJoCo wrote (tools/make_goldens.sh), as ../shared/oracle/compare.mjs does:
// a value agrees when |ref - ours| <= tol * max(1, |ref|).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rollout.h"
#include "simlab/simlab.h"

namespace simlab {
namespace {

using Json = nlohmann::json;

// One line of a case list: model, golden, steps, state (or -), and optionally the
// control schedule (or -) and the relative tolerance (default 1e-9).
struct Case {
  std::string model, golden, state, ctrl;
  int steps = 0;
  double tol = 1e-9;
};

// gtest prints a case by its model path.
void PrintTo(const Case& c, std::ostream* os) { *os << c.model; }

std::string Path(const std::string& relative) { return std::string(SIMLAB_SOURCE_DIR) + "/" + relative; }

// The cases of the smooth-dynamics list (tools/make_goldens.sh), the actuator list
// (tools/make_actuation_goldens.sh) and the spatial tendon list
// (tests/conformance/tendon/make_goldens.sh); the fluid-force list
// (tests/conformance/fluid/make_goldens.sh); gravity compensation
// (tests/conformance/gravcomp/make_goldens.sh); friction cones and noslip
// (tests/conformance/solver/make_goldens.sh); adhesion
// (tests/conformance/adhesion/make_goldens.sh); contact scenes and the gantry lab
// scenario (tools/make_contact_goldens.sh); height-field collisions
// (tools/make_hfield_goldens.sh); actuators newer than 3.5.1, from native MuJoCo
// (tests/conformance/actuators312/make_goldens.sh); MuJoCo's corpus models as they are
// (tests/conformance/corpus/make_goldens.sh); MuJoCo's models with signed distance field
// plugins, from native MuJoCo at the oracle's commit (tests/conformance/plugins/
// make_goldens.sh).
std::vector<Case> ReadCases() {
  std::vector<Case> cases;
  for (const char* list : {"tests/conformance/cases.txt", "tests/conformance/actuation_cases.txt",
                           "tests/conformance/corpus_cases.txt",
                           "tests/conformance/flex_cases.txt",
                           "tests/conformance/flex_native_cases.txt",
                           "tests/conformance/tendon_cases.txt",
                           "tests/conformance/constraint_cases.txt",
                           "tests/conformance/fluid_cases.txt",
                           "tests/conformance/gravcomp_cases.txt",
                           "tests/conformance/adhesion_cases.txt",
                           "tests/conformance/contact_cases.txt",
                           "tests/conformance/solver_cases.txt",
                           "tests/conformance/sensor_cases.txt",
                           "tests/conformance/ray_cases.txt",
                           "tests/conformance/hfield_cases.txt",
                           "tests/conformance/actuators312_cases.txt",
                           "tests/conformance/plugins_cases.txt"}) {
    std::ifstream in(Path(list));
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream fields(line);
      Case c;
      fields >> c.model >> c.golden >> c.steps >> c.state;
      if (!(fields >> c.ctrl)) c.ctrl.clear();
      if (!(fields >> c.tol)) c.tol = 1e-9;
      if (c.state == "-") c.state.clear();
      if (c.ctrl == "-") c.ctrl.clear();
      cases.push_back(c);
    }
  }
  return cases;
}

std::vector<Json> ParseLines(std::istream& in) {
  std::vector<Json> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty()) rows.push_back(Json::parse(line));
  }
  return rows;
}

class Conformance : public ::testing::TestWithParam<Case> {};

TEST_P(Conformance, MatchesMuJoCo) {
  const Case& c = GetParam();
  std::ifstream golden_file(Path(c.golden));
  ASSERT_TRUE(golden_file) << c.golden;
  std::vector<Json> golden = ParseLines(golden_file);

  // Our rollout, with the options the golden was made with.
  apps::RolloutOptions options;
  options.model = Path(c.model);
  // The state column names a state file, or "key:K" for a reset to keyframe K.
  if (c.state.rfind("key:", 0) == 0) {
    options.key = std::stoi(c.state.substr(4));
  } else if (!c.state.empty()) {
    options.state = Path(c.state);
  }
  if (!c.ctrl.empty()) options.ctrl = Path(c.ctrl);
  options.steps = c.steps;
  // Recorded as often as the golden was (its first two records after the header).
  options.every = golden.size() > 2 ? golden[2]["step"].get<int>() - golden[1]["step"].get<int>() : 10;
  std::stringstream ours_text;
  ASSERT_EQ(apps::RunRollout(options, ours_text), 0);
  std::vector<Json> ours = ParseLines(ours_text);
  ASSERT_EQ(ours.size(), golden.size());

  // Sizes in the header, then every recorded field at every recorded step.
  for (const char* size : {"nq", "nv", "nu", "na", "ntendon", "nsensordata"}) {
    EXPECT_EQ(ours[0][size], golden[0][size]) << size;
  }
  // (native MuJoCo's headers also count actuators and force outputs)
  for (const char* size : {"nactuator", "nout"}) {
    if (golden[0].contains(size)) EXPECT_EQ(ours[0][size], golden[0][size]) << size;
  }
  const double tol = c.tol;
  std::map<std::string, double> worst;
  for (size_t r = 1; r < golden.size(); r++) {
    for (auto& [name, ref] : golden[r].items()) {
      if (!ref.is_array()) continue;
      const Json& cand = ours[r][name];
      ASSERT_EQ(cand.size(), ref.size()) << name;
      for (size_t i = 0; i < ref.size(); i++) {
        double a = ref[i].get<double>(), b = cand[i].get<double>();
        double err = std::abs(a - b) / std::max(1.0, std::abs(a));
        if (!(err <= worst[name])) worst[name] = std::isnan(err) ? INFINITY : err;
      }
    }
  }
  for (auto& [name, err] : worst) {
    EXPECT_LE(err, tol) << c.model << ": " << name;
  }
  RecordProperty("worst_qacc", std::to_string(worst["qacc"]));
}

// (by the golden: one model can have cases from several states)
std::string CaseName(const ::testing::TestParamInfo<Case>& info) {
  std::string name = info.param.golden.substr(info.param.golden.rfind('/') + 1);
  name = name.substr(0, name.find('.'));
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Goldens, Conformance, ::testing::ValuesIn(ReadCases()), CaseName);

}  // namespace
}  // namespace simlab
