// PLY writers: clouds (ascii or binary little endian, organized grid kept in an obj_info line)
// and meshes (binary). The body is built in memory and written in one call.
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "text_io.hpp"

namespace binpick::io_detail {

namespace {

using Points = std::vector<Eigen::Vector3f>;

std::string vertexHeader(Encoding encoding, std::size_t vertexCount, bool withNormals) {
  std::string header = "ply\n";
  header +=
      encoding == Encoding::Ascii ? "format ascii 1.0\n" : "format binary_little_endian 1.0\n";
  header += "comment written by binpick\n";
  header += "element vertex " + std::to_string(vertexCount) + "\n";
  header += "property float x\nproperty float y\nproperty float z\n";
  if (withNormals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  return header;
}

// Binary floats keep every bit, including the NaN payloads of invalid pixels. `normals` may be
// empty.
void appendBinaryVertices(std::string& out, const Points& points, const Points& normals) {
  const bool withNormals = !normals.empty();
  const std::size_t floatsPerVertex = withNormals ? 6 : 3;
  const std::size_t start = out.size();
  out.resize(start + points.size() * floatsPerVertex * sizeof(float));
  char* cursor = out.data() + start;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int axis = 0; axis < 3; ++axis) cursor = storeLittleEndian(cursor, points[i][axis]);
    if (!withNormals) continue;
    for (int axis = 0; axis < 3; ++axis) cursor = storeLittleEndian(cursor, normals[i][axis]);
  }
}

void appendAsciiVector(std::string& out, const Eigen::Vector3f& vector, bool startsLine) {
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0 || !startsLine) out += ' ';
    appendNumber(out, vector[axis]);
  }
}

// Shortest round-trip text: reading it back gives the identical floats.
void appendAsciiVertices(std::string& out, const Points& points, const Points& normals) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    appendAsciiVector(out, points[i], true);
    if (!normals.empty()) appendAsciiVector(out, normals[i], false);
    out += '\n';
  }
}

void appendBinaryTriangles(std::string& out, const TriangleMesh& mesh) {
  out.reserve(out.size() + mesh.triangles.size() * (1 + 3 * sizeof(std::int32_t)));
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    out += static_cast<char>(3);
    for (int corner = 0; corner < 3; ++corner) {
      appendLittleEndian<std::int32_t>(out, triangle[corner]);
    }
  }
}

}  // namespace

void writePlyCloud(const std::string& path, const PointCloud& cloud, Encoding encoding) {
  std::string bytes = vertexHeader(encoding, cloud.size(), cloud.hasNormals());
  if (cloud.isOrganized()) {
    bytes += "obj_info organized " + std::to_string(cloud.width) + " " +
             std::to_string(cloud.height) + "\n";
  }
  bytes += "end_header\n";
  if (encoding == Encoding::Ascii) {
    appendAsciiVertices(bytes, cloud.points, cloud.normals);
  } else {
    appendBinaryVertices(bytes, cloud.points, cloud.normals);
  }
  writeFileBytes(path, bytes);
}

void writePlyMesh(const std::string& path, const TriangleMesh& mesh) {
  std::string bytes = vertexHeader(Encoding::Binary, mesh.vertices.size(), false);
  bytes += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  bytes += "property list uchar int vertex_indices\nend_header\n";
  appendBinaryVertices(bytes, mesh.vertices, {});
  appendBinaryTriangles(bytes, mesh);
  writeFileBytes(path, bytes);
}

}  // namespace binpick::io_detail
