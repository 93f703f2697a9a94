// PLY reader: ascii and binary (both byte orders) bodies through one element walker, templated on
// where the values come from. Vertices give points (+ normals, intensities), faces give
// fan-triangulated triangles, every other element is skipped by its declared types.
#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "binpick/core/file.hpp"
#include "byte_io.hpp"
#include "formats.hpp"
#include "ply_header.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

namespace {

// Which record is being read, for error messages.
struct RecordLocation {
  const std::string* element = nullptr;
  std::uint64_t index = 0;

  std::string describe() const { return *element + " " + std::to_string(index); }
};

// Converting an out-of-range double to float is undefined behaviour; saturate to inf instead so
// the finiteness checks report it.
float narrowToFloat(double value) {
  constexpr double kLargest = std::numeric_limits<float>::max();
  if (value > kLargest) return std::numeric_limits<float>::infinity();
  if (value < -kLargest) return -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

class BinarySource {
 public:
  BinarySource(std::string_view body, bool swapBytes, const std::string& path, const RecordLocation& location)
      : cursor_(body, path), swapBytes_(swapBytes), location_(location) {}

  float readFloat(PlyType type) { return floatAt(take(byteSize(type)), type); }

  float floatAt(const char* bytes, PlyType type) const {
    switch (type) {
      case PlyType::Float32: return loadScalar<float>(bytes, swapBytes_);
      case PlyType::Float64: return narrowToFloat(loadScalar<double>(bytes, swapBytes_));
      default: return static_cast<float>(integerAt(bytes, type));
    }
  }

  std::int64_t readInteger(PlyType type) { return integerAt(take(byteSize(type)), type); }

  bool swapsBytes() const { return swapBytes_; }

  // Binary records have no delimiters to check.
  void beginRecord() {}
  void endRecord() {}

  void skip(PlyType type, std::uint64_t count) {
    // count <= maxItems(type) was checked by the caller, so the product cannot overflow.
    take(static_cast<std::size_t>(count * byteSize(type)));
  }

  std::uint64_t maxItems(PlyType type) const { return cursor_.remaining() / byteSize(type); }

  // `count` records of `recordBytes` each, bounds-checked once. parsePlyHeader bounded
  // count x recordBytes by the file size, so the product cannot overflow.
  const char* takeRecords(std::uint64_t count, std::size_t recordBytes) {
    return cursor_.take(static_cast<std::size_t>(count * recordBytes),
                        [&] { return "the " + std::to_string(count) + " '" + *location_.element + "' records"; });
  }

 private:
  const char* take(std::size_t bytes) {
    return cursor_.take(bytes, [this] { return location_.describe(); });
  }

  std::int64_t integerAt(const char* bytes, PlyType type) const {
    switch (type) {
      case PlyType::Int8: return loadScalar<std::int8_t>(bytes, false);
      case PlyType::Uint8: return loadScalar<std::uint8_t>(bytes, false);
      case PlyType::Int16: return loadScalar<std::int16_t>(bytes, swapBytes_);
      case PlyType::Uint16: return loadScalar<std::uint16_t>(bytes, swapBytes_);
      case PlyType::Int32: return loadScalar<std::int32_t>(bytes, swapBytes_);
      case PlyType::Uint32: return loadScalar<std::uint32_t>(bytes, swapBytes_);
      default: return 0;  // float list counts and face indices are rejected before reading
    }
  }

  ByteCursor cursor_;
  bool swapBytes_;
  const RecordLocation& location_;
};

class AsciiSource {
 public:
  AsciiSource(std::string_view body, std::size_t firstLine, const std::string& path, const RecordLocation& location)
      : cursor_(body, firstLine), path_(path), location_(location) {}

  float readFloat(PlyType /*type*/) {
    const std::string_view token = next();
    float value = 0.0f;
    if (!parseFloat(token, value)) failValue(token, "a number");
    return value;
  }

  std::int64_t readInteger(PlyType /*type*/) {
    const std::string_view token = next();
    std::int64_t value = 0;
    if (!parseInteger(token, value)) failValue(token, "an integer");
    return value;
  }

  void skip(PlyType /*type*/, std::uint64_t count) {
    for (std::uint64_t i = 0; i < count; ++i) next();
  }

  // One record per line: a record that spills over or stops short means the values no longer
  // line up with the header, and reading on would silently shift every later value.
  void beginRecord() {
    cursor_.atEnd();  // moves to the record's first token, counting lines
    recordLine_ = cursor_.line();
  }

  void endRecord() {
    if (!cursor_.restOfLineIsBlank()) {
      fail(path_, "line " + std::to_string(recordLine_) + " (" + location_.describe() +
                      "): more values than the header declares");
    }
  }

  // Each value needs at least one character and a separator (the last may lack it).
  std::uint64_t maxItems(PlyType /*type*/) const { return (cursor_.remainingBytes() + 1) / 2; }

 private:
  std::string_view next() {
    const std::string_view token = cursor_.nextToken();
    if (token.empty()) {
      fail(path_, "file is truncated: it ends inside " + location_.describe());
    }
    if (cursor_.line() != recordLine_) {
      fail(path_, "line " + std::to_string(recordLine_) + " (" + location_.describe() +
                      "): fewer values than the header declares");
    }
    return token;
  }

  [[noreturn]] void failValue(std::string_view token, const char* expected) const {
    fail(path_, "line " + std::to_string(cursor_.line()) + " (" + location_.describe() + "): '" +
                    std::string(token.substr(0, 40)) + "' is not " + expected);
  }

  TextCursor cursor_;
  const std::string& path_;
  const RecordLocation& location_;
  std::size_t recordLine_ = 0;
};

// Values of one vertex record by slot: [x y z nx ny nz intensity].
constexpr int kVertexSlots = 7;
constexpr int kIntensitySlot = 6;
using VertexValues = float[kVertexSlots];

// Slot of each vertex property, or -1 for properties we skip.
struct VertexLayout {
  std::vector<int> slotOfProperty;
  bool hasNormals = false;
  bool hasIntensities = false;
};

// Index of the named vertex property, or -1; the values we read are never lists.
int scalarVertexProperty(const PlyElement& vertex, const char* name, const std::string& path) {
  const int property = vertex.find(name);
  if (property >= 0 && vertex.properties[property].isList) {
    fail(path, std::string("malformed PLY header: vertex property '") + name + "' is a list");
  }
  return property;
}

VertexLayout vertexLayoutOf(const PlyElement& vertex, const std::string& path) {
  static constexpr const char* kNames[kVertexSlots] = {"x", "y", "z", "nx", "ny", "nz", "intensity"};
  VertexLayout layout;
  layout.slotOfProperty.assign(vertex.properties.size(), -1);
  int normalsFound = 0;
  for (int slot = 0; slot < kVertexSlots; ++slot) {
    const int property = scalarVertexProperty(vertex, kNames[slot], path);
    if (property < 0) {
      if (slot < 3) {
        fail(path, std::string("the vertex element has no '") + kNames[slot] + "' property");
      }
      continue;
    }
    layout.slotOfProperty[property] = slot;
    if (slot == kIntensitySlot) {
      layout.hasIntensities = true;
    } else if (slot >= 3) {
      ++normalsFound;
    }
  }
  if (normalsFound != 0 && normalsFound != 3) {
    fail(path, "the vertex element has only some of nx, ny, nz; normals need all three");
  }
  layout.hasNormals = normalsFound == 3;
  return layout;
}

void resizeForVertices(const VertexLayout& layout, std::uint64_t count, PointCloud& cloud) {
  cloud.points.resize(count);
  if (layout.hasNormals) cloud.normals.resize(count);
  if (layout.hasIntensities) cloud.intensities.resize(count);
}

void storeVertex(const VertexValues& values, const VertexLayout& layout, std::uint64_t i, PointCloud& cloud) {
  cloud.points[i] = Eigen::Vector3f(values[0], values[1], values[2]);
  if (layout.hasNormals) cloud.normals[i] = Eigen::Vector3f(values[3], values[4], values[5]);
  if (layout.hasIntensities) cloud.intensities[i] = values[kIntensitySlot];
}

// The list property holding a face's vertex indices.
int faceIndexProperty(const PlyElement& face, const std::string& path) {
  int property = face.find("vertex_indices");
  if (property < 0) property = face.find("vertex_index");
  if (property < 0 || !face.properties[property].isList) {
    fail(path, "malformed PLY header: the face element has no 'vertex_indices' list");
  }
  if (!isInteger(face.properties[property].type)) {
    fail(path, "malformed PLY header: face vertex indices must have an integer type");
  }
  return property;
}

template <typename Source>
class BodyReader {
 public:
  BodyReader(Source& source, RecordLocation& location, const std::string& path)
      : source_(source), location_(location), path_(path) {}

  void readVertices(const PlyElement& element, PointCloud& cloud) {
    const VertexLayout layout = vertexLayoutOf(element, path_);
    resizeForVertices(layout, element.count, cloud);
    if constexpr (std::is_same_v<Source, BinarySource>) {
      if (!element.hasLists()) return readFixedSizeVertices(element, layout, cloud);
    }
    VertexValues values = {};
    for (std::uint64_t i = 0; i < element.count; ++i) {
      location_.index = i;
      source_.beginRecord();
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        const int slot = layout.slotOfProperty[p];
        if (slot >= 0) {
          values[slot] = source_.readFloat(element.properties[p].type);
        } else {
          skipProperty(element.properties[p]);
        }
      }
      source_.endRecord();
      storeVertex(values, layout, i, cloud);
    }
  }

  struct Field {
    std::size_t offset;
    PlyType type;
    int slot;
  };

  // Records of x, y, z as float in this order and nothing else: laid out as Eigen::Vector3f is.
  static bool isPackedXyz(const std::vector<Field>& fields, std::size_t recordBytes) {
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float));
    if (fields.size() != 3 || recordBytes != sizeof(Eigen::Vector3f)) return false;
    for (int slot = 0; slot < 3; ++slot) {
      const Field& field = fields[static_cast<std::size_t>(slot)];
      if (field.slot != slot || field.type != PlyType::Float32 || field.offset != slot * sizeof(float)) return false;
    }
    return true;
  }

  // Binary records without lists all have one size: one bounds check for the whole element,
  // then values decoded at precomputed offsets. This is the path of every camera-sized cloud.
  void readFixedSizeVertices(const PlyElement& element, const VertexLayout& layout, PointCloud& cloud) {
    std::vector<Field> fields;
    std::size_t recordBytes = 0;
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const PlyType type = element.properties[p].type;
      if (layout.slotOfProperty[p] >= 0) {
        fields.push_back({recordBytes, type, layout.slotOfProperty[p]});
      }
      recordBytes += byteSize(type);
    }
    const char* record = source_.takeRecords(element.count, recordBytes);
    if (isPackedXyz(fields, recordBytes) && !source_.swapsBytes()) {
      // binpick's own clouds (x, y, z as float, nothing else): the records are the points' bytes.
      // An element of no vertices has no buffer to copy into (memcpy must not see a null pointer).
      if (element.count == 0) return;
      std::memcpy(static_cast<void*>(cloud.points.data()), record, element.count * recordBytes);
      return;
    }
    VertexValues values = {};
    for (std::uint64_t i = 0; i < element.count; ++i, record += recordBytes) {
      for (const Field& field : fields) {
        values[field.slot] = source_.floatAt(record + field.offset, field.type);
      }
      storeVertex(values, layout, i, cloud);
    }
  }

  void readFaces(const PlyElement& element, std::uint64_t vertexCount, std::vector<Eigen::Vector3i>& triangles) {
    const int indexProperty = faceIndexProperty(element, path_);
    triangles.reserve(triangles.size() + element.count);
    std::vector<int> polygon;
    for (std::uint64_t i = 0; i < element.count; ++i) {
      location_.index = i;
      source_.beginRecord();
      for (std::size_t p = 0; p < element.properties.size(); ++p) {
        if (static_cast<int>(p) == indexProperty) {
          readPolygon(element.properties[p], vertexCount, polygon);
          appendFan(polygon, triangles);
        } else {
          skipProperty(element.properties[p]);
        }
      }
      source_.endRecord();
    }
  }

  void skipElement(const PlyElement& element) {
    for (std::uint64_t i = 0; i < element.count; ++i) {
      location_.index = i;
      source_.beginRecord();
      for (const PlyProperty& property : element.properties) skipProperty(property);
      source_.endRecord();
    }
  }

 private:
  // A list's length, checked against what the rest of the file can hold before anything is
  // allocated or skipped from it.
  std::uint64_t readListLength(const PlyProperty& property) {
    const std::int64_t length = source_.readInteger(property.countType);
    if (length < 0) {
      fail(path_, location_.describe() + " has a list of negative length " + std::to_string(length));
    }
    if (static_cast<std::uint64_t>(length) > source_.maxItems(property.type)) {
      fail(path_, "file is truncated: " + location_.describe() + " has a list of " + std::to_string(length) +
                      " items but the file ends before them");
    }
    return static_cast<std::uint64_t>(length);
  }

  void skipProperty(const PlyProperty& property) {
    source_.skip(property.type, property.isList ? readListLength(property) : 1);
  }

  void readPolygon(const PlyProperty& property, std::uint64_t vertexCount, std::vector<int>& polygon) {
    const std::uint64_t corners = readListLength(property);
    if (corners < 3) {
      fail(path_, location_.describe() + " has " + std::to_string(corners) + " vertices; a face needs at least 3");
    }
    polygon.resize(corners);
    for (int& corner : polygon) {
      const std::int64_t index = source_.readInteger(property.type);
      if (index < 0 || static_cast<std::uint64_t>(index) >= vertexCount) {
        fail(path_, location_.describe() + " refers to vertex " + std::to_string(index) + " but the file has " +
                        std::to_string(vertexCount) + " vertices");
      }
      corner = static_cast<int>(index);
    }
  }

  static void appendFan(const std::vector<int>& polygon, std::vector<Eigen::Vector3i>& triangles) {
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
      triangles.emplace_back(polygon[0], polygon[k], polygon[k + 1]);
    }
  }

  Source& source_;
  RecordLocation& location_;
  const std::string& path_;
};

