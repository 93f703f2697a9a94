// Putting any rig's capture into the decoder's layout (capture_completion.hpp).
#include "capture_completion.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "binpick/core/error.hpp"
#include "binpick/reconstruction/pattern_set.hpp"

namespace binpick::reconstruction::detail {
namespace {

// The set in codes: what the Gray code and the phase count.
io::PatternSetSpec inCodes(const io::PatternSetSpec& spec) {
  io::PatternSetSpec codes = spec;
  codes.projector_width = spec.columnCodes();
  codes.projector_height = spec.rowCodes();
  codes.phase_period = spec.phase_period / spec.code_step;
  codes.gray_unit = spec.grayUnitCodes() > 1 ? spec.grayUnitCodes() : 0;
  codes.code_step = 1;
  return codes;
}

bool partOfSet(const Pattern& pattern, const std::vector<Pattern>& sequence) {
  for (const Pattern& p : sequence) {
    if (p.kind == pattern.kind && p.axis == pattern.axis && p.index == pattern.index) return true;
  }
  return false;
}

// Image index per pattern name, every name checked against the set.
std::map<std::string, int> imagesByName(const io::CaptureMetadata& metadata, const std::vector<Pattern>& sequence) {
  std::map<std::string, int> images;
  for (std::size_t i = 0; i < metadata.patterns.size(); ++i) {
    const std::string& name = metadata.patterns[i];
    const std::string image = "capture: image " + std::to_string(i) + " ('" + name + "')";
    const std::optional<Pattern> pattern = patternFromName(name);
    if (!pattern) throw core::Error(image + " is no pattern name (white, black, gray_col_03[_inv], phase_row_1, ...)");
    if (!partOfSet(*pattern, sequence)) {
      throw core::Error(image + " is not part of the pattern set (" + std::to_string(sequence.size()) +
                        " patterns in codes: its axes, Gray bits and phase steps)");
    }
    if (!images.emplace(name, static_cast<int>(i)).second) {
      throw core::Error(image + " is listed twice (first as image " + std::to_string(images.at(name)) + ")");
    }
  }
  return images;
}

// What messages call the image of `name`: its file ("012_gray_col_03" for a capture in memory),
// or that it was made up.
std::string imageFileOf(const io::CaptureMetadata& metadata, const std::string& name) {
  const auto listed = std::find(metadata.patterns.begin(), metadata.patterns.end(), name);
  if (listed == metadata.patterns.end()) return "made up: " + name;
  const auto index = static_cast<std::size_t>(listed - metadata.patterns.begin());
  if (index < metadata.images.size()) return metadata.images[index];
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%03zu_", index);
  return prefix + name;
}

void checkImages(const io::Capture& capture) {
  const io::CaptureMetadata& metadata = capture.metadata;
  if (capture.images.size() != metadata.patterns.size()) {
    throw core::Error("capture: " + std::to_string(capture.images.size()) + " images for " +
                      std::to_string(metadata.patterns.size()) + " patterns");
  }
  if (metadata.bit_depth != 8 && metadata.bit_depth != 16) {
    throw core::Error("capture: bit depth must be 8 or 16 (got " + std::to_string(metadata.bit_depth) + ")");
  }
  const int type = metadata.bit_depth == 8 ? CV_8UC1 : CV_16UC1;
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    const cv::Mat& image = capture.images[i];
    const std::string name = "capture: image " + std::to_string(i) + " (" + metadata.patterns[i] + ")";
    if (image.cols != metadata.image_width || image.rows != metadata.image_height) {
      throw core::Error(name + " is " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                        ", the metadata says " + std::to_string(metadata.image_width) + "x" +
                        std::to_string(metadata.image_height));
    }
    if (image.type() != type) {
      throw core::Error(name + " is not a single-channel " + std::to_string(metadata.bit_depth) + "-bit image");
    }
  }
  if (metadata.image_width <= 0 || metadata.image_height <= 0) throw core::Error("capture: empty images");
}

class Completion {
 public:
  Completion(const io::Capture& capture, const std::vector<Pattern>& sequence)
      : capture_(capture), images_(imagesByName(capture.metadata, sequence)), type_(capture.images.front().type()) {}
  // The images are checked (checkImages) before a Completion is made.

  std::optional<cv::Mat> find(const Pattern& pattern) const {
    const auto found = images_.find(pattern.name());
    if (found == images_.end()) return std::nullopt;
    return capture_.images[static_cast<std::size_t>(found->second)];
  }

