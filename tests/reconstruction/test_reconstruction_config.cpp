// Reconstruction settings from the `reconstruction:` section of a YAML settings file.
#include "binpick/reconstruction/reconstruction_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "binpick/core/error.hpp"
#include "thrown_message.hpp"

namespace binpick::reconstruction {
namespace {

std::string parseError(const std::string& text) {
  return binpick::test::thrownMessage([&] { parseReconstructionParams(text, "cell.yaml"); });
}

TEST(ReconstructionConfig, ShippedDefaultsFileMatchesTheCodeDefaults) {
  const ReconstructionParams shipped = loadReconstructionParams(BINPICK_SOURCE_DIR "/config/reconstruction.yaml");
  const ReconstructionParams defaults;
  const DecodeParams& d = defaults.decode;
  const DecodeParams& s = shipped.decode;
  EXPECT_EQ(s.threads, d.threads);
  EXPECT_EQ(s.min_contrast, d.min_contrast);
  EXPECT_EQ(s.min_direct, d.min_direct);
  EXPECT_EQ(s.projector_black_level, d.projector_black_level);
  EXPECT_EQ(s.separation_min_stripe, d.separation_min_stripe);
  EXPECT_EQ(s.separation_max_stripe, d.separation_max_stripe);
  EXPECT_EQ(s.min_bit_difference, d.min_bit_difference);
  EXPECT_EQ(s.bit_margin, d.bit_margin);
  EXPECT_EQ(s.bit_noise_sigmas, d.bit_noise_sigmas);
  EXPECT_EQ(s.keep_column_without_row, d.keep_column_without_row);
  EXPECT_EQ(s.max_code_run_without_phase, d.max_code_run_without_phase);
  EXPECT_EQ(s.max_code_run_with_phase, d.max_code_run_with_phase);
  EXPECT_EQ(s.min_phase_amplitude, d.min_phase_amplitude);
  EXPECT_EQ(s.max_phase_gray_disagreement, d.max_phase_gray_disagreement);
  EXPECT_EQ(s.max_saturated_fraction, d.max_saturated_fraction);
  EXPECT_EQ(s.max_pair_sum_error, d.max_pair_sum_error);
  EXPECT_EQ(s.min_unwrap_neighbours, d.min_unwrap_neighbours);
  EXPECT_EQ(shipped.triangulation.max_epipolar_error, defaults.triangulation.max_epipolar_error);
  EXPECT_EQ(shipped.triangulation.threads, defaults.triangulation.threads);
  EXPECT_EQ(shipped.triangulation.column_when_row_inconsistent, defaults.triangulation.column_when_row_inconsistent);
  EXPECT_EQ(shipped.filter.min_depth, defaults.filter.min_depth);
  EXPECT_EQ(shipped.filter.max_depth, defaults.filter.max_depth);
  EXPECT_TRUE(shipped.filter.crop.isEmpty());
  EXPECT_EQ(shipped.filter.speckle_max_step, defaults.filter.speckle_max_step);
  EXPECT_EQ(shipped.filter.speckle_min_pixels, defaults.filter.speckle_min_pixels);
  EXPECT_EQ(shipped.filter.median_reach, defaults.filter.median_reach);
  EXPECT_EQ(shipped.filter.median_max_pull, defaults.filter.median_max_pull);
  EXPECT_EQ(shipped.filter.median_max_intensity, defaults.filter.median_max_intensity);
  EXPECT_EQ(shipped.filter.median_min_noise, defaults.filter.median_min_noise);
  EXPECT_EQ(shipped.filter.median_lone_max_noise, defaults.filter.median_lone_max_noise);
  EXPECT_EQ(shipped.filter.edge_max_jump, defaults.filter.edge_max_jump);
  EXPECT_EQ(shipped.filter.edge_min_support, defaults.filter.edge_min_support);
  EXPECT_EQ(shipped.filter.edge_min_neighbours, defaults.filter.edge_min_neighbours);
  EXPECT_EQ(shipped.filter.edge_side_reach, defaults.filter.edge_side_reach);
  EXPECT_EQ(shipped.filter.edge_side_min_contrast, defaults.filter.edge_side_min_contrast);
}

TEST(ReconstructionConfig, ReadsTheHarshLightSettingsAndNamesBadOnes) {
  const ReconstructionParams p = parseReconstructionParams(
      "reconstruction:\n"
      "  decode: {bit_noise_sigmas: 2.5, keep_column_without_row: false, min_unwrap_neighbours: 6}\n"
      "  triangulation: {column_when_row_inconsistent: false}\n"
      "  filter: {edge_max_jump: 6, edge_min_support: 2, edge_min_neighbours: 4, edge_side_reach: 2,\n"
      "           edge_side_min_contrast: 0.05}\n",
      "cell.yaml");
  EXPECT_EQ(p.decode.bit_noise_sigmas, 2.5);
  EXPECT_FALSE(p.decode.keep_column_without_row);
  EXPECT_EQ(p.decode.min_unwrap_neighbours, 6);
  EXPECT_FALSE(p.triangulation.column_when_row_inconsistent);
  EXPECT_EQ(p.filter.edge_max_jump, 6.0);
  EXPECT_EQ(p.filter.edge_min_support, 2);
  EXPECT_EQ(p.filter.edge_min_neighbours, 4);
  EXPECT_EQ(p.filter.edge_side_reach, 2);
  EXPECT_EQ(p.filter.edge_side_min_contrast, 0.05);
  EXPECT_NE(parseError("reconstruction: {decode: {bit_noise_sigmas: -1}}").find("bit_noise_sigmas"), std::string::npos);
  EXPECT_NE(parseError("reconstruction: {filter: {edge_min_support: 0}}").find("edge_min_support"), std::string::npos);
  EXPECT_NE(parseError("reconstruction: {decode: {min_unwrap_neighbours: 9}}").find("min_unwrap_neighbours"),
            std::string::npos);
  EXPECT_NE(parseError("reconstruction: {filter: {median_min_noise: -1}}").find("median_min_noise"), std::string::npos);
  EXPECT_NE(parseError("reconstruction: {filter: {median_lone_max_noise: -1}}").find("median_lone_max_noise"),
            std::string::npos);
  EXPECT_NE(parseError("reconstruction: {filter: {edge_side_reach: -2}}").find("edge_side_reach"), std::string::npos);
  EXPECT_NE(parseError("reconstruction: {decode: {keep_column_without_row: 3}}")
                .find("reconstruction.decode.keep_column_without_row has the wrong type"),
            std::string::npos);
}

TEST(ReconstructionConfig, ReadsOverridesAndLeavesEstimationSectionsAlone) {
  const ReconstructionParams p = parseReconstructionParams(
      "model: {sampling_ratio: 0.05}\n"
      "detection: {threads: 1}\n"
      "reconstruction:\n"
      "  threads: 2\n"
      "  decode: {bit_margin: 0.2}\n"
      "  filter: {max_depth: 1.2, crop: {min: [-0.2, -0.15, 0.5], max: [0.2, 0.15, 0.95]}}\n",
      "cell.yaml");
  EXPECT_EQ(p.decode.threads, 2);
  EXPECT_EQ(p.triangulation.threads, 2);
  EXPECT_EQ(p.filter.threads, 2);
  EXPECT_EQ(p.decode.bit_margin, 0.2);
  EXPECT_EQ(p.filter.max_depth, 1.2);
  EXPECT_TRUE(p.filter.crop.contains(Eigen::Vector3d(0.0, 0.0, 0.9)));
  EXPECT_FALSE(p.filter.crop.contains(Eigen::Vector3d(0.0, 0.0, 1.0)));
}

TEST(ReconstructionConfig, ErrorsNameTheFileAndTheKey) {
  EXPECT_EQ(parseError("reconstruction: {decode: {bit_margn: 0.2}}"),
            "cell.yaml: reconstruction.decode.bit_margn is not a known setting");
  EXPECT_EQ(parseError("reconstruction: {filter: {min_depth: near}}"),
            "cell.yaml: reconstruction.filter.min_depth has the wrong type");
  EXPECT_EQ(parseError("reconstruction: {filter: {crop: {min: [0, 0], max: [1, 1, 1]}}}"),
            "cell.yaml: reconstruction.filter.crop.min needs three numbers");
  EXPECT_NE(parseError("reconstruction: {decode: {bit_margin: 2}}").find("cell.yaml: decode params.bit_margin"),
            std::string::npos);
  EXPECT_NE(parseError("reconstruction: [1, 2]").find("must be a mapping"), std::string::npos);
  EXPECT_NE(parseError("reconstruction: {decode: {").find("not valid YAML"), std::string::npos);
  EXPECT_EQ(parseError("recon: {}"), "cell.yaml: recon is not a known setting");
}

}  // namespace
}  // namespace binpick::reconstruction
