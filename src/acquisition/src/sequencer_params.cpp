// SequencerParams::validate.
#include <string>

#include "binpick/acquisition/sequencer.hpp"

namespace binpick::acquisition {

void SequencerParams::validate() const {
  const std::string owner = "sequencer params";
  // Bounds catch unit mistakes (seconds for microseconds) rather than limit real rigs.
  requireField(settle_us >= 0 && settle_us <= 10000000, owner, "settle_us", "in [0, 10000000]", settle_us);
  requireField(frame_timeout_ms >= 1 && frame_timeout_ms <= 600000, owner, "frame_timeout_ms", "in [1, 600000]",
               frame_timeout_ms);
  requireField(max_retries >= 0 && max_retries <= 100, owner, "max_retries", "in [0, 100]", max_retries);
  requireField(order == TriggerOrder::ProjectorThenCamera || order == TriggerOrder::CameraOnly, owner, "order",
               "ProjectorThenCamera or CameraOnly", static_cast<int>(order));
}

}  // namespace binpick::acquisition
