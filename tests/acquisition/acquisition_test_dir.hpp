#pragma once
// The acquisition tests' temporary directory per test (tests/common).
#include "temp_directory_test.hpp"

namespace binpick::acquisition::testing {

using TempDirTest = binpick::test::TempDirectoryTest;

}  // namespace binpick::acquisition::testing
