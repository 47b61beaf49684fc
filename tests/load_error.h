// Helpers for tests of bad input: the message a load throws, and checks on its parts.
#ifndef SIMLAB_TESTS_LOAD_ERROR_H_
#define SIMLAB_TESTS_LOAD_ERROR_H_

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "simlab/simlab.h"

namespace simlab::test_util {

// The message of the Error that loading `xml` as "bad.xml" throws ("" if it loads).
inline std::string XmlLoadError(const std::string& xml) {
  try {
    LoadXmlString(xml, "bad.xml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The same for the file at `path`.
inline std::string FileLoadError(const std::string& path) {
  try {
    LoadXml(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// `msg` is an error message containing every one of `parts`.
inline void ExpectMessageParts(const std::string& msg, const std::vector<std::string>& parts,
                               const std::string& input) {
  ASSERT_FALSE(msg.empty()) << "expected an error for:\n" << input;
  for (const std::string& part : parts) {
    EXPECT_NE(msg.find(part), std::string::npos) << "missing '" << part << "' in: " << msg;
  }
}

}  // namespace simlab::test_util

#endif  // SIMLAB_TESTS_LOAD_ERROR_H_
