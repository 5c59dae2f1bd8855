#pragma once
// The evidence of one family's fit (render/arithmetic.h): every member tried against the same
// probes, with how many probe values each one misses. A family is pinned when a member
// reproduces every probe bit for bit; when none does, the parameter it stands for is bounded by
// the residual measured against the closest member, in the unit the precision model uses
// (render/precision_model.h), never rounded up.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vt::calibrate {

struct MemberResult {
  std::string member;       // the member's name, as in model files
  uint64_t mismatches = 0;  // probe values it does not reproduce bit for bit
};

struct ParameterFit {
  ParameterFit() = default;
  ParameterFit(std::string parameter, std::string probe, uint64_t probes,
               std::vector<MemberResult> members = {})
      : parameter(std::move(parameter)),
        probe(std::move(probe)),
        probes(probes),
        members(std::move(members)) {}

  std::string parameter;              // as in model files: "log2", "filter", ...
  std::string finding;                // what the probes showed, in words
  std::string probe;                  // the probes, in words
  uint64_t probes = 0;                // values compared
  std::vector<MemberResult> members;  // every member tried, in the family's order
  std::string chosen;                 // the member taken (pinned or closest)
  // Every member that reproduced every probe (more than one: the probes cannot tell them apart,
  // and `chosen` is the first).
  std::vector<std::string> consistent;
  uint64_t mismatches = 0;     // of the chosen member (0 when pinned)
  double largestResidual = 0;  // in the parameter's unit; 0 when pinned
  std::string unit;            // of largestResidual
  bool pinned = false;         // the chosen member reproduced every probe bit for bit
  bool fromGl45 = false;       // nothing fitted: the gl45 value is kept

  // Pins the first member with no mismatch, or takes the one with the fewest: `chosen`,
  // `consistent`, `mismatches` and `pinned` follow. Returns the chosen member's index.
  size_t choose();
  // "polynomial_fused 0 of 65536, libm 735 of 65536, ..."
  std::string memberSummary() const;
};

// The fit of `parameter` among `fits`; throws std::logic_error when there is none (a calibration
// always fits every parameter it names).
const ParameterFit& fitNamed(const std::vector<ParameterFit>& fits, const std::string& parameter);

// "k of n values differ".
std::string differ(uint64_t mismatches, uint64_t probes);

}  // namespace vt::calibrate
