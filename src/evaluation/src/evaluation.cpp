#include "binpick/evaluation/evaluation.hpp"

namespace binpick::evaluation {

estimation::CropBox binInterior(const simulation::PileScene& scene, const simulation::PileParams& params,
                                double floor_margin, double wall_margin) {
  const double top = params.camera_height - 0.1;
  Eigen::Isometry3d T_bin_box = Eigen::Isometry3d::Identity();
  T_bin_box.translation() = Eigen::Vector3d(0.0, 0.0, 0.5 * (floor_margin + top));
  estimation::CropBox box;
  box.T_camera_box = (scene.T_camera_bin * T_bin_box).cast<float>();
  box.half_extents = Eigen::Vector3f(static_cast<float>(0.5 * params.bin_length - wall_margin),
                                     static_cast<float>(0.5 * params.bin_width - wall_margin),
                                     static_cast<float>(0.5 * (top - floor_margin)));
  return box;
}

Score scoreDetections(const std::vector<estimation::Detection>& detections,
                      const std::vector<simulation::ObjectTruth>& truth, const simulation::Symmetry& symmetry,
                      const Thresholds& thresholds, double min_visible) {
  Score score;
  std::vector<bool> claimed(truth.size(), false);
  for (std::size_t d = 0; d < detections.size(); ++d) {
    const Eigen::Isometry3d estimate = detections[d].T_camera_model.cast<double>();
    int match = -1;
    for (std::size_t o = 0; o < truth.size() && match < 0; ++o) {
      const simulation::PoseError e = simulation::poseError(estimate, truth[o].T_camera_object, symmetry);
      if (e.translation <= thresholds.translation && e.rotation_deg <= thresholds.rotation_deg) {
        match = static_cast<int>(o);
      }
    }
    const bool correct = match >= 0 && !claimed[match];
    if (correct) {
      claimed[match] = true;
      ++score.correct;
    } else {
      ++score.wrong;
      if (d < 10) ++score.wrong_in_first_10;
    }
    score.matched_object.push_back(correct ? match : -1);
  }
  for (std::size_t o = 0; o < truth.size(); ++o) {
    if (truth[o].visible_fraction < min_visible) continue;
    ++score.findable;
    if (claimed[o]) ++score.found;
  }
  return score;
}

}  // namespace binpick::evaluation
