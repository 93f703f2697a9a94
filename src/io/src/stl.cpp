// STL reader and writer. STL stores every triangle with its own three corners, so the reader
// merges bit-identical corners into shared vertices; the mesh then has real connectivity.
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

namespace {

constexpr std::size_t kBinaryHeaderBytes = 84;    // 80 free bytes + uint32 triangle count
constexpr std::size_t kBinaryTriangleBytes = 50;  // normal, 3 corners, uint16 attribute

// Merges corners whose float bits are identical (after folding -0 into +0).
class VertexMerger {
 public:
  explicit VertexMerger(TriangleMesh& mesh, std::size_t expectedCorners) : mesh_(mesh) {
    indexOf_.reserve(expectedCorners / 2);
  }

  int indexOf(const Eigen::Vector3f& corner) {
    const Eigen::Vector3f folded = corner + Eigen::Vector3f::Zero();  // -0 + 0 == +0
    Key key;
    std::memcpy(key.data(), folded.data(), sizeof(key));
    const auto [entry, inserted] = indexOf_.try_emplace(key, static_cast<int>(mesh_.vertices.size()));
    if (inserted) mesh_.vertices.push_back(folded);
    return entry->second;
  }

 private:
  using Key = std::array<std::uint32_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& key) const {
      std::uint64_t hash = 1469598103934665603ull;
      for (std::uint32_t word : key) hash = (hash ^ word) * 1099511628211ull;
      return static_cast<std::size_t>(hash ^ (hash >> 29));
    }
  };

  TriangleMesh& mesh_;
  std::unordered_map<Key, int, KeyHash> indexOf_;
};

// NaN corners cannot be merged meaningfully (NaN != NaN), so they are rejected here, by facet.
void addFacet(const std::array<Eigen::Vector3f, 3>& corners, std::size_t facet, VertexMerger& merger,
              TriangleMesh& mesh, const std::string& path) {
  Eigen::Vector3i triangle;
  for (int c = 0; c < 3; ++c) {
    if (!corners[c].allFinite()) {
      fail(path, "facet " + std::to_string(facet) + " has a non-finite vertex " + describePoint(corners[c]));
    }
    triangle[c] = merger.indexOf(corners[c]);
  }
  mesh.triangles.push_back(triangle);
}

bool startsWithSolid(std::string_view bytes) {
  TextCursor cursor(bytes.substr(0, 256));
  return equalsIgnoringCase(cursor.nextToken(), "solid");
}

// Binary files are identified by their exact size, since many binary exporters also begin
// the free header with "solid".
bool hasBinaryStlSize(std::string_view bytes) {
  if (bytes.size() < kBinaryHeaderBytes) return false;
  const auto count = loadScalar<std::uint32_t>(bytes.data() + 80, !kHostIsLittleEndian);
  return bytes.size() == kBinaryHeaderBytes + std::uint64_t{count} * kBinaryTriangleBytes;
}

// A text file has no NUL bytes; a binary STL almost always does (in its count or its floats).
bool looksLikeText(std::string_view bytes) { return bytes.substr(0, 4096).find('\0') == std::string_view::npos; }

TriangleMesh readBinaryStl(std::string_view bytes, const std::string& path) {
  const std::size_t count = (bytes.size() - kBinaryHeaderBytes) / kBinaryTriangleBytes;
  TriangleMesh mesh;
  mesh.triangles.reserve(count);
  VertexMerger merger(mesh, 3 * count);
  const char* record = bytes.data() + kBinaryHeaderBytes;
  for (std::size_t facet = 0; facet < count; ++facet, record += kBinaryTriangleBytes) {
    std::array<Eigen::Vector3f, 3> corners;
    const char* value = record + 3 * sizeof(float);  // the stored normal is not needed
    for (auto& corner : corners) {
      for (int axis = 0; axis < 3; ++axis, value += sizeof(float)) {
        corner[axis] = loadScalar<float>(value, !kHostIsLittleEndian);
      }
    }
    addFacet(corners, facet, merger, mesh, path);
  }
  return mesh;
}

// Token-level parser for `solid NAME / facet normal ... / outer loop / vertex x y z (x3) /
// endloop / endfacet / endsolid NAME`, keywords case-insensitive, several solids allowed.
class AsciiStlParser {
 public:
  AsciiStlParser(std::string_view text, const std::string& path)
      : cursor_(text), path_(path), merger_(mesh_, text.size() / 40) {}

  TriangleMesh parse() {
    while (!cursor_.atEnd()) {
      expect("solid");
      cursor_.skipRestOfLine();  // the solid's name, possibly several words
      parseFacets();
    }
    return std::move(mesh_);
  }

