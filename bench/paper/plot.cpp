#include "plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "binpick/core/error.hpp"
#include "binpick/io/image_file.hpp"

namespace binpick::bench {
namespace {

constexpr int kMinWidth = 240;
constexpr int kMinHeight = 180;
constexpr int kMaxSide = 16384;  // beyond this a chart is a mistake, not a figure
constexpr int kFace = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kShift = 4;  // sub-pixel bits for OpenCV drawing: smooth lines between pixels

const cv::Scalar kWhite(255, 255, 255);
const cv::Scalar kInk(40, 40, 40);           // text and axes: softer than pure black
const cv::Scalar kGrid(222, 222, 222);       // major grid, light enough to read data over
const cv::Scalar kMinorGrid(242, 242, 242);  // log-axis minor grid, barely there
const cv::Scalar kLegendEdge(170, 170, 170);

// ---------------------------------------------------------------------------------------------
// Input checks and data ranges

void validate(const LinePlot& plot) {
  core::requireField(plot.width >= kMinWidth && plot.width <= kMaxSide, "LinePlot", "width", "240..16384 pixels",
                     plot.width);
  core::requireField(plot.height >= kMinHeight && plot.height <= kMaxSide, "LinePlot", "height", "180..16384 pixels",
                     plot.height);
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& series = plot.series[i];
    if (series.x.size() == series.y.size()) continue;
    std::ostringstream message;
    message << "LinePlot.series[" << i << "] ('" << series.label << "') has " << series.x.size() << " x values but "
            << series.y.size() << " y values";
    throw core::Error(message.str());
  }
}

bool drawable(double value, bool log) { return std::isfinite(value) && (!log || value > 0.0); }

// A series' drawable points in axis units, sorted by x so that its line runs left to right.
std::vector<cv::Point2d> axisPoints(const PlotSeries& series, const PlotAxis& x, const PlotAxis& y) {
  std::vector<cv::Point2d> points;
  for (std::size_t i = 0; i < series.x.size(); ++i) {
    if (drawable(series.x[i], x.log) && drawable(series.y[i], y.log)) {
      points.emplace_back(x.toAxis(series.x[i]), y.toAxis(series.y[i]));
    }
  }
  std::stable_sort(points.begin(), points.end(), [](const cv::Point2d& a, const cv::Point2d& b) { return a.x < b.x; });
  return points;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return lo > hi; }
};

// The x and y extent of every drawable point, in axis units.
std::pair<Range, Range> dataRanges(const LinePlot& plot, const PlotAxis& x, const PlotAxis& y) {
  Range xs, ys;
  for (const PlotSeries& series : plot.series) {
    for (const cv::Point2d& p : axisPoints(series, x, y)) {
      xs.add(p.x);
      ys.add(p.y);
    }
  }
  if (xs.empty()) {
    throw core::Error(std::string("LinePlot '") + plot.title + "' has no finite point to draw" +
                      (x.log || y.log ? " (log axes skip values <= 0)" : ""));
  }
  return {xs, ys};
}

// ---------------------------------------------------------------------------------------------
// Axes and ticks

// The smallest 1, 2 or 5 times a power of ten that is at least `raw` (> 0).
double niceStep(double raw) {
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  for (double mantissa : {1.0, 2.0, 5.0}) {
    if (mantissa * decade >= raw * (1.0 - 1e-9)) return mantissa * decade;
  }
  return 10.0 * decade;
}

// Widens a range too narrow for doubles to tell ticks apart (a single point, constant data), so
// the data sit in the middle of a readable axis instead of dividing by zero.
Range widenDegenerate(Range range) {
  const double magnitude = std::max(std::abs(range.lo), std::abs(range.hi));
  if (range.hi - range.lo > 1e-9 * magnitude) return range;
  const double half = magnitude > 0.0 ? 0.1 * magnitude : 1.0;
  return {range.lo - half, range.hi + half};
}

