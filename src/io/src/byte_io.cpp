#include "byte_io.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "binpick/core/error.hpp"

namespace binpick::io::detail {

namespace fs = std::filesystem;

void fail(const std::string& path, const std::string& what) { throw core::Error(path + ": " + what); }

namespace {

std::uint64_t regularFileSize(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) fail(path, "file does not exist");
  if (!fs::is_regular_file(status)) fail(path, "not a regular file");
  const std::uint64_t size = fs::file_size(path, error);
  if (error) fail(path, "cannot get the file size: " + error.message());
  return size;
}

}  // namespace

std::string readFileBytes(const std::string& path) {
  const std::uint64_t size = regularFileSize(path);
  std::ifstream stream(path, std::ios::binary);
  if (!stream) fail(path, std::string("cannot be opened: ") + std::strerror(errno));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  stream.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (static_cast<std::uint64_t>(stream.gcount()) != size) {
    fail(path, "read error: got " + std::to_string(stream.gcount()) + " of " + std::to_string(size) + " bytes");
  }
  return bytes;
}

std::string readNonEmptyFileBytes(const std::string& path) {
  std::string bytes = readFileBytes(path);
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
