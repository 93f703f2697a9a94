// PhotometryParams::validate: every field checked, the message names the first bad one.
#include <cmath>

#include "binpick/io/error.hpp"
#include "binpick/simulation/pattern_renderer.hpp"

namespace binpick::sim {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  requireField(ok, "PhotometryParams", field, rule, value);
}

bool nonNegative(double v) { return std::isfinite(v) && v >= 0.0; }
bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void PhotometryParams::validate() const {
  require(nonNegative(projector_white), "projector_white", ">= 0", projector_white);
  require(positive(reference_distance), "reference_distance", "positive", reference_distance);
  require(nonNegative(projector_black_level) && projector_black_level < 1.0,
          "projector_black_level", "in [0, 1)", projector_black_level);
  require(nonNegative(ambient), "ambient", ">= 0", ambient);
  require(nonNegative(global_light) && global_light <= 1.0, "global_light", "in [0, 1]",
          global_light);
  require(nonNegative(specular), "specular", ">= 0", specular);
  require(positive(shininess), "shininess", "positive", shininess);
  require(positive(focus_distance), "focus_distance", "positive", focus_distance);
  require(nonNegative(defocus_per_dioptre), "defocus_per_dioptre", ">= 0", defocus_per_dioptre);
  require(nonNegative(min_blur_sigma), "min_blur_sigma", ">= 0", min_blur_sigma);
  require(nonNegative(read_noise), "read_noise", ">= 0", read_noise);
  require(nonNegative(shot_noise_gain), "shot_noise_gain", ">= 0", shot_noise_gain);
  require(bit_depth == 8 || bit_depth == 16, "bit_depth", "8 or 16", bit_depth);
  require(threads >= 0, "threads", ">= 0", threads);
}

}  // namespace binpick::sim
