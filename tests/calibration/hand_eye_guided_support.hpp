#pragma once
// Test support for the guided hand-eye session: board images that pass the file mode's view
// check with a known camera, a camera that serves scripted images or failures (and can be held
// mid-grab), and the replies the session sends, per client.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <variant>

#include "binpick/core/error.hpp"
#include "hand_eye_guided_camera.hpp"
#include "hand_eye_guided_session.hpp"

namespace binpick::cli::testing {

// A 640x480 pinhole camera without distortion.
inline io::LensIntrinsics testCamera() {
  io::LensIntrinsics camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = camera.fy = 800.0;
  camera.cx = 319.5;
  camera.cy = 239.5;
  return camera;
}

// The default board (BoardLayout's) seen square-on, `shift` pixels right of the centre: the
// board is parallel to the image plane, which any pinhole camera sees exactly like this.
inline cv::Mat boardImage(int shift = 0) {
  const calibration::BoardLayout layout;
  const cv::Ptr<cv::aruco::CharucoBoard> board = cv::aruco::CharucoBoard::create(
      layout.squares_x, layout.squares_y, static_cast<float>(layout.square_size),
      static_cast<float>(layout.marker_size), cv::aruco::getPredefinedDictionary(cv::aruco::DICT_5X5_100));
  cv::Mat drawn;
  board->draw(cv::Size(450, 350), drawn, 0, 1);
  cv::Mat image(480, 640, CV_8UC1, cv::Scalar(255));
  drawn.copyTo(image(cv::Rect(95 + shift, 65, drawn.cols, drawn.rows)));
  return image;
}

inline cv::Mat blankImage() { return cv::Mat(480, 640, CV_8UC1, cv::Scalar(180)); }

// Serves what the test queued, in order: an image, or a failure (the message of the Error).
// hold() makes the next grab wait until release(): a view that takes as long as the test wants.
class ScriptedCamera : public ViewCamera {
 public:
  void queue(const cv::Mat& image) { push(image); }
  void queueFailure(const std::string& message) { push(message); }
  void hold() {
    std::lock_guard<std::mutex> lock(mutex_);
    held_ = true;
  }
  void release() {
    std::lock_guard<std::mutex> lock(mutex_);
    held_ = false;
    changed_.notify_all();
  }
  // Blocks until a grab is waiting on hold().
  void waitUntilGrabbing() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return grabbing_; });
  }

  cv::Mat grab() override {
    std::unique_lock<std::mutex> lock(mutex_);
    grabbing_ = true;
    changed_.notify_all();
    changed_.wait(lock, [this] { return !held_; });
    grabbing_ = false;
    if (script_.empty()) throw core::Error("scripted camera: nothing queued");
    const std::variant<cv::Mat, std::string> next = script_.front();
    script_.pop_front();
    if (const std::string* message = std::get_if<std::string>(&next)) throw core::Error(*message);
    return std::get<cv::Mat>(next);
  }
  std::string description() const override { return "scripted camera"; }

 private:
  void push(std::variant<cv::Mat, std::string> next) {
    std::lock_guard<std::mutex> lock(mutex_);
    script_.push_back(std::move(next));
  }

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::variant<cv::Mat, std::string>> script_;
  bool held_ = false;
  bool grabbing_ = false;
};

// The session's replies, per client, as a robot would read them.
class Replies {
 public:
  GuidedReplySink sink() {
    return [this](robot::ClientId client, const robot::Reply& reply) {
      std::lock_guard<std::mutex> lock(mutex_);
      replies_[client].push_back(reply);
      arrived_.notify_all();
    };
  }
  // The next reply to `client`; fails the test if none comes within a minute (a hang).
  robot::Reply next(robot::ClientId client) {
    std::unique_lock<std::mutex> lock(mutex_);
    const bool arrived = arrived_.wait_for(lock, std::chrono::minutes(1), [&] { return !replies_[client].empty(); });
    if (!arrived) {
      ADD_FAILURE() << "no reply to client " << client;
      return robot::Reply{robot::Command::Ping, robot::Status::InternalError};
    }
    const robot::Reply reply = replies_[client].front();
    replies_[client].pop_front();
    return reply;
  }
  std::size_t waiting(robot::ClientId client) {
    std::lock_guard<std::mutex> lock(mutex_);
    return replies_[client].size();
  }

 private:
  std::mutex mutex_;
  std::condition_variable arrived_;
  std::map<robot::ClientId, std::deque<robot::Reply>> replies_;
};

inline robot::Request pose(double x_m, double angle_deg = 0.0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x_m, -0.05, 0.4);
  T.linear() = Eigen::AngleAxisd(angle_deg * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  return robot::Request{robot::Command::Pose, std::nullopt, T};
}

inline robot::Request request(robot::Command command) { return robot::Request{command}; }

}  // namespace binpick::cli::testing
