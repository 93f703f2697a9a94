#pragma once
// Internal to binpick::io: the `quality` map of calib.yaml, shared by the rig reader and writer.
#include <opencv2/core.hpp>
#include <string>

#include "binpick/io/rig_calibration.hpp"

namespace binpick::io::detail {

// Opens PATH as a FileStorage YAML map; throws core::Error "PATH: ..." otherwise.
cv::FileStorage openForReading(const std::string& path);
// Throws core::Error naming the key ("quality.views[2].used must be an integer").
RigCalibrationQuality readQuality(const cv::FileNode& node);
void writeQuality(cv::FileStorage& fs, const RigCalibrationQuality& quality);

}  // namespace binpick::io::detail
