// `simlab rollout MODEL.xml [--key K] [--state S.json] [--ctrl C.csv] [--steps N]
//                 [--every M] [--out F] [--table]`
//
// Order of work (FORMAT.md): reset (default or keyframe), apply --state, forward,
// record step 0; then for each step: write the control row, step, record.
#include "rollout.h"

#include <CLI/CLI.hpp>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "simlab/simlab.h"

namespace simlab::apps {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// The Data arrays a rollout records, in FORMAT.md's order.
const char* const kRecordedFields[] = {
    "qpos", "qvel", "qacc", "act", "ctrl", "actuator_force", "actuator_length",
    "actuator_velocity", "qfrc_actuator", "qfrc_passive", "qfrc_constraint",
    "sensordata", "ten_length", "ten_velocity"};

// The largest --state or --ctrl file read (a pipe that never ends stops here).
constexpr std::uintmax_t kMaxInputBytes = std::uintmax_t{1} << 30;
// Cells longer than this are cut short when quoted in a message.
constexpr size_t kMaxQuoted = 40;

// `text` in double quotes for a message: printable ASCII as is, other bytes as \xNN,
// cut after kMaxQuoted characters, so a binary file cannot break the one-line message.
std::string Quoted(std::string_view text) {
  std::string quoted = "\"";
  for (size_t i = 0; i < text.size() && i < kMaxQuoted; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += static_cast<char>(c);
    } else if (c >= 0x20 && c < 0x7f) {
      quoted += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", c);
      quoted += hex;
    }
  }
  return quoted + (text.size() > kMaxQuoted ? "...\"" : "\"");
}

// "1 number", "3 numbers": a count with its noun.
std::string Count(size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// The text of the last system error, or `otherwise` when none was recorded.
std::string SystemError(const char* otherwise) {
  return errno != 0 ? std::strerror(errno) : otherwise;
}

// Why `path` cannot be an input file, or empty when it can: it must exist and be a
// regular file or a pipe (`--ctrl <(generator)`), never a folder or a device.
std::string InputFileProblem(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec) return ec.message();
  if (!fs::exists(status)) return "No such file or directory";
  if (fs::is_directory(status)) return "it is a folder, not a file";
  if (!fs::is_regular_file(status) && !fs::is_fifo(status)) {
    return "it is not a regular file (a device or socket)";
  }
  return "";
}

// The bytes of the file an option names (`option` is "--state" or "--ctrl", for
// messages), at most kMaxInputBytes; read errors are reported, never taken as an end.
std::string ReadInputFile(const std::string& path, const std::string& option) {
  const std::string cannot = path + ": cannot read the " + option + " file: ";
  if (const std::string problem = InputFileProblem(path); !problem.empty()) {
    throw Error(cannot + problem);
  }
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(cannot + SystemError("cannot open it"));
  // Read in pieces, so the size cap holds for pipes as well.
  std::string bytes;
  std::vector<char> piece(1 << 16);
  while (in.read(piece.data(), static_cast<std::streamsize>(piece.size())) || in.gcount() > 0) {
    bytes.append(piece.data(), static_cast<size_t>(in.gcount()));
    if (bytes.size() > kMaxInputBytes) throw Error(cannot + "larger than 1 GiB");
  }
  if (in.bad()) throw Error(cannot + SystemError("read error"));
  return bytes;
}

// The --state file as a JSON object; anything else is refused naming the file.
Json ParseStateFile(const std::string& path) {
  Json state;
  try {
    state = Json::parse(ReadInputFile(path, "--state"));
  } catch (const Json::exception& e) {
    throw Error(path + ": not valid JSON: " + e.what());
  }
  if (!state.is_object()) {
    throw Error(path + ": expected a JSON object of Data fields like {\"qpos\": [...], "
                "\"time\": 0}, found " + std::string(state.type_name()));
  }
  return state;
}

// One number of the state file; `where` names it ("time", "qpos"[2]).
double StateNumber(const Json& value, const std::string& path, const std::string& where) {
  if (!value.is_number()) {
    throw Error(path + ": " + where + ": expected a number, found " +
                std::string(value.type_name()));
  }
  return value.get<double>();
}

// The Data array a state field names, or nothing when there is none of that name.
std::optional<FieldView> FindDataField(const std::vector<FieldView>& fields,
                                       const std::string& name) {
  for (const FieldView& f : fields) {
    if (name == f.name) return f;
  }
  return std::nullopt;
}

// Copies one state field (an array of exactly rows * cols numbers) into Data.
void ApplyStateField(const FieldView& field, const Json& value, const std::string& path,
                     const std::string& quoted_name) {
  const size_t size = static_cast<size_t>(field.rows) * static_cast<size_t>(field.cols);
  const std::string wanted = "expected an array of " + Count(size, "number");
  if (!value.is_array()) {
    throw Error(path + ": " + quoted_name + ": " + wanted + ", found " +
                std::string(value.type_name()));
  }
  if (value.size() != size) {
    throw Error(path + ": " + quoted_name + ": " + wanted + ", found " +
                std::to_string(value.size()));
  }
  // Check every number before writing any, so a bad file changes nothing.
  std::vector<double> numbers(size);
  for (size_t i = 0; i < size; i++) {
    numbers[i] = StateNumber(value[i], path, quoted_name + "[" + std::to_string(i) + "]");
  }
  std::copy(numbers.begin(), numbers.end(), field.doubles);
}

