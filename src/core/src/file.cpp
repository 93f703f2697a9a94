#include "binpick/core/file.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "binpick/core/error.hpp"

namespace binpick::core {

namespace fs = std::filesystem;

namespace {

// PATH.tmp-PID-N: two processes (or threads) writing one path never share a temporary file.
std::string temporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> calls{0};
  return path + ".tmp-" + std::to_string(getpid()) + "-" + std::to_string(calls++);
}

[[noreturn]] void failWriting(const std::string& path, const std::string& reason) {
  throw Error(path + ": cannot write the file: " + reason);
}

void writeBytes(const std::string& path, const std::string& temporary, std::string_view bytes) {
  std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
  if (!file) failWriting(path, std::strerror(errno));
  file.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  file.close();  // flushes: a full disk shows here
  if (!file) failWriting(path, "writing " + std::to_string(bytes.size()) + " bytes failed");
}

void createParentDirectory(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  if (parent.empty()) return;
  std::error_code error;
  fs::create_directories(parent, error);
  if (error) failWriting(path, "cannot create " + parent.string() + ": " + error.message());
}

std::uint64_t regularFileSize(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw Error(path + ": the file does not exist");
  if (fs::is_directory(status)) throw Error(path + ": is a directory, not a regular file");
  if (!fs::is_regular_file(status)) throw Error(path + ": not a regular file");
  const std::uint64_t size = fs::file_size(path, error);
  if (error) throw Error(path + ": cannot get the file size: " + error.message());
  return size;
}

}  // namespace

// The size first, then one read of exactly that many bytes: much faster than streaming for large
// binary bodies, and a file that shrinks while being read is noticed.
std::string readFile(const std::string& path) {
  const std::uint64_t size = regularFileSize(path);
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw Error(path + ": cannot read the file: " + std::strerror(errno));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  stream.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (static_cast<std::uint64_t>(stream.gcount()) != size) {
    throw Error(path + ": cannot read the file: got " + std::to_string(stream.gcount()) + " of " +
                std::to_string(size) + " bytes");
  }
  return bytes;
}

void replaceFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  const std::string temporary = temporaryPathFor(path);
  std::error_code ignored;
  try {
    write(temporary);
  } catch (...) {
    fs::remove(temporary, ignored);
    throw;
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) {
    fs::remove(temporary, ignored);
    failWriting(path, error.message());
  }
}

void writeFileAtomically(const std::string& path, std::string_view bytes, ParentDirectory parent) {
  if (parent == ParentDirectory::Create) createParentDirectory(path);
  replaceFileAtomically(path, [&](const std::string& temporary) { writeBytes(path, temporary, bytes); });
}

std::shared_ptr<const MappedFile> MappedFile::open(const std::string& path) {
  regularFileSize(path);  // the same errors as readFile's for a missing file or a directory
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(path + ": cannot read the file: " + std::strerror(errno));
  struct stat info {};
  if (fstat(fd, &info) != 0) {
    const int reason = errno;
    ::close(fd);
    throw Error(path + ": cannot read the file: " + std::strerror(reason));
  }
  const auto size = static_cast<std::size_t>(info.st_size);
  void* data = nullptr;
  if (size > 0) data = mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
  const int reason = errno;
  ::close(fd);  // the mapping keeps the file
  if (data == MAP_FAILED) throw Error(path + ": cannot map the file: " + std::strerror(reason));
  return std::shared_ptr<const MappedFile>(new MappedFile(static_cast<const uint8_t*>(data), size));
}

MappedFile::~MappedFile() {
  if (data_ != nullptr) munmap(const_cast<uint8_t*>(data_), size_);
}

}  // namespace binpick::core
