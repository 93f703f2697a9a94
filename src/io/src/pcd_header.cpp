#include <limits>
#include <set>
#include <utility>

#include "byte_io.hpp"
#include "pcd_format.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

namespace {

// LZF encodes at most 264 bytes in a 3-byte back-reference, so no valid block expands more than
// ~90 times; anything claiming more is corrupt and must not be allocated.
constexpr std::uint64_t kMaxLzfExpansion = 100;
constexpr std::uint64_t kMaxFieldCount = 1u << 20;

class PcdHeaderParser {
 public:
  PcdHeaderParser(std::string_view bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  PcdHeader parse() {
    bool sawData = false;
    while (!sawData) {
      const std::vector<std::string_view> words = nextLineWords();
      if (words.empty() || words[0][0] == '#') continue;
      sawData = parseLine(words);
    }
    header_.bodyOffset = position_;
    header_.headerLines = lineNumber_;
    finish();
    return std::move(header_);
  }

 private:
  std::vector<std::string_view> nextLineWords() {
    const std::size_t end = bytes_.find('\n', position_);
    if (end == std::string_view::npos) {
      fail(path_, lineNumber_ == 0 ? "not a PCD file: no header lines"
                                   : "malformed PCD header: no DATA line (truncated or not a PCD file)");
    }
    TextCursor cursor(bytes_.substr(position_, end - position_));
    position_ = end + 1;
    ++lineNumber_;
    std::vector<std::string_view> words;
    for (std::string_view word = cursor.nextToken(); !word.empty(); word = cursor.nextToken()) {
      words.push_back(word);
    }
    return words;
  }

  // Returns true on the DATA line, which ends the header.
  bool parseLine(const std::vector<std::string_view>& words) {
    const std::string_view keyword = words[0];
    // A repeated line would make PCL and us disagree about the counts.
    if (!seenKeywords_.insert(std::string(keyword.substr(0, 40))).second) {
      malformed("'" + std::string(keyword.substr(0, 40)) + "' appears twice");
    }
    if (keyword == "VERSION") return false;
    if (keyword == "VIEWPOINT") {
      if (words.size() != 8) malformed("VIEWPOINT needs 7 values (tx ty tz qw qx qy qz)");
      return false;
    }
    if (keyword == "FIELDS" || keyword == "COLUMNS") {
      header_.fields.clear();
      for (std::size_t i = 1; i < words.size(); ++i) {
        header_.fields.push_back({std::string(words[i])});
      }
    } else if (keyword == "SIZE") {
      forEachFieldValue(words, [&](PcdField& field, std::string_view word) {
        field.size = positive(word, "SIZE");
        if (field.size != 1 && field.size != 2 && field.size != 4 && field.size != 8) {
          malformed("SIZE must be 1, 2, 4 or 8");
        }
      });
    } else if (keyword == "TYPE") {
      forEachFieldValue(words, [&](PcdField& field, std::string_view word) {
        if (word.size() != 1 || (word[0] != 'I' && word[0] != 'U' && word[0] != 'F')) {
          malformed("TYPE must be I, U or F");
        }
        field.type = word[0];
      });
    } else if (keyword == "COUNT") {
      forEachFieldValue(words, [&](PcdField& field, std::string_view word) {
        field.count = positive(word, "COUNT");
        if (field.count > kMaxFieldCount) malformed("COUNT is too large");
      });
    } else if (keyword == "WIDTH") {
      header_.width = single(words);
    } else if (keyword == "HEIGHT") {
      header_.height = single(words);
    } else if (keyword == "POINTS") {
      header_.points = single(words);
      sawPoints_ = true;
    } else if (keyword == "DATA") {
      parseData(words);
      return true;
    } else {
      fail(path_, lineNumber_ == 1 ? "not a PCD file: unexpected first line"
                                   : "malformed PCD header, line " + std::to_string(lineNumber_) +
                                         ": unknown keyword '" + std::string(keyword.substr(0, 40)) + "'");
    }
    return false;
  }

  template <typename Apply>
  void forEachFieldValue(const std::vector<std::string_view>& words, Apply apply) {
    if (words.size() != header_.fields.size() + 1) {
      malformed(std::string(words[0]) + " has " + std::to_string(words.size() - 1) + " values for " +
                std::to_string(header_.fields.size()) + " FIELDS");
    }
    for (std::size_t i = 0; i < header_.fields.size(); ++i) apply(header_.fields[i], words[i + 1]);
  }

  std::uint64_t single(const std::vector<std::string_view>& words) {
    if (words.size() != 2) malformed(std::string(words[0]) + " needs one value");
    std::int64_t value = 0;
    if (!parseInteger(words[1], value) || value < 0) {
      malformed(std::string(words[0]) + " must be an integer >= 0");
    }
    return static_cast<std::uint64_t>(value);
  }

  std::size_t positive(std::string_view word, const char* keyword) {
    std::int64_t value = 0;
    if (!parseInteger(word, value) || value <= 0) {
      malformed(std::string(keyword) + " values must be positive integers");
    }
    return static_cast<std::size_t>(value);
  }

  void parseData(const std::vector<std::string_view>& words) {
    if (words.size() != 2) malformed("expected 'DATA ascii|binary|binary_compressed'");
    if (words[1] == "ascii") {
      header_.data = PcdData::Ascii;
    } else if (words[1] == "binary") {
      header_.data = PcdData::Binary;
    } else if (words[1] == "binary_compressed") {
      header_.data = PcdData::BinaryCompressed;
    } else {
      malformed("unknown DATA '" + std::string(words[1].substr(0, 40)) + "'");
    }
  }

  [[noreturn]] void malformed(const std::string& what) const {
    fail(path_, "malformed PCD header, line " + std::to_string(lineNumber_) + ": " + what);
  }

  // A coordinate or normal field we read: one float or double.
  bool hasScalarFloat(std::string_view name) const {
    const PcdField* found = header_.find(name);
    if (!found) return false;
    if (found->type != 'F' || found->count != 1) {
      fail(path_, "PCD field '" + std::string(name) + "' must be a single float or double");
    }
    return true;
  }

  // The intensity field: one number of any type (sensors store it as float, uchar or ushort).
  bool hasScalarNumber(std::string_view name) const {
    const PcdField* found = header_.find(name);
    if (!found) return false;
    if (found->count != 1) {
      fail(path_, "PCD field '" + std::string(name) + "' must be a single number");
    }
    return true;
  }

  void finish() {
    if (header_.fields.empty()) fail(path_, "malformed PCD header: no FIELDS");
    for (const PcdField& f : header_.fields) {
      if (f.type == 'F' && f.size != 4 && f.size != 8) {
        fail(path_, "malformed PCD header: float field '" + f.name + "' has SIZE " + std::to_string(f.size));
      }
      header_.pointBytes += f.size * f.count;
    }
    if (header_.pointBytes > std::numeric_limits<std::uint32_t>::max()) {
      fail(path_, "malformed PCD header: " + std::to_string(header_.pointBytes) + " bytes per point");
    }
    checkFieldsWeRead();
    checkPointCount();
  }

  void checkFieldsWeRead() {
    for (const char* axis : {"x", "y", "z"}) {
      if (!hasScalarFloat(axis)) {
        fail(path_, std::string("the PCD file has no '") + axis + "' field");
      }
    }
    const int normals = hasScalarFloat("normal_x") + hasScalarFloat("normal_y") + hasScalarFloat("normal_z");
    if (normals != 0 && normals != 3) {
      fail(path_, "the PCD file has only some of normal_x, normal_y, normal_z");
    }
    header_.hasNormals = normals == 3;
    header_.hasIntensities = hasScalarNumber("intensity");
  }

  void checkPointCount() {
    constexpr std::uint64_t kMaxPoints = std::numeric_limits<int>::max();
    if (header_.width > kMaxPoints || header_.height > kMaxPoints) {
      fail(path_, "malformed PCD header: WIDTH or HEIGHT is too large");
    }
    const std::uint64_t gridPoints = header_.width * header_.height;
    if (!sawPoints_) header_.points = gridPoints;
    if (header_.points != gridPoints) {
      fail(path_, "malformed PCD header: WIDTH " + std::to_string(header_.width) + " x HEIGHT " +
                      std::to_string(header_.height) + " != POINTS " + std::to_string(header_.points));
    }
    if (header_.points > kMaxPoints) {
      fail(path_, "too many points (" + std::to_string(header_.points) + ")");
    }
  }

  std::string_view bytes_;
  const std::string& path_;
  std::size_t position_ = 0;
  std::size_t lineNumber_ = 0;
  bool sawPoints_ = false;
  std::set<std::string> seenKeywords_;
  PcdHeader header_;
};

std::string claimsMoreThanFile(const PcdHeader& header, std::uint64_t bodyBytes) {
  return "header claims " + std::to_string(header.points) + " points, more than the " + std::to_string(bodyBytes) +
         " bytes of data can hold (truncated or corrupt file)";
}

void checkBodySize(const PcdHeader& header, std::string_view bytes, const std::string& path) {
  const std::uint64_t bodyBytes = bytes.size() - header.bodyOffset;
  const std::uint64_t dataBytes = header.points * header.pointBytes;  // < 2^31 x 2^32
  if (header.data == PcdData::Binary) {
    if (dataBytes > bodyBytes) fail(path, claimsMoreThanFile(header, bodyBytes));
    return;
  }
  if (header.data == PcdData::Ascii) {
    std::uint64_t valuesPerPoint = 0;
    for (const PcdField& field : header.fields) valuesPerPoint += field.count;
    // Each value takes at least a digit and a separator; the last may lack the separator.
    if (header.points > (bodyBytes + 1) / (2 * valuesPerPoint)) {
      fail(path, claimsMoreThanFile(header, bodyBytes));
    }
    return;
  }
  if (bodyBytes < 8) fail(path, "file is truncated: binary_compressed data has no size words");
  const char* sizes = bytes.data() + header.bodyOffset;
  const auto compressed = loadScalar<std::uint32_t>(sizes, !kHostIsLittleEndian);
  const auto uncompressed = loadScalar<std::uint32_t>(sizes + 4, !kHostIsLittleEndian);
  if (compressed > bodyBytes - 8) {
    fail(path, "file is truncated: " + std::to_string(compressed) + " bytes of compressed data announced, " +
                   std::to_string(bodyBytes - 8) + " present");
  }
  // PCL would resize its buffer to whatever `uncompressed` says; only the size the header
  // implies, and only what LZF can actually produce from `compressed`, is accepted.
  if (uncompressed != dataBytes || uncompressed > std::uint64_t{compressed} * kMaxLzfExpansion) {
    fail(path, "corrupt binary_compressed data: " + std::to_string(compressed) + " compressed bytes for " +
                   std::to_string(uncompressed) + " uncompressed, but " + std::to_string(header.points) +
                   " points need " + std::to_string(dataBytes));
  }
}

}  // namespace

const PcdField* PcdHeader::find(std::string_view name) const {
  for (const PcdField& field : fields) {
    if (field.name == name) return &field;
  }
  return nullptr;
}

std::size_t PcdHeader::offsetOf(std::string_view name) const {
  std::size_t offset = 0;
  for (const PcdField& field : fields) {
    if (field.name == name) break;
    offset += field.size * field.count;
  }
  return offset;
}

PcdHeader checkPcdHeader(std::string_view bytes, const std::string& path) {
  PcdHeader header = PcdHeaderParser(bytes, path).parse();
  checkBodySize(header, bytes, path);
  return header;
}

}  // namespace binpick::io::detail
