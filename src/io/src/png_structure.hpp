#pragma once
// Internal: a PNG file's chunk structure checked before decoding. libpng reports a truncated or
// corrupt file by printing its own message to stderr before OpenCV gives up; checking the
// signature, every chunk's length and CRC, and the final IEND chunk first lets the reader refuse
// such a file with one message of its own, and libpng only ever sees well-formed files.
#include <cstdint>
#include <string>
#include <string_view>

namespace binpick::io::detail {

// "" when `bytes` is a structurally sound PNG file, else what is wrong with it, e.g.
// "truncated: chunk IDAT at byte 57 needs 8192 bytes, the file ends after 4000".
std::string pngStructureDefect(std::string_view bytes);

// Width and height from the IHDR chunk of a file pngStructureDefect found sound: what decoding
// would allocate for, known before it does.
struct PngSize {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};
PngSize pngSize(std::string_view bytes);

}  // namespace binpick::io::detail
