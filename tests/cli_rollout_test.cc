// `simlab rollout` on hostile inputs, run through RunSimlab (what main runs): a --state
// file whose values are strings, booleans, null or nested wrongly, --ctrl cells that are
// not finite decimal numbers, folders and devices given as files, and an --out that
// cannot be written. Each gives one line `simlab: FILE[:LINE]: why` and exit status 1,
// never an abort. The last tests run the built `simlab` as a process.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <streambuf>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "cli.h"

namespace simlab::apps {
namespace {

namespace fs = std::filesystem;

// One hinge with a motor: nq = nv = nu = 1.
constexpr char kPendulum[] = R"(<mujoco>
  <worldbody>
    <body>
      <joint name="hinge" axis="0 1 0"/>
      <geom type="capsule" size="0.05" fromto="0 0 0 0 0 -0.5"/>
    </body>
  </worldbody>
  <actuator><motor joint="hinge"/></actuator>
</mujoco>
)";

// What follows a --ctrl cell that is not a number.
constexpr char kNotANumber[] =
    ", not a number (a control is a decimal number like -0.5 or 2e-3, or NaN, Infinity, "
    "-Infinity)";

// What a run of the command line gave.
struct Outcome {
  int status = -1;
  std::string out;
  std::string err;
};

// A scratch folder with the pendulum, and the command line run in-process.
class CliRolloutTest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(scratch_);
    Write("model.xml", kPendulum);
  }
  void TearDown() override { fs::remove_all(scratch_); }

  // Writes a scratch file and returns its path.
  std::string Write(const std::string& name, const std::string& text) const {
    std::ofstream(scratch_ / name, std::ios::binary) << text;
    return (scratch_ / name).string();
  }
  std::string Model() const { return (scratch_ / "model.xml").string(); }
  std::string folder_lesson() const { return scratch_.string(); }

  // `simlab ARGS...` with standard output captured in `out` (or given).
  static Outcome Run(const std::vector<std::string>& args, std::ostream* out = nullptr) {
    std::vector<const char*> argv = {"simlab"};
    for (const std::string& arg : args) argv.push_back(arg.c_str());
    std::ostringstream captured, err;
    Outcome outcome;
    outcome.status = RunSimlab(static_cast<int>(argv.size()), argv.data(),
                               out ? *out : captured, err);
    outcome.out = captured.str();
    outcome.err = err.str();
    return outcome;
  }

  // A rollout of the pendulum with `--state` given `json`.
  Outcome WithState(const std::string& json) const {
    return Run({"rollout", Model(), "--state", Write("state.json", json)});
  }
  // A rollout of the pendulum for 2 steps with `--ctrl` given `csv`.
  Outcome WithCtrl(const std::string& csv) const {
    return Run({"rollout", Model(), "--steps", "2", "--ctrl", Write("ctrl.csv", csv)});
  }

  fs::path scratch_ = fs::temp_directory_path() / ("simlab_cli_test_" + std::to_string(::getpid()));
};

// Expects exit status 1 and exactly the one line `simlab: MESSAGE`.
void ExpectError(const Outcome& outcome, const std::string& message) {
  EXPECT_EQ(outcome.status, kExitError) << outcome.err;
  EXPECT_EQ(outcome.err, "simlab: " + message + "\n");
}

// The records of a JSON Lines rollout (the header dropped).
std::vector<nlohmann::json> Records(const std::string& jsonl) {
  std::vector<nlohmann::json> records;
  std::istringstream lines(jsonl);
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) records.push_back(nlohmann::json::parse(line));
  return records;
}

TEST_F(CliRolloutTest, StateValuesOfTheWrongTypeAreNamed) {
  const std::string file = (scratch_ / "state.json").string();
  ExpectError(WithState(R"({"qpos": ["0.5"]})"),
              file + ": \"qpos\"[0]: expected a number, found string");
  ExpectError(WithState(R"({"time": true})"), file + ": \"time\": expected a number, found boolean");
  ExpectError(WithState(R"({"time": null})"), file + ": \"time\": expected a number, found null");
  ExpectError(WithState(R"({"qvel": null})"),
              file + ": \"qvel\": expected an array of 1 number, found null");
  ExpectError(WithState(R"({"qvel": false})"),
              file + ": \"qvel\": expected an array of 1 number, found boolean");
  ExpectError(WithState(R"({"qpos": [[0.5]]})"),
              file + ": \"qpos\"[0]: expected a number, found array");
  ExpectError(WithState(R"({"qpos": {"x": 1}})"),
              file + ": \"qpos\": expected an array of 1 number, found object");
  ExpectError(WithState(R"({"qpos": [0.5, 1]})"),
              file + ": \"qpos\": expected an array of 1 number, found 2");
}

