// CameraParams::validate and the names of frame statuses.
#include <set>
#include <string>

#include "binpick/acquisition/camera.hpp"
#include "binpick/core/error.hpp"

namespace binpick::acquisition {

void CameraParams::validate() const {
  const std::string owner = "camera params";
  static const std::set<std::string> kFormats{"Mono8", "Mono10", "Mono12", "Mono16"};
  core::requireField(kFormats.count(pixel_format) > 0, owner, "pixel_format", "Mono8, Mono10, Mono12 or Mono16",
                     pixel_format);
  core::requireField(exposure_us > 0.0 && exposure_us < 1e7, owner, "exposure_us", "in (0, 1e7)", exposure_us);
  core::requireField(gain_db >= 0.0 && gain_db <= 48.0, owner, "gain_db", "in [0, 48]", gain_db);
  core::requireField(roi.x >= 0 && roi.y >= 0 && roi.width >= 0 && roi.height >= 0, owner, "roi",
                     "non-negative (empty: the whole sensor)", roi.x);
  core::requireField(packet_size == 0 || (packet_size >= 576 && packet_size <= 16384), owner, "packet_size",
                     "0 (negotiate) or in [576, 16384]", packet_size);
  core::requireField(trigger != TriggerSource::Hardware || !hardware_trigger_line.empty(), owner,
                     "hardware_trigger_line", "set for a hardware trigger", hardware_trigger_line);
  core::requireField(buffers >= 2 && buffers <= 256, owner, "buffers", "in [2, 256]", buffers);
}

const char* frameStatusName(FrameStatus status) {
  switch (status) {
    case FrameStatus::Ok: return "ok";
    case FrameStatus::Timeout: return "timeout";
    case FrameStatus::Incomplete: return "incomplete";
    case FrameStatus::ConnectionLost: return "connection lost";
    case FrameStatus::Failed: return "failed";
  }
  return "unknown";
}

}  // namespace binpick::acquisition
