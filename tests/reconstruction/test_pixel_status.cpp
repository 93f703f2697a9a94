// Pixel status names and counts.
#include "binpick/reconstruction/pixel_status.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::reconstruction {
namespace {

TEST(PixelStatus, EveryStatusHasItsOwnSnakeCaseName) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < kPixelStatusCount; ++i) {
    const std::string name = statusName(static_cast<PixelStatus>(i));
    EXPECT_EQ(name.find_first_not_of("abcdefghijklmnopqrstuvwxyz_"), std::string::npos) << name;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), kPixelStatusCount);
  EXPECT_STREQ(statusName(PixelStatus::Valid), "valid");
  EXPECT_STREQ(statusName(PixelStatus::NoIntersection), "no_intersection");
  EXPECT_STREQ(statusName(PixelStatus::Speckle), "speckle");
}

TEST(PixelStatus, CountsEveryPixelUnderItsStatus) {
  cv::Mat status(3, 4, CV_8UC1, cv::Scalar(static_cast<int>(PixelStatus::Valid)));
  status.at<uint8_t>(0, 1) = static_cast<uint8_t>(PixelStatus::Unlit);
  status.at<uint8_t>(2, 3) = static_cast<uint8_t>(PixelStatus::Unlit);
  status.at<uint8_t>(1, 0) = static_cast<uint8_t>(PixelStatus::Speckle);
  const StatusCounts counts = countStatuses(status);
  EXPECT_EQ(counts[static_cast<std::size_t>(PixelStatus::Valid)], 9u);
  EXPECT_EQ(counts[static_cast<std::size_t>(PixelStatus::Unlit)], 2u);
  EXPECT_EQ(counts[static_cast<std::size_t>(PixelStatus::Speckle)], 1u);
  std::size_t total = 0;
  for (std::size_t count : counts) total += count;
  EXPECT_EQ(total, 12u);
  // A view into a larger image (rows not contiguous) counts only its own pixels.
  EXPECT_EQ(countStatuses(status(cv::Rect(1, 0, 2, 2)))[1], 1u);
}

TEST(PixelStatus, RefusesImagesThatAreNoStatusImages) {
  EXPECT_THROW(countStatuses(cv::Mat(2, 2, CV_16UC1, cv::Scalar(0))), core::Error);
  cv::Mat status(2, 2, CV_8UC1, cv::Scalar(0));
  status.at<uint8_t>(1, 1) = static_cast<uint8_t>(kPixelStatusCount);
  try {
    countStatuses(status);
    ADD_FAILURE() << "accepted a value outside the enum";
  } catch (const core::Error& error) {
    EXPECT_NE(std::string(error.what()).find("1 pixels hold 12, which is no PixelStatus"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace binpick::reconstruction
