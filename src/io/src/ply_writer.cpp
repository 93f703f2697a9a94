// PLY writers: clouds (ascii or binary little endian; normals and intensities when present;
// organized grid kept in an obj_info line) and meshes (binary). The body is built in memory and written in one call.
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "formats.hpp"
#include "text_io.hpp"

namespace binpick::io::detail {

namespace {

using Points = std::vector<Eigen::Vector3f>;
using Intensities = std::vector<float>;

std::string vertexHeader(Encoding encoding, std::size_t vertexCount, bool withNormals, bool withIntensities) {
  std::string header = "ply\n";
  header += encoding == Encoding::Ascii ? "format ascii 1.0\n" : "format binary_little_endian 1.0\n";
  header += "comment written by binpick\n";
  header += "element vertex " + std::to_string(vertexCount) + "\n";
  header += "property float x\nproperty float y\nproperty float z\n";
  if (withNormals) header += "property float nx\nproperty float ny\nproperty float nz\n";
  if (withIntensities) header += "property float intensity\n";
  return header;
}

char* storeBinaryVector(char* cursor, const Eigen::Vector3f& vector) {
  for (int axis = 0; axis < 3; ++axis) cursor = storeLittleEndian(cursor, vector[axis]);
  return cursor;
}

// Binary floats keep every bit, including the NaN payloads of invalid pixels. `normals` and
// `intensities` may be empty.
void appendBinaryVertices(std::string& out, const Points& points, const Points& normals,
                          const Intensities& intensities) {
  const std::size_t floatsPerVertex = 3 + (normals.empty() ? 0 : 3) + (intensities.empty() ? 0 : 1);
  const std::size_t start = out.size();
  out.resize(start + points.size() * floatsPerVertex * sizeof(float));
  char* cursor = out.data() + start;
  for (std::size_t i = 0; i < points.size(); ++i) {
    cursor = storeBinaryVector(cursor, points[i]);
    if (!normals.empty()) cursor = storeBinaryVector(cursor, normals[i]);
    if (!intensities.empty()) cursor = storeLittleEndian(cursor, intensities[i]);
  }
}

void appendAsciiVector(std::string& out, const Eigen::Vector3f& vector, bool startsLine) {
  for (int axis = 0; axis < 3; ++axis) {
    if (axis > 0 || !startsLine) out += ' ';
    appendNumber(out, vector[axis]);
  }
}

// Shortest round-trip text: reading it back gives the identical floats.
void appendAsciiVertices(std::string& out, const Points& points, const Points& normals,
                         const Intensities& intensities) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    appendAsciiVector(out, points[i], true);
    if (!normals.empty()) appendAsciiVector(out, normals[i], false);
    if (!intensities.empty()) {
      out += ' ';
      appendNumber(out, intensities[i]);
    }
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
  std::string bytes = vertexHeader(encoding, cloud.size(), cloud.hasNormals(), cloud.hasIntensities());
  if (cloud.isOrganized()) {
    bytes += "obj_info organized " + std::to_string(cloud.width) + " " + std::to_string(cloud.height) + "\n";
  }
  bytes += "end_header\n";
  if (encoding == Encoding::Ascii) {
    appendAsciiVertices(bytes, cloud.points, cloud.normals, cloud.intensities);
  } else {
    appendBinaryVertices(bytes, cloud.points, cloud.normals, cloud.intensities);
  }
  writeFileBytes(path, bytes);
}

void writePlyMesh(const std::string& path, const TriangleMesh& mesh) {
  std::string bytes = vertexHeader(Encoding::Binary, mesh.vertices.size(), false, false);
  bytes += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  bytes += "property list uchar int vertex_indices\nend_header\n";
  appendBinaryVertices(bytes, mesh.vertices, {}, {});
  appendBinaryTriangles(bytes, mesh);
  writeFileBytes(path, bytes);
}

}  // namespace binpick::io::detail
