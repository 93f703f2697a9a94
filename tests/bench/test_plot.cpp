// The chart writer: the PNG it writes, where series land in the image, tick placement on linear
// and log axes, degenerate data, and the errors for malformed plots and unwritable paths.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "binpick/io/image_file.hpp"
#include "plot.hpp"
#include "temp_directory_test.hpp"
#include "thrown_message.hpp"

namespace binpick::bench {
namespace {

using test::throwsNaming;

LinePlot twoSeriesPlot() {
  LinePlot plot;
  plot.title = "Recall against clutter";
  plot.x_label = "objects in the bin";
  plot.y_label = "recall";
  plot.series = {{"binpick", {1, 5, 10}, {0.9, 0.8, 0.7}}, {"peer", {1, 5, 10}, {0.5, 0.3, 0.1}}};
  return plot;
}

cv::Vec3b colourOf(std::size_t series) {
  const cv::Scalar c = seriesColour(series);
  return {static_cast<uchar>(c[0]), static_cast<uchar>(c[1]), static_cast<uchar>(c[2])};
}

// Whether `colour` appears exactly within `radius` pixels of `at`.
bool colourNear(const cv::Mat& image, cv::Point2d at, const cv::Vec3b& colour, int radius = 2) {
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const cv::Point p(cvRound(at.x) + dx, cvRound(at.y) + dy);
      if (p.inside(cv::Rect(0, 0, image.cols, image.rows)) && image.at<cv::Vec3b>(p) == colour) {
        return true;
      }
    }
  }
  return false;
}

class PlotFile : public test::TempDirectoryTest {};

TEST_F(PlotFile, WritesPngOfRequestedSize) {
  LinePlot plot = twoSeriesPlot();
  plot.width = 640;
  plot.height = 400;
  const std::string path = pathOf("chart.png");
  writeLinePlot(path, plot);

  char signature[8] = {};
  std::ifstream(path, std::ios::binary).read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
  const cv::Mat read = io::readImageFile(path);
  ASSERT_FALSE(read.empty());
  EXPECT_EQ(read.cols, 640);
  EXPECT_EQ(read.rows, 400);
  EXPECT_EQ(read.type(), CV_8UC3);
}

TEST_F(PlotFile, PngEvenWhenTheNameSaysOtherwise) {
  const std::string path = pathOf("chart.jpg");
  writeLinePlot(path, twoSeriesPlot());
  char signature[8] = {};
  std::ifstream(path, std::ios::binary).read(signature, 8);
  EXPECT_EQ(std::string(signature + 1, 3), "PNG");
}

TEST(Plot, UnwritablePathThrowsNamingIt) {
  EXPECT_TRUE(throwsNaming([] { writeLinePlot("/nonexistent_dir/x.png", twoSeriesPlot()); }, "/nonexistent_dir/x.png"));
}

TEST(Plot, EachSeriesColourSitsOnItsPoints) {
  const LinePlot plot = twoSeriesPlot();
  const cv::Mat image = renderLinePlot(plot);
  const PlotFrame frame(plot);
  ASSERT_EQ(image.size(), cv::Size(plot.width, plot.height));
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    for (std::size_t i = 0; i < plot.series[s].x.size(); ++i) {
      const cv::Point2d at = frame.toPixel(plot.series[s].x[i], plot.series[s].y[i]);
      EXPECT_TRUE(frame.area().contains(cv::Point(cvRound(at.x), cvRound(at.y))));
      EXPECT_TRUE(colourNear(image, at, colourOf(s))) << "series " << s << " point " << i;
      EXPECT_FALSE(colourNear(image, at, colourOf(1 - s), 4)) << "series " << s << " point " << i;
    }
  }
  // Nothing is drawn where there is no data: the middle of the empty band between the series.
  const cv::Point2d gap = frame.toPixel(3.0, 0.625);
  EXPECT_FALSE(colourNear(image, gap, colourOf(0), 4));
  EXPECT_FALSE(colourNear(image, gap, colourOf(1), 4));
}

