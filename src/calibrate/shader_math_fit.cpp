#include "calibrate/shader_math_fit.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>
#include <random>

#include "calibrate/float_bits.h"
#include "probes/function_sweeps.h"
#include "probes/probe_draws.h"
#include "reference/linear_filter.h"
#include "reference/shader_math.h"

namespace vt::calibrate {
namespace {

// 65,536 positive normal floats: every exponent, random mantissas (a fixed seed), 1 and the
// powers of two among them.
std::vector<glm::vec4> mathInputs() {
  std::mt19937 random(20261123);
  std::vector<glm::vec4> inputs(65536);
  for (size_t i = 0; i < inputs.size(); ++i) {
    const uint32_t exponent = 1 + static_cast<uint32_t>(i % 254);
    const uint32_t mantissa = i % 509 == 0 ? 0u : static_cast<uint32_t>(random()) >> 9;
    inputs[i] = glm::vec4(std::bit_cast<float>((exponent << 23) | mantissa), 1.0f, 0.0f, 0.0f);
  }
  return inputs;
}

// What the implementation returned for one function: the probe's samples (one channel of its
// results), then the pack's sweep of it where there is one (probes/function_sweeps.h).
struct Returned {
  const std::vector<glm::vec4>& inputs;
  const std::vector<glm::vec4>& out;
  int channel;
  std::optional<std::vector<uint32_t>> swept;
  uint32_t first = 0;