// Overwrites Data fields from a JSON object {"qpos": [...], "time": t, ...}.
void ApplyState(const Model& m, Data& d, const std::string& path) {
  const Json state = ParseStateFile(path);
  const std::vector<FieldView> fields = DataFields(m, d);
  for (const auto& [name, value] : state.items()) {
    // Names are quoted as JSON, so control characters cannot break the message.
    const std::string quoted_name = Json(name).dump();
    if (name == "time") {
      d.time = StateNumber(value, path, quoted_name);
      continue;
    }
    const std::optional<FieldView> field = FindDataField(fields, name);
    if (!field) throw Error(path + ": unknown state field " + quoted_name);
    if (field->is_int) {
      throw Error(path + ": " + quoted_name + " holds integers and cannot be set by --state");
    }
    ApplyStateField(*field, value, path, quoted_name);
  }
}

// True when `cell` is a decimal number: [+-] digits [. digits] [(e|E) [+-] digits], with
// at least one digit before the exponent (".5" and "5." count). No hex, inf or nan.
bool IsDecimal(std::string_view cell) {
  size_t i = 0;
  auto digits = [&] {
    const size_t start = i;
    while (i < cell.size() && std::isdigit(static_cast<unsigned char>(cell[i]))) i++;
    return i - start;
  };
  if (i < cell.size() && (cell[i] == '+' || cell[i] == '-')) i++;
  size_t mantissa = digits();
  if (i < cell.size() && cell[i] == '.') {
    i++;
    mantissa += digits();
  }
  if (mantissa == 0) return false;
  if (i < cell.size() && (cell[i] == 'e' || cell[i] == 'E')) {
    i++;
    if (i < cell.size() && (cell[i] == '+' || cell[i] == '-')) i++;
    if (digits() == 0) return false;
  }
  return i == cell.size();
}

// `text` without spaces, tabs and carriage returns around it.
std::string_view TrimCell(std::string_view text) {
  const size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// The non-finite controls as the oracle (rollout.mjs, JavaScript's Number) spells them;
// MuJoCo's answer to them (bad controls are zeroed, with a warning) is part of what the
// conformance tests check.
std::optional<double> NonFinite(std::string_view cell) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (cell == "NaN") return std::numeric_limits<double>::quiet_NaN();
  if (cell == "Infinity" || cell == "+Infinity") return kInfinity;
  if (cell == "-Infinity") return -kInfinity;
  return std::nullopt;
}

// One control cell, or an error naming file, line and cell. A cell is a decimal number
// (one beyond the range of a double reads as +-Infinity, as in the oracle) or NaN,
// Infinity, -Infinity; never hex, "nan", "inf", an empty cell or trailing text.
double ControlCell(std::string_view raw, const std::string& where, size_t column) {
  const std::string_view cell = TrimCell(raw);
  if (IsDecimal(cell)) return std::strtod(std::string(cell).c_str(), nullptr);
  if (const std::optional<double> value = NonFinite(cell)) return *value;
  throw Error(where + ": cell " + std::to_string(column) + " is " + Quoted(cell) +
              ", not a number (a control is a decimal number like -0.5 or 2e-3, or NaN, "
              "Infinity, -Infinity)");
}

// The numbers of one control row: every comma-separated cell, empty ones included.
std::vector<double> ControlRow(std::string_view line, const std::string& where) {
  std::vector<double> row;
  for (size_t start = 0;;) {
    const size_t comma = line.find(',', start);
    row.push_back(ControlCell(line.substr(start, comma - start), where, row.size() + 1));
    if (comma == std::string_view::npos) return row;
    start = comma + 1;
  }
}

