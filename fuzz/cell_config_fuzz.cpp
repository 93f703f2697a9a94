// Fuzz target for binpickd's settings file (binpickd.yaml): the input is the file, read by
// loadCellConfig in a directory that also holds the grasps file and hand-eye result the seeds
// name (cell_files.hpp). Every key is checked there: a bad file must be refused with a
// core::Error naming it, never another exception, a crash, or work and memory sized by a value in
// it. Built with libFuzzer (fuzz/run-libfuzzer.sh cell_config) and with the seeded driver
// (random_input_driver.cpp, test cell_config_fuzz_smoke).
#include "cell_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  binpick::fuzz::fuzzCellFile("binpickd.yaml", binpick::fuzz::kSettingsFile, data, size);
  return 0;
}
