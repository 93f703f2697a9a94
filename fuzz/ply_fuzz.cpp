// Fuzz target for the PLY reader (ascii, binary little and big endian; vertex, face and other
// elements, lists, obj_info organized): the input is the file.
// Built with libFuzzer (fuzz/run-libfuzzer.sh ply) and with the seeded driver
// (random_input_driver.cpp, test ply_fuzz_smoke); geometry_fuzz.hpp says what is checked.
#include "geometry_fuzz.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  binpick::fuzz::fuzzGeometryFile(".ply", data, size);
  return 0;
}
