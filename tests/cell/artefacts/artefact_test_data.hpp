#pragma once
// Small artefacts for the store's tests, and a look at what a store directory holds.
#include <filesystem>
#include <opencv2/core.hpp>
#include <regex>
#include <set>
#include <string>

#include "binpick/cell/artefact_store.hpp"
#include "binpick/io/capture.hpp"
#include "binpick/io/point_cloud.hpp"

namespace binpick::test {

inline io::Capture tinyCapture() {
  io::Capture capture;
  io::CaptureMetadata& m = capture.metadata;
  m.source = "test";
  m.timestamp = io::utcTimestamp();
  m.image_width = 8;
  m.image_height = 6;
  m.bit_depth = 8;
  m.pattern_set.projector_width = 64;
  m.pattern_set.projector_height = 32;
  m.pattern_set.phase_steps = 0;
  m.patterns = {"white", "black"};
  capture.images = {cv::Mat(6, 8, CV_8UC1, cv::Scalar(200)), cv::Mat(6, 8, CV_8UC1, cv::Scalar(10))};
  return capture;
}

inline io::PointCloud tinyCloud() {
  io::PointCloud cloud;
  cloud.points = {{0.f, 0.f, 0.5f}, {0.01f, 0.f, 0.5f}, {0.f, 0.01f, 0.51f}};
  return cloud;
}

// Entry names directly in `directory`.
inline std::set<std::string> entriesOf(const std::string& directory) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

inline bool anyPartial(const std::string& directory) {
  for (const std::string& name : entriesOf(directory)) {
    if (name.rfind(".partial-", 0) == 0) return true;
  }
  return false;
}

inline std::string nameOf(const std::string& path) { return std::filesystem::path(path).filename().string(); }

// cycle-<6+ digits>-<UTC>[-n]
inline bool isCycleName(const std::string& name) {
  static const std::regex pattern("cycle-[0-9]{6,}-[0-9]{8}T[0-9]{6}Z(-[0-9]+)?");
  return std::regex_match(name, pattern);
}

inline std::string cycleNumberOf(const std::string& path) {
  return nameOf(path).substr(6, nameOf(path).find('-', 6) - 6);
}

}  // namespace binpick::test