const PlyElement* uniqueElement(const PlyHeader& header, const std::string& name, const std::string& path) {
  const PlyElement* found = nullptr;
  for (const PlyElement& element : header.elements) {
    if (element.name != name) continue;
    if (found) fail(path, "malformed PLY header: more than one '" + name + "' element");
    found = &element;
  }
  return found;
}

void applyGrid(const PlyHeader& header, PointCloud& cloud, const std::string& path) {
  if (!header.organized) return;
  const auto [width, height] = *header.organized;
  if (static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) != cloud.size()) {
    fail(path, "header says organized " + std::to_string(width) + " x " + std::to_string(height) +
                   " but the file has " + std::to_string(cloud.size()) + " vertices");
  }
  cloud.width = width;
  cloud.height = height;
}

template <typename Source>
ModelGeometry readBody(const PlyHeader& header, Source& source, RecordLocation& location, const std::string& path) {
  const PlyElement* vertices = uniqueElement(header, "vertex", path);
  uniqueElement(header, "face", path);
  if (!vertices) fail(path, "the file has no vertex element");
  if (vertices->count > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) {
    fail(path, "too many vertices (" + std::to_string(vertices->count) + ") for int indices");
  }
  ModelGeometry geometry;
  BodyReader<Source> reader(source, location, path);
  for (const PlyElement& element : header.elements) {
    location.element = &element.name;
    if (&element == vertices) {
      reader.readVertices(element, geometry.cloud);
    } else if (element.name == "face") {
      reader.readFaces(element, vertices->count, geometry.mesh.triangles);
    } else {
      reader.skipElement(element);
    }
  }
  applyGrid(header, geometry.cloud, path);
  if (!geometry.mesh.triangles.empty()) geometry.mesh.vertices = geometry.cloud.points;
  return geometry;
}

}  // namespace

ModelGeometry loadPly(const std::string& path) {
  // Mapped, not read into a string: a camera's cloud is 16 MB, and filling and copying a buffer of
  // it took as long as decoding it.
  const std::shared_ptr<const core::MappedFile> file = core::MappedFile::open(path);
  if (file->size() == 0) fail(path, "the file is empty");
  const std::string_view bytes(reinterpret_cast<const char*>(file->data()), file->size());
  const PlyHeader header = parsePlyHeader(bytes, path);
  const std::string_view body = bytes.substr(header.bodyOffset);
  RecordLocation location;
  if (header.encoding == PlyEncoding::Ascii) {
    AsciiSource source(body, header.headerLines + 1, path, location);
    return readBody(header, source, location, path);
  }
  const bool fileIsLittleEndian = header.encoding == PlyEncoding::BinaryLittleEndian;
  BinarySource source(body, fileIsLittleEndian != kHostIsLittleEndian, path, location);
  return readBody(header, source, location, path);
}

}  // namespace binpick::io::detail