// Control rows (FORMAT.md): nu comma-separated numbers per line (ControlCell); blank
// lines and lines starting with '#' are skipped.
std::vector<std::vector<double>> ReadControls(const std::string& path, int nu) {
  std::vector<std::vector<double>> rows;
  std::istringstream lines(ReadInputFile(path, "--ctrl"));
  std::string line;
  for (int lineno = 1; std::getline(lines, line); lineno++) {
    const std::string_view content = TrimCell(line);
    if (content.empty() || content[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(lineno);
    std::vector<double> row = ControlRow(content, where);
    if (static_cast<int>(row.size()) != nu) {
      throw Error(where + ": expected " + Count(static_cast<size_t>(nu), "control") +
                  ", found " + std::to_string(row.size()));
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
  h["nactuator"] = m.nactuator;  // (as the native MuJoCo's rollout: actuator_* arrays have
  h["nout"] = m.nout;            // nout entries, ctrl nu)
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

// Where rollout records go, under the name messages give it; every write is checked, so
// a full disk or an I/O error stops the rollout with a message instead of passing silently.
class RecordSink {
 public:
  // Opens `path` for writing, or uses `fallback` (standard output) when it is empty.
  RecordSink(const std::string& path, std::ostream& fallback)
      : name_(path.empty() ? "standard output" : path) {
    if (path.empty()) {
      out_ = &fallback;
      return;
    }
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
      throw Error(path + ": cannot write the --out file: it is a folder");
    }
    errno = 0;
    file_.open(path, std::ios::binary | std::ios::trunc);
    if (!file_) throw Error(path + ": cannot write the --out file: " + SystemError("cannot open it"));
    out_ = &file_;
  }

  std::ostream& stream() {
    errno = 0;  // so a failure below reports its own cause
    return *out_;
  }

  // Throws once a write has failed.
  void Check() const {
    if (!*out_) throw Error(name_ + ": cannot write: " + SystemError("write error"));
  }

  // Flushes (and closes a file), then checks that every byte went out.
  void Finish() {
    errno = 0;
    out_->flush();
    Check();
    if (file_.is_open()) {
      file_.close();
      Check();
    }
  }

 private:
  std::string name_;
  std::ofstream file_;
  std::ostream* out_ = nullptr;
};

// The header line: the table's column titles, or the JSON header.
void WriteHeader(std::ostream& out, const RolloutOptions& o, Model& m, Data& d) {
  if (!o.table) {
    out << Header(m, d).dump() << "\n";
    return;
  }
  out << "  step      time";
  for (int i = 0; i < std::min(m.nq, 4); i++) out << "     qpos[" << i << "]";
  out << "\n";
}

}  // namespace

RolloutWarnings::RolloutWarnings(Data& d, std::ostream& out) : out_(out) {
  d.warning_callback = [this](const Data& data, Warning w, int, const std::string& text) {
    if (data.warning[w].number != 1) return;  // the first of each kind only
    out_ << "simlab: warning: " << text << "\n";
  };
}

void RolloutWarnings::Summary(const Data& d) const {
  for (int w = 0; w < kNumWarnings; w++) {
    const WarningStat& stat = d.warning[w];
    if (stat.number == 0) continue;
    out_ << "simlab: warning: " << WarningName(w) << ": " << stat.number << " time"
         << (stat.number == 1 ? "" : "s") << " in the rollout (last info " << stat.lastinfo
         << ")\n";
  }
}

int RunRollout(const RolloutOptions& o, std::ostream& default_out, std::ostream* warnings) {
  // Inputs first, so a bad one leaves --out untouched.
  Model m = LoadXml(o.model);
  Data d = MakeData(m);
  std::optional<RolloutWarnings> report;
  if (warnings) report.emplace(d, *warnings);
  if (o.key >= 0) ResetDataKeyframe(m, d, o.key);
  if (!o.state.empty()) ApplyState(m, d, o.state);
  std::vector<std::vector<double>> ctrl;
  if (!o.ctrl.empty()) ctrl = ReadControls(o.ctrl, m.nu);

  // Output goes to the file, or standard output; each record is checked as it goes.
  RecordSink sink(o.out, default_out);
  WriteHeader(sink.stream(), o, m, d);
  sink.Check();
  auto record = [&](int step) {
    if (o.table) {
      PrintTableRow(sink.stream(), m, d, step);
    } else {
      sink.stream() << Record(m, d, step).dump() << "\n";
    }
    sink.Check();
  };

  // Step 0 after forward, then every M-th step and the last.
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
  sink.Finish();
  if (report) report->Summary(d);
  return 0;
}

void AddRolloutCommand(CLI::App& app, CommandIo& io) {
  // Integer ranges that say their bounds plainly ("not in range 0 to 2147483647").
  const CLI::Range kCount(0, std::numeric_limits<int>::max());
  const CLI::Range kPositive(1, std::numeric_limits<int>::max());
  auto options = std::make_shared<RolloutOptions>();
  CLI::App* cmd = app.add_subcommand("rollout", "simulate a model and write the rollout format");
  cmd->add_option("model", options->model, "MJCF file")->required();
  cmd->add_option("--key", options->key, "reset to this keyframe")->check(kCount);
  cmd->add_option("--state", options->state, "JSON object of Data fields to overwrite");
  cmd->add_option("--ctrl", options->ctrl,
                  "CSV of controls, one row per step (decimal numbers, NaN, Infinity)");
  cmd->add_option("--steps", options->steps, "number of steps")->check(kCount);
  cmd->add_option("--every", options->every, "record every M-th step")->check(kPositive);
  cmd->add_option("--out", options->out, "output file (default: standard output)");
  cmd->add_flag("--table", options->table, "print a short table instead of JSON Lines");
  cmd->callback([options, &io] { io.status = RunRollout(*options, *io.out, io.err); });
}

}  // namespace simlab::apps
