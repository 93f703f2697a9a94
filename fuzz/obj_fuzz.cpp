// Fuzz target for the OBJ reader (v and f lines, negative and slashed indices): the input is the
// file.
// Built with libFuzzer (fuzz/run-libfuzzer.sh obj) and with the seeded driver
// (random_input_driver.cpp, test obj_fuzz_smoke); geometry_fuzz.hpp says what is checked.
#include "geometry_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  binpick::fuzz::fuzzGeometryFile(".obj", data, size);
  return 0;
}
