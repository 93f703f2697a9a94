// PileParams::validate: every field checked, the message names the first bad one.
#include <cmath>

#include "binpick/io/error.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::sim {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  requireField(ok, "PileParams", field, rule, value);
}

bool positive(double value) { return std::isfinite(value) && value > 0.0; }

constexpr int kMaxObjects = 10000;

}  // namespace

void PileParams::validate() const {
  require(objects >= 0 && objects <= kMaxObjects, "objects", "in [0, 10000]", objects);
  require(positive(bin_length), "bin_length", "positive", bin_length);
  require(positive(bin_width), "bin_width", "positive", bin_width);
  require(positive(bin_wall_height), "bin_wall_height", "positive", bin_wall_height);
  require(std::isfinite(camera_height) && camera_height > bin_wall_height, "camera_height",
          "finite and above the bin walls", camera_height);
  require(std::isfinite(depth_noise) && depth_noise >= 0.0, "depth_noise", ">= 0", depth_noise);
  require(std::isfinite(dropout) && dropout >= 0.0 && dropout < 1.0, "dropout", "in [0, 1)",
          dropout);
  require(std::isfinite(max_view_angle_deg) && max_view_angle_deg > 0.0 &&
              max_view_angle_deg <= 90.0,
          "max_view_angle_deg", "in (0, 90]", max_view_angle_deg);
  require(std::isfinite(part_albedo) && part_albedo >= 0.0 && part_albedo <= 1.0, "part_albedo",
          "in [0, 1]", part_albedo);
  require(std::isfinite(bin_albedo) && bin_albedo >= 0.0 && bin_albedo <= 1.0, "bin_albedo",
          "in [0, 1]", bin_albedo);
  require(threads >= 0, "threads", ">= 0", threads);
  rig.validate();
  physics.validate("PileParams.physics");
}

}  // namespace binpick::sim
