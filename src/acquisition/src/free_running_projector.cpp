// A projector that runs its sequence on its own: nothing to drive per pattern.
#include "binpick/acquisition/projector.hpp"

namespace binpick::acquisition {
namespace {

class FreeRunningProjector : public ProjectorTrigger {
 public:
  // The projector advances by itself (and usually triggers the camera): the sequencer's call is
  // only bookkeeping.
  void showPattern(int /*index*/) override {}
  std::string description() const override { return "free-running projector (no trigger line)"; }
  bool advancesOnPulse() const override { return false; }
};

}  // namespace

std::unique_ptr<ProjectorTrigger> makeFreeRunningProjector() { return std::make_unique<FreeRunningProjector>(); }

}  // namespace binpick::acquisition
