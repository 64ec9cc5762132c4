// `ashlar test --junit FILE`: the run as JUnit XML, which CI systems (GitLab,
// Jenkins, GitHub actions that read test reports) show test by test.
#pragma once

#include <string>
#include <vector>

namespace ashlar::regression {

// One check script: a test case.
struct JunitCase {
  std::string name;                   // the script's file name
  double seconds = 0.0;
  std::vector<std::string> failures;  // the console's FAIL and ERROR lines for it
  std::string output;                 // what it wrote to stdout
  std::string error_output;           // ... and to stderr
};

// The XML of a suite (`suite` names it: the folder) of these cases: one
// <testcase> per script, with a <failure> holding its failure lines when
// it has any. Text that is not valid UTF-8 XML characters is replaced with
// U+FFFD.
std::string format_junit(const std::string& suite, const std::vector<JunitCase>& cases);

}  // namespace ashlar::regression
