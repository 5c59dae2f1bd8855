#include "eval/window_ssim.h"

#include <algorithm>
#include <stdexcept>

#include "eval/image_metrics.h"

namespace vt {

WindowSsim::WindowSsim(int width, int height, int window)
    : width_(width), height_(height), side_(window) {
  if (window < 1) throw std::invalid_argument("SSIM window of no pixels");
  if (width < window || height < window)
    throw std::invalid_argument("images smaller than the SSIM window");
  columns_ = static_cast<uint64_t>(width - window + 1);
  rows_ = static_cast<uint64_t>(height - window + 1);
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  reference_.resize(pixels);
  image_.resize(pixels);
  stamp_.assign(columns_ * rows_, 0);
  q_.resize(columns_ * rows_);
  known_.assign(columns_ * rows_, 0);
}

void WindowSsim::reset(std::span<const uint8_t> reference, std::span<const uint8_t> image) {
  if (reference.size() != reference_.size() * 4 || image.size() != image_.size() * 4)
    throw std::invalid_argument("images differ in size");
  for (size_t i = 0; i < image_.size(); ++i) {
    reference_[i] = luminanceOf(reference.data() + 4 * i);
    image_[i] = luminanceOf(image.data() + 4 * i);
  }
  std::fill(known_.begin(), known_.end(), 0);
}

double WindowSsim::currentQ(uint64_t window) {
  if (!known_[window]) {
    q_[window] = windowQ(window);
    known_[window] = 1;
  }
  return q_[window];
}

double WindowSsim::windowQ(uint64_t window) const {
  const size_t x0 = window % columns_, y0 = window / columns_;
  double sx = 0.0, sy = 0.0, sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (size_t y = y0; y < y0 + static_cast<size_t>(side_); ++y) {
    const size_t row = y * static_cast<size_t>(width_);
    for (size_t x = x0; x < x0 + static_cast<size_t>(side_); ++x) {
      const double a = image_[row + x], b = reference_[row + x];
      sx += a;
      sy += b;
      sxx += a * a;
      syy += b * b;
      sxy += a * b;
    }
  }
  const double n = static_cast<double>(side_) * side_;
  const double mx = sx / n, my = sy / n;
  const double vx = sxx / n - mx * mx, vy = syy / n - my * my, cxy = sxy / n - mx * my;
  return windowSsim(mx, my, vx, vy, cxy);
}

void WindowSsim::touch(std::span<const uint32_t> pixels) {
  touched_.clear();
  if (++calls_ == 0) {  // the stamps wrapped: start them again
    std::fill(stamp_.begin(), stamp_.end(), 0);
    calls_ = 1;
  }
  const int64_t lastColumn = static_cast<int64_t>(columns_) - 1,
                lastRow = static_cast<int64_t>(rows_) - 1;
  for (const uint32_t pixel : pixels) {
    const int64_t px = pixel % static_cast<uint32_t>(width_),
                  py = pixel / static_cast<uint32_t>(width_);
    // Windows whose top-left corner lies within side - 1 pixels up and left of the pixel.
    for (int64_t wy = std::max<int64_t>(0, py - side_ + 1); wy <= std::min(py, lastRow); ++wy)
      for (int64_t wx = std::max<int64_t>(0, px - side_ + 1); wx <= std::min(px, lastColumn);
           ++wx) {
        const uint64_t window = static_cast<uint64_t>(wy) * columns_ + static_cast<uint64_t>(wx);
        if (stamp_[window] == calls_) continue;
        stamp_[window] = calls_;
        touched_.push_back(window);
      }
  }
}

double WindowSsim::gain(std::span<const uint32_t> pixels, std::span<const uint8_t> rgba) {
  if (rgba.size() != pixels.size() * 4) throw std::invalid_argument("four bytes per pixel");
  touch(pixels);
  double before = 0.0;
  for (const uint64_t window : touched_) before += currentQ(window);
  std::vector<double> saved(pixels.size());
  for (size_t k = 0; k < pixels.size(); ++k) saved[k] = image_[pixels[k]];
  for (size_t k = 0; k < pixels.size(); ++k) image_[pixels[k]] = luminanceOf(rgba.data() + 4 * k);
  double after = 0.0;
  for (const uint64_t window : touched_) after += windowQ(window);
  for (size_t k = pixels.size(); k-- > 0;) image_[pixels[k]] = saved[k];  // last first: duplicates
  return after - before;
}

void WindowSsim::apply(std::span<const uint32_t> pixels, std::span<const uint8_t> rgba) {
  if (rgba.size() != pixels.size() * 4) throw std::invalid_argument("four bytes per pixel");
  for (size_t k = 0; k < pixels.size(); ++k) image_[pixels[k]] = luminanceOf(rgba.data() + 4 * k);
  touch(pixels);
  for (const uint64_t window : touched_) known_[window] = 0;
}

}  // namespace vt
