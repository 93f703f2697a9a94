#pragma once
// Point cloud and triangle mesh containers shared by every stage. Plain values: not synchronised,
// safe to read from many threads at once.
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace binpick::io {

// A cloud in one frame and one unit. Organized clouds (width x height, row-major, as a camera sees
// them) keep invalid pixels as NaN points so that the pixel grid stays intact.
struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  // empty, or one unit normal per point
  // Empty, or one brightness per point (structured light: the white image, 0 = black, 1 = the
  // sensor's full scale).
  std::vector<float> intensities;
  int width = 0;   // organized: image columns; unorganized: 0
  int height = 0;  // organized: image rows; unorganized: 0

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool hasNormals() const { return !normals.empty() && normals.size() == points.size(); }
  bool hasIntensities() const { return !intensities.empty() && intensities.size() == points.size(); }
  bool isOrganized() const {
    return width > 0 && height > 0 &&
           static_cast<std::size_t>(width) * static_cast<std::size_t>(height) == points.size();
  }
};

// A triangle soup with shared vertices; counter-clockwise winding seen from outside.
struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;

  bool empty() const { return triangles.empty(); }
};

// Throws core::Error naming `what` when a point, normal or intensity is not finite (NaN points
// of an organized cloud are allowed: they mark invalid pixels, and their normals and intensities
// are not checked) or a normal or intensity count does not match.
void validateCloud(const PointCloud& cloud, const std::string& what);
// Throws core::Error naming `what` on non-finite vertices or out-of-range triangle indices.
void validateMesh(const TriangleMesh& mesh, const std::string& what);

}  // namespace binpick::io
