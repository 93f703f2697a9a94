// The guided session's cameras: replayed images, or live frames from the camera.
#include "hand_eye_guided_camera.hpp"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/io/image_file.hpp"

namespace binpick::cli {
namespace {

namespace fs = std::filesystem;
using acquisition::Frame;
using acquisition::FrameStatus;

std::vector<std::string> pngImagesByName(const std::string& directory) {
  std::vector<std::string> images;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory, error)) {
    if (entry.is_regular_file() && entry.path().extension() == ".png") {
      images.push_back(entry.path().string());
    }
  }
  if (error) throw core::Error(directory + ": cannot list the images: " + error.message());
  if (images.empty()) throw core::Error(directory + ": no PNG images to replay");
  std::sort(images.begin(), images.end());
  return images;
}

class ReplayViewCamera : public ViewCamera {
 public:
  explicit ReplayViewCamera(const std::string& directory)
      : directory_(directory), images_(pngImagesByName(directory)) {}

  cv::Mat grab() override {
    if (next_ == images_.size()) {
      throw core::Error("replay: all " + std::to_string(images_.size()) + " images of " + directory_ + " were served");
    }
    const std::string& path = images_[next_++];
    cv::Mat image = io::readImageFile(path);
    if (image.empty()) throw core::Error("replay: cannot read " + path);
    return image;
  }

  std::string description() const override {
    return "replay of " + std::to_string(images_.size()) + " images in " + directory_;
  }

 private:
  std::string directory_;
  std::vector<std::string> images_;
  std::size_t next_ = 0;
};

class LiveViewCamera : public ViewCamera {
 public:
  LiveViewCamera(std::unique_ptr<acquisition::Camera> camera, int timeout_ms)
      : camera_(std::move(camera)), timeout_ms_(timeout_ms) {
    if (timeout_ms_ <= 0) throw core::Error("the frame timeout must be positive (--timeout-ms)");
  }
  ~LiveViewCamera() override { closeQuietly(); }

  cv::Mat grab() override {
    if (!streaming_ || camera_->connectionLost()) reopen();
    camera_->trigger();
    Frame frame = camera_->grab(timeout_ms_);
    if (frame.status != FrameStatus::Ok) {
      closeQuietly();  // a late frame must not answer the next view
      throw core::Error("camera " + camera_->description() + ": " + acquisition::frameStatusName(frame.status) +
                        (frame.detail.empty() ? "" : ": " + frame.detail));
    }
    return frame.image;
  }

  std::string description() const override { return camera_->description(); }

 private:
  // Throws naming the camera; the next grab tries again.
  void reopen() {
    closeQuietly();
    camera_->open();
    try {
      camera_->start();
    } catch (...) {
      closeQuietly();
      throw;
    }
    streaming_ = true;
  }

  // Closing a camera that already failed may fail again: nothing left to do about it.
  void closeQuietly() noexcept {
    try {
      if (streaming_) camera_->stop();
    } catch (...) {
    }
    streaming_ = false;
    try {
      if (camera_->isOpen()) camera_->close();
    } catch (...) {
    }
  }

  std::unique_ptr<acquisition::Camera> camera_;
  int timeout_ms_;
  bool streaming_ = false;
};

}  // namespace

std::unique_ptr<ViewCamera> makeReplayViewCamera(const std::string& directory) {
  return std::make_unique<ReplayViewCamera>(directory);
}

std::unique_ptr<ViewCamera> makeLiveViewCamera(std::unique_ptr<acquisition::Camera> camera, int timeout_ms) {
  return std::make_unique<LiveViewCamera>(std::move(camera), timeout_ms);
}

}  // namespace binpick::cli