TEST_F(CliRolloutTest, StateFileOfTheWrongShapeIsNamed) {
  const std::string file = (scratch_ / "state.json").string();
  const std::string object = ": expected a JSON object of Data fields like {\"qpos\": [...], "
                             "\"time\": 0}, found ";
  ExpectError(WithState("[0.5]"), file + object + "array");
  ExpectError(WithState("\"qpos\""), file + object + "string");
  ExpectError(WithState("null"), file + object + "null");
  ExpectError(WithState(R"({"nothing": [1]})"), file + ": unknown state field \"nothing\"");
  ExpectError(WithState("{\"a\\nb\": [1]}"), file + ": unknown state field \"a\\nb\"");
  ExpectError(WithState(R"({"dof_island": [0]})"),
              file + ": \"dof_island\" holds integers and cannot be set by --state");
  const Outcome broken = WithState(R"({"qpos": [0.5,)");
  EXPECT_EQ(broken.status, kExitError);
  EXPECT_EQ(broken.err.rfind("simlab: " + file + ": not valid JSON: ", 0), 0u) << broken.err;
  EXPECT_EQ(std::count(broken.err.begin(), broken.err.end(), '\n'), 1) << broken.err;
}

TEST_F(CliRolloutTest, GoodStateIsApplied) {
  const Outcome outcome = WithState(R"({"qpos": [0.5], "qvel": [-1], "time": 2})");
  ASSERT_EQ(outcome.status, 0) << outcome.err;
  const std::vector<nlohmann::json> records = Records(outcome.out);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0]["qpos"][0], 0.5);
  EXPECT_EQ(records[0]["qvel"][0], -1.0);
  EXPECT_EQ(records[0]["time"], 2.0);
}

// A control cell is a decimal number, or NaN/Infinity/-Infinity as the oracle writes
// them (FORMAT.md: rows of numbers); anything else is named with file, line and cell.
TEST_F(CliRolloutTest, ControlCellsMustBeNumbers) {
  const std::string file = (scratch_ / "ctrl.csv").string();
  const std::string why = kNotANumber;
  for (const std::string cell : {"1abc", "0x10", "nan", "inf", "-inf", "infinity", "NaN1",
                                 "1e", ".", "--1", "1.2.3", "1e5x", "e5", "1 2", "abc", "1_000"}) {
    ExpectError(WithCtrl("# a comment\n0.5\n" + cell + "\n"),
                file + ":3: cell 1 is \"" + cell + "\"" + why);
  }
  ExpectError(WithCtrl("0.5,\n"), file + ":1: cell 2 is \"\"" + why);
  ExpectError(WithCtrl(" ,0.5\n"), file + ":1: cell 1 is \"\"" + why);
  ExpectError(WithCtrl("\x01\xff\n"), file + ":1: cell 1 is \"\\x01\\xff\"" + why);
  ExpectError(WithCtrl(std::string(50, '7') + "z\n"),
              file + ":1: cell 1 is \"" + std::string(40, '7') + "...\"" + why);
  ExpectError(WithCtrl("0.5, 1\n"), file + ":1: expected 1 control, found 2");
}

// Every way of writing a decimal number is read as one, around blanks and a CR.
TEST_F(CliRolloutTest, DecimalControlCellsAreRead) {
  const std::vector<std::pair<std::string, double>> cells = {
      {" -0.5 ", -0.5}, {"+1", 1.0}, {".5", 0.5}, {"5.", 5.0},
      {"2e-3", 2e-3},   {"1E+2", 100.0}, {"\t3\r", 3.0}, {"1e-400", 0.0}};
  for (const auto& [cell, value] : cells) {
    const Outcome outcome = WithCtrl("0.25\n" + cell + "\n");
    ASSERT_EQ(outcome.status, 0) << cell << ": " << outcome.err;
    const std::vector<nlohmann::json> records = Records(outcome.out);
    ASSERT_EQ(records.size(), 3u);
    EXPECT_EQ(records[1]["ctrl"][0], 0.25);
    EXPECT_EQ(records[2]["ctrl"][0], value) << cell;
  }
}

