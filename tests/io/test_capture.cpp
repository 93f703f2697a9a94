// Capture directories: capture.json + images/NNN_<pattern>.png, written and read back, and every
// way the metadata and the images can disagree.
#include "binpick/io/capture.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/io/image_file.hpp"
#include "io_test_support.hpp"

namespace binpick::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Three 64 x 48 images of seeded noise over the full range of the bit depth.
io::Capture smallCapture(int bit_depth) {
  io::Capture capture;
  io::CaptureMetadata& m = capture.metadata;
  m.source = "test rig \"A\" / serial 0042";
  m.timestamp = "2026-11-22T08:15:02.512Z";
  m.image_width = 64;
  m.image_height = 48;
  m.bit_depth = bit_depth;
  m.exposure_us = 8000.125;
  m.gain_db = 1.5;
  m.pattern_set.projector_width = 912;
  m.pattern_set.projector_height = 1140;
  m.pattern_set.row_codes = false;
  m.pattern_set.phase_steps = 3;
  m.pattern_set.phase_period = 24;
  m.patterns = {"white", "black", "gray_col_00"};
  cv::RNG rng(12345 + bit_depth);
  for (std::size_t i = 0; i < m.patterns.size(); ++i) {
    cv::Mat image(m.image_height, m.image_width, bit_depth == 16 ? CV_16UC1 : CV_8UC1);
    rng.fill(image, cv::RNG::UNIFORM, 0, bit_depth == 16 ? 65536 : 256);
    capture.images.push_back(image);
  }
  return capture;
}

bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

class CaptureTest : public IoTest {
 protected:
  void SetUp() override {
    IoTest::SetUp();
    directory_ = pathOf("capture");
    metadata_path_ = (fs::path(directory_) / "capture.json").string();
  }

  // Writes the 8-bit sample capture, then lets `edit` change its capture.json.
  void writeSampleWithMetadata(const std::function<void(json&)>& edit) const {
    fs::remove_all(directory_);
    io::writeCapture(directory_, smallCapture(8));
    json document = json::parse(readFile(metadata_path_));
    edit(document);
    std::ofstream(metadata_path_, std::ios::binary | std::ios::trunc) << document.dump(2);
  }

  std::string imagePath(const std::string& file) const { return (fs::path(directory_) / "images" / file).string(); }

  std::string directory_;
  std::string metadata_path_;
};

TEST_F(CaptureTest, EightBitRoundTripIsBitIdentical) {
  const io::Capture written = smallCapture(8);
  io::writeCapture(directory_, written);
  const io::Capture read = io::readCapture(directory_);
  ASSERT_EQ(read.images.size(), written.images.size());
  for (std::size_t i = 0; i < read.images.size(); ++i) {
    EXPECT_EQ(read.images[i].type(), CV_8UC1);
    EXPECT_TRUE(identical(read.images[i], written.images[i])) << "image " << i;
  }
}

TEST_F(CaptureTest, SixteenBitRoundTripIsBitIdentical) {
  const io::Capture written = smallCapture(16);
  io::writeCapture(directory_, written);
  const io::Capture read = io::readCapture(directory_);
  ASSERT_EQ(read.images.size(), written.images.size());
  for (std::size_t i = 0; i < read.images.size(); ++i) {
    EXPECT_EQ(read.images[i].type(), CV_16UC1);
    EXPECT_TRUE(identical(read.images[i], written.images[i])) << "image " << i;
  }
}

TEST_F(CaptureTest, MetadataRoundTrips) {
  const io::Capture written = smallCapture(16);
  io::writeCapture(directory_, written);
  const io::CaptureMetadata& a = written.metadata;
  for (const io::CaptureMetadata& b : {io::readCaptureMetadata(directory_), io::readCapture(directory_).metadata}) {
    EXPECT_EQ(b.format_version, 1);
    EXPECT_EQ(b.source, a.source);
    EXPECT_EQ(b.timestamp, a.timestamp);
    EXPECT_EQ(b.image_width, a.image_width);
    EXPECT_EQ(b.image_height, a.image_height);
    EXPECT_EQ(b.bit_depth, 16);
    EXPECT_EQ(b.exposure_us, a.exposure_us);
    EXPECT_EQ(b.gain_db, a.gain_db);
    EXPECT_EQ(b.pattern_set.projector_width, 912);
    EXPECT_EQ(b.pattern_set.projector_height, 1140);
    EXPECT_TRUE(b.pattern_set.column_codes);
    EXPECT_FALSE(b.pattern_set.row_codes);
    EXPECT_EQ(b.pattern_set.phase_steps, 3);
    EXPECT_EQ(b.pattern_set.phase_period, 24);
    EXPECT_EQ(b.patterns, a.patterns);
    EXPECT_EQ(b.images,
              (std::vector<std::string>{"images/000_white.png", "images/001_black.png", "images/002_gray_col_00.png"}));
  }
}

