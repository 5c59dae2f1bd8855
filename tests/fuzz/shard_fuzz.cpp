// Fuzz target: a shard's record (common/shard.h) as `vt merge` reads it: shard.json read and
// checked as a whole job of one shard (a shard of several is refused as incomplete); then each
// record of a crosscheck's shard decoded as the merge decodes it (verify/crosscheck_captures.cpp:
// its counts and its JUnit case, a malformed one refused), each decoded record written and read
// back the same, and the case written as JUnit XML.

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "common/shard.h"
#include "fuzz/fuzz_files.h"
#include "fuzz/fuzz_targets.h"
#include "verify/comparison_report.h"
#include "verify/junit_report.h"

namespace vt::fuzz {
namespace {

void checkCapturesRecord(const nlohmann::json& record, const std::filesystem::path& folder) {
  const ComparisonTotals totals = ComparisonTotals::fromRecord(record.at("totals"));
  if (ComparisonTotals::fromRecord(totals.record()).record() != totals.record())
    throw std::logic_error("counts read back as others: " + totals.record().dump());
  (void)totals.json();
  (void)totals.line();
  const JUnitCase testCase = junitCaseFromRecord(record.at("case"));
  if (junitCaseRecord(junitCaseFromRecord(junitCaseRecord(testCase))) != junitCaseRecord(testCase))
    throw std::logic_error("a JUnit case read back as another: " +
                           junitCaseRecord(testCase).dump());
  writeJUnitReport(folder / "junit.xml", "fuzz", {testCase});
}

}  // namespace

void shardRecord(Input input) {
  static const ScratchFolder folder("shard");
  writeBytes(folder.path() / "shard.json", textOf(input));
  const ShardFile shard = readShardFile(folder.path());
  try {
    requireCompleteJob({shard});
  } catch (const InputError&) {
    // A shard of a job of several: its records are decoded all the same.
  }
  for (const nlohmann::json& record : shard.records) {
    try {
      checkCapturesRecord(record, folder.path());
    } catch (const nlohmann::json::exception&) {
      // The merge refuses the record as malformed, naming the shard's file.
    } catch (const std::invalid_argument&) {
      // An unknown JUnit outcome: refused as malformed the same way.
    }
  }
}

}  // namespace vt::fuzz

VT_FUZZ_TARGET(vt::fuzz::shardRecord)
