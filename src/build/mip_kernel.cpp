#include "build/mip_kernel.h"

#include <algorithm>
#include <cmath>

namespace vt {
namespace {

// IEC 61966-2-1 sRGB transfer functions, in double so the tables are exact to float precision.
double srgbToLinear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

constexpr std::array<uint32_t, 4> kTentWeights = {1, 3, 3, 1};

}  // namespace

MipKernel::MipKernel(MipFilter filter, ColorSpace colorSpace, uint32_t channels)
    : filter_(filter), channels_(channels) {
  // Gray and gray+alpha have one colour channel, RGB and RGBA three; alpha stays linear.
  colorChannels_ = colorSpace == ColorSpace::kSrgb ? (channels >= 3 ? 3 : 1) : 0;
  for (int code = 0; code < 256; ++code)
    decode_[static_cast<size_t>(code)] = static_cast<float>(srgbToLinear(code / 255.0));
  // Encoding rounds to the nearest code in sRGB space: code k + 1 starts at decode((k + 0.5) /
  // 255).
  for (int code = 0; code < 255; ++code)
    encodeThreshold_[static_cast<size_t>(code)] =
        static_cast<float>(srgbToLinear((code + 0.5) / 255.0));
  for (size_t i = 0; i < encodeStart_.size(); ++i)
    encodeStart_[i] =
        static_cast<uint8_t>(std::upper_bound(encodeThreshold_.begin(), encodeThreshold_.end(),
                                              static_cast<float>(i) / 4096.0f) -
                             encodeThreshold_.begin());
}

uint8_t MipKernel::encode(float linear) const {
  // The nearest code in sRGB space: the number of thresholds <= linear. The table gives the count
  // at the 1/4096 step below, and at most a few thresholds lie within one step.
  const float scaled = std::clamp(linear, 0.0f, 1.0f) * 4096.0f;
  uint32_t code = encodeStart_[static_cast<size_t>(scaled)];
  while (code < encodeThreshold_.size() && encodeThreshold_[code] <= linear) ++code;
  return static_cast<uint8_t>(code);
}

template <int Taps>
void MipKernel::filterTexel(const Rows& rows, uint64_t x, uint64_t side, uint64_t firstColumn,
                            uint8_t* out) const {
  // Source columns 2X - reach .. 2X + 1 + reach, clamped to the level (the box filter's 2X and
  // 2X + 1 always lie inside).
  constexpr int kReach = (Taps - 2) / 2;
  std::array<uint64_t, Taps> column{};
  for (int k = 0; k < Taps; ++k) {
    const int64_t c = static_cast<int64_t>(2 * x) - kReach + k;
    column[static_cast<size_t>(k)] =
        (Taps == 2
             ? static_cast<uint64_t>(c)
             : static_cast<uint64_t>(std::clamp<int64_t>(c, 0, static_cast<int64_t>(side) - 1))) -
        firstColumn;
  }
  constexpr std::array<uint32_t, 4> kWeights =
      Taps == 2 ? std::array<uint32_t, 4>{1, 1, 0, 0} : kTentWeights;
  constexpr uint32_t kTotal = Taps == 2 ? 4 : 64;
  for (uint32_t c = 0; c < channels_; ++c) {
    if (c < colorChannels_) {
      float sum = 0.0f;
      for (int j = 0; j < Taps; ++j)
        for (int i = 0; i < Taps; ++i)
          sum +=
              static_cast<float>(kWeights[static_cast<size_t>(i)] *
                                 kWeights[static_cast<size_t>(j)]) *
              decode_[rows[static_cast<size_t>(j)][column[static_cast<size_t>(i)] * channels_ + c]];
      out[c] = encode(sum / static_cast<float>(kTotal));
    } else {
      uint32_t sum = 0;
      for (int j = 0; j < Taps; ++j)
        for (int i = 0; i < Taps; ++i)
          sum += kWeights[static_cast<size_t>(i)] * kWeights[static_cast<size_t>(j)] *
                 rows[static_cast<size_t>(j)][column[static_cast<size_t>(i)] * channels_ + c];
      out[c] = static_cast<uint8_t>((sum + kTotal / 2) / kTotal);
    }
  }
}

void MipKernel::texel(const Rows& rows, uint64_t x, uint64_t side, uint8_t* out,
                      uint64_t firstColumn) const {
  if (filter_ == MipFilter::kBox)
    filterTexel<2>(rows, x, side, firstColumn, out);
  else
    filterTexel<4>(rows, x, side, firstColumn, out);
}

void MipKernel::downsample(const Rows& rows, uint64_t side, uint64_t begin, uint64_t count,
                           uint8_t* out, uint64_t firstColumn) const {
  if (filter_ == MipFilter::kBox) {
    for (uint64_t i = 0; i < count; ++i)
      filterTexel<2>(rows, begin + i, side, firstColumn, out + i * channels_);
  } else {
    for (uint64_t i = 0; i < count; ++i)
      filterTexel<4>(rows, begin + i, side, firstColumn, out + i * channels_);
  }
}

}  // namespace vt
