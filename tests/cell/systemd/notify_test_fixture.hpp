#pragma once
// A short-named temporary directory for notify sockets: a socket path must fit into 108 bytes,
// which the per-test directories named after the test do not guarantee.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>

namespace binpick::test {

class NotifySocketTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "bpn-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    directory_ = pattern;
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::remove_all(directory_, ignored);
  }
  std::string socketPath() const { return directory_ + "/notify"; }

 private:
  std::string directory_;
};

}  // namespace binpick::test
