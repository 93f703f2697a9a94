#pragma once
// Shared by the file-reader fuzz targets: a scratch directory of the process to write the input
// into, and the rule every reader must keep: bad input is a core::Error that names the file,
// never another exception. A broken rule aborts with the reader's name, what it threw and the
// input, so that both libFuzzer and the seeded driver (random_input_driver.cpp) report it.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::fuzz {

// The input bytes in C escapes, cut after `limit` bytes, for reports.
inline std::string escapedBytes(const std::string& bytes, std::size_t limit = 2000) {
  std::string text;
  char hex[8];
  for (std::size_t i = 0; i < bytes.size() && i < limit; ++i) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      text += static_cast<char>(c);
    } else {
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      text += hex;
    }
  }
  if (bytes.size() > limit) text += "... (" + std::to_string(bytes.size()) + " bytes)";
  return text;
}

[[noreturn]] inline void reportFinding(const std::string& reader, const std::string& what, const std::string& input) {
  std::fprintf(stderr, "%s: %s\n  input: \"%s\"\n", reader.c_str(), what.c_str(), escapedBytes(input).c_str());
  std::abort();
}

inline void require(bool ok, const std::string& reader, const std::string& invariant, const std::string& input) {
  if (!ok) reportFinding(reader, "invariant violated: " + invariant, input);
}

// A fresh directory for this process, removed when it exits normally (a crash leaves it, with
// the input that caused it).
inline const std::filesystem::path& scratchDirectory() {
  static const std::filesystem::path directory = [] {
    const char* base = std::getenv("TMPDIR");
    std::string pattern = std::string(base && *base ? base : "/tmp") + "/binpick-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) {
      std::perror("binpick fuzz: cannot create a scratch directory");
      std::abort();
    }
    static const std::string created = pattern;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(created, ignored);
    });
    return std::filesystem::path(pattern);
  }();
  return directory;
}

// A new file each time: rewriting one in place makes ext4 flush it to disk on close (its guard
// against truncate-and-rewrite), which would make each input take milliseconds.
inline void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  std::ofstream stream(path, std::ios::binary);
  stream.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!stream) {
    std::fprintf(stderr, "binpick fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

// Runs `read` (which reads the input from the file it was written to). Returns true when the
// reader accepted the input, false when it refused it with a core::Error naming `path`; any
// other exception, or an error that does not name the file, is a finding.
template <typename Read>
bool readsOrRefuses(const std::string& reader, const std::string& path, const std::string& input, Read&& read) {
  try {
    read();
    return true;
  } catch (const core::Error& error) {
    const std::string message = error.what();
    if (message.find(path) == std::string::npos) {
      reportFinding(reader, "core::Error without the file's name: " + message, input);
    }
    return false;
  } catch (const std::exception& error) {
    reportFinding(reader, std::string("threw a non-core::Error exception: ") + error.what(), input);
  } catch (...) {
    reportFinding(reader, "threw something that is not a std::exception", input);
  }
}

}  // namespace binpick::fuzz
