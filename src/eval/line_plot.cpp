#include "eval/line_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>
#include <stdexcept>

#include "common/image_file.h"

namespace vt {
namespace {

constexpr Rgba8 kWhite{255, 255, 255, 255}, kGrid{232, 232, 232, 255}, kFrame{64, 64, 64, 255},
    kText{32, 32, 32, 255}, kBandText{90, 90, 90, 255};
constexpr int kMaxSide = 16384;  // pixels; a bigger plot is a mistake, not a figure

// The sizes of the layout, in pixels, for a text scale s (pixels per font pixel): 2 for the
// default 1280 x 640, the title one larger where it fits.
struct Layout {
  int s = 1, titleScale = 2;
  int pad() const { return 4 * s; }
  int textHeight() const { return kGlyphHeight * s; }  // to the baseline
  int lineHeight() const { return kGlyphRows * s; }    // with the descenders
  int tickLength() const { return 3 * s; }
};

Layout layoutFor(const LinePlot& plot) {
  Layout layout;
  layout.s = std::max(1, std::min(plot.width / 640, plot.height / 320));
  const bool largerFits = textWidth(plot.title, layout.s + 1) <= plot.width - 2 * layout.pad();
  layout.titleScale = largerFits ? layout.s + 1 : layout.s;
  return layout;
}

// A step of 1, 2 or 5 times 10^exponent, the smallest such not below `rough`.
struct NiceStep {
  double step = 1;
  int exponent = 0;
};

NiceStep niceStep(double rough) {
  int exponent = static_cast<int>(std::floor(std::log10(rough)));
  for (;;) {
    const double power = std::pow(10.0, exponent);
    for (const double mantissa : {1.0, 2.0, 5.0})
      if (mantissa * power >= rough) return {mantissa * power, exponent};
    ++exponent;
  }
}

// The tick values i * step inside [lo, hi], computed from i (not accumulated). An end snapped to
// a multiple of the step divides back to an integer within a few ulp of the quotient; that much
// slack keeps its tick.
std::vector<double> ticks(double lo, double hi, double step) {
  const auto slack = [](double q) {
    return 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(q));
  };
  const double qLo = lo / step, qHi = hi / step;
  const auto first = static_cast<long long>(std::ceil(qLo - slack(qLo)));
  const auto last = static_cast<long long>(std::floor(qHi + slack(qHi)));
  std::vector<double> values;
  for (long long i = first; i <= last; ++i) values.push_back(static_cast<double>(i) * step);
  return values;
}

// How an axis writes its ticks: fixed with the step's decimals ("0.95"), or in scientific notation
// with as many digits ("1.06e+09") where fixed would be long.
struct TickFormat {
  bool scientific = false;
  int precision = 0;
};

TickFormat tickFormat(double lo, double hi, const NiceStep& step) {
  const double largest = std::max(std::abs(lo), std::abs(hi));
  const int magnitude = largest > 0 ? static_cast<int>(std::floor(std::log10(largest))) : 0;
  if (step.exponent >= -4 && magnitude < 7) return {false, std::max(0, -step.exponent)};
  return {true, std::max(0, magnitude - step.exponent)};
}

std::string tickLabel(double value, TickFormat format) {
  char text[64];
  std::snprintf(text, sizeof text, format.scientific ? "%.*e" : "%.*f", format.precision, value);
  return text;
}

struct DataRange {
  size_t frames = 0;  // the longest series' length
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
};

DataRange dataRange(const LinePlot& plot) {
  DataRange range;
  for (const PlotSeries& series : plot.series) {
    range.frames = std::max(range.frames, series.values.size());
    for (const double v : series.values)
      if (std::isfinite(v)) range.lo = std::min(range.lo, v), range.hi = std::max(range.hi, v);
  }
  return range;
}

void validate(const LinePlot& plot) {
  if (plot.series.empty()) throw std::invalid_argument("line plot '" + plot.title + "': no series");
  if (plot.width < 1 || plot.height < 1 || plot.width > kMaxSide || plot.height > kMaxSide)
    throw std::invalid_argument("line plot '" + plot.title + "': size " +
                                std::to_string(plot.width) + " x " + std::to_string(plot.height) +
                                " is outside 1.." + std::to_string(kMaxSide));
  for (const PlotBand& band : plot.bands)
    if (band.first > band.last)
      throw std::invalid_argument("line plot '" + plot.title + "': band '" + band.label +
                                  "' has first frame " + std::to_string(band.first) +
                                  " after its last " + std::to_string(band.last));
  for (const std::optional<double>& limit : {plot.yMin, plot.yMax})
    if (limit && !std::isfinite(*limit))
      throw std::invalid_argument("line plot '" + plot.title + "': a y limit is not finite");
}

// The y range before snapping to ticks: the data's (or the given limits), never empty, and the
// data's ends padded by 3 % so a curve does not run along the frame.
std::pair<double, double> valueRange(const LinePlot& plot, const DataRange& data) {
  double lo = plot.yMin.value_or(data.lo), hi = plot.yMax.value_or(data.hi);
  if (!(lo < hi)) {
    if (plot.yMin && plot.yMax)
      throw std::invalid_argument("line plot '" + plot.title + "': empty y range [" +
                                  std::to_string(lo) + ", " + std::to_string(hi) + "]");
    double width = 0.1 * std::max(std::abs(lo), std::abs(hi));
    if (width == 0) width = 1;
    if (plot.yMin)
      hi = lo + width;
    else if (plot.yMax)
      lo = hi - width;
    else
      lo -= width / 2, hi += width / 2;
  }
  const double margin = 0.03 * (hi - lo);
  if (!plot.yMin) lo -= margin;
  if (!plot.yMax) hi += margin;
  if (!std::isfinite(hi - lo))
    throw std::invalid_argument("line plot '" + plot.title + "': the y range is not finite");
  return {lo, hi};
}

// The plot area, both axes' ranges and steps, and how their ticks are written.
struct AxesAndTicks {
  PlotAxes axes;
  TickFormat yFormat, xFormat;
};

// `reservedRight` pixels are kept free right of the frame (for a legend outside the area).
AxesAndTicks computeAxes(const LinePlot& plot, int reservedRight) {
  validate(plot);
  const DataRange data = dataRange(plot);
  if (!(data.lo <= data.hi))
    throw std::invalid_argument("line plot '" + plot.title + "': no series has a finite value");
  const Layout l = layoutFor(plot);
  AxesAndTicks result;
  PlotAxes& axes = result.axes;

  // Rows: title, y label, the frame, tick marks, tick labels, x label.
  int top = l.pad();
  if (!plot.title.empty()) top += kGlyphRows * l.titleScale + l.pad();
  if (!plot.yLabel.empty()) top += l.lineHeight() + 3 * l.s;
  top += l.textHeight() / 2;  // room for the top tick's label, centred on the frame
  int bottom = plot.height - 1 - l.pad();
  if (!plot.xLabel.empty()) bottom -= l.lineHeight() + l.pad();
  bottom -= l.lineHeight() + 2 * l.s + l.tickLength();
  axes.top = top + 1;  // inside the frame
  axes.bottom = bottom - 1;

  // The y axis: a tick every 40 font pixels or so, snapped outwards where not given.
  auto [lo, hi] = valueRange(plot, data);
  const int areaHeight = std::max(1, axes.bottom - axes.top);
  const NiceStep yStep = niceStep((hi - lo) / std::max(2, areaHeight / (40 * l.s)));
  if (!plot.yMin) lo = std::floor(lo / yStep.step) * yStep.step;
  if (!plot.yMax) hi = std::ceil(hi / yStep.step) * yStep.step;
  axes.yMin = lo, axes.yMax = hi, axes.yStep = yStep.step;
  result.yFormat = tickFormat(lo, hi, yStep);

  // Columns: y tick labels, tick marks, the frame, and half the widest x label at the right.
  int labelWidth = 0;
  for (const double v : ticks(lo, hi, yStep.step))
    labelWidth = std::max(labelWidth, textWidth(tickLabel(v, result.yFormat), l.s));
  axes.xMin = 0;
  axes.xMax = static_cast<double>(std::max<size_t>(data.frames, 2) - 1);
  const int xLabelWidth = textWidth(tickLabel(axes.xMax, {}), l.s);
  axes.left = l.pad() + labelWidth + 2 * l.s + l.tickLength() + 1;
  axes.right = plot.width - 1 - std::max(l.pad(), xLabelWidth / 2 + l.s) - reservedRight - 1;
  if (axes.right - axes.left < 40 || axes.bottom - axes.top < 40)
    throw std::invalid_argument("line plot '" + plot.title + "': " + std::to_string(plot.width) +
                                " x " + std::to_string(plot.height) +
                                " pixels is too small for its text");

  // The x axis: whole frames, labels at least four characters apart.
  const int spacing = xLabelWidth + 4 * kGlyphAdvance * l.s;
  const NiceStep xStep =
      niceStep(std::max(1.0, axes.xMax / std::max(1, (axes.right - axes.left) / spacing)));
  axes.xStep = xStep.step;
  result.xFormat = tickFormat(axes.xMin, axes.xMax, xStep);
  return result;
}

class Canvas {
 public:
  Canvas(int width, int height) : width_(width), height_(height) {
    rgba_.resize(size_t(width) * size_t(height) * 4, 255);
  }
  RgbaCanvas view() { return {width_, height_, rgba_}; }
  PlotImage take() { return {width_, height_, std::move(rgba_)}; }

