// BoardSpec: its geometry is a calibration::BoardLayout; the rest is how it renders.
#include <cmath>

#include "binpick/core/error.hpp"
#include "binpick/simulation/calibration_board.hpp"

namespace binpick::simulation {
namespace {

template <typename T>
void require(bool ok, const char* field, const char* rule, const T& value) {
  core::requireField(ok, "BoardSpec", field, rule, value);
}

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

calibration::BoardLayout BoardSpec::layout() const {
  return {type, squares_x, squares_y, square_size, marker_size, dictionary};
}

void BoardSpec::validate() const {
  layout().validate();
  require(std::isfinite(margin) && margin >= 0.0, "margin", ">= 0", margin);
  require(positive(thickness), "thickness", "positive", thickness);
  require(std::isfinite(white_albedo) && white_albedo > 0.0 && white_albedo <= 1.0, "white_albedo", "in (0, 1]",
          white_albedo);
  require(std::isfinite(black_albedo) && black_albedo >= 0.0 && black_albedo < white_albedo, "black_albedo",
          "in [0, white_albedo)", black_albedo);
}

}  // namespace binpick::simulation
