// `simlab rollout MODEL.xml [--key K] [--state S.json] [--ctrl C.csv] [--steps N]
//                 [--every M] [--out F] [--table]`
//
// Order of work (FORMAT.md): reset (default or keyframe), apply --state, forward,
// record step 0; then for each step: write the control row, step, record.
#include "rollout.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "simlab/simlab.h"

namespace simlab::apps {

namespace {

using Json = nlohmann::ordered_json;

// The Data arrays a rollout records, in FORMAT.md's order.
const char* const kRecordedFields[] = {
    "qpos", "qvel", "qacc", "act", "ctrl", "actuator_force", "actuator_length",
    "actuator_velocity", "qfrc_actuator", "qfrc_passive", "qfrc_constraint",
    "sensordata", "ten_length", "ten_velocity"};

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Overwrites Data fields from a JSON object {"qpos": [...], "time": t, ...}.
void ApplyState(const Model& m, Data& d, const std::string& path) {
  Json state;
  try {
    state = Json::parse(ReadFile(path));
  } catch (const Json::exception& e) {
    throw Error(path + ": not valid JSON: " + e.what());
  }
  std::vector<FieldView> fields = DataFields(m, d);
  for (auto& [name, value] : state.items()) {
    if (name == "time") {
      d.time = value.get<double>();
      continue;
    }
    const FieldView* field = nullptr;
    for (const FieldView& f : fields) {
      if (name == f.name) field = &f;
    }
    if (!field || field->is_int) throw Error(path + ": unknown state field \"" + name + "\"");
    if (!value.is_array() || static_cast<int>(value.size()) != field->rows * field->cols) {
      throw Error(path + ": \"" + name + "\" needs " + std::to_string(field->rows * field->cols) +
                  " numbers");
    }
    for (size_t i = 0; i < value.size(); i++) field->doubles[i] = value[i].get<double>();
  }
}

// Control rows: comma-separated numbers, '#' lines are comments.
std::vector<std::vector<double>> ReadControls(const std::string& path, int nu) {
  std::vector<std::vector<double>> rows;
  std::istringstream lines(ReadFile(path));
  std::string line;
  for (int lineno = 1; std::getline(lines, line); lineno++) {
    size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::vector<double> row;
    std::stringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) {
      try {
        row.push_back(std::stod(cell));
      } catch (const std::exception&) {
        throw Error(path + ":" + std::to_string(lineno) + ": \"" + cell + "\" is not a number");
      }
    }
    if (static_cast<int>(row.size()) != nu) {
      throw Error(path + ":" + std::to_string(lineno) + ": expected " + std::to_string(nu) +
                  " controls, found " + std::to_string(row.size()));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

// {name: shape} of every array, in MuJoCo's shapes ([rows] or [rows, cols]).
Json Shapes(const std::vector<FieldView>& fields) {
  Json shapes = Json::object();
  for (const FieldView& f : fields) {
    shapes[f.name] = f.one_dimensional() ? Json::array({f.rows}) : Json::array({f.rows, f.cols});
  }
  return shapes;
}

Json Header(Model& m, Data& d) {
  Json h;
  h["engine"] = std::string("simlab (") + ReferenceVersion() + " semantics)";
  h["nq"] = m.nq;
  h["nv"] = m.nv;
  h["nu"] = m.nu;
  h["na"] = m.na;
  h["ntendon"] = m.ntendon;
  h["nsensordata"] = m.nsensordata;
  h["timestep"] = m.opt.timestep;
  // Sensors by name: where each one's numbers are in sensordata.
  Json sensors = Json::array();
  for (int i = 0; i < m.nsensor; i++) {
    sensors.push_back({{"name", m.sensor_names[i]},
                       {"type", SensorTypeName(m.sensor_type[i])},
                       {"adr", m.sensor_adr[i]},
                       {"dim", m.sensor_dim[i]}});
  }
  h["sensors"] = std::move(sensors);
  // Every array of Model and Data with its shape, as the Python bindings give them.
  h["model_fields"] = Shapes(m.Fields());
  h["data_fields"] = Shapes(DataFields(m, d));
  return h;
}

Json Record(const Model& m, Data& d, int step) {
  Json row;
  row["step"] = step;
  row["time"] = d.time;
  row["ncon"] = d.ncon;
  std::vector<FieldView> fields = DataFields(m, d);
  for (const char* name : kRecordedFields) {
    for (const FieldView& f : fields) {
      if (std::string(f.name) != name) continue;
      Json values = Json::array();
      for (int i = 0; i < f.rows * f.cols; i++) values.push_back(f.doubles[i]);
      row[name] = std::move(values);
    }
  }
  return row;
}

// A short table: time, the first few qpos, and the total actuator force.
void PrintTableRow(std::ostream& out, const Model& m, const Data& d, int step) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%6d %9.4f", step, d.time);
  out << buf;
  for (int i = 0; i < std::min(m.nq, 4); i++) {
    std::snprintf(buf, sizeof(buf), " %11.5f", d.qpos[i]);
    out << buf;
  }
  out << "\n";
}

}  // namespace

int RunRollout(const RolloutOptions& o, std::ostream& default_out) {
  Model m = LoadXml(o.model);
  Data d = MakeData(m);
  if (o.key >= 0) ResetDataKeyframe(m, d, o.key);
  if (!o.state.empty()) ApplyState(m, d, o.state);
  std::vector<std::vector<double>> ctrl;
  if (!o.ctrl.empty()) ctrl = ReadControls(o.ctrl, m.nu);

  // Output goes to the file, or standard output.
  std::unique_ptr<std::ofstream> file;
  if (!o.out.empty()) {
    file = std::make_unique<std::ofstream>(o.out);
    if (!*file) throw Error(o.out + ": cannot write");
  }
  std::ostream& out = file ? *file : default_out;
  if (o.table) {
    out << "  step      time";
    for (int i = 0; i < std::min(m.nq, 4); i++) out << "     qpos[" << i << "]";
    out << "\n";
  } else {
    out << Header(m, d).dump() << "\n";
  }
  auto record = [&](int step) {
    if (o.table) {
      PrintTableRow(out, m, d, step);
    } else {
      out << Record(m, d, step).dump() << "\n";
    }
  };

  Forward(m, d);
  record(0);
  for (int step = 1; step <= o.steps; step++) {
    if (!ctrl.empty()) {
      const std::vector<double>& row = ctrl[std::min<size_t>(step - 1, ctrl.size() - 1)];
      std::copy(row.begin(), row.end(), d.ctrl.begin());
    }
    Step(m, d);
    if (step % o.every == 0 || step == o.steps) record(step);
  }
  return 0;
}

void AddRolloutCommand(CLI::App& app) {
  auto options = std::make_shared<RolloutOptions>();
  CLI::App* cmd = app.add_subcommand("rollout", "simulate a model and write the rollout format");
  cmd->add_option("model", options->model, "MJCF file")->required();
  cmd->add_option("--key", options->key, "reset to this keyframe");
  cmd->add_option("--state", options->state, "JSON object of Data fields to overwrite");
  cmd->add_option("--ctrl", options->ctrl, "CSV of controls, one row per step");
  cmd->add_option("--steps", options->steps, "number of steps")->check(CLI::NonNegativeNumber);
  cmd->add_option("--every", options->every, "record every M-th step")->check(CLI::PositiveNumber);
  cmd->add_option("--out", options->out, "output file (default: standard output)");
  cmd->add_flag("--table", options->table, "print a short table instead of JSON Lines");
  cmd->callback([options] { std::exit(RunRollout(*options, std::cout)); });
}

}  // namespace simlab::apps
