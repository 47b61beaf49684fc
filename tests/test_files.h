// Helpers for tests that read files of the repository: paths below the source folder and
// control schedules (one row of comma-separated numbers per step, '#' lines comments).
#ifndef SIMLAB_TESTS_TEST_FILES_H_
#define SIMLAB_TESTS_TEST_FILES_H_

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace simlab::test_util {

// `relative` below the repository (SIMLAB_SOURCE_DIR).
inline std::string SourcePath(const std::string& relative) {
  return std::string(SIMLAB_SOURCE_DIR) + "/" + relative;
}

// The rows of a control file, `relative` below the repository.
inline std::vector<std::vector<double>> ReadControlRows(const std::string& relative) {
  std::vector<std::vector<double>> rows;
  std::ifstream in(SourcePath(relative));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<double> row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace simlab::test_util

#endif  // SIMLAB_TESTS_TEST_FILES_H_