TEST(Plot, LegendLeavesCrowdedCornerAlone) {
  // Points hug the top right and top left corners; the legend must go below and hide none.
  LinePlot plot;
  plot.series = {{"a", {0, 1, 2, 8, 9, 10}, {10, 9.5, 9, 9, 9.5, 10}}, {"b", {0, 1, 9, 10}, {9, 8.5, 8.5, 9}}};
  const cv::Mat image = renderLinePlot(plot);
  const PlotFrame frame(plot);
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    for (std::size_t i = 0; i < plot.series[s].x.size(); ++i) {
      const cv::Point2d at = frame.toPixel(plot.series[s].x[i], plot.series[s].y[i]);
      EXPECT_TRUE(colourNear(image, at, colourOf(s))) << "series " << s << " point " << i;
    }
  }
}

TEST(Plot, LogAxisPlacesDecadesAtEqualSpacing) {
  LinePlot plot;
  plot.log_x = true;
  plot.log_y = true;
  plot.series = {{"", {1, 10, 100}, {1, 10, 100}}};
  const PlotFrame frame(plot);
  const cv::Point2d p1 = frame.toPixel(1, 1), p10 = frame.toPixel(10, 10), p100 = frame.toPixel(100, 100);
  EXPECT_GT(p10.x - p1.x, 50.0);
  EXPECT_NEAR(p10.x - p1.x, p100.x - p10.x, 1e-9);
  EXPECT_GT(p1.y - p10.y, 50.0);
  EXPECT_NEAR(p1.y - p10.y, p10.y - p100.y, 1e-9);
  // Ticks on whole decades, in axis units (log10).
  const std::vector<double> decades = {0.0, 1.0, 2.0};
  EXPECT_EQ(frame.xAxis().ticks, decades);
  EXPECT_EQ(frame.yAxis().ticks, decades);
  const cv::Mat image = renderLinePlot(plot);
  EXPECT_TRUE(colourNear(image, p10, colourOf(0)));
}

TEST(Plot, LogAxisSkipsNonPositiveValues) {
  LinePlot plot;
  plot.log_y = true;
  plot.series = {{"", {1, 2, 3}, {0.0, -5.0, 1000.0}}};
  const PlotFrame frame(plot);
  EXPECT_LE(frame.yAxis().lo, 3.0);
  EXPECT_GE(frame.yAxis().hi, 3.0);
  EXPECT_TRUE(colourNear(renderLinePlot(plot), frame.toPixel(3, 1000), colourOf(0)));
}

bool isOneTwoFive(double step) {
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
  return std::abs(mantissa - 1.0) < 1e-9 || std::abs(mantissa - 2.0) < 1e-9 || std::abs(mantissa - 5.0) < 1e-9;
}

// Ticks evenly spaced by 1, 2 or 5 times a power of ten, covering the data, 3..12 of them.
void expectNiceTicks(const PlotAxis& axis, double lo, double hi) {
  ASSERT_GE(axis.ticks.size(), 3u);
  EXPECT_LE(axis.ticks.size(), 12u);
  const double step = axis.ticks[1] - axis.ticks[0];
  EXPECT_TRUE(isOneTwoFive(step)) << step;
  for (std::size_t i = 1; i < axis.ticks.size(); ++i) {
    EXPECT_NEAR(axis.ticks[i] - axis.ticks[i - 1], step, 1e-9 * step);
  }
  EXPECT_LE(axis.lo, lo);
  EXPECT_GE(axis.hi, hi);
  // The frame closes on the outer ticks, give or take the room left around markers at an end.
  const double span = axis.hi - axis.lo;
  EXPECT_NEAR(axis.lo, axis.ticks.front(), 0.05 * span);
  EXPECT_NEAR(axis.hi, axis.ticks.back(), 0.05 * span);
  EXPECT_LE(axis.lo, axis.ticks.front());
  EXPECT_GE(axis.hi, axis.ticks.back());
}

