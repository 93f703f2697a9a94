#pragma once
// A fresh temporary directory per test, removed afterwards, so that tests writing files may run in
// parallel (ctest runs each test in its own process, possibly at the same time).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <string>

namespace binpick::test {

class TempDirectoryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "binpick_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
                       std::to_string(::getpid()) + "_" + std::to_string(counter++);
    std::replace(name.begin(), name.end(), '/', '_');  // parameterised test names contain '/'
    directory_ = std::filesystem::path(::testing::TempDir()) / name;
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::remove_all(directory_, ignored);
  }

  std::string pathOf(const std::string& name) const { return (directory_ / name).string(); }
  std::string root() const { return directory_.string(); }

 private:
  std::filesystem::path directory_;
};

}  // namespace binpick::test