// Ticks at whole multiples of a nice step; the axis ends are rounded out to ticks so that the
// frame closes on labelled values. Multiples (not repeated addition) keep 0.1 + 0.2 exact.
PlotAxis linearAxis(Range range, int target) {
  range = widenDegenerate(range);
  if (!std::isfinite(range.hi - range.lo)) throw core::Error("LinePlot: data span more than a double");
  const double step = niceStep((range.hi - range.lo) / std::max(target, 1));
  const auto first = static_cast<std::int64_t>(std::floor(range.lo / step + 1e-9));
  const auto last = static_cast<std::int64_t>(std::ceil(range.hi / step - 1e-9));
  PlotAxis axis;
  for (std::int64_t k = first; k <= last; ++k) {
    const double tick = static_cast<double>(k) * step;
    axis.ticks.push_back(std::abs(tick) < 1e-9 * step ? 0.0 : tick);  // no "-0"
  }
  axis.lo = axis.ticks.front();
  axis.hi = axis.ticks.back();
  return axis;
}

// Ticks every 1, 2, 5, 10... decades so that huge ranges stay legible, and minor 2..9 lines when
// there is room for them. An end stops at the data rather than at a far tick (10^7 for data that
// end at 1.05e6 would waste a sixth of the plot), as long as two labelled ticks remain.
PlotAxis logAxis(Range range, int target) {
  double first = std::floor(range.lo + 1e-9);
  double last = std::ceil(range.hi - 1e-9);
  if (last <= first) {  // data on a single decade: show the decades either side
    first -= 1.0;
    last += 1.0;
  }
  const double step = std::max(1.0, std::round(niceStep((last - first) / std::max(target, 1))));
  first = std::floor(first / step) * step;
  last = std::ceil(last / step) * step;
  const double slack = 0.25 * step;
  const double inner_lo = range.lo - first > slack ? range.lo : first;
  const double inner_hi = last - range.hi > slack ? range.hi : last;
  const double inner_ticks = std::floor(inner_hi / step + 1e-9) - std::ceil(inner_lo / step - 1e-9);
  PlotAxis axis;
  axis.log = true;
  axis.lo = inner_ticks >= 1.0 ? inner_lo : first;
  axis.hi = inner_ticks >= 1.0 ? inner_hi : last;
  for (double decade = first; decade <= last + 0.5; decade += step) {
    if (decade >= axis.lo - 1e-9 && decade <= axis.hi + 1e-9) axis.ticks.push_back(decade);
  }
  if (step == 1.0 && last - first <= 6.0) {
    for (double decade = first; decade < last; decade += 1.0) {
      for (int m = 2; m <= 9; ++m) {
        const double minor = decade + std::log10(m);
        if (minor > axis.lo && minor < axis.hi) axis.minor_ticks.push_back(minor);
      }
    }
  }
  return axis;
}

PlotAxis makeAxis(bool log, Range range, int target) {
  return log ? logAxis(range, target) : linearAxis(range, target);
}

// ---------------------------------------------------------------------------------------------
// Text

struct Font {
  double scale;
  int thickness;
};

struct Fonts {
  Font tick, label, title, exponent;
  explicit Fonts(double s)
      : tick{0.5 * s, 1}, label{0.6 * s, 1}, title{0.75 * s, std::max(1, cvRound(2 * s))}, exponent{0.38 * s, 1} {}
};

// Height counts only what is above the baseline: labels are placed by their cap height, the way
// a reader's eye lines them up.
cv::Size measure(const std::string& text, Font font) {
  int baseline = 0;
  return cv::getTextSize(text, kFace, font.scale, font.thickness, &baseline);
}

// Where the anchor point sits on the text's box: 0 = left/top, 0.5 = centre, 1 = right/bottom.
struct Anchor {
  double x, y;
};

void drawText(cv::Mat& image, const std::string& text, cv::Point2d at, Anchor anchor, Font font,
              const cv::Scalar& colour) {
  const cv::Size size = measure(text, font);
  const cv::Point origin(cvRound(at.x - anchor.x * size.width), cvRound(at.y + (1.0 - anchor.y) * size.height));
  cv::putText(image, text, origin, kFace, font.scale, colour, font.thickness, cv::LINE_AA);
}

// A tick label, possibly a power of ten drawn as "10" with a raised, smaller exponent, since the
// Hershey fonts have no superscripts and "1e+12" reads poorly in a figure.
struct TickLabel {
  std::string base, exponent;

  cv::Size size(const Fonts& fonts) const {
    const cv::Size b = measure(base, fonts.tick);
    if (exponent.empty()) return b;
    const cv::Size e = measure(exponent, fonts.exponent);
    return {b.width + e.width + 1, std::max(b.height, raise(b) + e.height)};
  }

