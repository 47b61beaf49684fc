// simlab lint (simlab/lint.h, apps/lint.h): each check fires on a small model that has
// its trap (tests/lint_models/NAME.xml) and stays quiet on the same model without it
// (NAME_ok.xml, or another model without the trap), with the element's line and the numbers that show the problem; the
// lesson's models lint clean (the actuator bench has one note: its motor's gear of 2);
// the command's exit status and JSON.
#include "lint.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/simlab.h"

namespace simlab {
namespace {

std::string Path(const std::string& relative) { return std::string(SIMLAB_SOURCE_DIR) + "/" + relative; }
std::string Trap(const std::string& name) { return Path("tests/lint_models/" + name + ".xml"); }

// The findings of `check` when linting `name` at keyframe `key`.
std::vector<LintFinding> Found(const std::string& name, const std::string& check, int key = -1) {
  std::vector<LintFinding> out;
  for (const LintFinding& f : LintFile(Trap(name), key).findings) {
    if (f.check == check) out.push_back(f);
  }
  return out;
}

struct Case {
  std::string model, check;
  int key;
  int line;                  // of the (first) element
  LintSeverity severity;
  std::vector<std::string> numbers;  // pieces of its numbers text
  size_t count = 1;          // findings of the check
  std::string twin = "";     // the model without the trap (default: model + "_ok")
};

const Case kCases[] = {
    {"bias_ignored", "bias-ignored", -1, 13, LintSeverity::kWarning, {"b1 = -500", "b2 = -20"}},
    {"weak_servo", "servo-too-weak", -1, 13, LintSeverity::kWarning, {"4.905 N m", "kp 1", "sags 4.905 rad"}},
    {"zero_target", "servo-targets-zero", 0, 13, LintSeverity::kWarning, {"ctrl = 0", "length is -0.8"}},
    {"euler_filter", "filter-faster-than-timestep", -1, 13, LintSeverity::kWarning, {"0.0005 s", "timestep 0.002 s"}},
    {"gear", "gear-scales-force", -1, 13, LintSeverity::kNote, {"gear 10"}},
    {"key_ctrl", "key-ctrl-clamped", 0, 15, LintSeverity::kWarning, {"ctrl[0] = 3", "[-1, 1]"}},
    {"key_range", "key-outside-range", 0, 15, LintSeverity::kWarning, {"\"shoulder\" at 2", "[-1.57, 1.57]"}},
    {"range_ignored", "range-ignored", -1, 13, LintSeverity::kWarning, {"ctrllimited=\"false\"", "[-1, 1]"}, 1, "gear_ok"},
    {"cannot_hold", "servo-cannot-hold", -1, 13, LintSeverity::kWarning, {"forcerange [-2, 2]"}, 1, "weak_servo_ok"},
    {"finger_equality", "equality-stretches", -1, 25, LintSeverity::kWarning, {"\"grip\"", "2.5 N", "0.004524 m"}},
    {"servo_unstable", "servo-unstable", -1, 12, LintSeverity::kWarning, {"joint inertia 0.02", "w dt = 1"}},
    {"collides_nothing", "collides-with-nothing", -1, 4, LintSeverity::kWarning, {"contype 1, conaffinity 1"}, 2},
    {"range_degrees", "range-in-degrees", -1, 7, LintSeverity::kNote, {"[-1.57, 1.57]", "[-0.0274, 0.0274] rad"}, 1, "weak_servo_ok"},
    {"unused_class", "unused-class", -1, 7, LintSeverity::kNote, {"nor a class nested in it"}},
    {"key_equality", "key-breaks-equality", 0, 20, LintSeverity::kWarning, {"\"mirror\"", "violated by 0.03"}},
    {"massless", "nearly-massless", -1, 8, LintSeverity::kWarning, {"0.0001 kg", "0.5 kg"}},
    {"joint_clamp", "joint-clamps-force", -1, 13, LintSeverity::kWarning, {"1570", "[-2, 2]"}, 1, "weak_servo_ok"},
    {"sleep_ignored", "sleep-ignored", -1, 5, LintSeverity::kWarning, {"sleep=\"init\"", "not enabled"}},
    {"newer_flex", "follows-mujoco-3.12", -1, 6, LintSeverity::kNote, {"only MuJoCo 3.12 defines"}},
};

TEST(Lint, EachTrapIsCaughtWithItsNumbersAndLine) {
  for (const Case& c : kCases) {
    const std::vector<LintFinding> found = Found(c.model, c.check, c.key);
    ASSERT_EQ(found.size(), c.count) << c.model;
    EXPECT_EQ(found[0].line, c.line) << c.model;
    EXPECT_EQ(found[0].file, Trap(c.model)) << c.model;
    EXPECT_EQ(found[0].severity, c.severity) << c.model;
    for (const std::string& piece : c.numbers) {
      EXPECT_NE(found[0].numbers.find(piece), std::string::npos) << c.model << ": " << found[0].numbers;
    }
    EXPECT_FALSE(found[0].meaning.empty() || found[0].advice.empty()) << c.model;
  }
}

TEST(Lint, WithoutTheTrapNothingIsFound) {
  for (const Case& c : kCases) {
    const std::string twin = c.twin.empty() ? c.model + "_ok" : c.twin;
    const LintReport report = LintFile(Trap(twin), c.twin.empty() ? c.key : -1);
    for (const LintFinding& f : report.findings) EXPECT_NE(f.check, c.check) << twin;
    if (c.twin.empty()) EXPECT_TRUE(report.findings.empty()) << twin;
  }
}

// The stretch lint estimates is what the engine shows: the right finger pushed with the
// 2.5 N the equality would carry, the left one held by its servo, the fingers end up
// about 4.5 mm apart after 6 s.
TEST(Lint, EqualityStretchIsWhatTheEngineShows) {
  Model m = LoadXml(Trap("finger_equality"));
  Data d = MakeData(m);
  d.ctrl[0] = 0.02;
  d.qpos[0] = d.qpos[1] = 0.02;
  for (int i = 0; i < 3000; i++) {
    d.qfrc_applied[1] = 2.5;
    Step(m, d);
  }
  const double simulated = std::abs(d.qpos[0] - d.qpos[1]);
  EXPECT_NEAR(simulated, 0.004524, 0.1 * 0.004524);
}

TEST(Lint, TheLessonsModelsLintClean) {
  EXPECT_TRUE(LintFile(Path("models/gantry_gripper.xml"), 0).findings.empty());
  EXPECT_TRUE(LintFile(Path("models/gantry_gripper.xml")).findings.empty());
  const LintReport bench = LintFile(Path("models/actuator_bench.xml"));
  ASSERT_EQ(bench.findings.size(), 1u);
  EXPECT_EQ(bench.findings[0].check, "gear-scales-force");
  EXPECT_EQ(bench.Warnings(), 0);
}

TEST(Lint, ABadKeyIsAnError) {
  EXPECT_THROW(LintFile(Trap("gear"), 0), Error);
  EXPECT_THROW(LintFile(Trap("missing")), Error);
}

TEST(Lint, CommandExitsOneOnWarningsAndPrintsJson) {
  std::ostringstream text;
  EXPECT_EQ(apps::RunLint(Trap("weak_servo"), -1, false, text), 1);
  EXPECT_NE(text.str().find("weak_servo.xml:13: warning: actuator \"servo\" [servo-too-weak]"),
            std::string::npos) << text.str();
  std::ostringstream notes;
  EXPECT_EQ(apps::RunLint(Trap("gear"), -1, false, notes), 0);
  std::ostringstream json;
  EXPECT_EQ(apps::RunLint(Trap("key_ctrl"), 0, true, json), 1);
  const nlohmann::json report = nlohmann::json::parse(json.str());
  EXPECT_EQ(report["warnings"], 1);
  EXPECT_EQ(report["key"], 0);
  EXPECT_EQ(report["findings"][0]["check"], "key-ctrl-clamped");
  EXPECT_EQ(report["findings"][0]["element"], "keyframe \"push\"");
  EXPECT_EQ(report["findings"][0]["line"], 15);
}

}  // namespace
}  // namespace simlab
