// Fuzz target for a recipe's grasps file (`binpick grasps` writes it): the input is the file a
// valid binpickd.yaml names (cell_files.hpp), read by loadCellConfig, which must refuse a bad one
// with a core::Error naming it. Built with libFuzzer (fuzz/run-libfuzzer.sh grasps_file) and with
// the seeded driver (random_input_driver.cpp, test grasps_file_fuzz_smoke).
#include "cell_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  binpick::fuzz::fuzzCellFile("part.grasps.yaml", binpick::fuzz::kGraspsFile, data, size);
  return 0;
}
