// `simlab lint` (see lint.h).
#include "lint.h"

#include <CLI/CLI.hpp>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace simlab::apps {

std::string LintJson(const LintReport& report) {
  nlohmann::ordered_json findings = nlohmann::ordered_json::array();
  for (const LintFinding& f : report.findings) {
    findings.push_back({{"check", f.check}, {"severity", LintSeverityName(f.severity)},
                        {"element", f.element}, {"kind", f.kind}, {"id", f.id},
                        {"file", f.file}, {"line", f.line},
                        {"numbers", f.numbers}, {"meaning", f.meaning}, {"advice", f.advice}});
  }
  const int warnings = report.Warnings();
  nlohmann::ordered_json out = {{"file", report.file},
                                {"key", report.key},
                                {"warnings", warnings},
                                {"notes", static_cast<int>(report.findings.size()) - warnings},
                                {"findings", findings}};
  return out.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

int RunLint(const std::string& path, int key, bool json, std::ostream& out) {
  const LintReport report = LintFile(path, key);
  out << (json ? LintJson(report) : LintText(report));
  return report.Warnings() > 0 ? 1 : 0;
}

void AddLintCommand(CLI::App& app, CommandIo& io) {
  struct Options {
    std::string path;
    int key = -1;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "lint", "find mistakes that compile and run silently (the lesson's traps, and more)");
  cmd->add_option("model", options->path, "MJCF file")->required();
  cmd->add_option("--key", options->key, "check the state at this keyframe (default: none)");
  cmd->add_flag("--json", options->json, "print the findings as JSON");
  cmd->callback([options, &io] { io.status = RunLint(options->path, options->key, options->json, *io.out); });
}

}  // namespace simlab::apps
