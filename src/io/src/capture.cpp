// Capture directories: the pattern images beside capture.json, checked against it on reading.
#include "binpick/io/capture.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <set>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"
#include "binpick/core/thread_count.hpp"
#include "binpick/io/image_file.hpp"
#include "byte_io.hpp"
#include "capture_paths.hpp"
#include "png_structure.hpp"

namespace binpick::io {
namespace fs = std::filesystem;
using detail::fail;

namespace capture_detail {

std::string metadataPath(const std::string& directory) { return (fs::path(directory) / "capture.json").string(); }

std::string imagesDirectory(const std::string& directory) { return (fs::path(directory) / "images").string(); }

std::string imageName(std::size_t index, const std::string& pattern) {
  char prefix[16];
  std::snprintf(prefix, sizeof prefix, "%03zu_", index);
  return "images/" + std::string(prefix) + pattern + ".png";
}

bool isPlainImageName(const std::string& name) {
  const fs::path path(name);
  auto it = path.begin();
  if (it == path.end() || *it != "images") return false;
  ++it;
  if (it == path.end()) return false;
  const fs::path file = *it;
  ++it;
  return it == path.end() && file.extension() == ".png" && file != ".." && file != "." &&
         file.stem().string().find_first_not_of('.') != std::string::npos;
}

}  // namespace capture_detail

namespace {

int expectedType(int bit_depth) { return bit_depth == 16 ? CV_16UC1 : CV_8UC1; }

[[noreturn]] void failWrongSize(const std::string& path, const std::string& size, const CaptureMetadata& m) {
  fail(path, "image is " + size + ", capture.json says " + std::to_string(m.image_width) + "x" +
                 std::to_string(m.image_height));
}

cv::Mat readImage(const std::string& path, const CaptureMetadata& m) {
  if (!fs::exists(path)) fail(path, "the image listed in capture.json is missing");
  // Decoded from memory: OpenCV logs its own warning for unreadable files, our error says it.
  // The chunk structure is checked first: libpng prints its own message on a truncated or
  // corrupt file, and the error should be one line.
  const std::string bytes = core::readFile(path);
  const std::string defect = detail::pngStructureDefect(bytes);
  if (!defect.empty()) fail(path, "not a readable PNG image: " + defect);
  // The size first: decoding allocates for the size the file claims, however little data follows.
  const detail::PngSize size = detail::pngSize(bytes);
  if (size.width != static_cast<uint32_t>(m.image_width) || size.height != static_cast<uint32_t>(m.image_height)) {
    failWrongSize(path, std::to_string(size.width) + "x" + std::to_string(size.height), m);
  }
  const cv::Mat image = decodeImage(bytes);
  if (image.empty()) fail(path, "not a readable PNG image");
  if (image.cols != m.image_width || image.rows != m.image_height) {
    failWrongSize(path, std::to_string(image.cols) + "x" + std::to_string(image.rows), m);
  }
  if (image.type() != expectedType(m.bit_depth)) {
    fail(path, "image is not single-channel " + std::to_string(m.bit_depth) + "-bit as capture.json says");
  }
  return image;
}

// Every file in DIR/images must be listed: a stray image means the metadata and the images do not
// belong together (an interrupted recording, or files copied over).
void rejectUnlistedImages(const std::string& directory, const CaptureMetadata& m) {
  const std::set<std::string> listed(m.images.begin(), m.images.end());
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(capture_detail::imagesDirectory(directory), error)) {
    const std::string name = "images/" + entry.path().filename().string();
    if (listed.count(name) == 0) {
      fail(entry.path().string(), "file in the capture is not listed in capture.json");
    }
  }
}

std::string pngBytes(const cv::Mat& image, const std::string& path) {
  // Level 1: nearly the size of the default level at a fraction of its time.
  std::string bytes = encodePng(image, 1);
  if (bytes.empty()) fail(path, "PNG encoding failed");
  return bytes;
}

// Runs task(i) for i in [0, count) on `threads` threads; rethrows the error of the lowest i that
// failed, so the message does not depend on the thread count.
template <typename Task>
void forEachInParallel(std::size_t count, int threads, const Task& task) {
  std::vector<std::string> errors(count);
#pragma omp parallel for num_threads(core::resolveThreadCount(threads)) schedule(dynamic, 1)
  for (long i = 0; i < static_cast<long>(count); ++i) {
    try {
      task(static_cast<std::size_t>(i));
    } catch (const std::exception& e) {
      errors[static_cast<std::size_t>(i)] = e.what();
    }
  }
  for (const std::string& error : errors) {
    if (!error.empty()) throw core::Error(error);
  }
}

}  // namespace

Capture readCapture(const std::string& directory, int threads) {
  Capture capture;
  capture.metadata = readCaptureMetadata(directory);
  rejectUnlistedImages(directory, capture.metadata);
  capture.images.resize(capture.metadata.images.size());
  // PNG decoding dominates reading a capture: one image per thread.
  forEachInParallel(capture.images.size(), threads, [&](std::size_t i) {
    capture.images[i] = readImage((fs::path(directory) / capture.metadata.images[i]).string(), capture.metadata);
  });
  return capture;
}

void writeCapture(const std::string& directory, Capture capture, int threads) {
  CaptureMetadata& m = capture.metadata;
  if (capture.images.size() != m.patterns.size()) {
    fail(directory, "writeCapture: " + std::to_string(capture.images.size()) + " images for " +
                        std::to_string(m.patterns.size()) + " patterns");
  }
  m.images.clear();
  for (std::size_t i = 0; i < m.patterns.size(); ++i) {
    m.images.push_back(capture_detail::imageName(i, m.patterns[i]));
  }
  capture_detail::checkMetadata(m, capture_detail::metadataPath(directory));
  // Never mix two captures, nor overwrite a recording: the caller picks a fresh directory.
  if (fs::exists(capture_detail::metadataPath(directory)) || fs::exists(capture_detail::imagesDirectory(directory))) {
    fail(directory, "already holds a capture; write each capture to a new directory");
  }
  std::error_code error;
  fs::create_directories(capture_detail::imagesDirectory(directory), error);
  if (error) fail(directory, "cannot create the capture directory: " + error.message());
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    const cv::Mat& image = capture.images[i];
    if (image.cols != m.image_width || image.rows != m.image_height || image.type() != expectedType(m.bit_depth)) {
      fail((fs::path(directory) / m.images[i]).string(),
           "writeCapture: image " + std::to_string(i) + " does not match the metadata's size and bit depth");
    }
  }
  // PNG encoding dominates writing: one image per thread; capture.json only after all of them.
  forEachInParallel(capture.images.size(), threads, [&](std::size_t i) {
    const std::string path = (fs::path(directory) / m.images[i]).string();
    core::writeFileAtomically(path, pngBytes(capture.images[i], path));
  });
  capture_detail::writeCaptureMetadata(directory, m);
}

std::string utcTimestamp() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const auto millis = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%S", &utc);
  char full[40];
  std::snprintf(full, sizeof full, "%s.%03dZ", text, static_cast<int>(millis));
  return full;
}

}  // namespace binpick::io
