#pragma once
// Scene preparation (sections II and III-A): the full-resolution cloud in the camera frame (camera
// at the origin looking along +z) is subsampled at the model's step, and each kept point gets a
// normal fitted to its full-resolution neighbours, turned towards the camera. The neighbours are
// those within the model's normal radius, or within 1.5 of the cloud's typical point spacings (at
// most 2 steps) where the cloud is sparser than that: a decimated cloud would otherwise leave
// every point alone in its radius, and the detector would find nothing.
// Free function, no shared state: thread-safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "binpick/estimation/detector_params.hpp"
#include "binpick/estimation/model.hpp"
#include "binpick/io/point_cloud.hpp"
#include "line_of_sight.hpp"

namespace binpick::estimation {

struct PreparedScene {
  std::vector<Eigen::Vector3f> points;   // subsampled scene, camera frame
  std::vector<Eigen::Vector3f> normals;  // unit, towards the camera
  std::vector<uint32_t> source_index;    // index of each point in the input cloud
  std::size_t valid_input_points = 0;    // finite points inside the crop box
  std::size_t without_normal = 0;        // subsampled points dropped: too few neighbours for a normal
  LineOfSightMap line_of_sight;          // every finite input point, cropped or not
  std::size_t size() const { return points.size(); }
};

// Throws core::Error when the cloud is malformed (non-finite points in an unorganized cloud,
// normals of the wrong count); an empty or fully cropped cloud gives an empty scene.
// `threads`: 0 = all hardware threads.
PreparedScene prepareScene(const io::PointCloud& cloud, const PreparedModel& model, const SceneParams& params,
                           int threads = 0);

}  // namespace binpick::estimation