// NaN and infinite controls, as the oracle spells them (and a decimal beyond the double
// range, which both read as Infinity), are taken: MuJoCo's bad-control handling is
// tested with them.
TEST_F(CliRolloutTest, NonFiniteControlsAreRead) {
  for (const std::string cell : {"NaN", "Infinity", "+Infinity", "-Infinity", "1e999"}) {
    const Outcome outcome = WithCtrl(cell + "\n");
    EXPECT_EQ(outcome.status, 0) << cell << ": " << outcome.err;
    // MuJoCo zeroes them with a warning: the first as raised, then the count.
    EXPECT_EQ(outcome.err,
              "simlab: warning: bad ctrl (NaN or too large): controls zeroed (info 0, time "
              "0.0000)\n"
              "simlab: warning: bad ctrl (NaN or too large): controls zeroed: 2 times in the "
              "rollout (last info 0)\n")
        << cell;
  }
}

// The engine's warnings reach standard error, the first of each kind as it is raised
// and a count at the end; the rollout goes on (MuJoCo resets the state).
TEST_F(CliRolloutTest, WarningsArePrinted) {
  const Outcome outcome = Run({"rollout", Model(), "--steps", "3", "--state",
                               Write("state.json", R"({"qvel": [1e300]})")});
  EXPECT_EQ(outcome.status, 0) << outcome.err;
  EXPECT_EQ(outcome.err,
            "simlab: warning: bad qvel (NaN or too large): simulation reset (info 0, time "
            "0.0000)\n"
            "simlab: warning: bad qvel (NaN or too large): simulation reset: 1 time in the "
            "rollout (last info 0)\n");
  EXPECT_EQ(Records(outcome.out).size(), 4u);
}

// Folders, devices and missing files are refused by name; a pipe is read.
TEST_F(CliRolloutTest, InputsMustBeFilesOrPipes) {
  const std::string folder = scratch_.string();
  ExpectError(Run({"rollout", Model(), "--ctrl", folder}),
              folder + ": cannot read the --ctrl file: it is a folder, not a file");
  ExpectError(Run({"rollout", Model(), "--state", folder}),
              folder + ": cannot read the --state file: it is a folder, not a file");
  ExpectError(Run({"rollout", Model(), "--ctrl", folder + "/none.csv"}),
              folder + "/none.csv: cannot read the --ctrl file: No such file or directory");
  if (fs::exists("/dev/zero")) {
    ExpectError(Run({"rollout", Model(), "--ctrl", "/dev/zero"}),
                "/dev/zero: cannot read the --ctrl file: it is not a regular file (a device or "
                "socket)");
  }
  // A named pipe, as `--ctrl <(generator)` gives.
  const fs::path fifo = scratch_ / "ctrl.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(fifo) << "0.125\n"; });
  const Outcome piped = Run({"rollout", Model(), "--steps", "1", "--ctrl", fifo.string()});
  writer.join();
  ASSERT_EQ(piped.status, 0) << piped.err;
  EXPECT_EQ(Records(piped.out).at(1)["ctrl"][0], 0.125);
}

// An --out that cannot be opened or written (a folder, a missing folder, a full disk)
// is an error; a bad input leaves an existing --out as it was.
TEST_F(CliRolloutTest, OutputThatCannotBeWrittenIsReported) {
  const std::string folder = scratch_.string();
  ExpectError(Run({"rollout", Model(), "--out", folder}),
              folder + ": cannot write the --out file: it is a folder");
  ExpectError(Run({"rollout", Model(), "--out", folder + "/none/out.jsonl"}),
              folder + "/none/out.jsonl: cannot write the --out file: No such file or directory");
  if (fs::exists("/dev/full")) {
    ExpectError(Run({"rollout", Model(), "--steps", "10", "--out", "/dev/full"}),
                "/dev/full: cannot write: No space left on device");
  }
  const std::string kept = Write("kept.jsonl", "kept");
  ExpectError(Run({"rollout", Model(), "--ctrl", Write("ctrl.csv", "x\n"), "--out", kept}),
              (scratch_ / "ctrl.csv").string() + ":1: cell 1 is \"x\"" + kNotANumber);
  std::ifstream in(kept);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "kept");
}

// A stream buffer that takes `room` bytes and then fails, as a full disk does.
class FullBuffer : public std::streambuf {
 public:
  explicit FullBuffer(size_t room) : room_(room) {}

 protected:
  int_type overflow(int_type c) override {
    if (room_ == 0) return traits_type::eof();
    room_--;
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    const auto taken = std::min<std::streamsize>(n, static_cast<std::streamsize>(room_));
    room_ -= static_cast<size_t>(taken);
    return taken;
  }

