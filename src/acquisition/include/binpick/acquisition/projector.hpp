#pragma once
// The projector, as the sequencer drives it: show pattern k of the preloaded sequence. A real
// projector in external-trigger mode advances to its next pattern on each pulse of an input line
// and holds it until the next pulse, so the sequencer pulses once per pattern and may re-trigger
// the camera for a lost frame without touching the projector. After its last pattern it wraps to
// the first: a capture that stopped early leaves it mid-sequence, and the sequencer pulses the
// rest of the sequence before the next capture (CaptureSequencer).
//
// Thread-safety: used from the sequencer's thread only.
#include <memory>
#include <string>

namespace binpick::acquisition {

class ProjectorTrigger {
 public:
  virtual ~ProjectorTrigger() = default;
  // Called with 0, 1, 2, ... in order for every capture. Throws core::Error when the trigger
  // line cannot be driven.
  virtual void showPattern(int index) = 0;
  virtual std::string description() const = 0;
  // Whether showPattern() advances the projector, so that the sequencer can tell where it stands.
  // A free-running projector keeps its own place: nothing the software does can resynchronise it
  // (its sync output triggers the camera, so images and patterns stay paired by hardware).
  virtual bool advancesOnPulse() const { return true; }
};

struct GpioTriggerParams {
  std::string chip = "gpiochip0";  // name (gpiochip0) or path (/dev/gpiochip0)
  unsigned line = 0;               // line offset on the chip
  bool active_high = true;
  int pulse_us = 100;     // pulse width, microseconds
  void validate() const;  // throws core::Error naming the field
};

// A pulse on a GPIO line (libgpiod) per pattern. Throws core::Error naming the chip and line
// when the chip does not exist or the line cannot be requested.
std::unique_ptr<ProjectorTrigger> makeGpioTrigger(const GpioTriggerParams& params);

// No trigger line: the projector runs its sequence on its own (and usually triggers the camera
// through the camera's hardware line).
std::unique_ptr<ProjectorTrigger> makeFreeRunningProjector();

}  // namespace binpick::acquisition
