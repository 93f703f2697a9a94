// PCD ascii bodies, parsed strictly here rather than by PCL (which reads unparseable values as 0
// and skips malformed lines with only a warning).
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "pcd_format.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

namespace {

// Values of one line by slot: [x y z nx ny nz intensity].
constexpr int kPointSlots = 7;
constexpr int kIntensitySlot = 6;
using PointValues = float[kPointSlots];

// Slot of each value within a line, -1 for values we skip.
std::vector<int> slotOfValues(const PcdHeader& header) {
  static constexpr const char* kNames[kPointSlots] = {"x", "y", "z", "normal_x", "normal_y", "normal_z", "intensity"};
  std::vector<int> slots;
  for (const PcdField& field : header.fields) {
    int slot = -1;
    for (int candidate = 0; candidate < kPointSlots; ++candidate) {
      if (field.name == kNames[candidate]) slot = candidate;
    }
    for (std::size_t c = 0; c < field.count; ++c) slots.push_back(slot);
  }
  return slots;
}

class AsciiBodyParser {
 public:
  AsciiBodyParser(std::string_view body, const PcdHeader& header, const std::string& path)
      : body_(body),
        header_(header),
        path_(path),
        slots_(slotOfValues(header)),
        valuesPerLine_(slots_.size()),
        lineNumber_(header.headerLines) {}

  PointCloud parse() {
    PointCloud cloud;
    cloud.points.resize(header_.points);
    if (header_.hasNormals) cloud.normals.resize(header_.points);
    if (header_.hasIntensities) cloud.intensities.resize(header_.points);
    for (std::size_t point = 0; point < header_.points; ++point) {
      const std::string_view line = nextNonEmptyLine(point);
      PointValues values = {};
      parseLine(line, point, values);
      store(values, point, cloud);
    }
    return cloud;
  }

 private:
  std::string_view nextNonEmptyLine(std::size_t point) {
    for (;;) {
      if (position_ >= body_.size()) {
        fail(path_, "file is truncated: it ends before point " + std::to_string(point) + " of " +
                        std::to_string(header_.points));
      }
      std::size_t end = body_.find('\n', position_);
      if (end == std::string_view::npos) end = body_.size();
      const std::string_view line = body_.substr(position_, end - position_);
      position_ = end + 1;
      ++lineNumber_;
      if (line.find_first_not_of(" \t\r") != std::string_view::npos) return line;
    }
  }

  // The count is checked first: a line with too few or too many values means the file is out of
  // step, and its values should not be trusted.
  void parseLine(std::string_view line, std::size_t point, PointValues& values) const {
    std::vector<std::string_view> tokens;
    TextCursor cursor(line);
    for (std::string_view token = cursor.nextToken(); !token.empty(); token = cursor.nextToken()) {
      tokens.push_back(token);
    }
    if (tokens.size() != valuesPerLine_) {
      failAt(point, std::to_string(tokens.size()) + " values but the header declares " +
                        std::to_string(valuesPerLine_) + " per point");
    }
    for (std::size_t i = 0; i < tokens.size(); ++i) {
      const int slot = slots_[i];
      if (slot >= 0 && !parseFloat(tokens[i], values[slot])) {
        failAt(point, "'" + std::string(tokens[i].substr(0, 40)) + "' is not a number");
      }
    }
  }

  void store(const PointValues& values, std::size_t point, PointCloud& cloud) const {
    cloud.points[point] = Eigen::Vector3f(values[0], values[1], values[2]);
    if (header_.hasNormals) {
      cloud.normals[point] = Eigen::Vector3f(values[3], values[4], values[5]);
    }
    if (header_.hasIntensities) cloud.intensities[point] = values[kIntensitySlot];
  }

  [[noreturn]] void failAt(std::size_t point, const std::string& what) const {
    fail(path_, "line " + std::to_string(lineNumber_) + " (point " + std::to_string(point) + "): " + what);
  }

  std::string_view body_;
  const PcdHeader& header_;
  const std::string& path_;
  std::vector<int> slots_;
  std::size_t valuesPerLine_ = 0;
  std::size_t position_ = 0;
  std::size_t lineNumber_;
};

}  // namespace

PointCloud readPcdAsciiBody(std::string_view body, const PcdHeader& header, const std::string& path) {
  return AsciiBodyParser(body, header, path).parse();
}

}  // namespace binpick::io::detail
