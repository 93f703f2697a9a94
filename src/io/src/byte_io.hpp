#pragma once
// Internal: file loading and bounds-checked binary decoding shared by the format readers and
// writers. Every error is a core::Error whose message starts with the file path.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>

namespace binpick::io::detail {

// Throws core::Error("PATH: what").
[[noreturn]] void fail(const std::string& path, const std::string& what);

// core::readFile, and an empty file is an error: no format we read can be empty.
std::string readNonEmptyFileBytes(const std::string& path);
// Replaces the file's contents with `bytes`; throws when the file cannot be written completely.
void writeFileBytes(const std::string& path, std::string_view bytes);

constexpr bool kHostIsLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

// Decodes a T stored at `bytes` (any alignment), reversing the byte order when `swapBytes`.
template <typename T>
T loadScalar(const char* bytes, bool swapBytes) {
  static_assert(std::is_trivially_copyable_v<T>);
  char ordered[sizeof(T)];
  if (swapBytes) {
    std::reverse_copy(bytes, bytes + sizeof(T), ordered);
  } else {
    std::memcpy(ordered, bytes, sizeof(T));
  }
  T value;
  std::memcpy(&value, ordered, sizeof(T));
  return value;
}

// Stores `value` at `destination` in little-endian byte order, the order every binpick writer
// uses; returns the position after it.
template <typename T>
char* storeLittleEndian(char* destination, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::memcpy(destination, &value, sizeof(T));
  if (!kHostIsLittleEndian) std::reverse(destination, destination + sizeof(T));
  return destination + sizeof(T);
}

template <typename T>
void appendLittleEndian(std::string& out, T value) {
  char bytes[sizeof(T)];
  storeLittleEndian(bytes, value);
  out.append(bytes, sizeof(T));
}

// A read position inside a byte buffer that never reads past its end: running out of bytes is a
// "truncated" error naming the file and what was being read.
class ByteCursor {
 public:
  ByteCursor(std::string_view bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  std::size_t remaining() const { return bytes_.size() - position_; }

  // The next n bytes, then moves past them. `describe()` (e.g. "vertex 12") is only called when
  // the bytes are missing, so the common path builds no strings.
  template <typename Describe>
  const char* take(std::size_t n, Describe&& describe) {
    if (n > remaining()) failTruncated(n, describe());
    const char* start = bytes_.data() + position_;
    position_ += n;
    return start;
  }

 private:
  [[noreturn]] void failTruncated(std::size_t needed, const std::string& what) const;

  std::string_view bytes_;
  const std::string& path_;
  std::size_t position_ = 0;
};

}  // namespace binpick::io::detail
