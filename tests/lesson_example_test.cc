// The lesson's example program on our engine: examples/l2_3_actuators.cpp prints the
// lines the lesson prints (lines 54-70 of the lesson's text), digit for digit.
//
// The lesson's text has its runs of spaces collapsed to one, so lines are compared with
// whitespace collapsed; the table's column layout (the Python f-string widths and
// numpy's alignment) is checked separately, exactly.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#define SIMLAB_L2_3_NO_MAIN
#include "../examples/l2_3_actuators.cpp"

namespace {

const std::string kSourceDir = SIMLAB_SOURCE_DIR;

// The lesson's printed output, as the lesson's text shows it.
const std::vector<std::string> kLessonLines = {
    "force laws at q = 0.3 rad, qdot = -0.5 rad/s:",
    "actuator gainprm[0] biasprm[0:3] actuator_force formula qfrc_actuator",
    "motor 1 [0. 0. 0.] 0.4000 0.4000 0.8000",
    "position 10 [ 0. -10. -1.] 2.5000 2.5000 2.5000",
    "velocity 3 [ 0. 0. -3.] 4.5000 4.5000 4.5000",
    "filter 5 [0. 0. 0.] 0.0000 0.0000 0.0000",
    "(the motor's actuator_force is in actuator space, 0.4; the joint torque is gear * 0.4 = 0.8)",
    "clamping:",
    "motor ctrl 5.0 with ctrlrange [-1, 1] -> actuator_force 1.000 (data.ctrl still reads 5.0)",
    "position target 2 rad, kp 10, forcerange [-3, 3] -> actuator_force 3.000",
    "filter activation, time constant 0.1 s, control stepped to 1 at t = 0:",
    "t = 0.05 s: act = 0.3965, 1 - exp(-t/tau) = 0.3935",
    "t = 0.10 s: act = 0.6358, 1 - exp(-t/tau) = 0.6321",
    "t = 0.20 s: act = 0.8674, 1 - exp(-t/tau) = 0.8647",
    "t = 0.50 s: act = 0.9936, 1 - exp(-t/tau) = 0.9933",
    "gripper coupling (tendon + joint equality):",
    "grip command 0.03 m: finger_left 0.03000 m, finger_right 0.03000 m, tendon length 0.03000 m",
};

// Runs of whitespace become one space; leading and trailing whitespace go.
std::string Collapse(const std::string& line) {
  std::istringstream words(line);
  std::string word, out;
  while (words >> word) out += (out.empty() ? "" : " ") + word;
  return out;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The example's whole output.
std::string RunExample() {
  std::ostringstream out;
  l2_3::RunLesson(kSourceDir + "/models", out);
  return out.str();
}

TEST(LessonExample, PrintsTheLessonsLines) {
  std::vector<std::string> lines = Lines(RunExample());
  ASSERT_EQ(lines.size(), kLessonLines.size());
  for (size_t i = 0; i < kLessonLines.size(); i++) {
    EXPECT_EQ(Collapse(lines[i]), kLessonLines[i]) << "line " << i;
  }
}

TEST(LessonExample, TableColumnsHaveThePythonWidths) {
  std::vector<std::string> lines = Lines(RunExample());
  ASSERT_GE(lines.size(), 6u);
  // ' {:<9}{:>11}{:>22}{:>16}{:>10}{:>15}', numpy padding each number to a common width.
  EXPECT_EQ(lines[1],
            " actuator  gainprm[0]          biasprm[0:3]  actuator_force   formula  qfrc_actuator");
  EXPECT_EQ(lines[2],
            " motor              1            [0. 0. 0.]          0.4000    0.4000         0.8000");
  EXPECT_EQ(lines[3],
            " position          10      [  0. -10.  -1.]          2.5000    2.5000         2.5000");
  EXPECT_EQ(lines[4],
            " velocity           3         [ 0.  0. -3.]          4.5000    4.5000         4.5000");
}

// Guards the copy above: every expected line is a line of the lesson, when the lesson
// is checked out beside the repository.
TEST(LessonExample, ExpectedLinesAreTheLessonsText) {
  std::ifstream in(kSourceDir + "/../shared/lesson/lesson-2.3-actuators.txt");
  if (!in) GTEST_SKIP() << "lesson text not found beside the repository";
  std::stringstream text;
  text << in.rdbuf();
  std::vector<std::string> lesson = Lines(text.str());
  for (const std::string& expected : kLessonLines) {
    bool found = false;
    for (const std::string& line : lesson) found = found || Collapse(line) == expected;
    EXPECT_TRUE(found) << expected;
  }
}

// Python's float repr and numpy's array2string, as the example reproduces them.
TEST(LessonExample, PythonAndNumpyNumberText) {
  EXPECT_EQ(l2_3::PythonFloat(5.0), "5.0");
  EXPECT_EQ(l2_3::PythonFloat(0.3), "0.3");
  EXPECT_EQ(l2_3::PythonFloat(-0.1), "-0.1");
  EXPECT_EQ(l2_3::PythonFloat(5000.0), "5000.0");
  EXPECT_EQ(l2_3::PythonFloat(1e16), "1e+16");
  EXPECT_EQ(l2_3::PythonFloat(1e-5), "1e-05");
  EXPECT_EQ(l2_3::PythonFloat(0.1 + 0.2), "0.30000000000000004");
  const double zeros[] = {0, 0, 0}, servo[] = {0, -10, -1}, mixed[] = {0.5, -0.125};
  EXPECT_EQ(l2_3::NumpyArray(zeros, 3, 3), "[0. 0. 0.]");
  EXPECT_EQ(l2_3::NumpyArray(servo, 3, 3), "[  0. -10.  -1.]");
  EXPECT_EQ(l2_3::NumpyArray(mixed, 2, 3), "[ 0.5   -0.125]");
}

}  // namespace