  void draw(cv::Mat& image, cv::Point2d at, Anchor anchor, const Fonts& fonts) const {
    const cv::Size box = size(fonts);
    const double left = at.x - anchor.x * box.width;
    const double top = at.y - anchor.y * box.height;
    const cv::Size b = measure(base, fonts.tick);
    cv::putText(image, base, cv::Point(cvRound(left), cvRound(top + box.height)), kFace, fonts.tick.scale, kInk,
                fonts.tick.thickness, cv::LINE_AA);
    if (exponent.empty()) return;
    const cv::Size e = measure(exponent, fonts.exponent);
    cv::putText(image, exponent, cv::Point(cvRound(left + b.width + 1), cvRound(top + e.height)), kFace,
                fonts.exponent.scale, kInk, fonts.exponent.thickness, cv::LINE_AA);
  }

 private:
  static int raise(cv::Size base) { return cvRound(0.5 * base.height); }
};

// "1e+06" -> "1e6", "2e-05" -> "2e-5": the same number, less clutter.
std::string tidyExponent(std::string text) {
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e), digits = text.substr(e + 1);
  std::string sign;
  if (!digits.empty() && (digits[0] == '+' || digits[0] == '-')) {
    if (digits[0] == '-') sign = "-";
    digits.erase(0, 1);
  }
  digits.erase(0, std::min(digits.find_first_not_of('0'), digits.size() - 1));
  return mantissa + "e" + sign + digits;
}

// Enough significant digits that neighbouring ticks differ, and whole numbers below a million in
// full ("250000", not "2.5e5").
std::string linearLabel(double value, double step, double largest) {
  const int magnitude = static_cast<int>(std::floor(std::log10(std::max(largest, step))));
  const int step_magnitude = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  int digits = magnitude - step_magnitude + 1;
  if (largest < 1e6) digits = std::max(digits, magnitude + 1);
  std::ostringstream text;
  text.precision(std::clamp(digits, 1, 15));
  text << value;
  return tidyExponent(text.str());
}

// 0.001 .. 10000 written out; beyond that every label of the axis is a power of ten, so that an
// axis never mixes the two styles.
std::string plainDecade(int exponent) {
  if (exponent >= 0) return "1" + std::string(static_cast<std::size_t>(exponent), '0');
  return "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + "1";
}

std::vector<TickLabel> tickLabels(const PlotAxis& axis) {
  std::vector<TickLabel> labels;
  if (axis.log) {
    const bool plain = axis.ticks.front() >= -3.0 && axis.ticks.back() <= 4.0;
    for (double tick : axis.ticks) {
      const int exponent = static_cast<int>(std::lround(tick));
      labels.push_back(plain ? TickLabel{plainDecade(exponent), ""} : TickLabel{"10", std::to_string(exponent)});
    }
    return labels;
  }
  const double step = axis.ticks.size() > 1 ? axis.ticks[1] - axis.ticks[0] : 1.0;
  const double largest = std::max(std::abs(axis.lo), std::abs(axis.hi));
  for (double tick : axis.ticks) labels.push_back({linearLabel(tick, step, largest), ""});
  return labels;
}

int widestLabel(const std::vector<TickLabel>& labels, const Fonts& fonts) {
  int widest = 0;
  for (const TickLabel& label : labels) widest = std::max(widest, label.size(fonts).width);
  return widest;
}

// ---------------------------------------------------------------------------------------------
// Layout: the sizes every margin is made of, in pixels for the chart's font scale.

struct Spacing {
  int pad, gap, tick;
  explicit Spacing(double s) : pad(cvRound(14 * s)), gap(cvRound(6 * s)), tick(std::max(2, cvRound(5 * s))) {}
};

// The y extent a chart starts from: zero included on a linear axis unless the data go negative,
// so that values compare by their height above the axis.
Range withZero(Range y, bool log) {
  if (!log && y.lo >= 0.0) y.lo = 0.0;
  return y;
}

// A little room beyond data that reach an end of the axis, so that markers there stand clear of
// the frame. A zero start stays flush: the axis line is then the baseline the data rise from.
void padEnds(PlotAxis& axis, Range data, bool keep_zero) {
  const double room = 0.04 * (axis.hi - axis.lo);
  if (data.lo - axis.lo < room && !(keep_zero && axis.lo == 0.0)) axis.lo -= room;
  if (axis.hi - data.hi < room) axis.hi += room;
}

