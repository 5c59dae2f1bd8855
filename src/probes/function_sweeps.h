#pragma once
// Exhaustive sweeps of one GLSL function over every float of an interval, drawn in one call each:
// the fragment at pixel i (row by row, 4096 a row) makes its input from its own index, x =
// uintBitsToFloat(first + i), and writes the bits of the result to an R32UI target, so no input
// travels to the implementation. A depth sweep writes the value to gl_FragDepth instead, into a
// Z24 depth buffer, and returns the stored 24-bit integers: the conversion to Z24 of every float
// of the interval. The calibration draws them with its probes (recorded and drawn
// elsewhere as files: capture/sweep_files.h) and compares every value with each member of the
// function's family (calibrate/shader_math_fit.h).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vt::calibrate {

// Where a sweep's fragment puts its value: the result's bits in an R32UI target, or the value as
// gl_FragDepth into a Z24 depth buffer (the stored integer comes back).
enum class SweepTarget { kFloatBits, kDepth24 };

struct FunctionSweep {
  std::string name;        // "log2", "sqrt": also the file's name (sweep-NAME.delta)
  std::string expression;  // GLSL of `float x`
  uint32_t first = 0;      // the bits of the first input
  uint32_t count = 0;      // inputs: first, first + 1, ... (a multiple of kSweepWidth)
  SweepTarget target = SweepTarget::kFloatBits;
  bool operator==(const FunctionSweep&) const = default;
};

constexpr uint32_t kSweepWidth = 4096;
// The largest sweep a file may hold: 2^25 inputs (four binades), a 4096 x 8192 target.
constexpr uint32_t kMaxSweepCount = uint32_t{1} << 25;

// The pack: log2 of every float of [0.5, 2) (2^24 inputs) and sqrt of every float of [1, 4)
// (2^24), where implementations reduce their range (near 1 for log2, two binades for sqrt); the
// reciprocal 1.0 / x of every float of [1, 2) (2^23), one binade, which every other binade
// scales by a power of two; and every float of [0.5, 1) and of [2^-8, 2^-7) (2^23 each) written
// to gl_FragDepth into Z24. Near 1, where a scene's depths crowd, z * (2^24 - 1) rounded to a
// float is already whole, so the float product's members agree there and only a conversion
// through the exact product differs; in the lower binade the float product keeps 7 fractional
// bits, so rounding and truncation part.
const std::vector<FunctionSweep>& functionSweeps();

// The sweep named `name` in the pack, or none.
const FunctionSweep* packSweep(const std::string& name);

// The sweep drawn on the current context: the result bits, input order.
std::vector<uint32_t> drawFunctionSweepHere(const FunctionSweep& sweep);

// The sweep drawn on the current context, or by the set probe drawer (probes/probe_draws.h): none
// where that is a folder recorded without it (before sweeps were drawn). A result that is not a
// finite number (a depth sweep: a stored value above 2^24 - 1) breaks a rule: std::runtime_error,
// as for the probes (probes/probe_draws.cpp).
std::optional<std::vector<uint32_t>> functionSweep(const FunctionSweep& sweep);

}  // namespace vt::calibrate
