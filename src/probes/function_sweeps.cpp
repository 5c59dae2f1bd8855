#include "probes/function_sweeps.h"

namespace vt::calibrate {

const std::vector<FunctionSweep>& functionSweeps() {
  static const std::vector<FunctionSweep> sweeps = {
      {"log2", "log2(x)", 0x3f000000u, uint32_t{1} << 24},  // [0.5, 2)
      {"sqrt", "sqrt(x)", 0x3f800000u, uint32_t{1} << 24},  // [1, 4)
  };
  return sweeps;
}

}  // namespace vt::calibrate