TEST(Plot, LinearTicksStepByOneTwoFiveAndYStartsAtZero) {
  LinePlot plot;
  plot.series = {{"", {0.13, 0.71}, {3.2, 47.0}}};
  const PlotFrame frame(plot);
  expectNiceTicks(frame.xAxis(), 0.13, 0.71);
  expectNiceTicks(frame.yAxis(), 0.0, 47.0);
  EXPECT_EQ(frame.yAxis().lo, 0.0);
  EXPECT_GT(frame.xAxis().lo, 0.0);  // x does not start at zero
}

TEST(Plot, NegativeDataExtendTheYAxisBelowZero) {
  LinePlot plot;
  plot.series = {{"", {1, 2}, {-30.0, 12.0}}};
  const PlotFrame frame(plot);
  expectNiceTicks(frame.yAxis(), -30.0, 12.0);
}

TEST(Plot, HugeRangesKeepFewTicks) {
  LinePlot plot;
  plot.log_y = true;
  plot.series = {{"", {0, 1e12}, {1e-200, 1e200}}};
  const PlotFrame frame(plot);
  expectNiceTicks(frame.xAxis(), 0.0, 1e12);
  EXPECT_LE(frame.yAxis().ticks.size(), 12u);
  EXPECT_LE(frame.yAxis().lo, -200.0);
  EXPECT_GE(frame.yAxis().hi, 200.0);
  EXPECT_NO_THROW(renderLinePlot(plot));
}

TEST(Plot, SinglePointAndConstantDataSitInsideTheFrame) {
  for (const PlotSeries& series : {PlotSeries{"one", {5.0}, {2.0}}, PlotSeries{"flat", {1, 2, 3}, {0, 0, 0}},
                                   PlotSeries{"flat", {7, 7}, {-4, -4}}}) {
    LinePlot plot;
    plot.series = {series};
    const PlotFrame frame(plot);
    EXPECT_LT(frame.xAxis().lo, frame.xAxis().hi);
    EXPECT_LT(frame.yAxis().lo, frame.yAxis().hi);
    const cv::Point2d at = frame.toPixel(series.x[0], series.y[0]);
    EXPECT_TRUE(std::isfinite(at.x) && std::isfinite(at.y));
    EXPECT_TRUE(cv::Rect2d(frame.area()).contains(at)) << series.label;
    EXPECT_TRUE(colourNear(renderLinePlot(plot), at, colourOf(0))) << series.label;
  }
}

TEST(Plot, NonFiniteValuesAreSkipped) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  LinePlot plot;
  plot.series = {{"", {1, nan, 3, 4}, {1, 2, std::numeric_limits<double>::infinity(), 4}}};
  const PlotFrame frame(plot);
  EXPECT_EQ(frame.yAxis().lo, 0.0);
  EXPECT_LT(frame.yAxis().hi, 10.0);  // the infinity did not stretch the axis
}

TEST(Plot, MalformedPlotsThrowNamingTheProblem) {
  LinePlot mismatch;
  mismatch.series = {{"ok", {1}, {1}}, {"bad", {1, 2}, {1}}};
  EXPECT_TRUE(throwsNaming([&] { renderLinePlot(mismatch); }, "series[1]"));

  LinePlot empty;
  EXPECT_TRUE(throwsNaming([&] { renderLinePlot(empty); }, "no finite point"));

  LinePlot all_nan;
  all_nan.series = {{"", {std::nan("")}, {1.0}}};
  EXPECT_TRUE(throwsNaming([&] { renderLinePlot(all_nan); }, "no finite point"));

  LinePlot non_positive_log;
  non_positive_log.log_x = true;
  non_positive_log.series = {{"", {0.0, -1.0}, {1.0, 2.0}}};
  EXPECT_TRUE(throwsNaming([&] { renderLinePlot(non_positive_log); }, "no finite point"));

  LinePlot tiny = twoSeriesPlot();
  tiny.width = 50;
  EXPECT_TRUE(throwsNaming([&] { renderLinePlot(tiny); }, "width"));
  tiny.width = 960;
  tiny.height = 0;
  EXPECT_TRUE(throwsNaming([&] { writeLinePlot("/nonexistent_dir/never.png", tiny); }, "height"));
}

}  // namespace
}  // namespace binpick::bench
