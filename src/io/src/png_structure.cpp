// PNG chunk walk: signature, then length / type / data / CRC-32 per chunk up to IEND.
#include "png_structure.hpp"

#include <array>
#include <cstdint>

namespace binpick::io::detail {
namespace {

constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);
constexpr std::size_t kChunkOverhead = 12;  // length, type, CRC: 4 bytes each
constexpr uint32_t kHeaderLength = 13;      // IHDR: width, height, depth, colour, 3 methods
constexpr std::size_t kWidthAt = 16;        // after the signature, IHDR's length and type

// CRC-32 as PNG defines it (ISO 3309, polynomial 0xEDB88320, reflected), table-driven.
std::array<uint32_t, 256> crcTable() {
  std::array<uint32_t, 256> table{};
  for (uint32_t n = 0; n < 256; ++n) {
    uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[n] = c;
  }
  return table;
}

uint32_t crc32(std::string_view bytes) {
  static const std::array<uint32_t, 256> table = crcTable();
  uint32_t c = 0xFFFFFFFFu;
  for (const char byte : bytes) c = table[(c ^ static_cast<uint8_t>(byte)) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

uint32_t bigEndian32(std::string_view bytes, std::size_t at) {
  uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | static_cast<uint8_t>(bytes[at + i]);
  return value;
}

std::string printableType(std::string_view type) {
  std::string text;
  for (const char c : type) text += (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ? c : '?';
  return text;
}

}  // namespace

std::string pngStructureDefect(std::string_view bytes) {
  if (bytes.substr(0, kSignature.size()) != kSignature) return "not a PNG file (no PNG signature)";
  std::size_t at = kSignature.size();
  bool first = true;
  while (true) {
    if (bytes.size() - at < kChunkOverhead) {
      return "truncated: the file ends at byte " + std::to_string(bytes.size()) + " before the IEND chunk";
    }
    const uint32_t length = bigEndian32(bytes, at);
    const std::string type = printableType(bytes.substr(at + 4, 4));
    const std::string where = "chunk " + type + " at byte " + std::to_string(at);
    if (first && type != "IHDR") return "corrupt: the first chunk is " + type + ", not IHDR";
    if (first && length != kHeaderLength) {
      return "corrupt: the IHDR chunk holds " + std::to_string(length) + " bytes, not " + std::to_string(kHeaderLength);
    }
    first = false;
    if (length > bytes.size() - at - kChunkOverhead) {
      return "truncated: " + where + " needs " + std::to_string(length + kChunkOverhead) +
             " bytes, the file ends after " + std::to_string(bytes.size() - at);
    }
    const std::string_view typed_data = bytes.substr(at + 4, 4 + length);
    if (crc32(typed_data) != bigEndian32(bytes, at + 8 + length)) return "corrupt: " + where + " fails its CRC check";
    at += kChunkOverhead + length;
    if (type == "IEND") return "";
  }
}

PngSize pngSize(std::string_view bytes) {
  return {bigEndian32(bytes, kWidthAt), bigEndian32(bytes, kWidthAt + 4)};
}

}  // namespace binpick::io::detail
