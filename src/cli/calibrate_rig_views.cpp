// Calibration views from directories or from the live path.
#include "calibrate_rig_views.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "binpick/core/error.hpp"
#include "live_capture.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;

// "pose_003: 48 of 48 corners, 47 with a projector pixel" on stderr, as each view is measured.
void reportView(const calibration::RigView& view) {
  if (!view.board.found()) {
    std::cerr << view.name << ": board not found (" << view.board.problem << ")\n";
    return;
  }
  std::cerr << view.name << ": " << view.board.ids.size() << " of " << view.board.expected << " corners, "
            << view.projector.corners.size() << " with a projector pixel\n";
}

std::string viewDirectory(const std::string& record, int index) {
  char name[32];
  std::snprintf(name, sizeof name, "view_%03d", index);
  return (fs::path(record) / name).string();
}

// A new session never mixes its views with an old one's.
void requireFreshRecord(const std::string& record) {
  std::error_code error;
  if (fs::exists(record, error) && !(fs::is_directory(record, error) && fs::is_empty(record, error))) {
    throw core::Error(record + ": already exists and is not empty; choose a new --record directory");
  }
  fs::create_directories(record, error);
  if (error) throw core::Error(record + ": cannot create the directory: " + error.message());
}

// False when the user stops the session (q, or the end of the input).
bool waitForUser(std::istream& input, int index, int count) {
  std::cerr << "view " << index + 1 << " of " << count
            << ": set the board, then press Enter (q and Enter: stop here)\n";
  std::string line;
  if (!std::getline(input, line)) return false;
  return line != "q" && line != "Q";
}

}  // namespace

std::vector<std::string> sequenceCaptures(const std::string& directory) {
  std::error_code error;
  if (!fs::is_directory(directory, error)) throw core::Error(directory + ": not a directory");
  std::vector<std::string> captures;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    if (entry.is_directory() && fs::exists(entry.path() / "capture.json")) {
      captures.push_back(entry.path().string());
    }
  }
  if (error) throw core::Error(directory + ": cannot list the directory: " + error.message());
  if (captures.empty()) {
    throw core::Error(directory + ": holds no capture directory (a subdirectory with a capture.json)");
  }
  std::sort(captures.begin(), captures.end());
  return captures;
}

std::vector<calibration::RigView> readViews(const std::vector<std::string>& directories,
                                            const calibration::BoardLayout& layout,
                                            const calibration::RigViewParams& params) {
  std::vector<calibration::RigView> views;
  for (const std::string& directory : directories) {
    views.push_back(calibration::readRigView(directory, layout, params));
    reportView(views.back());
  }
  return views;
}

std::vector<calibration::RigView> captureLiveViews(const Arguments& args, int count, const std::string& record,
                                                   const calibration::BoardLayout& layout,
                                                   const calibration::RigViewParams& params, std::istream& input) {
  const auto fake = args.value("--fake-camera");
  const std::vector<std::string> recorded = fake ? sequenceCaptures(*fake) : std::vector<std::string>{};
  if (fake && static_cast<int>(recorded.size()) < count) {
    throw core::Error(*fake + ": holds " + std::to_string(recorded.size()) + " captures, fewer than the " +
                      std::to_string(count) + " views asked for (--count)");
  }
  const io::PatternSetSpec patterns = patternSetFromArguments(args);
  requireFreshRecord(record);
  std::vector<calibration::RigView> views;
  for (int i = 0; i < count && waitForUser(input, i, count); ++i) {
    io::Capture capture =
        fake ? captureFromFake(args, io::readCapture(recorded[i])) : captureFromCamera(args, patterns);
    const std::string directory = viewDirectory(record, i);
    io::writeCapture(directory, capture);
    try {
      views.push_back(calibration::measureRigView(capture, directory, layout, params));
      reportView(views.back());
    } catch (const core::Error& e) {
      std::cerr << "warning: " << e.what() << "; view left out\n";
    }
  }
  return views;
}

}  // namespace binpick::cli
