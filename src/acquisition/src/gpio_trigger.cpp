// The projector trigger on a GPIO line (libgpiod 1.6 C++ bindings): one pulse per pattern.
#include <bitset>
#include <cerrno>
#include <chrono>
#include <gpiod.hpp>
#include <memory>
#include <string>
#include <system_error>
#include <thread>

#include "binpick/acquisition/projector.hpp"
#include "binpick/core/component_logger.hpp"
#include "binpick/core/error.hpp"

namespace binpick::acquisition {

void GpioTriggerParams::validate() const {
  const std::string owner = "gpio trigger params";
  core::requireField(!chip.empty(), owner, "chip", "a chip name (gpiochip0) or path (/dev/gpiochip0)", "\"\"");
  // Projectors latch edges of a few microseconds; a second-long pulse is a units mistake.
  core::requireField(pulse_us >= 1 && pulse_us <= 1000000, owner, "pulse_us", "in [1, 1000000]", pulse_us);
}

namespace {

const char* const kConsumer = "binpick-projector";

std::string lineName(const GpioTriggerParams& params) {
  return "GPIO chip '" + params.chip + "' line " + std::to_string(params.line);
}

// What went wrong opening a chip, in the words an installer looks for.
const char* openProblem(int error) {
  if (error == ENOENT) return "no such chip";                        // wrong name, or no GPIO driver loaded
  if (error == ENOTTY || error == ENODEV) return "not a GPIO chip";  // a path to another device
  return "cannot open it";                                           // e.g. EACCES: not in the gpio group
}

// chip() throws std::system_error (errno) when the chip cannot be opened: name the chip.
gpiod::chip openChip(const std::string& name) {
  try {
    return gpiod::chip(name, gpiod::chip::OPEN_LOOKUP);
  } catch (const std::system_error& e) {
    throw core::Error("GPIO chip '" + name + "': " + openProblem(e.code().value()) + " (" + e.what() + ")");
  } catch (const std::exception& e) {
    throw core::Error("GPIO chip '" + name + "': cannot open it (" + e.what() + ")");
  }
}

// Drives the line inactive between pulses; libgpiod inverts the level for an active-low line, so
// 1 always means "pulse".
gpiod::line requestLine(const gpiod::chip& chip, const GpioTriggerParams& params) {
  try {
    gpiod::line line = chip.get_line(params.line);  // std::out_of_range past the chip's lines
    const std::bitset<32> flags = params.active_high ? std::bitset<32>() : gpiod::line_request::FLAG_ACTIVE_LOW;
    line.request({kConsumer, gpiod::line_request::DIRECTION_OUTPUT, flags}, 0);
    return line;
  } catch (const std::exception& e) {
    throw core::Error(lineName(params) + ": cannot request it as an output (" + e.what() + ")");
  }
}

class GpioTrigger : public ProjectorTrigger {
 public:
  explicit GpioTrigger(const GpioTriggerParams& params)
      : params_(params), chip_(openChip(params.chip)), line_(requestLine(chip_, params)) {
    core::componentLogger("gpio trigger")
        ->info("{}: pulses of {} us, active {}", lineName(params_), params_.pulse_us,
               params_.active_high ? "high" : "low");
  }

  ~GpioTrigger() override {
    try {
      line_.release();
    } catch (const std::exception&) {
      // The chip is closed with the last reference anyway; nothing to report from a destructor.
    }
  }

  void showPattern(int index) override {
    try {
      line_.set_value(1);
      std::this_thread::sleep_for(std::chrono::microseconds(params_.pulse_us));
      line_.set_value(0);
    } catch (const std::exception& e) {
      throw core::Error(lineName(params_) + ": cannot pulse it for pattern " + std::to_string(index) + " (" + e.what() +
                        ")");
    }
  }

  std::string description() const override { return lineName(params_); }

 private:
  GpioTriggerParams params_;
  gpiod::chip chip_;  // keeps the line's chip open
  gpiod::line line_;
};

}  // namespace

std::unique_ptr<ProjectorTrigger> makeGpioTrigger(const GpioTriggerParams& params) {
  params.validate();
  return std::make_unique<GpioTrigger>(params);
}

}  // namespace binpick::acquisition
