#include "probes/function_sweeps.h"

namespace vt::calibrate {

const std::vector<FunctionSweep>& functionSweeps() {
  static const std::vector<FunctionSweep> sweeps = {
      {"log2", "log2(x)", 0x3f000000u, uint32_t{1} << 24},  // [0.5, 2)
      {"sqrt", "sqrt(x)", 0x3f800000u, uint32_t{1} << 24},  // [1, 4)
      {"reciprocal", "1.0 / x", 0x3f800000u, uint32_t{1} << 23},  // [1, 2)
      {"frag_depth", "x", 0x3f000000u, uint32_t{1} << 23, SweepTarget::kDepth24},  // [0.5, 1)
      {"frag_depth_low", "x", 0x3b800000u, uint32_t{1} << 23, SweepTarget::kDepth24},  // [2^-8, 2^-7)
  };
  return sweeps;
}

const FunctionSweep* packSweep(const std::string& name) {
  for (const FunctionSweep& sweep : functionSweeps())
    if (sweep.name == name) return &sweep;
  return nullptr;
}

}  // namespace vt::calibrate
