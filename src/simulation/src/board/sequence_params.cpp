// CalibrationSequenceParams::validate: its own fields, then every nested struct's, each error
// prefixed with the member it came from.
#include <cmath>
#include <functional>

#include "binpick/io/error.hpp"
#include "binpick/simulation/calibration_sequence.hpp"

namespace binpick::sim {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  requireField(ok, "CalibrationSequenceParams", field, rule, value);
}

void nested(const char* member, const std::function<void()>& validate) {
  try {
    validate();
  } catch (const Error& e) {
    throw Error(std::string("CalibrationSequenceParams.") + member + ": " + e.what());
  }
}

bool finite(double v) { return std::isfinite(v); }

// The farthest a point of the board can be from the camera: its centre's distance plus the
// half diagonal of its outline (and its thickness).
double farthestBoardPoint(const CalibrationSequenceParams& p) {
  const double x = p.board.squares_x * p.board.square_size + 2.0 * p.board.margin;
  const double y = p.board.squares_y * p.board.square_size + 2.0 * p.board.margin;
  return p.poses.max_distance + 0.5 * std::hypot(x, y) + p.board.thickness;
}

}  // namespace

void CalibrationSequenceParams::validate() const {
  nested("board", [&] { board.validate(); });
  nested("poses", [&] { poses.validate(); });
  nested("rig", [&] { rig.validate(); });
  nested("pattern_set", [&] { pattern_set.validate(); });
  nested("photometry", [&] { photometry.validate(); });
  nested("geometry", [&] { geometry.validate(); });
  require(pattern_set.projector_width == rig.projector.width, "pattern_set.projector_width",
          "the rig projector's width", pattern_set.projector_width);
  require(pattern_set.projector_height == rig.projector.height, "pattern_set.projector_height",
          "the rig projector's height", pattern_set.projector_height);
  require(finite(texel_size) && texel_size > 0.0, "texel_size", "positive", texel_size);
  require(pixel_samples >= 1 && pixel_samples <= 16, "pixel_samples", "in [1, 16]", pixel_samples);
  require(finite(background_distance) &&
              (background_distance == 0.0 || background_distance > farthestBoardPoint(*this)),
          "background_distance", "0 (no wall) or beyond the farthest board point",
          background_distance);
  require(finite(background_albedo) && background_albedo >= 0.0 && background_albedo <= 1.0,
          "background_albedo", "in [0, 1]", background_albedo);
  require(finite(exposure_us) && exposure_us > 0.0, "exposure_us", "positive", exposure_us);
  require(finite(max_white_counts) && max_white_counts >= 0.0, "max_white_counts", ">= 0 (0: off)",
          max_white_counts);
}

}  // namespace binpick::sim