// The x axis with as many ticks as fit without their labels touching.
PlotAxis fitXAxis(bool log, Range range, int plot_width, const Fonts& fonts, const Spacing& sp, double s) {
  PlotAxis axis;
  for (int target = std::max(2, cvRound(plot_width / (95 * s))); target >= 1; --target) {
    axis = makeAxis(log, range, target);
    const double per_tick =
        plot_width * (axis.ticks.size() > 1 ? (axis.ticks[1] - axis.ticks[0]) / (axis.hi - axis.lo) : 1.0);
    if (widestLabel(tickLabels(axis), fonts) + 2 * sp.gap <= per_tick) break;
  }
  return axis;
}

int textBlock(const std::string& text, Font font, int gap) {
  return text.empty() ? 0 : measure(text, font).height + gap;
}

}  // namespace

// -----------------------------------------------------------------------------------------------

double PlotAxis::toAxis(double value) const { return log ? std::log10(value) : value; }
double PlotAxis::fromAxis(double position) const { return log ? std::pow(10.0, position) : position; }

// Vertical margins depend only on fonts; the y ticks then follow from the plot height, the left
// margin from the y labels, the plot width from that, and the x ticks last.
PlotFrame::PlotFrame(const LinePlot& plot) {
  validate(plot);
  const double s = std::clamp(std::min(plot.width / 960.0, plot.height / 600.0), 0.6, 3.0);
  font_scale_ = s;
  const Fonts fonts(s);
  const Spacing sp(s);
  x_.log = plot.log_x;
  y_.log = plot.log_y;
  const auto [xs, ys] = dataRanges(plot, x_, y_);

  const int tick_h = TickLabel{"10", "-8"}.size(fonts).height;
  const int top = sp.pad + textBlock(plot.title, fonts.title, sp.pad) +
                  textBlock(plot.y_label, fonts.label, 2 * sp.gap + tick_h / 2) + tick_h / 2;
  const int bottom = sp.tick + sp.gap + tick_h + textBlock(plot.x_label, fonts.label, 2 * sp.gap) + sp.pad;
  const int plot_height = plot.height - top - bottom;
  y_ = makeAxis(plot.log_y, withZero(ys, plot.log_y), std::max(2, cvRound(plot_height / (70 * s))));
  padEnds(y_, ys, !plot.log_y);

  const int left = sp.pad + widestLabel(tickLabels(y_), fonts) + sp.gap + sp.tick;
  int right = 2 * sp.pad;
  for (int pass = 0; pass < 2; ++pass) {  // the last x label may need more room on the right
    x_ = fitXAxis(plot.log_x, xs, plot.width - left - right, fonts, sp, s);
    right = std::max(2 * sp.pad, tickLabels(x_).back().size(fonts).width / 2 + sp.gap);
  }
  padEnds(x_, xs, false);
  area_ = cv::Rect(left, top, plot.width - left - right, plot_height);
  if (area_.width < 40 || area_.height < 40) {
    throw core::Error("LinePlot " + std::to_string(plot.width) + "x" + std::to_string(plot.height) +
                      " is too small for its labels");
  }
}

cv::Point2d PlotFrame::toPixel(double x, double y) const {
  const double u = (x_.toAxis(x) - x_.lo) / (x_.hi - x_.lo);
  const double v = (y_.toAxis(y) - y_.lo) / (y_.hi - y_.lo);
  return {area_.x + u * area_.width, area_.y + (1.0 - v) * area_.height};
}

cv::Scalar seriesColour(std::size_t index) {
  // Okabe-Ito, in BGR, ordered so the first series get the colours that read best on white
  // (yellow last).
  static const std::array<cv::Scalar, 8> palette = {
      cv::Scalar(178, 114, 0),   cv::Scalar(0, 159, 230),  cv::Scalar(115, 158, 0), cv::Scalar(0, 94, 213),
      cv::Scalar(167, 121, 204), cv::Scalar(233, 180, 86), cv::Scalar(0, 0, 0),     cv::Scalar(66, 228, 240)};
  return palette[index % palette.size()];
}

