#pragma once
// Line plots of a quality measure over the frames of a camera path, one curve per configuration
// (the figures of thesis chapter 4), drawn by our own code into RGBA8 and written as PNG.
//
// Layout (pixels, rows top to bottom):
//
//            title (centred)
//   yLabel
//         +--------------------------------------+
//    1.00 |-   [band label]        +----------+  |   the frame box lies one pixel outside the
//         |    ##########          | # series |  |   plot area [left, right] x [top, bottom];
//    0.95 |-   ##shaded##   /\__   | # series |  |   data maps into the area (PlotAxes), curves
//         |    ##########__/       +----------+  |   are clipped to it
//         +--------------------------------------+
//         0        10        20        30
//                        xLabel
//
// The legend goes into a corner of the area that no curve crosses or, where every corner is
// crossed, right of the area (which narrows for it). Same input, same bytes: nothing depends on
// time, threads or the locale.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "common/bitmap_font.h"

namespace vt {

// One value per frame; NaN (or any non-finite value) = no value, a gap in the curve.
struct PlotSeries {
  std::string label;
  std::vector<double> values;
};

// A shaded range of frames [first, last] (e.g. a named camera motion), its label at the top.
struct PlotBand {
  int first = 0, last = 0;
  std::string label;
};

struct LinePlot {
  std::string title, xLabel = "frame", yLabel;
  std::vector<PlotSeries> series;  // of any lengths; x runs from 0 to the longest's size - 1
  std::vector<PlotBand> bands;
  // The value range; by default from the finite values, padded by 3 % and widened to ticks.
  std::optional<double> yMin, yMax;
  int width = 1280, height = 640;
};

struct PlotImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // rows top to bottom
};

// Where a plot puts (frame, value): x = xMin..xMax maps linearly onto columns left..right,
// y = yMin..yMax onto rows bottom..top, both rounded to the nearest pixel.
struct PlotAxes {
  int left = 0, top = 0, right = 0, bottom = 0;  // the plot area, inclusive
  double xMin = 0, xMax = 1, yMin = 0, yMax = 1;
  double xStep = 1, yStep = 1;  // between ticks: 1, 2 or 5 times a power of ten

  double columnAt(double frame) const;  // unrounded
  double rowAt(double value) const;
  int column(double frame) const;
  int row(double value) const;
};

// Throws std::invalid_argument (with what was wrong) for a plot with no series, no finite value,
// a size too small for its text, an empty or inverted y range, or a band with first > last.
PlotAxes plotAxes(const LinePlot& plot);

// Series i is drawn in plotColour(i): twelve colours that stay apart, repeated after twelve.
Rgba8 plotColour(size_t series);
// Bands alternate between two greys, so that neighbouring bands stay apart.
inline constexpr Rgba8 kPlotBandColour{222, 222, 222, 255};
inline constexpr Rgba8 kPlotBandColourAlternate{238, 238, 238, 255};

// Throws as plotAxes.
PlotImage renderLinePlot(const LinePlot& plot);

// Writes renderLinePlot(plot) in the format `file`'s extension names (.png), through a temporary
// file renamed at the end (common/image_file.h).
void writeLinePlot(const std::filesystem::path& file, const LinePlot& plot);

}  // namespace vt
