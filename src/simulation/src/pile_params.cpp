// PileParams::validate: every field checked, the message names the first bad one.
#include <cmath>
#include <sstream>

#include "binpick/io/error.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::sim {
namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  if (ok) return;
  std::ostringstream message;
  message << "PileParams." << field << " must be " << rule << " (got " << value << ")";
  throw Error(message.str());
}

bool positive(double value) { return std::isfinite(value) && value > 0.0; }

// Guards against an image size that would exhaust memory rather than describe a real sensor.
constexpr int kMaxImageSide = 16384;
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
  require(camera.width > 0 && camera.width <= kMaxImageSide, "camera.width", "in [1, 16384]",
          camera.width);
  require(camera.height > 0 && camera.height <= kMaxImageSide, "camera.height", "in [1, 16384]",
          camera.height);
  require(positive(camera.fx), "camera.fx", "positive", camera.fx);
  require(positive(camera.fy), "camera.fy", "positive", camera.fy);
  require(std::isfinite(camera.cx), "camera.cx", "finite", camera.cx);
  require(std::isfinite(camera.cy), "camera.cy", "finite", camera.cy);
}

}  // namespace binpick::sim