  uint64_t size() const { return out.size() + (swept ? swept->size() : 0); }
  // f(x, result) for every input, the samples first.
  template <class F>
  void visit(F&& f) const {
    for (size_t i = 0; i < out.size(); ++i) f(inputs[i].x, out[i][channel]);
    if (!swept) return;
    for (uint32_t i = 0; i < swept->size(); ++i)
      f(std::bit_cast<float>(first + i), std::bit_cast<float>((*swept)[i]));
  }
};

Returned returned(const std::vector<glm::vec4>& inputs, const std::vector<glm::vec4>& out,
                  int channel, const std::string& function) {
  Returned r{inputs, out, channel, std::nullopt};
  if (const FunctionSweep* sweep = packSweep(function)) {
    r.swept = functionSweep(*sweep);
    r.first = sweep->first;
  }
  return r;
}

// The sweep of log2 over [0.5, 2) cut to its [1, 2) as a table, where it was drawn, no closed form
// reproduced log2, and its results there lie in [0, 1] (else none).
std::shared_ptr<const MeasuredTable> log2Table(const Returned& logs, bool pinned) {
  constexpr uint32_t kHalf = MeasuredTable::kLog2First - 0x3f000000u;  // the index of 1.0
  if (!logs.swept || pinned || logs.first != 0x3f000000u ||
      logs.swept->size() != kHalf + MeasuredTable::kLog2Count)
    return nullptr;
  try {
    return std::make_shared<const MeasuredTable>(
        TabledFunction::kLog2, std::vector<uint32_t>(logs.swept->begin() + kHalf,
                                                     logs.swept->end()));
  } catch (const std::invalid_argument&) {
    return nullptr;
  }
}

// The sweep of sqrt over [1, 4) as a table, where it was drawn, IEEE missed some values, and its
// results lie in [1, 2] (else none: such a sqrt is bounded, not tabled).
std::shared_ptr<const MeasuredTable> sqrtTable(const Returned& roots, uint64_t notIeee) {
  if (!roots.swept || notIeee == 0 || roots.first != MeasuredTable::kSqrtFirst ||
      roots.swept->size() != MeasuredTable::kSqrtCount)
    return nullptr;
  try {
    return std::make_shared<const MeasuredTable>(TabledFunction::kSqrt, *roots.swept);
  } catch (const std::invalid_argument&) {
    return nullptr;
  }
}

std::optional<ParameterFit> fitReciprocal(Reciprocal& measured) {
  const FunctionSweep& sweep = *packSweep("reciprocal");
  std::optional<std::vector<uint32_t>> bits = functionSweep(sweep);
  if (!bits) return std::nullopt;
  uint64_t missed = 0;
  double ulps = 0;
  for (uint32_t i = 0; i < bits->size(); ++i) {
    const float x = std::bit_cast<float>(sweep.first + i);
    const float y = std::bit_cast<float>((*bits)[i]);
    missed += !sameBits(y, 1.0f / x);
    ulps = std::max(ulps, ulpsFrom(y, 1.0 / static_cast<double>(x)));
  }
  ParameterFit fit{"reciprocal", "1.0 / x of every float of [1, 2)", bits->size(),
                   {{"ieee", missed}}};
  fit.choose();
  fit.unit = "ulps";
  if (!fit.pinned) fit.largestResidual = ulps;
  fit.finding = missed == 0 ? "IEEE division, correctly rounded, bit for bit"
                            : differ(missed, bits->size()) + " from IEEE division, largest " +
                                  std::to_string(ulps) + " ulps (GLSL 4.50 allows " +
                                  std::to_string(kGlslReciprocalUlps) + ")";
  // A table of results in [0.5, 1] becomes a member; one beyond is far outside GLSL's 2.5 ulps
  // and reported as such (calibration.h's conformance).
  if (missed > 0 && fit.largestResidual <= kGlslReciprocalUlps) {
    measured.table = std::make_shared<const MeasuredTable>(TabledFunction::kReciprocal, std::move(*bits));
    fit.finding += "; the measured table " + measured.table->checksum() +
                   " is offered to the perspective probes";
  }
  return fit;
}

// log2's finding once its members are counted: where no closed form reproduced it, its table
// (log2Table) is tried on every value; the residuals are kept wherever a table pins it.
void findLog2(ShaderMathFits& m, const Returned& logs) {
  // No closed form reproduces it: the sweep's [1, 2) as a table, tried on every value.
  const std::shared_ptr<const MeasuredTable> logTable = log2Table(logs, m.log2.pinned);
  if (logTable) {
    uint64_t missed = 0;
    logs.visit([&](float x, float y) { missed += !sameBits(y, logTable->of(x)); });
    m.log2.members.push_back({"measured", missed});
    m.log2.choose();
  }
  if (logTable && m.log2.pinned) {
    // The residuals stay: the result sets widen log2 by them (reference/set_fragment.cpp).
    m.log2Table.table = logTable;
    m.log2.finding = "the measured table " + logTable->checksum() +
                     " over [1, 2), plus the exponent in one float addition, bit for bit (" +
                     m.log2.memberSummary() + ")";
  } else if (m.log2.pinned) {
    m.log2.finding = m.log2.chosen + ", bit for bit (" + m.log2.memberSummary() + ")";
    m.log2Absolute = m.log2Ulps = 0;
  } else {
    m.log2.unit = "ulps outside [0.5, 2]";
    m.log2.largestResidual = m.log2Ulps;
    m.log2.finding = "no member of the family (" + m.log2.memberSummary() +
                     "): largest error against the true log2 inside [0.5, 2] " +
                     std::to_string(m.log2Absolute) + ", outside " + std::to_string(m.log2Ulps) +
                     " ulps";
  }
}

void fitLog2AndSqrt(ShaderMathFits& m) {
  ShaderProbe probe;
  probe.body = "result = vec4(log2(x.x), sqrt(x.x), x.z * x.y, 0.0);";
  probe.inputs = mathInputs();
  probe.inputs[0].z = 0x1p-130f;  // a denormal, times the 1 in y
  const std::vector<glm::vec4> out = runShaderProbe(probe);
  const Returned logs = returned(probe.inputs, out, 0, "log2");
  const Returned roots = returned(probe.inputs, out, 1, "sqrt");
  std::string inputs = "log2 and sqrt of 65,536 positive floats of every exponent";
  if (logs.swept) inputs += ", log2 of every float of [0.5, 2)";
  if (roots.swept) inputs += ", sqrt of every float of [1, 4)";

  m.log2 = {"log2", inputs, logs.size()};
  for (const auto& member : kLog2FormNames) {
    uint64_t missed = 0;
    logs.visit(
        [&](float x, float y) { missed += !sameBits(y, reference::log2Of(member.value, x)); });
    m.log2.members.push_back({std::string(member.name), missed});
  }
  m.log2Form = kLog2FormNames[m.log2.choose()].value;
  logs.visit([&](float x, float y) {
    const double exact = std::log2(static_cast<double>(x));
    if (x >= 0.5f && x <= 2.0f)
      m.log2Absolute = std::max(m.log2Absolute, std::fabs(y - exact));
    else
      m.log2Ulps = std::max(m.log2Ulps, ulpsFrom(y, exact));
  });
  uint64_t notSqrt = 0;
  roots.visit([&](float x, float y) {
    notSqrt += !sameBits(y, std::sqrt(x));
    m.sqrtUlps = std::max(m.sqrtUlps, ulpsFrom(y, std::sqrt(static_cast<double>(x))));
  });
  const uint64_t nSqrt = roots.size();
  findLog2(m, logs);
  m.sqrt = {"sqrt", inputs, nSqrt, {{"ieee", notSqrt}}};
  const std::shared_ptr<const MeasuredTable> table = sqrtTable(roots, notSqrt);
  if (table) {
    uint64_t missed = 0;
    roots.visit([&](float x, float y) { missed += !sameBits(y, table->of(x)); });
    m.sqrt.members.push_back({"measured", missed});
  }
  m.sqrt.choose();
  m.sqrt.unit = "ulps";
  // Under a table the residual stays: the result sets widen sqrt by it (reference/set_fragment.cpp).
  if (notSqrt > 0) m.sqrt.largestResidual = m.sqrtUlps;
  m.sqrt.finding = notSqrt == 0 ? "IEEE sqrt, correctly rounded, bit for bit"
                                : differ(notSqrt, nSqrt) + " from IEEE sqrt, largest " +
                                      std::to_string(m.sqrtUlps) + " ulps";
  const bool tabled = m.sqrt.pinned && m.sqrt.chosen == "measured";
  if (table)
    m.sqrt.finding += tabled ? "; the measured table " + table->checksum() +
                                   " over [1, 4), scaled by powers of 4, reproduces every value"
                             : "; the measured table over [1, 4), scaled by powers of 4: " +
                                   differ(m.sqrt.members.back().mismatches, nSqrt);
  if (tabled) m.sqrtMember.table = table;
  if (notSqrt == 0) m.sqrtUlps = 0;

  // The same product in a draw the clipper leaves whole (the one above is clipped).
  ShaderProbe whole;
  whole.body = "result = vec4(x.z * x.y, 0.0, 0.0, 0.0);";
  whole.width = 16;
  whole.inputs.assign(16 * 16, glm::vec4(0.0f, 1.0f, 0x1p-130f, 0.0f));
  whole.clipped = false;
  const std::vector<glm::vec4> unclipped = runShaderProbe(whole);
  uint64_t flushedUnclipped = 0;
  for (const glm::vec4& v : unclipped) flushedUnclipped += v.x == 0.0f;
  const bool flushedClipped = out[0].z == 0.0f;
  m.flushesDenormals = flushedUnclipped == unclipped.size();
  m.denormalsAlike = flushedClipped == m.flushesDenormals &&
                     (flushedUnclipped == 0 || flushedUnclipped == unclipped.size());
  const uint64_t values = 1 + unclipped.size();
  const uint64_t kept = (flushedClipped ? 0 : 1) + unclipped.size() - flushedUnclipped;
  m.denormals = {"denormals",
                 "a denormal times a 1 read from the inputs, in a clipped draw and "
                 "in 256 pixels of an unclipped one",
                 values,
                 {{"flushed", kept}, {"kept", values - kept}}};
  m.denormals.choose();
  m.denormals.pinned = m.denormalsAlike;
  m.denormals.finding = m.denormalsAlike
                            ? (m.flushesDenormals ? "a denormal times 1 gives 0: flushed to zero"
                                                  : "a denormal times 1 stays a denormal: kept")
                            : std::string("flushed in ") + std::to_string(flushedUnclipped) +
                                  " of 256 pixels of the unclipped draw, " +
                                  (flushedClipped ? "flushed" : "kept") +
                                  " in the clipped one: the mode changes between batches, free";
}

// texelFetch of every unorm8 value, and the shader's lerps.
void fitConversionAndLerps(ShaderMathFits& m) {
  ShaderProbe fetch;
  fetch.body = "result = texelFetch(uTexture, ivec2(int(x.x), 0), 0);";
  fetch.width = 256;
  for (int k = 0; k < 256; ++k) {
    fetch.inputs.push_back(glm::vec4(static_cast<float>(k), 0, 0, 0));
    const auto v = static_cast<uint8_t>(k);
    fetch.texels.push_back(glm::u8vec4(v, static_cast<uint8_t>(255 - k), v, 255));
  }
  fetch.textureSize = {256, 1};
  const std::vector<glm::vec4> fetched = runShaderProbe(fetch);
  m.texelConversion = {"texel_conversion", "texelFetch of the 256 unorm8 values", 1024};
  double conversionUlps = 0;
  for (const auto& [conversion, name] : kUnormConversionNames) {
    uint64_t missed = 0;
    for (size_t k = 0; k < 256; ++k) {
      const glm::vec4 expected = reference::unorm8ToFloat(fetch.texels[k], conversion);
      for (int c = 0; c < 4; ++c) missed += !sameBits(fetched[k][c], expected[c]);
    }
    m.texelConversion.members.push_back({std::string(name), missed});
  }
  m.conversion = kUnormConversionNames[m.texelConversion.choose()].value;
  for (size_t k = 0; k < 256; ++k) {
    const glm::vec4 expected = reference::unorm8ToFloat(fetch.texels[k], m.conversion);
    for (int c = 0; c < 4; ++c)
      conversionUlps = std::max(conversionUlps, std::fabs(fetched[k][c] - expected[c]) / kFloatUlp);
  }
  m.texelConversion.unit = "units of 2^-23";
  if (!m.texelConversion.pinned) m.texelConversion.largestResidual = conversionUlps;
  m.texelConversion.finding =
      (m.texelConversion.pinned
           ? m.texelConversion.chosen + ", bit for bit"
           : "no member, largest " + std::to_string(conversionUlps) + " units of 2^-23") +
      " (" + m.texelConversion.memberSummary() + ")";

  // The shader's lerps (the exact bilinear filter's rows and columns, the trilinear blend):
  // a + (b - a) * w under `precise`, colours of unorm8 values or any in [0, 1], weights in [0, 1).
  ShaderProbe blend;
  blend.body = "result = vec4(x.x + (x.y - x.x) * x.z, 0.0, 0.0, 0.0);";
  std::mt19937 random(20261124);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto colour = [&]() {
    return random() % 2 ? static_cast<float>(random() % 256) * (1.0f / 255.0f) : unit(random);
  };
  for (int i = 0; i < 16384; ++i) {
    const float a = colour(), b = colour();
    blend.inputs.push_back(glm::vec4(a, b, unit(random), 0.0f));
  }
  const std::vector<glm::vec4> blended = runShaderProbe(blend);
  uint64_t missed = 0;
  double lerpUlps = 0;
  for (size_t i = 0; i < blended.size(); ++i) {
    const glm::vec4 in = blend.inputs[i];
    const float expected = in.x + (in.y - in.x) * in.z;  // no contraction (-ffp-contract=off)
    missed += !sameBits(blended[i].x, expected);
    const double scale = std::max({std::fabs(in.x), std::fabs(in.y), 0x1p-126f});
    lerpUlps = std::max(lerpUlps, std::fabs(blended[i].x - expected) / (kFloatUlp * scale));
  }
  m.lerp = {"arithmetic",
            "16,384 precise lerps a + (b - a) * w",
            blended.size(),
            {{"rounded_per_operation", missed}}};
  m.lerp.choose();
  m.lerp.unit = "units of 2^-23 of the larger operand";
  if (!m.lerp.pinned) m.lerp.largestResidual = lerpUlps;
  m.lerp.finding = missed == 0
                       ? "the lerp a + (b - a) * w rounds each operation, bit for bit"
                       : differ(missed, blended.size()) +
                             " from rounding each operation, largest " + std::to_string(lerpUlps) +
                             " units of 2^-23 of the larger "
                             "operand";
  m.arithmeticUlps = std::max(m.texelConversion.largestResidual, m.lerp.largestResidual);
}

}  // namespace

ShaderMathFits fitShaderMath() {
  ShaderMathFits m;
  fitLog2AndSqrt(m);
  fitConversionAndLerps(m);
  m.reciprocal = fitReciprocal(m.measuredReciprocal);
  return m;
}

}  // namespace vt::calibrate