 private:
  size_t room_;
};

// Standard output that stops taking bytes is reported, by rollout and by explain.
TEST_F(CliRolloutTest, StandardOutputThatFailsIsReported) {
  FullBuffer full(100);
  std::ostream out(&full);
  ExpectError(Run({"rollout", Model(), "--steps", "5"}, &out),
              "standard output: cannot write: write error");
  FullBuffer none(0);
  std::ostream nothing(&none);
  ExpectError(Run({"explain", Model()}, &nothing), "standard output: cannot write: write error");
}

// A model that does not load, a missing keyframe and a missing lesson: one line each.
TEST_F(CliRolloutTest, OtherFailuresAreOneLine) {
  const Outcome missing = Run({"rollout", (scratch_ / "none.xml").string()});
  EXPECT_EQ(missing.status, kExitError);
  EXPECT_EQ(missing.err.rfind("simlab: ", 0), 0u) << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  ExpectError(Run({"rollout", Model(), "--key", "3"}),
              "keyframe 3 does not exist (the model has 0)");
  ExpectError(Run({"lab", folder_lesson()}), "lab: " + folder_lesson() +
                                                ": a folder, not a lesson file");
  ExpectError(Run({"view", (scratch_ / "none.xml").string()}),
              "view: no model file " + (scratch_ / "none.xml").string());
  // A repository without the WebAssembly build: the command says how to build it.
  fs::create_directories(scratch_ / "site/web/lesson");
  std::ofstream(scratch_ / "site/web/lesson/index.html") << "<html></html>";
  const Outcome unbuilt = Run({"view", Model(), "--root", (scratch_ / "site").string()});
  EXPECT_EQ(unbuilt.status, kExitError);
  EXPECT_NE(unbuilt.err.find("view: the WebAssembly engine is not built"), std::string::npos) << unbuilt.err;
  EXPECT_NE(unbuilt.err.find("bash tools/build_wasm.sh"), std::string::npos) << unbuilt.err;
  EXPECT_EQ(OneLine("a\nb\r\n\tc\n"), "a b   c");
}

// Arguments the command does not take: one line and status 2; --help still prints.
TEST_F(CliRolloutTest, UsageErrorsAreOneLine) {
  const Outcome key = Run({"rollout", Model(), "--key", "-2"});
  EXPECT_EQ(key.status, kExitUsage);
  EXPECT_EQ(key.err,
            "simlab: --key: Value -2 not in range 0 to 2147483647 (simlab --help lists the "
            "options)\n");
  const Outcome none = Run({});
  EXPECT_EQ(none.status, kExitUsage);
  EXPECT_EQ(none.err.rfind("simlab: ", 0), 0u) << none.err;
  EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
  const Outcome help = Run({"--help"});
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("rollout"), std::string::npos) << help.out;
}

// The built command, as a process: its status and the one line on standard error.
class CliProcessTest : public CliRolloutTest {
 protected:
  void SetUp() override {
    CliRolloutTest::SetUp();
    simlab_ = fs::read_symlink("/proc/self/exe").parent_path() / "simlab";
    if (!fs::exists(simlab_)) GTEST_SKIP() << "no simlab executable beside the tests";
  }
  // Runs `simlab ARGS` through the shell; standard error lands in `err`.
  Outcome Shell(const std::string& args) const {
    const fs::path err = scratch_ / "stderr.txt";
    const std::string command = "'" + simlab_.string() + "' " + args + " 2>'" + err.string() + "'";
    const int raw = std::system(command.c_str());
    Outcome outcome;
    outcome.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    std::ifstream in(err);
    outcome.err.assign(std::istreambuf_iterator<char>(in), {});
    return outcome;
  }
  fs::path simlab_;
};

TEST_F(CliProcessTest, BadStateIsOneLineAndStatusOne) {
  const std::string state = Write("state.json", R"({"qpos": [true]})");
  ExpectError(Shell("rollout '" + Model() + "' --state '" + state + "' >/dev/null"),
              state + ": \"qpos\"[0]: expected a number, found boolean");
}

TEST_F(CliProcessTest, FullStandardOutputIsReported) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  ExpectError(Shell("explain '" + Model() + "' >/dev/full"),
              "standard output: cannot write: No space left on device");
  ExpectError(Shell("rollout '" + Model() + "' --steps 3 >/dev/full"),
              "standard output: cannot write: No space left on device");
}

}  // namespace
}  // namespace simlab::apps
