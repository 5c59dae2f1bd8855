#include "verify/junit_report.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>

#include "common/posix_file.h"

namespace vt {

std::string escapeXml(const std::string& text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        // Tab, line feed and carriage return are the only control characters XML 1.0 allows.
        escaped +=
            static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r' ? '?' : c;
    }
  }
  return escaped;
}

namespace {

constexpr std::array<const char*, 3> kOutcomes = {"passed", "failed", "error"};

}  // namespace

nlohmann::json junitCaseRecord(const JUnitCase& testCase) {
  return {{"name", testCase.name},
          {"seconds", testCase.seconds},
          {"outcome", kOutcomes[static_cast<size_t>(testCase.outcome)]},
          {"message", testCase.message},
          {"details", testCase.details},
          {"properties", testCase.properties}};
}

JUnitCase junitCaseFromRecord(const nlohmann::json& record) {
  JUnitCase testCase;
  record.at("name").get_to(testCase.name);
  record.at("seconds").get_to(testCase.seconds);
  const std::string outcome = record.at("outcome").get<std::string>();
  const auto known = std::find(kOutcomes.begin(), kOutcomes.end(), outcome);
  if (known == kOutcomes.end()) throw std::invalid_argument("unknown outcome \"" + outcome + "\"");
  testCase.outcome = static_cast<JUnitCase::Outcome>(known - kOutcomes.begin());
  record.at("message").get_to(testCase.message);
  record.at("details").get_to(testCase.details);
  record.at("properties").get_to(testCase.properties);
  return testCase;
}

void writeJUnitReport(const std::filesystem::path& file, const std::string& name,
                      const std::vector<JUnitCase>& cases) {
  size_t failures = 0, errors = 0;
  double seconds = 0.0;
  for (const JUnitCase& c : cases) {
    failures += c.outcome == JUnitCase::Outcome::kFailed;
    errors += c.outcome == JUnitCase::Outcome::kError;
    seconds += c.seconds;
  }
  const auto number = [](double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", value);
    return std::string(text);
  };
  const std::string counts = " tests=\"" + std::to_string(cases.size()) + "\" failures=\"" +
                             std::to_string(failures) + "\" errors=\"" + std::to_string(errors) +
                             "\" time=\"" + number(seconds) + "\"";
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml.append("<testsuites name=\"")
      .append(escapeXml(name))
      .append("\"")
      .append(counts)
      .append(">\n");
  xml.append("  <testsuite name=\"")
      .append(escapeXml(name))
      .append("\"")
      .append(counts)
      .append(">\n");
  for (const JUnitCase& c : cases) {
    xml.append("    <testcase classname=\"").append(escapeXml(name)).append("\" name=\"");
    xml.append(escapeXml(c.name)).append("\" time=\"").append(number(c.seconds)).append("\"");
    if (c.outcome == JUnitCase::Outcome::kPassed && c.properties.empty()) {
      xml.append("/>\n");
      continue;
    }
    xml.append(">\n");
    if (!c.properties.empty()) {
      xml.append("      <properties>\n");
      for (const auto& [property, value] : c.properties)
        xml.append("        <property name=\"")
            .append(escapeXml(property))
            .append("\" value=\"")
            .append(escapeXml(value))
            .append("\"/>\n");
      xml.append("      </properties>\n");
    }
    if (c.outcome == JUnitCase::Outcome::kPassed) {
      xml.append("    </testcase>\n");
      continue;
    }
    const char* tag = c.outcome == JUnitCase::Outcome::kFailed ? "failure" : "error";
    xml.append("      <").append(tag).append(" message=\"").append(escapeXml(c.message));
    xml.append("\" type=\"")
        .append(c.outcome == JUnitCase::Outcome::kFailed ? "mismatch" : "input");
    xml.append("\">").append(escapeXml(c.details)).append("</").append(tag).append(">\n");
    xml.append("    </testcase>\n");
  }
  xml.append("  </testsuite>\n</testsuites>\n");
  writeFileAtomically(file, xml);
}

}  // namespace vt
