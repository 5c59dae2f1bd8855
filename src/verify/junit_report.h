#pragma once
// A JUnit XML report, the format CI systems (GitLab, Jenkins, GitHub test reporters) display:
// one test suite of test cases, each passed, failed (a check found a difference) or in error (it
// could not run: a malformed input).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace vt {

struct JUnitCase {
  std::string name;
  double seconds = 0.0;
  enum class Outcome { kPassed, kFailed, kError } outcome = Outcome::kPassed;
  std::string message;  // one line, for failures and errors
  std::string details;  // the body of <failure> or <error>
  // <properties> of the test case (name, value), as Jenkins' and pytest's JUnit XML write them.
  std::vector<std::pair<std::string, std::string>> properties;
};

// Writes the suite `name` through a temporary file renamed into place.
void writeJUnitReport(const std::filesystem::path& file, const std::string& name,
                      const std::vector<JUnitCase>& cases);

// A case as JSON and back, for a shard's record (common/shard.h); junitCaseFromRecord throws
// nlohmann::json::exception when the record is malformed, std::invalid_argument for an unknown
// outcome.
nlohmann::json junitCaseRecord(const JUnitCase& testCase);
JUnitCase junitCaseFromRecord(const nlohmann::json& record);

// Text with &, <, >, " and ' escaped, and control characters XML 1.0 cannot hold replaced by '?'.
std::string escapeXml(const std::string& text);

}  // namespace vt
