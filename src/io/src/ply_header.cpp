#include "ply_header.hpp"

#include <limits>
#include <utility>

#include "byte_io.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

std::size_t byteSize(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::Uint8: return 1;
    case PlyType::Int16:
    case PlyType::Uint16: return 2;
    case PlyType::Int32:
    case PlyType::Uint32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

bool isInteger(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

bool PlyElement::hasLists() const {
  for (const PlyProperty& property : properties) {
    if (property.isList) return true;
  }
  return false;
}

int PlyElement::find(std::string_view propertyName) const {
  for (std::size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == propertyName) return static_cast<int>(i);
  }
  return -1;
}

namespace {

std::optional<PlyType> typeNamed(std::string_view name) {
  static constexpr std::pair<std::string_view, PlyType> kNames[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::Uint8},
      {"uint8", PlyType::Uint8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::Uint16},  {"uint16", PlyType::Uint16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::Uint32},     {"uint32", PlyType::Uint32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [typeName, type] : kNames) {
    if (typeName == name) return type;
  }
  return std::nullopt;
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  TextCursor cursor(line);
  for (std::string_view word = cursor.nextToken(); !word.empty(); word = cursor.nextToken()) {
    words.push_back(word);
  }
  return words;
}

// Parses one header line at a time; knows the line number for messages.
class HeaderParser {
 public:
  HeaderParser(std::string_view bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  PlyHeader parse() {
    // Checked on the raw bytes so that binary garbage is named as such, not as a bad header.
    if (bytes_.substr(0, 4) != "ply\n" && bytes_.substr(0, 5) != "ply\r\n") {
      fail(path_, "not a PLY file: it does not start with a 'ply' line");
    }
    nextLine();
    bool sawFormat = false;
    for (;;) {
      const std::string_view line = nextLine();
      const std::vector<std::string_view> words = splitWords(line);
      if (words.empty()) continue;
      const std::string_view keyword = words[0];
      if (keyword == "end_header") break;
      if (keyword == "comment") continue;
      if (keyword == "format") {
        parseFormat(words);
        sawFormat = true;
      } else if (keyword == "obj_info") {
        parseObjInfo(words);
      } else if (keyword == "element") {
        parseElement(words);
      } else if (keyword == "property") {
        parseProperty(words);
      } else {
        malformed("unknown keyword '" + std::string(keyword) + "'");
      }
    }
    if (!sawFormat) fail(path_, "malformed PLY header: no 'format' line");
    header_.bodyOffset = position_;
    header_.headerLines = lineNumber_;
    return std::move(header_);
  }

 private:
  // The next line without its line ending; a header that never reaches end_header is an error
  // rather than a scan through a whole binary file.
  std::string_view nextLine() {
    const std::size_t end = bytes_.find('\n', position_);
    if (end == std::string_view::npos) {
      fail(path_, "malformed PLY header: no 'end_header' line (truncated or not a PLY file)");
    }
    std::string_view line = bytes_.substr(position_, end - position_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    position_ = end + 1;
    ++lineNumber_;
    return line;
  }

  [[noreturn]] void malformed(const std::string& what) const {
    fail(path_, "malformed PLY header, line " + std::to_string(lineNumber_) + ": " + what);
  }

  PlyType type(std::string_view name) const {
    const std::optional<PlyType> parsed = typeNamed(name);
    if (!parsed) malformed("unknown property type '" + std::string(name) + "'");
    return *parsed;
  }

  void parseFormat(const std::vector<std::string_view>& words) {
    if (words.size() != 3) malformed("expected 'format ENCODING 1.0'");
    if (words[1] == "ascii") {
      header_.encoding = PlyEncoding::Ascii;
    } else if (words[1] == "binary_little_endian") {
      header_.encoding = PlyEncoding::BinaryLittleEndian;
    } else if (words[1] == "binary_big_endian") {
      header_.encoding = PlyEncoding::BinaryBigEndian;
    } else {
      malformed("unknown format '" + std::string(words[1]) + "'");
    }
  }

  // Only `obj_info organized WIDTH HEIGHT` means something to us; other obj_info is free text.
  void parseObjInfo(const std::vector<std::string_view>& words) {
    if (words.size() < 2 || words[1] != "organized") return;
    std::int64_t width = 0;
    std::int64_t height = 0;
    if (words.size() != 4 || !parseInteger(words[2], width) || !parseInteger(words[3], height) || width <= 0 ||
        height <= 0 || width > std::numeric_limits<int>::max() || height > std::numeric_limits<int>::max()) {
      malformed("expected 'obj_info organized WIDTH HEIGHT' with positive integers");
    }
    header_.organized = PlyGridSize{static_cast<int>(width), static_cast<int>(height)};
  }

  void parseElement(const std::vector<std::string_view>& words) {
    std::int64_t count = 0;
    if (words.size() != 3 || !parseInteger(words[2], count) || count < 0) {
      malformed("expected 'element NAME COUNT' with a count >= 0");
    }
    PlyElement element;
    element.name = std::string(words[1]);
    element.count = static_cast<std::uint64_t>(count);
    header_.elements.push_back(std::move(element));
  }

  void parseProperty(const std::vector<std::string_view>& words) {
    if (header_.elements.empty()) malformed("property before any element");
    PlyProperty property;
    if (words.size() == 5 && words[1] == "list") {
      property.isList = true;
      property.countType = type(words[2]);
      property.type = type(words[3]);
      property.name = std::string(words[4]);
      if (!isInteger(property.countType)) malformed("a list count must have an integer type");
    } else if (words.size() == 3) {
      property.type = type(words[1]);
      property.name = std::string(words[2]);
    } else {
      malformed("expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
    }
    header_.elements.back().properties.push_back(std::move(property));
  }

  std::string_view bytes_;
  const std::string& path_;
  std::size_t position_ = 0;
  std::size_t lineNumber_ = 0;
  PlyHeader header_;
};

// Fewest bytes one record can occupy: binary values have fixed sizes (lists at least their
// count), and every ascii value takes at least a digit and a separator.
std::uint64_t minimumRecordBytes(const PlyElement& element, PlyEncoding encoding) {
  std::uint64_t bytes = 0;
  for (const PlyProperty& property : element.properties) {
    if (encoding == PlyEncoding::Ascii) {
      bytes += 2;
    } else {
      bytes += byteSize(property.isList ? property.countType : property.type);
    }
  }
  return bytes;
}

// Rejects counts the file cannot hold before anyone allocates from them (a corrupt header
// claiming 10^12 vertices must fail here, not in operator new).
void checkCountsFitBody(const PlyHeader& header, std::uint64_t bodyBytes, const std::string& path) {
  // The last ascii value may lack its trailing separator.
  const std::uint64_t budget = bodyBytes + (header.encoding == PlyEncoding::Ascii ? 1 : 0);
  std::uint64_t used = 0;
  for (const PlyElement& element : header.elements) {
    if (element.count == 0) continue;
    const std::uint64_t recordBytes = minimumRecordBytes(element, header.encoding);
    if (recordBytes == 0) {
      fail(path, "malformed PLY header: element '" + element.name + "' has no properties");
    }
    if (element.count > (budget - used) / recordBytes) {
      fail(path, "header claims " + std::to_string(element.count) + " '" + element.name + "' elements, more than the " +
                     std::to_string(bodyBytes) + " bytes of data can hold (truncated or corrupt file)");
    }
    used += element.count * recordBytes;
  }
}

}  // namespace

PlyHeader parsePlyHeader(std::string_view bytes, const std::string& path) {
  PlyHeader header = HeaderParser(bytes, path).parse();
  checkCountsFitBody(header, bytes.size() - header.bodyOffset, path);
  return header;
}

}  // namespace binpick::io::detail
