// makeVirtualProjector: "showing" pattern k makes the fake GigE camera serve image k.
#include <string>
#include <utility>
#include <vector>

#include "binpick/acquisition/fake_gige_camera.hpp"
#include "binpick/core/error.hpp"

namespace binpick::acquisition {
namespace {

class VirtualProjector final : public ProjectorTrigger {
 public:
  VirtualProjector(FakeGigECamera& camera, std::vector<cv::Mat> images) : camera_(camera), images_(std::move(images)) {}

  void showPattern(int index) override {
    if (index < 0 || index >= static_cast<int>(images_.size())) {
      throw core::Error("virtual projector: pattern " + std::to_string(index) + " out of range (it holds " +
                        std::to_string(images_.size()) + " images)");
    }
    try {
      camera_.serve(images_[static_cast<std::size_t>(index)]);
    } catch (const core::Error& e) {
      throw core::Error("virtual projector: pattern " + std::to_string(index) + ": " + e.what());
    }
  }

  std::string description() const override {
    return "virtual projector (" + std::to_string(images_.size()) + " images) on fake camera " + camera_.id();
  }

 private:
  FakeGigECamera& camera_;
  std::vector<cv::Mat> images_;
};

}  // namespace

std::unique_ptr<ProjectorTrigger> makeVirtualProjector(FakeGigECamera& camera, std::vector<cv::Mat> pattern_images) {
  if (pattern_images.empty()) throw core::Error("virtual projector: no pattern images");
  return std::make_unique<VirtualProjector>(camera, std::move(pattern_images));
}

}  // namespace binpick::acquisition