// Another rig's code step, Gray-code words and phase convention are kept; binpick's own are not
// written (older readers read such a file as before).
TEST_F(CaptureTest, CodeStepAndPhaseConventionRoundTrip) {
  io::Capture written = smallCapture(8);
  written.metadata.pattern_set.code_step = 2;
  written.metadata.pattern_set.gray_unit = 8;
  written.metadata.pattern_set.phase_direction = -1;
  written.metadata.pattern_set.phase_offset_deg = 90.0;
  io::writeCapture(directory_, written);
  const io::PatternSetSpec read = io::readCaptureMetadata(directory_).pattern_set;
  EXPECT_EQ(read.code_step, 2);
  EXPECT_EQ(read.gray_unit, 8);
  EXPECT_EQ(read.phase_direction, -1);
  EXPECT_EQ(read.phase_offset_deg, 90.0);

  const std::string ours = pathOf("ours");
  io::writeCapture(ours, smallCapture(8));
  std::ifstream file(ours + "/capture.json");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.find("phase_direction"), std::string::npos);
  EXPECT_EQ(text.find("phase_offset_deg"), std::string::npos);
  EXPECT_EQ(text.find("gray_unit"), std::string::npos);
}

TEST_F(CaptureTest, FrameTimesAreOptionalAndRoundTrip) {
  io::writeCapture(directory_, smallCapture(8));
  EXPECT_TRUE(io::readCaptureMetadata(directory_).frame_times_ms.empty());  // none recorded, none read
  io::Capture written = smallCapture(8);
  written.metadata.frame_times_ms = {0.5, 41.25, 83.0};
  const std::string timed = pathOf("timed");
  io::writeCapture(timed, written);
  EXPECT_EQ(io::readCaptureMetadata(timed).frame_times_ms, written.metadata.frame_times_ms);
  writeSampleWithMetadata([](json& d) { d["frame_times_ms"] = {1.0, 2.0}; });
  EXPECT_TRUE(
      failsWith([&] { io::readCapture(directory_); }, metadata_path_, "'frame_times_ms' has 2 entries for 3 patterns"));
  writeSampleWithMetadata([](json& d) { d["frame_times_ms"] = {1.0, "late", 3.0}; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "frame_times_ms"));
}

TEST_F(CaptureTest, WriterLeavesNoTemporaryFiles) {
  io::writeCapture(directory_, smallCapture(8));
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(directory_)) {
    names.push_back(fs::relative(entry.path(), directory_).string());
  }
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"capture.json", "images", "images/000_white.png", "images/001_black.png",
                                             "images/002_gray_col_00.png"}));
}

TEST_F(CaptureTest, WriterRejectsImagesThatDoNotMatchTheMetadata) {
  io::Capture capture = smallCapture(8);
  capture.images.pop_back();
  EXPECT_TRUE(failsWith([&] { io::writeCapture(directory_, capture); }, directory_, "2 images for 3 patterns"));

  capture = smallCapture(8);
  capture.images[1] = cv::Mat::zeros(48, 64, CV_16UC1);
  EXPECT_THROW(io::writeCapture(directory_, capture), core::Error);
  EXPECT_FALSE(fs::exists(metadata_path_));

  capture = smallCapture(8);
  capture.images[2] = cv::Mat::zeros(47, 64, CV_8UC1);
  EXPECT_THROW(io::writeCapture(directory_, capture), core::Error);
  EXPECT_FALSE(fs::exists(metadata_path_));
}

TEST_F(CaptureTest, AnExistingCaptureIsNeverOverwritten) {
  io::writeCapture(directory_, smallCapture(8));
  const std::string before = readFile(metadata_path_);
  EXPECT_TRUE(
      failsWith([&] { io::writeCapture(directory_, smallCapture(16)); }, directory_, "already holds a capture"));
  EXPECT_EQ(readFile(metadata_path_), before);
  EXPECT_EQ(io::readCapture(directory_).metadata.bit_depth, 8);
}