 private:
  void parseFacets() {
    for (;;) {
      const std::string_view keyword = next("'facet' or 'endsolid'");
      if (equalsIgnoringCase(keyword, "endsolid")) {
        cursor_.skipRestOfLine();
        return;
      }
      if (!equalsIgnoringCase(keyword, "facet")) unexpected(keyword, "'facet' or 'endsolid'");
      parseFacet();
    }
  }

  void parseFacet() {
    expect("normal");
    readVector();  // recomputed from the winding when needed; stored normals are often wrong
    expect("outer");
    expect("loop");
    std::array<Eigen::Vector3f, 3> corners;
    for (auto& corner : corners) {
      expect("vertex");
      corner = readVector();
    }
    expect("endloop");
    expect("endfacet");
    addFacet(corners, mesh_.triangles.size(), merger_, mesh_, path_);
  }

  Eigen::Vector3f readVector() {
    Eigen::Vector3f vector;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string_view token = next("a number");
      if (!parseFloat(token, vector[axis])) unexpected(token, "a number");
    }
    return vector;
  }

  std::string_view next(const char* expected) {
    const std::string_view token = cursor_.nextToken();
    if (token.empty()) {
      fail(path_, "file is truncated: it ends at line " + std::to_string(cursor_.line()) + " where " + expected +
                      " was expected");
    }
    return token;
  }

  void expect(const char* keyword) {
    const std::string quoted = std::string("'") + keyword + "'";
    const std::string_view token = next(quoted.c_str());
    if (!equalsIgnoringCase(token, keyword)) unexpected(token, quoted);
  }

  [[noreturn]] void unexpected(std::string_view token, const std::string& expected) const {
    fail(path_, "line " + std::to_string(cursor_.line()) + ": expected " + expected + " but found '" +
                    std::string(token.substr(0, 40)) + "'");
  }

  TextCursor cursor_;
  const std::string& path_;
  TriangleMesh mesh_;
  VertexMerger merger_;
};

TriangleMesh parseStl(std::string_view bytes, const std::string& path) {
  if (hasBinaryStlSize(bytes)) return readBinaryStl(bytes, path);
  if (startsWithSolid(bytes) && looksLikeText(bytes)) return AsciiStlParser(bytes, path).parse();
  if (bytes.size() < kBinaryHeaderBytes) {
    fail(path, "not an STL file: too short for a binary STL and does not start with 'solid'");
  }
  const auto count = loadScalar<std::uint32_t>(bytes.data() + 80, !kHostIsLittleEndian);
  fail(path, "binary STL header claims " + std::to_string(count) + " triangles, which need " +
                 std::to_string(kBinaryHeaderBytes + std::uint64_t{count} * kBinaryTriangleBytes) +
                 " bytes, but the file has " + std::to_string(bytes.size()) + " (truncated or corrupt file)");
}

Eigen::Vector3f unitNormalOf(const TriangleMesh& mesh, const Eigen::Vector3i& triangle) {
  const Eigen::Vector3f& a = mesh.vertices[triangle[0]];
  const Eigen::Vector3f normal = (mesh.vertices[triangle[1]] - a).cross(mesh.vertices[triangle[2]] - a);
  const float length = normal.norm();
  return length > 0.0f ? Eigen::Vector3f(normal / length) : Eigen::Vector3f::Zero();
}

}  // namespace

ModelGeometry loadStl(const std::string& path) {
  ModelGeometry geometry;
  geometry.mesh = parseStl(readNonEmptyFileBytes(path), path);
  geometry.cloud.points = geometry.mesh.vertices;
  return geometry;
}

void writeStl(const std::string& path, const TriangleMesh& mesh) {
  if (mesh.triangles.size() > UINT32_MAX) fail(path, "too many triangles for a binary STL");
  // The free header must not start with "solid", or naive readers take the file for ascii.
  std::string bytes = "binary STL written by binpick";
  bytes.resize(80, ' ');
  appendLittleEndian(bytes, static_cast<std::uint32_t>(mesh.triangles.size()));
  bytes.reserve(kBinaryHeaderBytes + mesh.triangles.size() * kBinaryTriangleBytes);
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    const Eigen::Vector3f normal = unitNormalOf(mesh, triangle);
    for (int axis = 0; axis < 3; ++axis) appendLittleEndian(bytes, normal[axis]);
    for (int corner = 0; corner < 3; ++corner) {
      for (int axis = 0; axis < 3; ++axis) {
        appendLittleEndian(bytes, mesh.vertices[triangle[corner]][axis]);
      }
    }
    appendLittleEndian<std::uint16_t>(bytes, 0);
  }
  writeFileBytes(path, bytes);
}

}  // namespace binpick::io::detail