  // White and black as shown, or made up; `made_up` names them when they are.
  std::pair<cv::Mat, cv::Mat> whiteAndBlack(const io::PatternSetSpec& codes, std::vector<std::string>& made_up) const {
    const std::optional<cv::Mat> white = find({PatternKind::White});
    const std::optional<cv::Mat> black = find({PatternKind::Black});
    if (white && black) return {*white, *black};
    if (white || black)
      throw core::Error("capture: " + std::string(white ? "white without black" : "black without white"));
    made_up.insert(made_up.end(), {"white", "black"});
    const std::optional<cv::Mat> bit = find({PatternKind::GrayBit, PatternAxis::Columns, 0});
    const std::optional<cv::Mat> inverse = find({PatternKind::GrayBitInverse, PatternAxis::Columns, 0});
    if (bit && inverse) return {cv::max(*bit, *inverse), cv::min(*bit, *inverse)};
    if (codes.phase_steps > 0) return phaseEnvelope(codes.phase_steps);
    throw core::Error(
        "capture: no white and black images, and neither the inverse of the coarsest column bit nor phase images "
        "to make them up from");
  }

  // mean +- amplitude of the column phase steps: the brightest and darkest a pixel gets.
  std::pair<cv::Mat, cv::Mat> phaseEnvelope(int steps) const {
    cv::Mat sum, cosine, sine;
    for (int k = 0; k < steps; ++k) {
      const std::optional<cv::Mat> image = find({PatternKind::PhaseStep, PatternAxis::Columns, k});
      if (!image) throw core::Error("capture: phase_col_" + std::to_string(k) + " is missing");
      cv::Mat value;
      image->convertTo(value, CV_32F);
      const double angle = 2.0 * M_PI * k / steps;
      accumulate(sum, value, 1.0);
      accumulate(cosine, value, std::cos(angle));
      accumulate(sine, value, std::sin(angle));
    }
    cv::Mat amplitude;
    cv::magnitude(cosine, sine, amplitude);
    const cv::Mat mean = sum / steps;
    amplitude *= 2.0 / steps;
    return {toCaptureType(mean + amplitude), toCaptureType(mean - amplitude)};
  }

  cv::Mat inverseOf(const cv::Mat& bit, const cv::Mat& white, const cv::Mat& black) const {
    cv::Mat sum;
    cv::add(white, black, sum, cv::noArray(), CV_32S);
    cv::subtract(sum, bit, sum, cv::noArray(), CV_32S);
    return toCaptureType(sum);
  }

 private:
  static void accumulate(cv::Mat& total, const cv::Mat& value, double weight) {
    if (total.empty()) total = cv::Mat::zeros(value.size(), CV_32F);
    cv::scaleAdd(value, weight, total, total);
  }
  cv::Mat toCaptureType(const cv::Mat& values) const {
    cv::Mat image;
    values.convertTo(image, type_);  // saturating
    return image;
  }

  const io::Capture& capture_;
  std::map<std::string, int> images_;
  int type_;
};

}  // namespace

CompleteCapture completeCapture(const io::Capture& capture) {
  const io::CaptureMetadata& metadata = capture.metadata;
  metadata.pattern_set.validate();
  if (capture.images.empty()) throw core::Error("capture: no images");
  checkImages(capture);
  const io::PatternSetSpec codes = inCodes(metadata.pattern_set);
  const std::vector<Pattern> sequence = patternSequence(codes);
  const Completion completion(capture, sequence);

  CompleteCapture complete;
  complete.code_step = metadata.pattern_set.code_step;
  io::Capture& out = complete.capture;
  out.metadata = metadata;
  out.metadata.pattern_set = codes;
  out.metadata.patterns.clear();
  out.metadata.images.clear();
  const auto [white, black] = completion.whiteAndBlack(codes, complete.made_up);
  for (const Pattern& pattern : sequence) {
    std::optional<cv::Mat> image = pattern.kind == PatternKind::White   ? white
                                   : pattern.kind == PatternKind::Black ? black
                                                                        : completion.find(pattern);
    if (!image && pattern.kind == PatternKind::GrayBitInverse) {
      const std::optional<cv::Mat> bit = completion.find({PatternKind::GrayBit, pattern.axis, pattern.index});
      if (bit) image = completion.inverseOf(*bit, white, black);
      if (image) complete.made_up.push_back(pattern.name());
    }
    if (!image) throw core::Error("capture: " + pattern.name() + " is missing (the pattern set's Gray code and phase)");
    out.images.push_back(*image);
    out.metadata.patterns.push_back(pattern.name());
    out.metadata.images.push_back(imageFileOf(metadata, pattern.name()));
  }
  return complete;
}

}  // namespace binpick::reconstruction::detail
