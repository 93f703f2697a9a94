// Prints the directory of the shared rig calibration test data, rendering it first if needed:
// how the command-line test finds the same views as the library tests.
#include <exception>
#include <iostream>

#include "rig_test_data.hpp"

int main() {
  try {
    std::cout << binpick::test::rigTestData().directory << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