  // Fills [x0, x1] x [y0, y1] (inclusive) clipped to the image.
  void fill(int x0, int y0, int x1, int y1, Rgba8 c) {
    for (int y = std::max(y0, 0); y <= std::min(y1, height_ - 1); ++y)
      for (int x = std::max(x0, 0); x <= std::min(x1, width_ - 1); ++x) {
        uint8_t* p = &rgba_[(size_t(y) * size_t(width_) + size_t(x)) * 4];
        p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = c.a;
      }
  }
  void text(int x, int y, std::string_view s, int scale, Rgba8 c) {
    drawText(view(), x, y, s, scale, c);
  }

 private:
  int width_, height_;
  std::vector<uint8_t> rgba_;
};

// The curves: each pixel drawn also marks `covered`, which the legend's placement avoids.
class CurvePainter {
 public:
  CurvePainter(Canvas& canvas, const PlotAxes& axes, int width, int height)
      : canvas_(canvas), axes_(axes), width_(width), covered_(size_t(width) * size_t(height), 0) {}

  // A size x size brush at (x, y) (its top-left pixel), clipped to the plot area.
  void brush(int x, int y, int size, Rgba8 c) {
    const int x0 = std::max(x, axes_.left), x1 = std::min(x + size - 1, axes_.right);
    const int y0 = std::max(y, axes_.top), y1 = std::min(y + size - 1, axes_.bottom);
    if (x0 > x1 || y0 > y1) return;
    canvas_.fill(x0, y0, x1, y1, c);
    for (int yy = y0; yy <= y1; ++yy)
      for (int xx = x0; xx <= x1; ++xx) covered_[size_t(yy) * size_t(width_) + size_t(xx)] = 1;
  }

