#pragma once
// The record of a guided hand-eye session: a views directory that the file mode
// (`binpick calibrate hand-eye --views DIR`) reads as it is, plus what it must not read:
//   DIR/poses.txt, DIR/view_NNN.png   the accepted views (robot_pose_file.hpp's format)
//   DIR/received.txt                  every pose received, before it was used (attempt_NNN)
//   DIR/rejected/poses.txt            the poses of the views without a usable board ...
//   DIR/rejected/attempt_NNN.png      ... and their images
// Every file is written as the session goes (appended and flushed, images renamed into place),
// so that an interrupted session keeps every view it took. A directory holding a session is
// continued: the new views are added to those it has.
//
// Thread-safety: used from one thread.
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <set>
#include <string>

#include "binpick/core/orientation.hpp"

namespace binpick::cli {

class GuidedViewRecorder {
 public:
  // Creates DIR (and DIR/rejected) or continues the session in it. Throws core::Error when
  // the directory cannot be created, or when its files are unreadable or in another orientation
  // convention than `orientation` (the robot's, in which the poses are written).
  GuidedViewRecorder(const std::string& directory, core::Orientation orientation);

  const std::string& directory() const { return directory_; }
  int accepted() const { return static_cast<int>(views_.size()); }

  // Journals a pose as received, before anything is done with it; returns the attempt's name.
  std::string receive(const Eigen::Isometry3d& T_base_flange);
  // Writes the attempt's image outside the views' naming pattern; returns where, for the check.
  std::string stage(const cv::Mat& image);
  // The staged image and its pose become the next view; returns the view's name.
  std::string accept(const Eigen::Isometry3d& T_base_flange);
  // The staged image and its pose go to rejected/ under the attempt's name; returns the image.
  std::string reject(const std::string& attempt, const Eigen::Isometry3d& T_base_flange);

 private:
  std::string directory_;
  core::Orientation orientation_;
  std::set<std::string> views_;     // accepted views, those of an earlier session included
  std::set<std::string> attempts_;  // received poses
  int next_view_ = 0;
  int next_attempt_ = 1;
};

}  // namespace binpick::cli