TEST_F(CaptureTest, MissingMetadataIsAnError) {
  fs::create_directories(directory_);
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "does not exist"));
}

TEST_F(CaptureTest, MalformedJsonIsAnError) {
  io::writeCapture(directory_, smallCapture(8));
  std::ofstream(metadata_path_, std::ios::trunc) << "{\"format_version\": 1, \"source\": ";
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "malformed JSON"));
  std::ofstream(metadata_path_, std::ios::trunc) << "[1, 2, 3]";
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "must be a JSON object"));
}

TEST_F(CaptureTest, EachMissingKeyIsNamed) {
  for (const char* key : {"format_version", "source", "timestamp", "image_width", "image_height", "bit_depth",
                          "exposure_us", "gain_db", "pattern_set", "patterns", "images"}) {
    SCOPED_TRACE(key);
    writeSampleWithMetadata([&](json& d) { d.erase(key); });
    EXPECT_TRUE(
        failsWith([&] { io::readCapture(directory_); }, metadata_path_, std::string("missing key '") + key + "'"));
  }
  writeSampleWithMetadata([&](json& d) { d["pattern_set"].erase("phase_period"); });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "missing key 'phase_period'"));
}

TEST_F(CaptureTest, WrongTypesAreNamed) {
  writeSampleWithMetadata([](json& d) { d["image_width"] = "64"; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'image_width' has the wrong type"));
  writeSampleWithMetadata([](json& d) { d["patterns"] = "white"; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'patterns' has the wrong type"));
  writeSampleWithMetadata([](json& d) { d["images"][1] = 7; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'images' has the wrong type"));
  writeSampleWithMetadata([](json& d) { d["pattern_set"]["row_codes"] = 0; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'row_codes' has the wrong type"));
  writeSampleWithMetadata([](json& d) { d["pattern_set"] = 3; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "'pattern_set' must be an object"));
  writeSampleWithMetadata([](json& d) { d["exposure_us"] = "8000"; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'exposure_us' has the wrong type"));
}

TEST_F(CaptureTest, IntegersAreNotSilentlyTruncatedOrTakenFromOtherTypes) {
  writeSampleWithMetadata([](json& d) { d["image_width"] = 64.5; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'image_width' has the wrong type"));
  writeSampleWithMetadata([](json& d) { d["image_height"] = true; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'image_height' has the wrong type"));
  // 2^32 + 64 would wrap to 64 in an int.
  writeSampleWithMetadata([](json& d) { d["image_width"] = 4294967360LL; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "'image_width'"));
  writeSampleWithMetadata([](json& d) { d["gain_db"] = false; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "key 'gain_db' has the wrong type"));
  // An integral value is a fine number of microseconds.
  writeSampleWithMetadata([](json& d) { d["exposure_us"] = 8000; });
  EXPECT_EQ(io::readCapture(directory_).metadata.exposure_us, 8000.0);
}

TEST_F(CaptureTest, UnsupportedVersionIsNamed) {
  writeSampleWithMetadata([](json& d) { d["format_version"] = 2; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "format_version 2 is not supported"));
}

TEST_F(CaptureTest, BadPatternSetIsNamed) {
  writeSampleWithMetadata([](json& d) { d["pattern_set"]["phase_steps"] = 2; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "PatternSetSpec.phase_steps"));
}

TEST_F(CaptureTest, BadImageGeometryInMetadataIsNamed) {
  writeSampleWithMetadata([](json& d) { d["bit_depth"] = 12; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "bit_depth must be 8 or 16"));
  writeSampleWithMetadata([](json& d) { d["image_height"] = 0; });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "image_height"));
}

TEST_F(CaptureTest, PatternAndImageListsMustHaveTheSameLength) {
  writeSampleWithMetadata([](json& d) { d["images"].erase(2); });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_,
                        "'patterns' and 'images' differ in length (3 vs 2)"));
  writeSampleWithMetadata([](json& d) {
    d["patterns"] = json::array();
    d["images"] = json::array();
  });
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "'patterns' is empty"));
}

TEST_F(CaptureTest, ListedButMissingImageIsNamed) {
  io::writeCapture(directory_, smallCapture(8));
  fs::remove(imagePath("001_black.png"));
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, imagePath("001_black.png"),
                        "the image listed in capture.json is missing"));
}

TEST_F(CaptureTest, CorruptPngIsAnError) {
  io::writeCapture(directory_, smallCapture(8));
  // A PNG cut short, and one with its pixel data overwritten.
  const std::string path = imagePath("002_gray_col_00.png");
  const std::string bytes = readFile(path);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, 40);
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, path, "not a readable PNG image"));
  std::ofstream(path, std::ios::binary | std::ios::trunc) << garbageBytes(bytes.size(), 3);
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, path, "not a readable PNG image"));
}

// libpng prints its own complaint about a damaged file to stderr; the reader's error must be the
// only message, so that a command prints one line.
TEST_F(CaptureTest, DamagedPngIsNamedWithoutLibpngOutput) {
  io::writeCapture(directory_, smallCapture(8));
  const std::string path = imagePath("001_black.png");
  const std::string bytes = readFile(path);
  const auto readQuietly = [&](const std::string& expected) {
    ::testing::internal::CaptureStderr();
    const ::testing::AssertionResult refused = failsWith([&] { io::readCapture(directory_, 1); }, path, expected);
    const std::string printed = ::testing::internal::GetCapturedStderr();
    EXPECT_TRUE(refused);
    EXPECT_EQ(printed, "") << expected;
  };
  // Cut inside the pixel data.
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() - 30);
  readQuietly("not a readable PNG image: truncated: chunk IDAT at byte");
  // One byte of the pixel data changed.
  std::string flipped = bytes;
  flipped[bytes.size() - 30] = static_cast<char>(flipped[bytes.size() - 30] ^ 0x5A);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << flipped;
  readQuietly("not a readable PNG image: corrupt: chunk IDAT at byte");
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  EXPECT_NO_THROW(io::readCapture(directory_, 1));
}

