// `simlab lint MODEL.xml [--key K] [--json]`: the checks of simlab/lint.h, each finding
// with its element's file and line, its numbers, what it means and what to do. Exit
// status 0 when there are no warnings (notes only), 1 with warnings.
#ifndef SIMLAB_APPS_LINT_H_
#define SIMLAB_APPS_LINT_H_

#include <ostream>
#include <string>

#include "cli.h"
#include "simlab/lint.h"

namespace CLI {
class App;
}

namespace simlab::apps {

void AddLintCommand(CLI::App& app, CommandIo& io);

// The report as JSON: {file, key, warnings, notes, findings: [{check, severity, element,
// kind, id, file, line, numbers, meaning, advice}]}.
std::string LintJson(const LintReport& report);

// Lints `path` at keyframe `key` (-1: none) and writes text or JSON to `out`; returns
// the exit status. Throws simlab::Error on a bad model or key.
int RunLint(const std::string& path, int key, bool json, std::ostream& out);

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_LINT_H_