namespace {

// ---------------------------------------------------------------------------------------------
// Drawing

cv::Point fixedPoint(cv::Point2d p) { return {cvRound(p.x * (1 << kShift)), cvRound(p.y * (1 << kShift))}; }

void drawLine(cv::Mat& image, cv::Point2d a, cv::Point2d b, const cv::Scalar& colour, int thickness) {
  cv::line(image, fixedPoint(a), fixedPoint(b), colour, thickness, cv::LINE_AA, kShift);
}

void fillPolygon(cv::Mat& image, cv::Point2d centre, double r, std::initializer_list<cv::Point2d> unit,
                 const cv::Scalar& colour) {
  std::vector<cv::Point> corners;
  for (const cv::Point2d& u : unit) corners.push_back(fixedPoint(centre + r * u));
  cv::fillConvexPoly(image, corners, colour, cv::LINE_AA, kShift);
}

// Eight shapes, so that series stay apart in greyscale print and for readers who confuse colours.
// Sizes are tuned by eye so that every shape looks about as heavy as the circle.
void drawMarker(cv::Mat& image, cv::Point2d c, std::size_t index, double r, const cv::Scalar& colour) {
  const int stroke = std::max(1, cvRound(r / 2.5));
  switch (index % 8) {
    case 0:
      cv::circle(image, fixedPoint(c), cvRound(r * (1 << kShift)), colour, cv::FILLED, cv::LINE_AA, kShift);
      break;
    case 1: fillPolygon(image, c, 0.9 * r, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, colour); break;
    case 2: fillPolygon(image, c, 1.3 * r, {{0, -1}, {0.87, 0.55}, {-0.87, 0.55}}, colour); break;
    case 3: fillPolygon(image, c, 1.3 * r, {{0, -1}, {1, 0}, {0, 1}, {-1, 0}}, colour); break;
    case 4: fillPolygon(image, c, 1.3 * r, {{0, 1}, {0.87, -0.55}, {-0.87, -0.55}}, colour); break;
    case 5:
      drawLine(image, c + r * cv::Point2d(-1, -1), c + r * cv::Point2d(1, 1), colour, stroke);
      drawLine(image, c + r * cv::Point2d(-1, 1), c + r * cv::Point2d(1, -1), colour, stroke);
      break;
    case 6:
      drawLine(image, c + 1.2 * r * cv::Point2d(-1, 0), c + 1.2 * r * cv::Point2d(1, 0), colour, stroke);
      drawLine(image, c + 1.2 * r * cv::Point2d(0, -1), c + 1.2 * r * cv::Point2d(0, 1), colour, stroke);
      break;
    default:  // a ring: hollow, so it still differs from the filled circle
      cv::circle(image, fixedPoint(c), cvRound(0.9 * r * (1 << kShift)), colour, stroke, cv::LINE_AA, kShift);
      break;
  }
}

struct Style {
  Fonts fonts;
  Spacing sp;
  double marker_r;
  int line_thickness;
  explicit Style(double s) : fonts(s), sp(s), marker_r(4.5 * s), line_thickness(std::max(1, cvRound(2 * s))) {}
};

double pixelX(const PlotFrame& frame, double position) {
  const PlotAxis& x = frame.xAxis();
  return frame.area().x + (position - x.lo) / (x.hi - x.lo) * frame.area().width;
}

double pixelY(const PlotFrame& frame, double position) {
  const PlotAxis& y = frame.yAxis();
  return frame.area().y + (1.0 - (position - y.lo) / (y.hi - y.lo)) * frame.area().height;
}

void drawGrid(cv::Mat& image, const PlotFrame& frame) {
  const cv::Rect a = frame.area();
  const auto vertical = [&](double position, const cv::Scalar& colour) {
    const double px = pixelX(frame, position);
    drawLine(image, {px, double(a.y)}, {px, double(a.br().y)}, colour, 1);
  };
  const auto horizontal = [&](double position, const cv::Scalar& colour) {
    const double py = pixelY(frame, position);
    drawLine(image, {double(a.x), py}, {double(a.br().x), py}, colour, 1);
  };
  for (double t : frame.xAxis().minor_ticks) vertical(t, kMinorGrid);
  for (double t : frame.yAxis().minor_ticks) horizontal(t, kMinorGrid);
  for (double t : frame.xAxis().ticks) vertical(t, kGrid);
  for (double t : frame.yAxis().ticks) horizontal(t, kGrid);
}

void drawAxes(cv::Mat& image, const PlotFrame& frame, const Style& style) {
  const cv::Rect a = frame.area();
  cv::rectangle(image, a.tl(), a.br(), kInk, 1, cv::LINE_8);
  const int tick = style.sp.tick;
  const std::vector<TickLabel> x_labels = tickLabels(frame.xAxis());
  for (std::size_t i = 0; i < x_labels.size(); ++i) {
    const double px = pixelX(frame, frame.xAxis().ticks[i]);
    drawLine(image, {px, double(a.br().y)}, {px, double(a.br().y + tick)}, kInk, 1);
    x_labels[i].draw(image, {px, double(a.br().y + tick + style.sp.gap)}, {0.5, 0.0}, style.fonts);
  }
  const std::vector<TickLabel> y_labels = tickLabels(frame.yAxis());
  for (std::size_t i = 0; i < y_labels.size(); ++i) {
    const double py = pixelY(frame, frame.yAxis().ticks[i]);
    drawLine(image, {double(a.x - tick), py}, {double(a.x), py}, kInk, 1);
    y_labels[i].draw(image, {double(a.x - tick - style.sp.gap), py}, {1.0, 0.5}, style.fonts);
  }
}

// Every series in pixels, in x order.
std::vector<std::vector<cv::Point2d>> pixelSeries(const LinePlot& plot, const PlotFrame& frame) {
  std::vector<std::vector<cv::Point2d>> all;
  for (const PlotSeries& series : plot.series) {
    std::vector<cv::Point2d> pixels;
    for (const cv::Point2d& p : axisPoints(series, frame.xAxis(), frame.yAxis())) {
      pixels.emplace_back(pixelX(frame, p.x), pixelY(frame, p.y));
    }
    all.push_back(std::move(pixels));
  }
  return all;
}

// All lines first, then all markers, so that no line crosses over another series' marker.
void drawSeries(cv::Mat& image, const std::vector<std::vector<cv::Point2d>>& series, const Style& style) {
  for (std::size_t i = 0; i < series.size(); ++i) {
    for (std::size_t k = 1; k < series[i].size(); ++k) {
      drawLine(image, series[i][k - 1], series[i][k], seriesColour(i), style.line_thickness);
    }
  }
  for (std::size_t i = 0; i < series.size(); ++i) {
    for (const cv::Point2d& p : series[i]) {
      drawMarker(image, p, i, style.marker_r, seriesColour(i));
    }
  }
}

// How much of the data a box would hide: markers count heavily, line samples (every 2 px) lightly.
double coverage(const cv::Rect2d& box, const std::vector<std::vector<cv::Point2d>>& series) {
  double hidden = 0.0;
  for (const std::vector<cv::Point2d>& points : series) {
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (box.contains(points[k])) hidden += 10.0;
      if (k == 0) continue;
      const cv::Point2d step = points[k] - points[k - 1];
      const int samples = std::min(4096, static_cast<int>(std::hypot(step.x, step.y) / 2.0));
      for (int j = 1; j < samples; ++j) {
        if (box.contains(points[k - 1] + step * (double(j) / samples))) hidden += 1.0;
      }
    }
  }
  return hidden;
}

