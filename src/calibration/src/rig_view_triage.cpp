// Usable views, and messages that name the others and say what was wrong.
#include "rig_view_triage.hpp"

#include <sstream>

#include "binpick/core/error.hpp"

namespace binpick::calibration::detail {
namespace {

// "4 with too few decoded pixels, 2 outside the decoded area".
std::string droppedReasons(const ProjectorCorners& projector) {
  std::ostringstream text;
  const char* separator = "";
  const auto add = [&](int count, const char* reason) {
    if (count == 0) return;
    text << separator << count << " " << reason;
    separator = ", ";
  };
  add(projector.too_few_decoded, "with too few decoded pixels");
  add(projector.poor_fit, "where no homography fitted the decoded pixels");
  add(projector.outside_data, "at the edge of the decoded area");
  return text.str();
}

}  // namespace

std::string viewProblem(const RigView& view, const RigCalibrationParams& params) {
  if (!view.board.found()) return "board not found: " + view.board.problem;
  const int shared = static_cast<int>(view.projector.corners.size());
  if (shared >= params.min_corners) return "";
  std::ostringstream text;
  text << "only " << shared << " corners with both a camera and a projector pixel (needs " << params.min_corners
       << "; camera found " << view.board.ids.size() << " of " << view.board.expected;
  if (view.projector.dropped() > 0) text << ", projector lost " << droppedReasons(view.projector);
  text << ")";
  return text.str();
}

std::vector<std::string> viewWarnings(const RigView& view) {
  std::vector<std::string> warnings;
  const int found = static_cast<int>(view.board.ids.size());
  if (found < view.board.expected) {
    std::ostringstream text;
    text << view.name << ": only " << found << " of " << view.board.expected
         << " board corners found in the camera image (board partly outside the image, hidden,"
            " or its markers not recognised); calibrating with those";
    warnings.push_back(text.str());
  }
  if (view.projector.dropped() > 0) {
    std::ostringstream text;
    text << view.name << ": " << view.projector.dropped() << " of " << found << " corners have no projector pixel ("
         << droppedReasons(view.projector) << "; board partly outside the projector's light?)";
    warnings.push_back(text.str());
  }
  return warnings;
}

void requireSameSizes(const std::vector<RigView>& views, const std::vector<std::size_t>& usable) {
  const RigView& first = views[usable.front()];
  for (const std::size_t i : usable) {
    const RigView& view = views[i];
    if (view.camera_width == first.camera_width && view.camera_height == first.camera_height &&
        view.projector_width == first.projector_width && view.projector_height == first.projector_height) {
      continue;
    }
    std::ostringstream text;
    text << view.name << ": camera " << view.camera_width << "x" << view.camera_height << ", projector "
         << view.projector_width << "x" << view.projector_height << ", but " << first.name << " has camera "
         << first.camera_width << "x" << first.camera_height << ", projector " << first.projector_width << "x"
         << first.projector_height << ": all views must come from the same rig";
    throw core::Error(text.str());
  }
}

std::string tooFewViewsMessage(const std::vector<RigView>& views, const std::vector<std::string>& problems, int usable,
                               int min_views) {
  std::ostringstream text;
  text << "calibrate rig: " << usable << " usable view" << (usable == 1 ? "" : "s") << " of " << views.size()
       << ", at least " << min_views << " needed";
  const char* separator = "; not usable: ";
  for (std::size_t i = 0; i < views.size(); ++i) {
    if (problems[i].empty()) continue;
    text << separator << views[i].name << " (" << problems[i] << ")";
    separator = ", ";
  }
  return text.str();
}

}  // namespace binpick::calibration::detail
