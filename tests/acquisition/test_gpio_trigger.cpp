// The projector triggers: a GPIO line that cannot be had is named in the error (these machines
// have no GPIO chip), and the free-running projector needs nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "binpick/acquisition/projector.hpp"
#include "binpick/core/error.hpp"
#include "thrown_message.hpp"

namespace binpick::acquisition {
namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::string validationError(const GpioTriggerParams& params) {
  return binpick::test::thrownMessage([&] { params.validate(); });
}

std::string gpioError(const GpioTriggerParams& params) {
  return binpick::test::thrownMessage([&] { makeGpioTrigger(params); });
}

TEST(GpioTriggerParams, DefaultsAreValid) { EXPECT_EQ(validationError(GpioTriggerParams{}), ""); }

TEST(GpioTriggerParams, RefusesNonsenseNamingTheField) {
  GpioTriggerParams chip;
  chip.chip = "";
  EXPECT_TRUE(contains(validationError(chip), "gpio trigger params.chip")) << validationError(chip);
  GpioTriggerParams pulse;
  pulse.pulse_us = 0;
  EXPECT_TRUE(contains(validationError(pulse), "gpio trigger params.pulse_us")) << validationError(pulse);
  EXPECT_TRUE(contains(gpioError(pulse), "gpio trigger params.pulse_us"));  // checked before the chip
}

TEST(GpioTrigger, AMissingChipIsNamed) {
  if (std::filesystem::exists("/dev/gpiochip0")) GTEST_SKIP() << "this machine has a GPIO chip 0";
  GpioTriggerParams params;
  params.chip = "gpiochip0";
  params.line = 17;
  const std::string error = gpioError(params);
  EXPECT_TRUE(contains(error, "GPIO chip 'gpiochip0': no such chip")) << error;
}

TEST(GpioTrigger, AMissingChipPathIsNamed) {
  GpioTriggerParams params;
  params.chip = "/dev/binpick-no-such-gpiochip";
  const std::string error = gpioError(params);
  EXPECT_TRUE(contains(error, "GPIO chip '/dev/binpick-no-such-gpiochip'")) << error;
}

TEST(GpioTrigger, ADeviceThatIsNoChipIsNamed) {
  GpioTriggerParams params;
  params.chip = "/dev/null";
  const std::string error = gpioError(params);
  EXPECT_TRUE(contains(error, "GPIO chip '/dev/null': not a GPIO chip")) << error;
}

TEST(FreeRunningProjector, ShowsPatternsWithoutAnyLine) {
  const auto projector = makeFreeRunningProjector();
  for (int k = 0; k < 3; ++k) EXPECT_NO_THROW(projector->showPattern(k));
  EXPECT_FALSE(projector->description().empty());
}

}  // namespace
}  // namespace binpick::acquisition
