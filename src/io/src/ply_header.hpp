#pragma once
// Internal: the PLY header model and its parser, shared by the PLY reader and writer.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace binpick::io::detail {

enum class PlyType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

std::size_t byteSize(PlyType type);
bool isInteger(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // scalar type, or the item type of a list
  bool isList = false;
  PlyType countType = PlyType::Uint8;  // lists only
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;

  bool hasLists() const;
  // Index of the named property, or -1.
  int find(std::string_view propertyName) const;
};

enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyGridSize {
  int width = 0;
  int height = 0;
};

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::Ascii;
  std::vector<PlyElement> elements;
  std::optional<PlyGridSize> organized;  // from `obj_info organized WIDTH HEIGHT`
  std::size_t bodyOffset = 0;            // first byte after the end_header line
  std::size_t headerLines = 0;           // so ascii body errors can give file line numbers
};

// Parses and checks the header at the start of `bytes`, including that the element counts fit
// in the bytes that follow it, so callers may allocate from the counts.
PlyHeader parsePlyHeader(std::string_view bytes, const std::string& path);

}  // namespace binpick::io::detail
