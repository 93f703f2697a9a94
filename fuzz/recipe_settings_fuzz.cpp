// Fuzz target for a recipe's estimation settings (`settings:` of a recipe in binpickd.yaml,
// `binpick detect --config`; config/detection.yaml lists the keys): the input is the file, read
// by loadEstimationConfig, which must refuse a bad one with a core::Error naming it. Built with
// libFuzzer (fuzz/run-libfuzzer.sh recipe_settings) and with the seeded driver
// (random_input_driver.cpp, test recipe_settings_fuzz_smoke).
#include "binpick/estimation/config.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace binpick;
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string path = (fuzz::scratchDirectory() / "detection.yaml").string();
  fuzz::writeBytes(path, input);
  fuzz::readsOrRefuses("loadEstimationConfig", path, input, [&] { estimation::loadEstimationConfig(path); });
  return 0;
}
