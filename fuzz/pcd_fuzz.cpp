// Fuzz target for the PCD reader (ascii, binary and binary_compressed (LZF); fields of any size,
// type and count): the input is the file.
// Built with libFuzzer (fuzz/run-libfuzzer.sh pcd) and with the seeded driver
// (random_input_driver.cpp, test pcd_fuzz_smoke); geometry_fuzz.hpp says what is checked.
#include "geometry_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  binpick::fuzz::fuzzGeometryFile(".pcd", data, size);
  return 0;
}