struct LegendEntry {
  std::size_t series;
  std::string label;
};

// The legend box in whichever corner of the plot area hides the least data; ties go to the
// conventional top right.
cv::Rect2d placeLegend(cv::Size2d box, const PlotFrame& frame, const Style& style,
                       const std::vector<std::vector<cv::Point2d>>& series) {
  const cv::Rect a = frame.area();
  const double inset = style.sp.pad * 0.7;
  const double left = a.x + inset, right = a.br().x - inset - box.width;
  const double top = a.y + inset, bottom = a.br().y - inset - box.height;
  const std::array<cv::Point2d, 4> corners = {cv::Point2d(right, top), cv::Point2d(left, top),
                                              cv::Point2d(right, bottom), cv::Point2d(left, bottom)};
  cv::Rect2d best;
  double least = std::numeric_limits<double>::infinity();
  for (const cv::Point2d& corner : corners) {
    const cv::Rect2d candidate(corner, box);
    const double margin = style.marker_r;  // a marker just outside the box still touches it
    const double hidden = coverage(cv::Rect2d(candidate.x - margin, candidate.y - margin, candidate.width + 2 * margin,
                                              candidate.height + 2 * margin),
                                   series);
    if (hidden < least) {
      least = hidden;
      best = candidate;
    }
  }
  return best;
}

