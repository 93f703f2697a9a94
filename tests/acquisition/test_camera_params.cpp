// Camera settings are checked before any camera is touched.
#include <gtest/gtest.h>

#include <string>

#include "binpick/acquisition/camera.hpp"
#include "binpick/core/error.hpp"
#include "thrown_message.hpp"

namespace binpick::acquisition {
namespace {

std::string validationError(const CameraParams& params) {
  return binpick::test::thrownMessage([&] { params.validate(); });
}

TEST(CameraParams, DefaultsAreValid) { EXPECT_EQ(validationError(CameraParams{}), ""); }

TEST(CameraParams, RefusesNonsenseNamingTheField) {
  CameraParams format;
  format.pixel_format = "RGB8";
  EXPECT_NE(validationError(format).find("camera params.pixel_format"), std::string::npos);
  CameraParams exposure;
  exposure.exposure_us = -1.0;
  EXPECT_NE(validationError(exposure).find("camera params.exposure_us"), std::string::npos);
  CameraParams buffers;
  buffers.buffers = 1;
  EXPECT_NE(validationError(buffers).find("camera params.buffers"), std::string::npos);
  CameraParams packets;
  packets.packet_size = 100;
  EXPECT_NE(validationError(packets).find("camera params.packet_size"), std::string::npos);
}

TEST(FrameStatus, HasAName) {
  EXPECT_STREQ(frameStatusName(FrameStatus::Incomplete), "incomplete");
  EXPECT_STREQ(frameStatusName(FrameStatus::ConnectionLost), "connection lost");
}

}  // namespace
}  // namespace binpick::acquisition
