#include "binpick/estimation/result_json.hpp"

#include "binpick/core/json_fields.hpp"

namespace binpick::estimation {
nlohmann::json toJson(const DetectionResult& result) {
  nlohmann::json detections = nlohmann::json::array();
  for (const Detection& d : result.detections) {
    detections.push_back({{"pose", core::poseRows(d.T_camera_model)},
                          {"score", d.score},
                          {"coverage", d.coverage},
                          {"icp_rmse", d.icp_rmse},
                          {"seen_through", d.seen_through},
                          {"twin_margin", d.twin_margin},
                          {"sure", d.sure},
                          {"votes", d.votes}});
  }
  const StageTimings& t = result.timing_ms;
  return {
      {"detections", detections},
      {"timing_ms",
       {{"prepare_scene", t.prepare_scene},
        {"voting", t.voting},
        {"verification", t.verification},
        {"selection", t.selection},
        {"icp", t.icp},
        {"total", t.total}}},
      {"counts",
       {{"scene_points", result.scene_points},
        {"scene_points_without_normal", result.scene_points_without_normal},
        {"candidates", result.candidates},
        {"refreshes", result.refreshes},
        {"seen_through_rejected", result.seen_through_rejected}}}};
}

nlohmann::json poseJson(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d t = pose.translation();
  return {{"translation", {t.x(), t.y(), t.z()}}, {"quaternion_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

}  // namespace binpick::estimation
