// `simlab explain MODEL.xml`: every actuator of a model read as an instance of the one
// force law p = a u + b0 + b1 l + b2 l' (lesson 2.3): its gain and bias, what u is,
// its dynamics, its transmission and gear, and which clamps are on.
#ifndef SIMLAB_APPS_EXPLAIN_H_
#define SIMLAB_APPS_EXPLAIN_H_

#include <ostream>
#include <string>

#include "cli.h"
#include "simlab/model.h"

namespace CLI {
class App;
}

namespace simlab::apps {

// Registers the subcommand; its callback prints the explanation to io.out.
void AddExplainCommand(CLI::App& app, CommandIo& io);

// One readable block for actuator i.
std::string ExplainActuator(const Model& m, int i);

// A header line and one block per actuator.
std::string ExplainModel(const Model& m);
// One line per sensor: type, object, where its numbers are, its stage and timing.
std::string ExplainSensor(const Model& m, int i);

// Loads `path` and writes ExplainModel to `out`. Returns the process exit code;
// throws simlab::Error on a bad model.
int RunExplain(const std::string& path, std::ostream& out);

}  // namespace simlab::apps

#endif  // SIMLAB_APPS_EXPLAIN_H_
