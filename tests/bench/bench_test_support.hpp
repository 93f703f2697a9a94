#pragma once
// Checks every benchmark method must pass, whatever library is behind it.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "pose_method.hpp"

namespace binpick::bench::testing {

// An organized cloud of NaN pixels and an empty cloud give no poses, and no exception.
inline void expectNoPosesWithoutPoints(const PoseMethod& method, const estimation::CropBox& crop) {
  io::PointCloud nan_cloud;
  nan_cloud.width = 64;
  nan_cloud.height = 48;
  nan_cloud.points.assign(64 * 48, Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  std::vector<Eigen::Isometry3f> poses;
  EXPECT_NO_THROW(poses = method.detect(MethodInput{&nan_cloud, crop}));
  EXPECT_TRUE(poses.empty());

  const io::PointCloud empty_cloud;
  EXPECT_NO_THROW(poses = method.detect(MethodInput{&empty_cloud, crop}));
  EXPECT_TRUE(poses.empty());
}

}  // namespace binpick::bench::testing
