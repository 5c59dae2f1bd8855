#pragma once
// SSIM (eval/image_metrics.h: Rec. 709 luminance, uniform t x t windows wholly inside the image,
// population statistics) kept per window, so that a change of a few pixels is priced by the
// windows it touches alone: what the change adds to the sum of every window's Q, in O(touched
// windows x t^2) instead of O(image). The mean SSIM changes by that sum over windowCount().
// For trying many small changes of one image (eval/selection_ceiling.h); the sums agree with
// ssim() of the changed images to rounding (tests/eval/window_ssim_test.cpp).

#include <cstdint>
#include <span>
#include <vector>

namespace vt {

class WindowSsim {
 public:
  static constexpr int kSide = 8;  // the thesis's window, image_metrics.h's default

  // Images of width x height RGBA8 pixels; throws std::invalid_argument when smaller than the
  // window or the window has no pixels.
  WindowSsim(int width, int height, int window = kSide);

  // The reference and the current image, RGBA8 rows as ssim() reads them.
  void reset(std::span<const uint8_t> reference, std::span<const uint8_t> image);

  // What the sum of Q over every window would gain if pixels[k] took rgba[4 k .. 4 k + 2] (the
  // current image is left as it is). Pixels listed twice take their last value.
  double gain(std::span<const uint32_t> pixels, std::span<const uint8_t> rgba);
  // Makes that change to the current image.
  void apply(std::span<const uint32_t> pixels, std::span<const uint8_t> rgba);

  uint64_t windowCount() const { return columns_ * rows_; }

 private:
  double windowQ(uint64_t window) const;  // Q of the window (index row * columns + column)
  double currentQ(uint64_t window);       // the same, kept until the window changes
  // The windows whose support holds one of the pixels, each once, into touched_.
  void touch(std::span<const uint32_t> pixels);

  int width_, height_, side_;
  uint64_t columns_, rows_;
  std::vector<double> reference_, image_;  // luminance
  std::vector<uint32_t> stamp_;            // per window: the touch() call that listed it last
  std::vector<double> q_;                  // per window: its Q in the current image, when known
  std::vector<uint8_t> known_;
  uint32_t calls_ = 0;
  std::vector<uint64_t> touched_;
};

}  // namespace vt
