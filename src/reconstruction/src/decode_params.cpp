// DecodeParams::validate.
#include <cmath>

#include "binpick/io/error.hpp"
#include "binpick/reconstruction/decoder.hpp"

namespace binpick::reconstruction {
namespace {

bool nonNegative(double value) { return std::isfinite(value) && value >= 0.0; }

}  // namespace

void DecodeParams::validate() const {
  const std::string owner = "decode params";
  requireField(nonNegative(min_contrast), owner, "min_contrast", "finite and >= 0", min_contrast);
  requireField(nonNegative(min_direct), owner, "min_direct", "finite and >= 0", min_direct);
  requireField(std::isfinite(projector_black_level) && projector_black_level >= 0.0 &&
                   projector_black_level < 0.5,
               owner, "projector_black_level", "in [0, 0.5)", projector_black_level);
  requireField(separation_min_stripe >= 1, owner, "separation_min_stripe", ">= 1", separation_min_stripe);
  requireField(separation_max_stripe >= separation_min_stripe, owner, "separation_max_stripe",
               ">= separation_min_stripe", separation_max_stripe);
  requireField(nonNegative(min_bit_difference), owner, "min_bit_difference", "finite and >= 0",
               min_bit_difference);
  requireField(std::isfinite(bit_margin) && bit_margin >= 0.0 && bit_margin < 1.0, owner, "bit_margin",
               "in [0, 1)", bit_margin);
  requireField(max_code_run_without_phase >= 1 && max_code_run_without_phase <= 64, owner,
               "max_code_run_without_phase", "in [1, 64]", max_code_run_without_phase);
  requireField(max_code_run_with_phase >= 1 && max_code_run_with_phase <= 64, owner,
               "max_code_run_with_phase", "in [1, 64]", max_code_run_with_phase);
  requireField(nonNegative(min_phase_amplitude), owner, "min_phase_amplitude", "finite and >= 0",
               min_phase_amplitude);
  requireField(nonNegative(max_phase_gray_disagreement), owner, "max_phase_gray_disagreement",
               "finite and >= 0", max_phase_gray_disagreement);
  requireField(std::isfinite(max_saturated_fraction) && max_saturated_fraction >= 0.0 &&
                   max_saturated_fraction <= 1.0,
               owner, "max_saturated_fraction", "in [0, 1]", max_saturated_fraction);
  requireField(std::isfinite(max_pair_sum_error) && max_pair_sum_error > 0.0, owner,
               "max_pair_sum_error", "positive", max_pair_sum_error);
  requireField(threads >= 0, owner, "threads", ">= 0", threads);
}

}  // namespace binpick::reconstruction
