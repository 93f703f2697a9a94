// Fuzz target for the STL reader (ascii and binary, told apart by the binary size): the input is
// the file.
// Built with libFuzzer (fuzz/run-libfuzzer.sh stl) and with the seeded driver
// (random_input_driver.cpp, test stl_fuzz_smoke); geometry_fuzz.hpp says what is checked.
#include "geometry_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  binpick::fuzz::fuzzGeometryFile(".stl", data, size);
  return 0;
}
