#pragma once
// Google Benchmark's console output plus the ratio of two benchmarks' times per iteration, which
// the benchmarks print because absolute times on shared machines are noisy and ratios are not.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& run : runs) seconds_[run.run_name.function_name] = run.GetAdjustedRealTime();
    ConsoleReporter::ReportRuns(runs);
  }

  // Prints `format` with time(numerator) / time(denominator), when both ran.
  void printRatio(const std::string& numerator, const std::string& denominator,
                  const char* format) const {
    const auto a = seconds_.find(numerator), b = seconds_.find(denominator);
    if (a == seconds_.end() || b == seconds_.end()) return;
    std::printf(format, a->second / b->second);
  }

 private:
  std::map<std::string, double> seconds_;
};
