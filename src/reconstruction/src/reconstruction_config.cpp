// The `reconstruction:` section of a settings file.
#include "binpick/reconstruction/reconstruction_config.hpp"

#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"
#include "binpick/core/yaml_section.hpp"

namespace binpick::reconstruction {
namespace {

void readDecode(core::YamlSection s, DecodeParams& p) {
  s.read("min_contrast", p.min_contrast);
  s.read("min_direct", p.min_direct);
  s.read("projector_black_level", p.projector_black_level);
  s.read("separation_min_stripe", p.separation_min_stripe);
  s.read("separation_max_stripe", p.separation_max_stripe);
  s.read("min_bit_difference", p.min_bit_difference);
  s.read("bit_margin", p.bit_margin);
  s.read("bit_noise_sigmas", p.bit_noise_sigmas);
  s.read("max_code_run_without_phase", p.max_code_run_without_phase);
  s.read("max_code_run_with_phase", p.max_code_run_with_phase);
  s.read("min_phase_amplitude", p.min_phase_amplitude);
  s.read("max_phase_gray_disagreement", p.max_phase_gray_disagreement);
  s.read("keep_column_without_row", p.keep_column_without_row);
  s.read("min_unwrap_neighbours", p.min_unwrap_neighbours);
  s.read("stripe_reach", p.stripe_reach);
  s.read("max_code_run_along_stripe", p.max_code_run_along_stripe);
  s.read("max_saturated_fraction", p.max_saturated_fraction);
  s.read("max_pair_sum_error", p.max_pair_sum_error);
  s.finish();
}

void readCrop(core::YamlSection s, CloudFilterParams& p) {
  if (s.isNull()) return;
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::nan(""));
  Eigen::Vector3d max = min;
  s.readVector3("min", min);
  s.readVector3("max", max);
  if (!min.allFinite()) s.fail("min", "needs three numbers");
  if (!max.allFinite()) s.fail("max", "needs three numbers");
  if ((min.array() > max.array()).any()) s.fail("min", "must not exceed max on any axis");
  s.finish();
  p.crop = Eigen::AlignedBox3d(min, max);
}

void readFilter(core::YamlSection s, CloudFilterParams& p) {
  s.read("min_depth", p.min_depth);
  s.read("max_depth", p.max_depth);
  readCrop(s.child("crop"), p);
  s.read("speckle_max_step", p.speckle_max_step);
  s.read("speckle_min_pixels", p.speckle_min_pixels);
  s.read("min_step_in_codes", p.min_step_in_codes);
  s.read("median_reach", p.median_reach);
  s.read("median_max_pull", p.median_max_pull);
  s.read("median_max_intensity", p.median_max_intensity);
  s.read("median_min_noise", p.median_min_noise);
  s.read("median_lone_max_noise", p.median_lone_max_noise);
  s.read("edge_max_jump", p.edge_max_jump);
  s.read("edge_min_neighbours", p.edge_min_neighbours);
  s.read("edge_min_support", p.edge_min_support);
  s.read("edge_side_reach", p.edge_side_reach);
  s.read("edge_side_min_contrast", p.edge_side_min_contrast);
  s.finish();
}

void readReconstruction(core::YamlSection s, ReconstructionParams& p) {
  int threads = 0;
  s.read("threads", threads);
  p.setThreads(threads);
  readDecode(s.child("decode"), p.decode);
  core::YamlSection triangulation = s.child("triangulation");
  triangulation.read("max_epipolar_error", p.triangulation.max_epipolar_error);
  triangulation.read("column_when_row_inconsistent", p.triangulation.column_when_row_inconsistent);
  triangulation.read("max_calibration_residual", p.triangulation.max_calibration_residual);
  triangulation.finish();
  readFilter(s.child("filter"), p.filter);
  s.finish();
}

}  // namespace

ReconstructionParams parseReconstructionParams(const std::string& yaml_text, const std::string& origin) {
  core::YamlSection top(core::parseYaml(yaml_text, origin), "", origin);
  ReconstructionParams params;
  readReconstruction(top.child("reconstruction"), params);
  top.skip("model");  // estimation's sections of the same file
  top.skip("detection");
  top.finish();
  core::validateSettings(origin, [&] { params.validate(); });
  return params;
}

ReconstructionParams readReconstructionSection(core::YamlSection section, const std::string& origin) {
  ReconstructionParams params;
  readReconstruction(std::move(section), params);
  core::validateSettings(origin, [&] { params.validate(); });
  return params;
}

ReconstructionParams loadReconstructionParams(const std::string& path) {
  return parseReconstructionParams(core::readConfigFile(path), path);
}

}  // namespace binpick::reconstruction