void drawLegend(cv::Mat& image, const LinePlot& plot, const PlotFrame& frame, const Style& style,
                const std::vector<std::vector<cv::Point2d>>& series) {
  std::vector<LegendEntry> entries;
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    if (!plot.series[i].label.empty()) entries.push_back({i, plot.series[i].label});
  }
  if (entries.empty()) return;

  const Font font = style.fonts.tick;
  const double s = frame.fontScale();
  const double sample = 30 * s, pad = 8 * s, gap = 8 * s;
  const double row = std::max<double>(measure("Ag", font).height, 2 * style.marker_r) + 8 * s;
  int widest = 0;
  for (const LegendEntry& e : entries) widest = std::max(widest, measure(e.label, font).width);
  const cv::Size2d box(2 * pad + sample + gap + widest, 2 * pad + row * entries.size() - 4 * s);

  const cv::Rect2d at = placeLegend(box, frame, style, series);
  cv::rectangle(image, cv::Rect(cvRound(at.x), cvRound(at.y), cvRound(at.width), cvRound(at.height)), kWhite,
                cv::FILLED);
  cv::rectangle(image, cv::Rect(cvRound(at.x), cvRound(at.y), cvRound(at.width), cvRound(at.height)), kLegendEdge, 1);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const double mid_y = at.y + pad + row * k + (row - 4 * s) / 2;
    const double x0 = at.x + pad;
    const cv::Scalar colour = seriesColour(entries[k].series);
    drawLine(image, {x0, mid_y}, {x0 + sample, mid_y}, colour, style.line_thickness);
    drawMarker(image, {x0 + sample / 2, mid_y}, entries[k].series, style.marker_r, colour);
    drawText(image, entries[k].label, {x0 + sample + gap, mid_y}, {0.0, 0.5}, font, kInk);
  }
}

// Title centred over the plot area (shrunk if it would not fit), the y label horizontally above
// the y axis (OpenCV cannot rotate text), the x label centred below the tick labels.
void drawTitles(cv::Mat& image, const LinePlot& plot, const PlotFrame& frame, const Style& style) {
  const cv::Rect a = frame.area();
  const Spacing& sp = style.sp;
  if (!plot.title.empty()) {
    Font font = style.fonts.title;
    const int room = image.cols - 2 * sp.pad;
    const int wide = measure(plot.title, font).width;
    if (wide > room) font.scale *= double(room) / wide;
    const double centre = std::clamp(a.x + a.width / 2.0, sp.pad + std::min(wide, room) / 2.0,
                                     image.cols - sp.pad - std::min(wide, room) / 2.0);
    drawText(image, plot.title, {centre, double(sp.pad)}, {0.5, 0.0}, font, kInk);
  }
  const int tick_h = TickLabel{"10", "-8"}.size(style.fonts).height;
  if (!plot.y_label.empty()) {
    drawText(image, plot.y_label, {double(sp.pad), double(a.y - tick_h / 2 - 2 * sp.gap)}, {0.0, 1.0},
             style.fonts.label, kInk);
  }
  if (!plot.x_label.empty()) {
    const double y = a.br().y + sp.tick + sp.gap + tick_h + 2 * sp.gap;
    drawText(image, plot.x_label, {a.x + a.width / 2.0, y}, {0.5, 0.0}, style.fonts.label, kInk);
  }
}

}  // namespace

cv::Mat renderLinePlot(const LinePlot& plot) {
  const PlotFrame frame(plot);
  const Style style(frame.fontScale());
  cv::Mat image(plot.height, plot.width, CV_8UC3, kWhite);
  const std::vector<std::vector<cv::Point2d>> series = pixelSeries(plot, frame);
  drawGrid(image, frame);
  drawAxes(image, frame, style);
  drawSeries(image, series, style);
  drawLegend(image, plot, frame, style, series);
  drawTitles(image, plot, frame, style);
  return image;
}

// Encoded in memory and written by us, so that the file is PNG whatever its name ends with.
void writeLinePlot(const std::string& path, const LinePlot& plot) {
  const std::string png = io::encodePng(renderLinePlot(plot));
  if (png.empty()) throw core::Error("cannot encode the plot for '" + path + "'");
  std::ofstream out(path, std::ios::binary);
  out.write(png.data(), static_cast<std::streamsize>(png.size()));
  out.close();
  if (!out) throw core::Error("cannot write the plot '" + path + "'");
}

}  // namespace binpick::bench
