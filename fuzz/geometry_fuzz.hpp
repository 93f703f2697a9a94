#pragma once
// The body of the mesh and point-cloud fuzz targets (ply_fuzz.cpp, pcd_fuzz.cpp, stl_fuzz.cpp,
// obj_fuzz.cpp): the input is written as a file of one format and read by the real readers.
// Besides refusing bad files with a core::Error, the readers promise what they return
// (geometry_io.hpp): at least one point, finite mesh vertices and triangle indices in range,
// unit normals and finite intensities for valid points, NaN only in organized clouds, a grid
// that matches the point count. Clouds must also survive the writer: whatever a reader
// accepted, writePointCloud writes and readPointCloud reads back bit for bit (NaN as NaN).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "binpick/io/geometry_io.hpp"
#include "fuzz_support.hpp"

namespace binpick::fuzz {

// Equal bits, or both NaN: an ascii file writes every NaN as "nan", dropping its sign and payload.
inline bool sameValues(const float* a, const float* b, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0 && !(std::isnan(a[i]) && std::isnan(b[i]))) return false;
  }
  return true;
}

inline bool sameCloud(const io::PointCloud& a, const io::PointCloud& b) {
  return a.size() == b.size() && a.normals.size() == b.normals.size() &&
         a.intensities.size() == b.intensities.size() && a.width == b.width && a.height == b.height &&
         sameValues(a.points.data()->data(), b.points.data()->data(), 3 * a.size()) &&
         (a.normals.empty() || sameValues(a.normals.data()->data(), b.normals.data()->data(), 3 * a.size())) &&
         (a.intensities.empty() || sameValues(a.intensities.data(), b.intensities.data(), a.size()));
}

inline void checkCloudGuarantees(const io::PointCloud& cloud, const std::string& reader, const std::string& input) {
  require(!cloud.empty(), reader, "a cloud read has at least one point", input);
  require(cloud.normals.empty() || cloud.normals.size() == cloud.size(), reader, "one normal per point", input);
  require(cloud.intensities.empty() || cloud.intensities.size() == cloud.size(), reader, "one intensity per point",
          input);
  require((cloud.width == 0 && cloud.height == 0) || cloud.isOrganized(), reader, "the grid matches the points",
          input);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3f& point = cloud.points[i];
    if (!point.allFinite()) {
      require(cloud.isOrganized() && point.array().isNaN().any() && !point.array().isInf().any(), reader,
              "only organized clouds hold invalid (NaN) points, and never inf", input);
      continue;
    }
    if (!cloud.normals.empty()) {
      require(std::abs(cloud.normals[i].norm() - 1.0f) <= 1e-5f, reader, "normals of valid points are unit", input);
    }
    if (!cloud.intensities.empty()) {
      require(std::isfinite(cloud.intensities[i]), reader, "intensities of valid points are finite", input);
    }
  }
}

inline void checkMeshGuarantees(const io::TriangleMesh& mesh, const std::string& reader, const std::string& input) {
  const auto vertices = static_cast<int>(mesh.vertices.size());
  for (const Eigen::Vector3f& vertex : mesh.vertices) {
    require(vertex.allFinite(), reader, "mesh vertices are finite", input);
  }
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    require((triangle.array() >= 0).all() && (triangle.array() < vertices).all(), reader,
            "triangle indices are in range", input);
  }
}

// The cloud written in `extension`'s format, binary and ascii, reads back unchanged.
inline void checkCloudRoundTrip(const io::PointCloud& cloud, const std::string& extension, const std::string& reader,
                                const std::string& input) {
  for (io::Encoding encoding : {io::Encoding::Binary, io::Encoding::Ascii}) {
    const std::string path = (scratchDirectory() / ("written" + extension)).string();
    std::error_code ignored;
    std::filesystem::remove(path, ignored);  // a new file: see writeBytes
    try {
      io::writePointCloud(path, cloud, encoding);
      require(sameCloud(io::readPointCloud(path), cloud), reader, "a cloud read back from its writer is unchanged",
              input);
    } catch (const core::Error& error) {
      reportFinding(reader, std::string("a cloud it read does not write and read back: ") + error.what(), input);
    }
  }
}

// Reads the input as a file named input<extension> with readModelGeometry (and readMesh /
// readPointCloud, which must agree with it).
inline void fuzzGeometryFile(const std::string& extension, const uint8_t* data, size_t size) {
  const std::string reader = "readModelGeometry(" + extension + ")";
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string path = (scratchDirectory() / ("input" + extension)).string();
  writeBytes(path, input);
  io::ModelGeometry geometry;
  if (!readsOrRefuses(reader, path, input, [&] { geometry = io::readModelGeometry(path); })) return;
  checkCloudGuarantees(geometry.cloud, reader, input);
  checkMeshGuarantees(geometry.mesh, reader, input);
  if (geometry.hasMesh()) {
    io::TriangleMesh mesh;
    require(readsOrRefuses(reader, path, input, [&] { mesh = io::readMesh(path); }) &&
                mesh.triangles == geometry.mesh.triangles,
            reader, "readMesh gives readModelGeometry's mesh", input);
  }
  if (extension == ".ply" || extension == ".pcd") {
    io::PointCloud cloud;
    require(readsOrRefuses(reader, path, input, [&] { cloud = io::readPointCloud(path); }) &&
                sameCloud(cloud, geometry.cloud),
            reader, "readPointCloud gives readModelGeometry's cloud", input);
    checkCloudRoundTrip(geometry.cloud, extension, reader, input);
  }
}

}  // namespace binpick::fuzz
