// Image files through the codecs' plugin: what is written reads back the same, bad files and bytes
// read as nothing, and a write that fails names the file.
#include "binpick/io/image_file.hpp"

#include <gtest/gtest.h>

#include <string>

#include "io_test_support.hpp"
#include "thrown_message.hpp"

namespace binpick::test {
namespace {

// A gradient that uses the whole range of the type, so that a lost bit or byte order shows.
cv::Mat gradient(int type) {
  cv::Mat image(24, 40, type);
  const double top = CV_MAT_DEPTH(type) == CV_16U ? 65535.0 : 255.0;
  for (int row = 0; row < image.rows; ++row) {
    for (int col = 0; col < image.cols * image.channels(); ++col) {
      const double value = top * (row * image.cols * image.channels() + col) / (image.total() * image.channels() - 1);
      if (CV_MAT_DEPTH(type) == CV_16U) {
        image.ptr<uint16_t>(row)[col] = static_cast<uint16_t>(value);
      } else {
        image.ptr<uint8_t>(row)[col] = static_cast<uint8_t>(value);
      }
    }
  }
  return image;
}

bool sameImage(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

using ImageFiles = IoTest;

TEST_F(ImageFiles, A16BitGreyPngReadsBackBitForBit) {
  const cv::Mat image = gradient(CV_16UC1);
  io::writeImageFile(pathOf("grey16.png"), image);
  EXPECT_TRUE(sameImage(io::readImageFile(pathOf("grey16.png")), image));
}

TEST_F(ImageFiles, EveryFormatAFileNameAsksForIsWrittenAndRead) {
  const cv::Mat image = gradient(CV_8UC3);
  for (const std::string name : {"colour.png", "colour.bmp", "colour.tiff"}) {
    io::writeImageFile(pathOf(name), image);
    EXPECT_TRUE(sameImage(io::readImageFile(pathOf(name)), image)) << name;
  }
}

TEST_F(ImageFiles, AlphaIsKeptAsStoredAndDroppedWhenAsked) {
  io::writeImageFile(pathOf("alpha.png"), gradient(CV_16UC4));
  EXPECT_EQ(io::readImageFile(pathOf("alpha.png")).type(), CV_16UC4);
  EXPECT_EQ(io::readImageFile(pathOf("alpha.png"), io::ImageChannels::without_alpha).type(), CV_16UC3);
}

TEST_F(ImageFiles, EncodedPngBytesDecodeToTheSameImageAtEveryLevel) {
  const cv::Mat image = gradient(CV_8UC1);
  for (const int level : {0, 1, 9}) {
    const std::string bytes = io::encodePng(image, level);
    ASSERT_EQ(bytes.substr(1, 3), "PNG") << level;
    EXPECT_TRUE(sameImage(io::decodeImage(bytes), image)) << level;
  }
}

TEST_F(ImageFiles, AMissingOrCorruptFileReadsAsNothing) {
  EXPECT_TRUE(io::readImageFile(pathOf("missing.png")).empty());
  const std::string png = io::encodePng(gradient(CV_8UC1));
  EXPECT_TRUE(io::readImageFile(writeFile("cut.png", png.substr(0, png.size() / 2))).empty());
  EXPECT_TRUE(io::readImageFile(writeFile("text.png", "not an image")).empty());
  EXPECT_TRUE(io::decodeImage("").empty());
  EXPECT_TRUE(io::decodeImage(std::string(64, '\xff')).empty());
}

TEST_F(ImageFiles, AnImageTheFormatCannotHoldIsRefusedNamingTheFile) {
  const cv::Mat two_channels(8, 8, CV_8UC2, cv::Scalar(1, 2));
  EXPECT_TRUE(io::encodePng(two_channels).empty());
  EXPECT_TRUE(throwsNaming([&] { io::writeImageFile(pathOf("two.png"), two_channels); }, pathOf("two.png")));
  EXPECT_TRUE(throwsNaming([&] { io::writeImageFile(pathOf("grey.unknown"), gradient(CV_8UC1)); },
                           "grey.unknown: cannot write the image: "));
  EXPECT_TRUE(throwsNaming([&] { io::writeImageFile(pathOf("no/such/dir/grey.png"), gradient(CV_8UC1)); },
                           "no/such/dir/grey.png: cannot write the image"));
}

}  // namespace
}  // namespace binpick::test
