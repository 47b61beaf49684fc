// simlab lint: mistakes that compile and run silently, found in a model before they bite.
// The checks read the compiled model and, where a load matters, the model at a keyframe
// (gravity through the engine's own qfrc_bias at rest): the traps of lesson 2.3 (a
// general actuator's ignored biasprm, a position servo too weak to hold its load, a
// position servo commanding 0 at the start, an Euler-integrated filter faster than the
// timestep, keyframe controls outside ctrlrange, gear != 1 and what actuator_force then
// means) and what experienced MuJoCo users check (ranges switched off by limited="false",
// keyframes outside the joint ranges), and a note when the model follows MuJoCo 3.12's rules
// rather than 3.5.1's (Model::release).
//
//   simlab::LintReport report = simlab::LintFile("robot.xml", /*key=*/0);
//   for (const simlab::LintFinding& f : report.findings) ...  // f.file, f.line, f.numbers
#ifndef SIMLAB_LINT_H_
#define SIMLAB_LINT_H_

#include <string>
#include <vector>

namespace simlab {

// A warning is a likely mistake; a note says how to read a quantity right.
enum class LintSeverity { kWarning, kNote };

struct LintFinding {
  std::string check;      // which check: "bias-ignored", "servo-too-weak", ...
  LintSeverity severity = LintSeverity::kWarning;
  std::string element;    // the element, as "actuator \"grip\"" or "joint 3"
  std::string file;       // where it was written
  int line = 0;
  std::string numbers;    // the numbers that show the problem
  std::string meaning;    // what it means
  std::string advice;     // what to do
  std::string kind;       // the element's kind in the compiled model ("actuator", "geom",
  int id = -1;            // "equality", "keyframe") and id; "" and -1 when it has none there
};

struct LintReport {
  std::string file;
  int key = -1;           // the keyframe the state checks used, or -1: the default state
  std::vector<LintFinding> findings;
  int Warnings() const;
};

// Loads and compiles `path`, then runs every check, at keyframe `key` (-1: the model's
// default state). Throws simlab::Error for a model that does not load or a bad key.
LintReport LintFile(const std::string& path, int key = -1);

// The report as text: one block per finding, then a count.
std::string LintText(const LintReport& report);

// "warning" or "note".
const char* LintSeverityName(LintSeverity severity);

}  // namespace simlab

#endif  // SIMLAB_LINT_H_