  // The segment between two data points (pixel coordinates, unrounded), clipped to the plot area
  // widened by half a pixel (Liang-Barsky), then Bresenham between the rounded ends.
  void segment(double xa, double ya, double xb, double yb, Rgba8 c) {
    // A value far off the axis (or overflowing to infinity) is brought to 1e12 pixels away: with
    // sides of at most kMaxSide pixels its visible part moves by under kMaxSide^2 / 1e12 < 0.001.
    ya = std::clamp(ya, axes_.top - 1e12, axes_.bottom + 1e12);
    yb = std::clamp(yb, axes_.top - 1e12, axes_.bottom + 1e12);
    double t0 = 0, t1 = 1;
    const double dx = xb - xa, dy = yb - ya;
    const std::array<std::pair<double, double>, 4> edges = {{
        {-dx, xa - (axes_.left - 0.5)},
        {dx, (axes_.right + 0.5) - xa},
        {-dy, ya - (axes_.top - 0.5)},
        {dy, (axes_.bottom + 0.5) - ya},
    }};
    for (const auto& [p, q] : edges) {
      if (p == 0) {
        if (q < 0) return;  // parallel to this edge and outside it
        continue;
      }
      const double t = q / p;
      if (p < 0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
      if (t0 > t1) return;
    }
    line(static_cast<int>(std::lround(xa + t0 * dx)), static_cast<int>(std::lround(ya + t0 * dy)),
         static_cast<int>(std::lround(xa + t1 * dx)), static_cast<int>(std::lround(ya + t1 * dy)),
         c);
  }

  // Curve pixels inside [x0, x1] x [y0, y1].
  int coveredIn(int x0, int y0, int x1, int y1) const {
    int count = 0;
    for (int y = std::max(y0, axes_.top); y <= std::min(y1, axes_.bottom); ++y)
      for (int x = std::max(x0, axes_.left); x <= std::min(x1, axes_.right); ++x)
        count += covered_[size_t(y) * size_t(width_) + size_t(x)];
    return count;
  }

 private:
  void line(int x0, int y0, int x1, int y1, Rgba8 c) {
    const int dx = std::abs(x1 - x0), dy = -std::abs(y1 - y0);
    const int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1;
    for (int error = dx + dy;;) {
      brush(x0, y0, 2, c);
      if (x0 == x1 && y0 == y1) return;
      const int e2 = 2 * error;
      if (e2 >= dy) error += dy, x0 += sx;
      if (e2 <= dx) error += dx, y0 += sy;
    }
  }

  Canvas& canvas_;
  const PlotAxes& axes_;
  int width_;
  std::vector<uint8_t> covered_;  // 1 where a curve was drawn
};

}  // namespace

double PlotAxes::columnAt(double frame) const {
  return left + (frame - xMin) / (xMax - xMin) * (right - left);
}

double PlotAxes::rowAt(double value) const {
  return bottom - (value - yMin) / (yMax - yMin) * (bottom - top);
}

int PlotAxes::column(double frame) const { return static_cast<int>(std::lround(columnAt(frame))); }

int PlotAxes::row(double value) const { return static_cast<int>(std::lround(rowAt(value))); }

Rgba8 plotColour(size_t series) {
  // The ten of d3's category10, then black and a dark indigo: apart in hue or in lightness.
  static constexpr std::array<Rgba8, 12> kPalette = {{
      {31, 119, 180, 255},
      {255, 127, 14, 255},
      {44, 160, 44, 255},
      {214, 39, 40, 255},
      {148, 103, 189, 255},
      {140, 86, 75, 255},
      {227, 119, 194, 255},
      {127, 127, 127, 255},
      {188, 189, 34, 255},
      {23, 190, 207, 255},
      {0, 0, 0, 255},
      {57, 59, 121, 255},
  }};
  return kPalette[series % kPalette.size()];
}

namespace {

// Frames [first, last] cover from half a frame before the first to half a frame after the last,
// within the plot area; nothing when the band lies outside the frames.
std::optional<std::pair<int, int>> bandColumns(const PlotBand& band, const PlotAxes& axes) {
  const int x0 = std::max(axes.left, axes.column(band.first - 0.5));
  const int x1 = std::min(axes.right, axes.column(band.last + 0.5));
  if (x0 > x1) return std::nullopt;
  return std::pair{x0, x1};
}

void drawCurves(const LinePlot& plot, const PlotAxes& axes, CurvePainter& painter) {
  // In order: a later series is drawn over an earlier one.
  for (size_t s = 0; s < plot.series.size(); ++s) {
    const std::vector<double>& v = plot.series[s].values;
    const Rgba8 colour = plotColour(s);
    for (size_t i = 0; i < v.size(); ++i) {
      if (!std::isfinite(v[i])) continue;
      const bool before = i > 0 && std::isfinite(v[i - 1]);
      const bool after = i + 1 < v.size() && std::isfinite(v[i + 1]);
      const double x = axes.columnAt(static_cast<double>(i)), y = axes.rowAt(v[i]);
      if (before)
        painter.segment(axes.columnAt(static_cast<double>(i - 1)), axes.rowAt(v[i - 1]), x, y,
                        colour);
      else if (!after && y > axes.top - 0.5 && y < axes.bottom + 0.5)  // a lone value: a dot
        painter.brush(axes.column(static_cast<double>(i)) - 1, axes.row(v[i]) - 1, 4, colour);
    }
  }
}

struct TextAt {
  int x = 0, y = 0;
  std::string text;
};

// Band labels along the top of the area, centred over their bands, moved down a row (of three)
// where they would run into the label before.
std::vector<TextAt> bandLabels(const LinePlot& plot, const PlotAxes& axes, const Layout& l) {
  constexpr int kRows = 3;
  std::array<int, kRows> rowEnd;
  rowEnd.fill(std::numeric_limits<int>::min() / 2);
  std::vector<TextAt> labels;
  for (const PlotBand& band : plot.bands) {
    const auto columns = bandColumns(band, axes);
    if (!columns || band.label.empty()) continue;
    const int w = textWidth(band.label, l.s);
    const int x = std::clamp((columns->first + columns->second) / 2 - w / 2, axes.left + l.s,
                             std::max(axes.left + l.s, axes.right - w - l.s));
    int r = 0;
    while (r < kRows && x <= rowEnd[size_t(r)] + 2 * kGlyphAdvance * l.s) ++r;
    if (r == kRows)  // all taken: the row that ends first
      r = static_cast<int>(std::min_element(rowEnd.begin(), rowEnd.end()) - rowEnd.begin());
    rowEnd[size_t(r)] = x + w;
    labels.push_back({x, axes.top + 3 * l.s + r * 10 * l.s, band.label});
  }
  return labels;
}

struct Box {
  int x = 0, y = 0, width = 0, height = 0;
};

// Where everything goes.
struct PlotLayout {
  AxesAndTicks axes;
  std::vector<TextAt> bandLabels;
  Box legend;
};

// The legend goes into the corner of the plot area that no curve crosses (tried in the order top
// right, top left, bottom right, bottom left, below the band labels), or, where every corner is
// crossed, outside the area at its right, which then narrows (by at most half).
PlotLayout layoutPlot(const LinePlot& plot) {
  const Layout l = layoutFor(plot);
  int longest = 0;
  for (const PlotSeries& series : plot.series)
    longest = std::max(longest, textWidth(series.label, l.s));
  Box legend;
  legend.width = 4 * l.s + l.textHeight() + 3 * l.s + longest + 4 * l.s;
  legend.height = 5 * l.s + static_cast<int>(plot.series.size()) * 10 * l.s;

  PlotLayout layout{computeAxes(plot, 0), {}, legend};
  const PlotAxes& axes = layout.axes.axes;
  layout.bandLabels = bandLabels(plot, axes, l);
  int labelsBottom = axes.top;
  for (const TextAt& label : layout.bandLabels)
    labelsBottom = std::max(labelsBottom, label.y + l.lineHeight());
  Canvas scratch(plot.width, plot.height);
  CurvePainter painter(scratch, axes, plot.width, plot.height);
  drawCurves(plot, axes, painter);
  const int inset = 4 * l.s;
  const int topY = labelsBottom + inset, bottomY = axes.bottom - inset - legend.height + 1;
  const int leftX = axes.left + inset, rightX = axes.right - inset - legend.width + 1;
  const std::array<std::pair<int, int>, 4> corners = {
      {{rightX, topY}, {leftX, topY}, {rightX, bottomY}, {leftX, bottomY}}};
  const bool fits = leftX <= rightX && topY <= bottomY;
  int least = std::numeric_limits<int>::max();
  for (const auto& [x, y] : corners) {
    const int covered = painter.coveredIn(x, y, x + legend.width - 1, y + legend.height - 1);
    if (covered < least) least = covered, layout.legend.x = x, layout.legend.y = y;
  }
  // Outside only while the area keeps at least half its width; else over the fewest curves.
  if ((fits && least == 0) || 2 * (legend.width + l.pad()) > axes.right - axes.left) return layout;
  layout.axes = computeAxes(plot, legend.width + l.pad());
  layout.bandLabels = bandLabels(plot, layout.axes.axes, l);
  layout.legend.x = layout.axes.axes.right + 2 + l.pad();
  layout.legend.y = layout.axes.axes.top - 1;
  return layout;
}

}  // namespace

PlotAxes plotAxes(const LinePlot& plot) { return layoutPlot(plot).axes.axes; }

PlotImage renderLinePlot(const LinePlot& plot) {
  const PlotLayout layout = layoutPlot(plot);
  const PlotAxes& axes = layout.axes.axes;
  const Layout l = layoutFor(plot);
  Canvas canvas(plot.width, plot.height);

  // Bands and grid lines under the curves.
  for (size_t b = 0; b < plot.bands.size(); ++b)
    if (const auto columns = bandColumns(plot.bands[b], axes))
      canvas.fill(columns->first, axes.top, columns->second, axes.bottom,
                  b % 2 ? kPlotBandColourAlternate : kPlotBandColour);
  const std::vector<double> yTicks = ticks(axes.yMin, axes.yMax, axes.yStep);
  const std::vector<double> xTicks = ticks(axes.xMin, axes.xMax, axes.xStep);
  for (const double v : yTicks) canvas.fill(axes.left, axes.row(v), axes.right, axes.row(v), kGrid);
  for (const double f : xTicks)
    canvas.fill(axes.column(f), axes.top, axes.column(f), axes.bottom, kGrid);
  CurvePainter painter(canvas, axes, plot.width, plot.height);
  drawCurves(plot, axes, painter);

  // The frame one pixel outside the area, tick marks outwards, tick labels.
  canvas.fill(axes.left - 1, axes.top - 1, axes.right + 1, axes.top - 1, kFrame);
  canvas.fill(axes.left - 1, axes.bottom + 1, axes.right + 1, axes.bottom + 1, kFrame);
  canvas.fill(axes.left - 1, axes.top - 1, axes.left - 1, axes.bottom + 1, kFrame);
  canvas.fill(axes.right + 1, axes.top - 1, axes.right + 1, axes.bottom + 1, kFrame);
  for (const double v : yTicks) {
    const int y = axes.row(v), x = axes.left - 1 - l.tickLength();
    canvas.fill(x, y, axes.left - 2, y, kFrame);
    const std::string label = tickLabel(v, layout.axes.yFormat);
    canvas.text(x - 2 * l.s - textWidth(label, l.s), y - l.textHeight() / 2, label, l.s, kText);
  }
  const int xLabelsTop = axes.bottom + 2 + l.tickLength() + 2 * l.s;
  for (const double f : xTicks) {
    const int x = axes.column(f);
    canvas.fill(x, axes.bottom + 2, x, axes.bottom + 1 + l.tickLength(), kFrame);
    const std::string label = tickLabel(f, layout.axes.xFormat);
    canvas.text(x - textWidth(label, l.s) / 2, xLabelsTop, label, l.s, kText);
  }
  for (const TextAt& label : layout.bandLabels)
    canvas.text(label.x, label.y, label.text, l.s, kBandText);

  // The legend: a swatch of each series' colour and its label.
  const Box& box = layout.legend;
  canvas.fill(box.x, box.y, box.x + box.width - 1, box.y + box.height - 1, kFrame);
  canvas.fill(box.x + 1, box.y + 1, box.x + box.width - 2, box.y + box.height - 2, kWhite);
  for (size_t s = 0; s < plot.series.size(); ++s) {
    const int x = box.x + 4 * l.s, y = box.y + 4 * l.s + static_cast<int>(s) * 10 * l.s;
    canvas.fill(x, y, x + l.textHeight() - 1, y + l.textHeight() - 1, plotColour(s));
    canvas.text(x + l.textHeight() + 3 * l.s, y, plot.series[s].label, l.s, kText);
  }

  // The title on top, the y label above its axis, the x label under its tick labels.
  canvas.text(plot.width / 2 - textWidth(plot.title, l.titleScale) / 2, l.pad(), plot.title,
              l.titleScale, kText);
  canvas.text(l.pad(), axes.top - 1 - l.textHeight() / 2 - 3 * l.s - l.lineHeight(), plot.yLabel,
              l.s, kText);
  canvas.text((axes.left + axes.right) / 2 - textWidth(plot.xLabel, l.s) / 2,
              xLabelsTop + l.lineHeight() + l.pad(), plot.xLabel, l.s, kText);
  return canvas.take();
}

void writeLinePlot(const std::filesystem::path& file, const LinePlot& plot) {
  const PlotImage image = renderLinePlot(plot);
  // Opaque, so written as RGB: no alpha channel for a viewer to composite.
  std::vector<uint8_t> rgb;
  rgb.reserve(image.rgba.size() / 4 * 3);
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    rgb.insert(rgb.end(), image.rgba.begin() + static_cast<std::ptrdiff_t>(i),
               image.rgba.begin() + static_cast<std::ptrdiff_t>(i + 3));
  writeImage8(file, static_cast<uint32_t>(image.width), static_cast<uint32_t>(image.height), 3,
              std::as_bytes(std::span(rgb)));
}

}  // namespace vt
