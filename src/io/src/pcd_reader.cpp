// PCD reading: our checked header, then the body by its DATA kind. Only decompression needs PCL.
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "pcd_format.hpp"

namespace binpick::io_detail {

namespace {

// Where one float or double field sits in a record.
struct FloatField {
  std::size_t offset = 0;
  bool isDouble = false;
};

FloatField floatField(const PcdHeader& header, const char* name) {
  return {header.offsetOf(name), header.find(name)->size == 8};
}

float floatAt(const char* record, FloatField field) {
  if (!field.isDouble) {
    float value;
    std::memcpy(&value, record + field.offset, sizeof(value));
    return value;
  }
  double value;
  std::memcpy(&value, record + field.offset, sizeof(value));
  // Out-of-range double-to-float conversion is undefined; saturate so validation reports inf.
  if (value > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
  if (value < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

// Copies three fields of every record into `out` (already sized).
void copyVectors(const char* records, const PcdHeader& header, const char* const (&names)[3],
                 std::vector<Eigen::Vector3f>& out) {
  const FloatField fields[3] = {floatField(header, names[0]), floatField(header, names[1]),
                                floatField(header, names[2])};
  const char* record = records;
  for (Eigen::Vector3f& vector : out) {
    vector = Eigen::Vector3f(floatAt(record, fields[0]), floatAt(record, fields[1]),
                             floatAt(record, fields[2]));
    record += header.pointBytes;
  }
}

}  // namespace

PointCloud readPcdBinaryRecords(const char* records, const PcdHeader& header) {
  PointCloud cloud;
  cloud.points.resize(header.points);
  copyVectors(records, header, {"x", "y", "z"}, cloud.points);
  if (header.hasNormals) {
    cloud.normals.resize(header.points);
    copyVectors(records, header, {"normal_x", "normal_y", "normal_z"}, cloud.normals);
  }
  return cloud;
}

ModelGeometry loadPcd(const std::string& path) {
  const std::string bytes = readNonEmptyFileBytes(path);
  const PcdHeader header = checkPcdHeader(bytes, path);
  ModelGeometry geometry;
  if (header.points == 0) return geometry;
  const std::string_view body = std::string_view(bytes).substr(header.bodyOffset);
  switch (header.data) {
    case PcdData::Ascii:
      geometry.cloud = readPcdAsciiBody(body, header, path);
      break;
    case PcdData::Binary:
      geometry.cloud = readPcdBinaryRecords(body.data(), header);
      break;
    case PcdData::BinaryCompressed: {
      const std::vector<std::uint8_t> records = decompressPcdBody(bytes, header, path);
      geometry.cloud = readPcdBinaryRecords(reinterpret_cast<const char*>(records.data()), header);
      break;
    }
  }
  // Like PCL, a single row means unorganized: PCD cannot mark a one-row grid.
  if (header.height > 1) {
    geometry.cloud.width = static_cast<int>(header.width);
    geometry.cloud.height = static_cast<int>(header.height);
  }
  return geometry;
}

}  // namespace binpick::io_detail
