#pragma once
// Line charts as PNG for the benchmark's plots, drawn with OpenCV alone (no plotting library among
// binpick's dependencies). One call draws a whole chart: nice 1-2-5 ticks
// (decades on log axes), light grid, title and axis labels, one colour-blind-friendly colour and
// marker per series, and a legend in the corner that hides the fewest points.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace binpick::bench {

struct PlotSeries {
  std::string label;         // legend text; series with an empty label stay out of the legend
  std::vector<double> x, y;  // same length; non-finite values are skipped
};

struct LinePlot {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;  // log10 axes (non-positive values skipped)
  std::vector<PlotSeries> series;
  int width = 960, height = 600;  // pixels
};

// One axis after layout. Positions are in axis units: the value itself on a linear axis, its
// log10 on a log axis, so that pixels are linear in axis units either way.
struct PlotAxis {
  bool log = false;
  double lo = 0.0, hi = 1.0;        // the ends: the outer ticks, a bit beyond where data reach
  std::vector<double> ticks;        // labelled ticks, lo..hi
  std::vector<double> minor_ticks;  // log axes spanning few decades: 2..9 times each decade
  double toAxis(double value) const;
  double fromAxis(double position) const;
};

// Where a chart puts things: the plot area inside the image and both axes. Built from the plot
// alone, so tests (and anything composing charts) can find a data point's pixel.
class PlotFrame {
 public:
  // Throws core::Error when the plot is malformed (see writeLinePlot).
  explicit PlotFrame(const LinePlot& plot);

  // Pixel (x right, y down) of a data point; meaningful for points the plot would draw.
  cv::Point2d toPixel(double x, double y) const;
  cv::Rect area() const { return area_; }  // the plot area, axes on its border
  const PlotAxis& xAxis() const { return x_; }
  const PlotAxis& yAxis() const { return y_; }
  double fontScale() const { return font_scale_; }  // 1 at the default 960 x 600

 private:
  cv::Rect area_;
  PlotAxis x_, y_;
  double font_scale_ = 1.0;
};

// The colour (BGR) of the index-th series; the palette repeats after 8 series.
cv::Scalar seriesColour(std::size_t index);

// Draws the chart and writes it as PNG; throws core::Error naming the path when it cannot be
// written, or naming the problem when the plot is malformed (x/y length mismatch, no finite point
// at all, size too small).
void writeLinePlot(const std::string& path, const LinePlot& plot);

// The same chart as an 8-bit BGR image of plot.width x plot.height (for tests and composing).
cv::Mat renderLinePlot(const LinePlot& plot);

}  // namespace binpick::bench
