// PCD reading: our checked header, then the body by its DATA kind.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "pcd_format.hpp"

namespace binpick::io::detail {

namespace {

// Where one scalar field sits in a record and how it is stored (x/y/z and normals are always
// float or double; intensity may be any type).
struct ScalarField {
  std::size_t offset = 0;
  char type = 'F';
  std::size_t size = 4;
};

ScalarField scalarField(const PcdHeader& header, const char* name) {
  const PcdField& field = *header.find(name);
  return {header.offsetOf(name), field.type, field.size};
}

float floatFrom(double value) {
  // Out-of-range double-to-float conversion is undefined; saturate so validation reports inf.
  if (value > std::numeric_limits<float>::max()) return std::numeric_limits<float>::infinity();
  if (value < -std::numeric_limits<float>::max()) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

// PCD binary values are in host byte order, as PCL reads and writes them.
template <typename Signed, typename Unsigned>
float integerAt(const char* bytes, bool isSigned) {
  return isSigned ? static_cast<float>(loadScalar<Signed>(bytes, false))
                  : static_cast<float>(loadScalar<Unsigned>(bytes, false));
}

float valueAt(const char* record, ScalarField field) {
  const char* bytes = record + field.offset;
  if (field.type == 'F') {
    return field.size == 8 ? floatFrom(loadScalar<double>(bytes, false)) : loadScalar<float>(bytes, false);
  }
  const bool isSigned = field.type == 'I';
  switch (field.size) {
    case 1: return integerAt<std::int8_t, std::uint8_t>(bytes, isSigned);
    case 2: return integerAt<std::int16_t, std::uint16_t>(bytes, isSigned);
    case 4: return integerAt<std::int32_t, std::uint32_t>(bytes, isSigned);
    default: return integerAt<std::int64_t, std::uint64_t>(bytes, isSigned);
  }
}

// Copies three fields of every record into `out` (already sized).
void copyVectors(const char* records, const PcdHeader& header, const char* const (&names)[3],
                 std::vector<Eigen::Vector3f>& out) {
  const ScalarField fields[3] = {scalarField(header, names[0]), scalarField(header, names[1]),
                                 scalarField(header, names[2])};
  const char* record = records;
  for (Eigen::Vector3f& vector : out) {
    vector = Eigen::Vector3f(valueAt(record, fields[0]), valueAt(record, fields[1]), valueAt(record, fields[2]));
    record += header.pointBytes;
  }
}

// Copies one field of every record into `out` (already sized).
void copyScalars(const char* records, const PcdHeader& header, const char* name, std::vector<float>& out) {
  const ScalarField field = scalarField(header, name);
  const char* record = records;
  for (float& value : out) {
    value = valueAt(record, field);
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
  if (header.hasIntensities) {
    cloud.intensities.resize(header.points);
    copyScalars(records, header, "intensity", cloud.intensities);
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
    case PcdData::Ascii: geometry.cloud = readPcdAsciiBody(body, header, path); break;
    case PcdData::Binary: geometry.cloud = readPcdBinaryRecords(body.data(), header); break;
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

}  // namespace binpick::io::detail
