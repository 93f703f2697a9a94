// The `quality` map of calib.yaml: how well a calibration fitted, view by view, and when it ran.
// Readers of the rig itself never look at it.
#include "rig_calibration_quality.hpp"

#include <cmath>
#include <fstream>
#include <limits>

#include "binpick/core/error.hpp"

namespace binpick::io {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw core::Error(path + ": " + what); }

// A key of the `quality` map (or of one of its views); `where` names it in errors.
double qualityReal(const cv::FileNode& map, const std::string& key, const std::string& where) {
  const cv::FileNode node = map[key];
  if (node.empty()) return std::numeric_limits<double>::quiet_NaN();
  if (!node.isReal() && !node.isInt()) throw core::Error(where + "." + key + " must be a number");
  return static_cast<double>(node);
}

int qualityInt(const cv::FileNode& map, const std::string& key, const std::string& where) {
  const cv::FileNode node = map[key];
  if (!node.isInt()) throw core::Error(where + "." + key + " must be an integer");
  return static_cast<int>(node);
}

std::string qualityString(const cv::FileNode& map, const std::string& key, const std::string& where, bool required) {
  const cv::FileNode node = map[key];
  if (node.empty() && !required) return "";
  if (!node.isString()) throw core::Error(where + "." + key + " must be a string");
  return static_cast<std::string>(node);
}

RigViewQuality readViewQuality(const cv::FileNode& node, const std::string& where) {
  if (!node.isMap()) throw core::Error(where + " must be a map");
  RigViewQuality view;
  view.name = qualityString(node, "name", where, true);
  view.camera_corners = qualityInt(node, "camera_corners", where);
  view.projector_corners = qualityInt(node, "projector_corners", where);
  view.camera_rms_px = qualityReal(node, "camera_rms_px", where);
  view.projector_rms_px = qualityReal(node, "projector_rms_px", where);
  view.outlier = qualityInt(node, "outlier", where) != 0;
  view.used = qualityInt(node, "used", where) != 0;
  view.problem = qualityString(node, "problem", where, false);
  return view;
}

// NaN (a view never calibrated) is left out rather than written as .nan.
void writeFinite(cv::FileStorage& fs, const std::string& key, double value) {
  if (std::isfinite(value)) fs << key << value;
}

}  // namespace

namespace detail {

RigCalibrationQuality readQuality(const cv::FileNode& node) {
  if (!node.isMap()) throw core::Error("'quality' must be a map");
  RigCalibrationQuality quality;
  quality.date = qualityString(node, "date", "quality", true);
  quality.camera_rms_px = qualityReal(node, "camera_rms_px", "quality");
  quality.projector_rms_px = qualityReal(node, "projector_rms_px", "quality");
  quality.stereo_rms_px = qualityReal(node, "stereo_rms_px", "quality");
  const cv::FileNode views = node["views"];
  if (!views.isSeq()) throw core::Error("quality.views must be a list");
  for (int i = 0; i < static_cast<int>(views.size()); ++i) {
    quality.views.push_back(readViewQuality(views[i], "quality.views[" + std::to_string(i) + "]"));
  }
  return quality;
}

void writeQuality(cv::FileStorage& fs, const RigCalibrationQuality& quality) {
  const int used = quality.viewsUsed();
  fs << "quality"
     << "{"
     << "date" << quality.date << "views_used" << used << "views_dropped"
     << static_cast<int>(quality.views.size()) - used;
  writeFinite(fs, "camera_rms_px", quality.camera_rms_px);
  writeFinite(fs, "projector_rms_px", quality.projector_rms_px);
  writeFinite(fs, "stereo_rms_px", quality.stereo_rms_px);
  fs << "views"
     << "[";
  for (const RigViewQuality& view : quality.views) {
    fs << "{"
       << "name" << view.name << "camera_corners" << view.camera_corners << "projector_corners"
       << view.projector_corners;
    writeFinite(fs, "camera_rms_px", view.camera_rms_px);
    writeFinite(fs, "projector_rms_px", view.projector_rms_px);
    fs << "outlier" << static_cast<int>(view.outlier) << "used" << static_cast<int>(view.used);
    if (!view.problem.empty()) fs << "problem" << view.problem;
    fs << "}";
  }
  fs << "]"
     << "}";
}

}  // namespace detail

int RigCalibrationQuality::viewsUsed() const {
  int used = 0;
  for (const RigViewQuality& view : views) used += view.used ? 1 : 0;
  return used;
}

std::optional<RigCalibrationQuality> readRigCalibrationQuality(const std::string& path) {
  cv::FileStorage fs = detail::openForReading(path);
  try {
    const cv::FileNode node = fs["quality"];
    if (node.empty()) return std::nullopt;
    return detail::readQuality(node);
  } catch (const core::Error& e) {
    fail(path, e.what());
  } catch (const cv::Exception& e) {
    fail(path, "malformed OpenCV FileStorage content: " + e.err);
  }
}

}  // namespace binpick::io
