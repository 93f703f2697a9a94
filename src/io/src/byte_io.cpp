#include "byte_io.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "binpick/core/error.hpp"
#include "binpick/core/file.hpp"

namespace binpick::io::detail {

namespace fs = std::filesystem;

void fail(const std::string& path, const std::string& what) { throw core::Error(path + ": " + what); }

std::string readNonEmptyFileBytes(const std::string& path) {
  std::string bytes = core::readFile(path);
  if (bytes.empty()) fail(path, "the file is empty");
  return bytes;
}

void writeFileBytes(const std::string& path, std::string_view bytes) {
  std::ofstream stream(path, std::ios::binary | std::ios::trunc);
  if (!stream) fail(path, std::string("cannot be opened for writing: ") + std::strerror(errno));
  stream.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  stream.close();
  // close() flushes; a full disk shows up only here.
  if (!stream) {
    fail(path, "write failed after " + std::to_string(bytes.size()) + " bytes requested");
  }
}

void ByteCursor::failTruncated(std::size_t needed, const std::string& what) const {
  fail(path_, "file is truncated: " + what + " needs " + std::to_string(needed) + " more bytes but only " +
                  std::to_string(remaining()) + " remain");
}

}  // namespace binpick::io::detail
