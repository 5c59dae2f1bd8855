// Line plots of quality over frames (eval/line_plot.h): curves where the axes put them, gaps for
// missing values, shaded bands, the same bytes for the same input, nonsense rejected.

#include "eval/line_plot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/image_file.h"
#include "test_support.h"

namespace vt {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Rgba8 pixel(const PlotImage& image, int x, int y) {
  const uint8_t* p = &image.rgba[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
  return {p[0], p[1], p[2], p[3]};
}

// Two configurations over 100 frames in [0, 1]: a wave and a flat line well below it.
LinePlot twoCurves() {
  LinePlot plot;
  plot.title = "SSIM per frame";
  plot.yLabel = "SSIM";
  plot.yMin = 0.0, plot.yMax = 1.0;
  PlotSeries wave{"wave", {}}, flat{"flat", std::vector<double>(100, 0.05)};
  for (int i = 0; i < 100; ++i) wave.values.push_back(0.6 + 0.3 * std::sin(i / 8.0));
  plot.series = {wave, flat};
  return plot;
}

TEST(LinePlot, MapsTheGivenRangeOntoThePlotAreasEdges) {
  const LinePlot plot = twoCurves();
  const PlotAxes axes = plotAxes(plot);
  EXPECT_EQ(axes.xMin, 0.0);
  EXPECT_EQ(axes.xMax, 99.0);
  EXPECT_EQ(axes.yMin, 0.0);
  EXPECT_EQ(axes.yMax, 1.0);
  EXPECT_EQ(axes.column(0), axes.left);
  EXPECT_EQ(axes.column(99), axes.right);
  EXPECT_EQ(axes.row(0.0), axes.bottom);
  EXPECT_EQ(axes.row(1.0), axes.top);
  EXPECT_GT(axes.right - axes.left, plot.width / 2);
  EXPECT_GT(axes.bottom - axes.top, plot.height / 2);
}

TEST(LinePlot, DrawsAKnownValueAtTheRowAndColumnItsAxesGiveIt) {
  const LinePlot plot = twoCurves();
  const PlotAxes axes = plotAxes(plot);
  const PlotImage image = renderLinePlot(plot);
  ASSERT_EQ(image.width, plot.width);
  ASSERT_EQ(image.height, plot.height);
  ASSERT_EQ(image.rgba.size(), size_t(plot.width) * size_t(plot.height) * 4);
  for (const int frame : {30, 45, 52, 67}) {
    const double value = plot.series[0].values[size_t(frame)];
    EXPECT_EQ(pixel(image, axes.column(frame), axes.row(value)), plotColour(0)) << frame;
    EXPECT_EQ(pixel(image, axes.column(frame), axes.row(0.05)), plotColour(1)) << frame;
    // Well above the wave there is no curve.
    EXPECT_NE(pixel(image, axes.column(frame), axes.row(value) - 20), plotColour(0)) << frame;
  }
  EXPECT_EQ(pixel(image, 0, 0), (Rgba8{255, 255, 255, 255}));  // a white background
}

TEST(LinePlot, LeavesAGapWhereValuesAreNaNAndDotsALoneValue) {
  LinePlot plot;
  plot.yMin = 0.0, plot.yMax = 1.0;
  std::vector<double> values(100, 0.5);
  for (int i = 40; i <= 44; ++i) values[size_t(i)] = kNaN;
  values[69] = values[71] = kNaN;  // frame 70 stands alone
  plot.series = {{"with gaps", values}};
  const PlotAxes axes = plotAxes(plot);
  const PlotImage image = renderLinePlot(plot);
  const Rgba8 colour = plotColour(0);
  const int y = axes.row(0.5);
  // The 2-pixel line covers its row and the one below; the gap covers neither.
  for (int x = axes.column(39) + 2; x < axes.column(45); ++x)
    for (const int dy : {-1, 0, 1, 2}) EXPECT_NE(pixel(image, x, y + dy), colour) << x;
  EXPECT_EQ(pixel(image, axes.column(39), y), colour);
  EXPECT_EQ(pixel(image, axes.column(45), y), colour);
  EXPECT_EQ(pixel(image, axes.column(20), y), colour);
  // The lone value: a dot at frame 70, nothing halfway to its neighbours.
  EXPECT_EQ(pixel(image, axes.column(70), y), colour);
  EXPECT_NE(pixel(image, axes.column(69.5), y), colour);
  EXPECT_NE(pixel(image, axes.column(70.5), y), colour);
}

TEST(LinePlot, ShadesABandAtItsFramesAndNowhereElse) {
  LinePlot plot;
  plot.yMin = 0.0, plot.yMax = 1.0;
  plot.series = {{"high", std::vector<double>(100, 0.95)}};
  plot.bands = {{31, 47, "turn"}};
  const PlotAxes axes = plotAxes(plot);
  const PlotImage image = renderLinePlot(plot);
  const auto bandPixels = [&](int frame) {
    int count = 0;
    for (int y = axes.top; y <= axes.bottom; ++y)
      count += pixel(image, axes.column(frame), y) == kPlotBandColour;
    return count;
  };
  const int areaRows = axes.bottom - axes.top + 1;
  for (const int frame : {31, 39, 47}) EXPECT_GT(bandPixels(frame), areaRows * 8 / 10) << frame;
  for (const int frame : {0, 29, 49, 99}) EXPECT_EQ(bandPixels(frame), 0) << frame;
  // The band's half frames end it: halfway to the next frame outside is unshaded.
  const int y = axes.row(0.45);  // no grid line there
  EXPECT_EQ(pixel(image, axes.column(47.5), y), kPlotBandColour);
  EXPECT_NE(pixel(image, axes.column(47.5) + 1, y), kPlotBandColour);
  EXPECT_EQ(pixel(image, axes.column(30.5), y), kPlotBandColour);
  EXPECT_NE(pixel(image, axes.column(30.5) - 1, y), kPlotBandColour);
}

TEST(LinePlot, SeriesOfDifferentLengthsShareTheLongestFrameAxis) {
  LinePlot plot;
  plot.series = {{"short", std::vector<double>(50, 2.0)}, {"long", std::vector<double>(200, 3.0)}};
  const PlotAxes axes = plotAxes(plot);
  EXPECT_EQ(axes.xMax, 199.0);
  const PlotImage image = renderLinePlot(plot);
  EXPECT_EQ(pixel(image, axes.column(150), axes.row(3.0)), plotColour(1));
  EXPECT_NE(pixel(image, axes.column(150), axes.row(2.0)), plotColour(0));  // 'short' has ended
}

TEST(LinePlot, PadsTheDataRangeOutToNiceTicks) {
  LinePlot plot;
  plot.series = {{"ssim", {0.81, 0.9, 0.97, 0.93}}};
  const PlotAxes axes = plotAxes(plot);
  EXPECT_LT(axes.yMin, 0.81);
  EXPECT_GT(axes.yMax, 0.97);
  EXPECT_LT(axes.yMax - axes.yMin, 0.5);
  // The step is 1, 2 or 5 times a power of ten, and both ends lie on a tick.
  const double power = std::pow(10.0, std::floor(std::log10(axes.yStep)));
  const double mantissa = axes.yStep / power;
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
              std::abs(mantissa - 5) < 1e-9)
      << axes.yStep;
  for (const double end : {axes.yMin, axes.yMax})
    EXPECT_NEAR(end / axes.yStep, std::round(end / axes.yStep), 1e-9) << end;
  EXPECT_GE(axes.xStep, 1.0);  // whole frames
}

TEST(LinePlot, GivesTwelveSeriesTwelveDistinctColours) {
  for (size_t a = 0; a < 12; ++a) {
    const Rgba8 ca = plotColour(a);
    for (const Rgba8 other : {Rgba8{255, 255, 255, 255}, kPlotBandColour})
      EXPECT_GT(std::abs(ca.r - other.r) + std::abs(ca.g - other.g) + std::abs(ca.b - other.b), 60);
    for (size_t b = a + 1; b < 12; ++b) {
      const Rgba8 cb = plotColour(b);
      EXPECT_GT(std::abs(ca.r - cb.r) + std::abs(ca.g - cb.g) + std::abs(ca.b - cb.b), 60)
          << a << " " << b;
    }
  }
  EXPECT_EQ(plotColour(12), plotColour(0));
}

TEST(LinePlot, TheLegendHidesNoCurveWhenCurvesCrossEveryCorner) {
  LinePlot plot;
  for (int s = 0; s < 12; ++s) {
    PlotSeries series{"configuration " + std::to_string(s), {}};
    for (int i = 0; i < 300; ++i) series.values.push_back(s + 2 * std::sin(i / 20.0 + s));
    plot.series.push_back(series);
  }
  const PlotAxes axes = plotAxes(plot);
  const PlotImage image = renderLinePlot(plot);
  // The last series is drawn over the others: every one of its values is seen.
  for (int frame = 0; frame < 300; ++frame) {
    const double value = plot.series[11].values[size_t(frame)];
    ASSERT_EQ(pixel(image, axes.column(frame), axes.row(value)), plotColour(11)) << frame;
  }
  // The legend went to the right of the area (text scale 2 at 1280 x 640).
  EXPECT_LT(axes.right, plot.width - textWidth("configuration 11", 2));
}

TEST(LinePlot, TheSameInputGivesTheSameBytes) {
  LinePlot plot = twoCurves();
  plot.bands = {{10, 20, "pan"}, {60, 80, "dolly"}};
  plot.series[1].values[50] = kNaN;
  EXPECT_EQ(renderLinePlot(plot).rgba, renderLinePlot(plot).rgba);
  test::ScratchDirectory dir;
  writeLinePlot(dir / "a.png", plot);
  writeLinePlot(dir / "b.png", plot);
  EXPECT_EQ(test::readBytes(dir / "a.png"), test::readBytes(dir / "b.png"));
  const std::optional<ImageHeader> header = readImageHeader(dir / "a.png");
  ASSERT_TRUE(header);
  EXPECT_EQ(header->width, plot.width);
  EXPECT_EQ(header->height, plot.height);
  // Written through a temporary file: nothing else is left in the folder.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            2);
}

void expectRejected(const LinePlot& plot, const std::string& message) {
  try {
    renderLinePlot(plot);
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const std::invalid_argument& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr(message));
  }
}

TEST(LinePlot, RejectsNonsenseWithAMessage) {
  LinePlot plot = twoCurves();
  plot.title = "broken";
  LinePlot noSeries = plot;
  noSeries.series.clear();
  expectRejected(noSeries, "'broken': no series");
  LinePlot allNaN = plot;
  for (PlotSeries& series : allNaN.series) series.values.assign(10, kNaN);
  expectRejected(allNaN, "no series has a finite value");
  LinePlot tiny = plot;
  tiny.width = 120, tiny.height = 60;
  expectRejected(tiny, "120 x 60 pixels is too small");
  LinePlot negative = plot;
  negative.width = -5;
  expectRejected(negative, "size -5 x 640");
  LinePlot backwards = plot;
  backwards.bands = {{20, 10, "pan"}};
  expectRejected(backwards, "band 'pan' has first frame 20 after its last 10");
  LinePlot empty = plot;
  empty.yMin = empty.yMax = 0.5;
  expectRejected(empty, "empty y range");
  LinePlot infinite = plot;
  infinite.yMax = std::numeric_limits<double>::infinity();
  expectRejected(infinite, "not finite");
}

}  // namespace
}  // namespace vt
