// Fuzz target for the hand-eye result file binpickd.yaml may name (`hand_eye: {file: ...}`,
// written by `binpick calibrate hand-eye`): the input is that file, read by loadCellConfig with
// a valid binpickd.yaml (cell_files.hpp), which must refuse a bad one with a core::Error naming
// it. Built with libFuzzer (fuzz/run-libfuzzer.sh hand_eye_file) and with the seeded driver
// (random_input_driver.cpp, test hand_eye_file_fuzz_smoke).
#include "cell_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  binpick::fuzz::fuzzCellFile("hand_eye.yaml", binpick::fuzz::kHandEyeFile, data, size);
  return 0;
}