TEST_F(CaptureTest, ImageOfTheWrongSizeIsNamed) {
  io::writeCapture(directory_, smallCapture(8));
  const std::string path = imagePath("000_white.png");
  io::writeImageFile(path, cv::Mat::zeros(48, 32, CV_8UC1));
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, path, "image is 32x48, capture.json says 64x48"));
}

TEST_F(CaptureTest, ImageOfTheWrongBitDepthIsNamed) {
  io::writeCapture(directory_, smallCapture(8));
  const std::string path = imagePath("001_black.png");
  io::writeImageFile(path, cv::Mat::zeros(48, 64, CV_16UC1));
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, path, "not single-channel 8-bit"));

  fs::remove_all(directory_);
  io::writeCapture(directory_, smallCapture(16));
  io::writeImageFile(path, cv::Mat::zeros(48, 64, CV_8UC1));
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, path, "not single-channel 16-bit"));

  io::writeImageFile(path, cv::Mat::zeros(48, 64, CV_16UC3));
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, path, "not single-channel 16-bit"));
}

TEST_F(CaptureTest, UnlistedFileInImagesIsAnError) {
  io::writeCapture(directory_, smallCapture(8));
  const std::string stray = imagePath("003_extra.png");
  io::writeImageFile(stray, cv::Mat::zeros(48, 64, CV_8UC1));
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, stray, "not listed in capture.json"));
  fs::remove(stray);
  const std::string leftover = imagePath("000_white.png.tmp");
  std::ofstream(leftover) << "x";
  EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, leftover, "not listed in capture.json"));
  fs::remove(leftover);
  EXPECT_NO_THROW(io::readCapture(directory_));
}

TEST_F(CaptureTest, ImageNamesCannotLeaveTheDirectory) {
  const std::string outside = pathOf("x.png");
  io::writeImageFile(outside, cv::Mat::zeros(48, 64, CV_8UC1));
  for (const std::string& name :
       {std::string("../x.png"), std::string("images/../../x.png"), std::string("images/../x.png"), outside,
        std::string("/images/000_white.png"), std::string("000_white.png"), std::string("images/sub/000_white.png"),
        std::string("images/000_white.tiff"), std::string("images/..png"), std::string("images/")}) {
    SCOPED_TRACE(name);
    writeSampleWithMetadata([&](json& d) { d["images"][0] = name; });
    EXPECT_TRUE(failsWith([&] { io::readCapture(directory_); }, metadata_path_, "must be images/<name>.png"));
  }
}

TEST(CaptureTimestamp, IsIso8601UtcWithMilliseconds) {
  const std::string now = io::utcTimestamp();
  EXPECT_TRUE(std::regex_match(now, std::regex(R"(\d{4}-\d{2}-\d{2}T\d{2}:\d{2}:\d{2}\.\d{3}Z)"))) << now;
}

}  // namespace
}  // namespace binpick::test
