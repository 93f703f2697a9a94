// Wavefront OBJ: only geometry matters here. `v` lines give vertices, `f` lines give polygons
// (fan-triangulated); texture coordinates, normals, groups and materials are ignored.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

namespace {

class ObjParser {
 public:
  ObjParser(std::string_view text, const std::string& path) : text_(text), path_(path) {}

  TriangleMesh parse() {
    std::size_t start = 0;
    while (start < text_.size()) {
      std::size_t end = text_.find('\n', start);
      if (end == std::string_view::npos) end = text_.size();
      ++lineNumber_;
      parseLine(withoutComment(text_.substr(start, end - start)));
      start = end + 1;
    }
    checkFaceIndices();
    return std::move(mesh_);
  }

 private:
  static std::string_view withoutComment(std::string_view line) { return line.substr(0, line.find('#')); }

  void parseLine(std::string_view line) {
    TextCursor cursor(line);
    const std::string_view keyword = cursor.nextToken();
    if (keyword == "v") {
      parseVertex(cursor);
    } else if (keyword == "f") {
      parseFace(cursor);
    }
    // Everything else (vn, vt, g, o, s, usemtl, mtllib, l, ...) carries no geometry we use.
  }

  // `v x y z [w]` or `v x y z r g b`: the extra values are ignored.
  void parseVertex(TextCursor& cursor) {
    Eigen::Vector3f vertex;
    for (int axis = 0; axis < 3; ++axis) {
      const std::string_view token = cursor.nextToken();
      if (!parseFloat(token, vertex[axis])) {
        failHere("vertex coordinate '" + std::string(token.substr(0, 40)) + "' is not a number");
      }
    }
    mesh_.vertices.push_back(vertex);
  }

  // `f a b c ...` where each corner is `v`, `v/vt`, `v/vt/vn` or `v//vn`; negative v counts back
  // from the last vertex defined so far.
  void parseFace(TextCursor& cursor) {
    polygon_.clear();
    for (std::string_view corner = cursor.nextToken(); !corner.empty(); corner = cursor.nextToken()) {
      polygon_.push_back(vertexIndexOf(corner));
    }
    if (polygon_.size() < 3) {
      failHere("face has " + std::to_string(polygon_.size()) + " vertices; a face needs at least 3");
    }
    for (std::size_t k = 1; k + 1 < polygon_.size(); ++k) {
      mesh_.triangles.emplace_back(polygon_[0], polygon_[k], polygon_[k + 1]);
      lineOfTriangle_.push_back(lineNumber_);
    }
  }

  // 0-based index; positive indices are range-checked once all vertices are known.
  int vertexIndexOf(std::string_view corner) {
    const std::string_view text = corner.substr(0, corner.find('/'));
    std::int64_t index = 0;
    if (!parseInteger(text, index) || index == 0) {
      failHere("face corner '" + std::string(corner.substr(0, 40)) + "' has no valid vertex index");
    }
    const auto defined = static_cast<std::int64_t>(mesh_.vertices.size());
    const std::int64_t resolved = index > 0 ? index - 1 : defined + index;
    if (resolved < 0 || resolved > INT32_MAX) {
      failHere("face refers to vertex " + std::to_string(index) + " but only " + std::to_string(defined) +
               " vertices are defined before it");
    }
    return static_cast<int>(resolved);
  }

  void checkFaceIndices() const {
    const auto vertexCount = static_cast<std::int64_t>(mesh_.vertices.size());
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      for (int corner = 0; corner < 3; ++corner) {
        const int index = mesh_.triangles[t][corner];
        if (index >= vertexCount) {
          // 1-based as in the file, in 64 bits: the index may be INT_MAX.
          fail(path_, "line " + std::to_string(lineOfTriangle_[t]) + ": face refers to vertex " +
                          std::to_string(std::int64_t{index} + 1) + " but the file has " + std::to_string(vertexCount) +
                          " vertices");
        }
      }
    }
  }

  [[noreturn]] void failHere(const std::string& what) const {
    fail(path_, "line " + std::to_string(lineNumber_) + ": " + what);
  }

  std::string_view text_;
  const std::string& path_;
  std::size_t lineNumber_ = 0;
  TriangleMesh mesh_;
  std::vector<std::size_t> lineOfTriangle_;  // only for messages about bad indices
  std::vector<int> polygon_;
};

void appendObjLine(std::string& out, char keyword, const Eigen::Vector3f& values) {
  out += keyword;
  for (int axis = 0; axis < 3; ++axis) {
    out += ' ';
    appendNumber(out, values[axis]);
  }
  out += '\n';
}

}  // namespace

ModelGeometry loadObj(const std::string& path) {
  const std::string text = readNonEmptyFileBytes(path);
  // OBJ is text; without this, binary garbage would just be "lines" with unknown keywords.
  if (text.find('\0') != std::string::npos) fail(path, "not an OBJ file: it contains binary data");
  ModelGeometry geometry;
  geometry.mesh = ObjParser(text, path).parse();
  geometry.cloud.points = geometry.mesh.vertices;
  return geometry;
}

void writeObj(const std::string& path, const TriangleMesh& mesh) {
  std::string text = "# written by binpick\n";
  for (const Eigen::Vector3f& vertex : mesh.vertices) appendObjLine(text, 'v', vertex);
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    text += "f " + std::to_string(triangle[0] + 1) + " " + std::to_string(triangle[1] + 1) + " " +
            std::to_string(triangle[2] + 1) + "\n";
  }
  writeFileBytes(path, text);
}

}  // namespace binpick::io::detail
