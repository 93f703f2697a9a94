#pragma once
// What bad input throws: every stage reports it as a core::Error whose message names what was
// wrong, and the tests check that message.
#include <gtest/gtest.h>

#include <string>

#include "binpick/core/error.hpp"

namespace binpick::test {

// The message of the core::Error `action` throws, or "" when it throws none.
template <typename Action>
std::string thrownMessage(Action&& action) {
  try {
    action();
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

// Succeeds when `action` throws a core::Error whose message contains `text`.
template <typename Action>
::testing::AssertionResult throwsNaming(Action&& action, const std::string& text) {
  try {
    action();
  } catch (const core::Error& error) {
    const std::string message = error.what();
    if (message.find(text) == std::string::npos) {
      return ::testing::AssertionFailure() << "message lacks '" << text << "': " << message;
    }
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

}  // namespace binpick::test
