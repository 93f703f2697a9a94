// Validation of clouds and meshes, used by every reader and writer and available to callers.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/io/point_cloud.hpp"
#include "byte_io.hpp"
#include "formats.hpp"
#include "text_io.hpp"

namespace binpick::io {

using detail::appendNumber;
using detail::describePoint;
using detail::fail;

namespace {

bool isInvalidPixel(const Eigen::Vector3f& point) { return point.array().isNaN().any(); }

void checkGrid(const PointCloud& cloud, const std::string& what) {
  if (cloud.width == 0 && cloud.height == 0) return;
  if (!cloud.isOrganized()) {
    fail(what, "width " + std::to_string(cloud.width) + " x height " + std::to_string(cloud.height) +
                   " does not match the " + std::to_string(cloud.size()) + " points");
  }
}

// Whether any coordinate is infinite, or with `nan_too` NaN as well: one pass over the floats'
// bits, branch-free so that it vectorises. A camera's cloud has a million points and most of them
// are fine; checking them point by point took several milliseconds of every `binpick detect`.
bool anyNonFinite(const std::vector<Eigen::Vector3f>& points, bool nan_too) {
  constexpr uint32_t kMagnitude = 0x7fffffffu, kInfinity = 0x7f800000u;
  const float* values = points.empty() ? nullptr : points.front().data();
  uint32_t found = 0;
  for (std::size_t i = 0; i < 3 * points.size(); ++i) {
    uint32_t bits = 0;
    std::memcpy(&bits, values + i, sizeof(bits));
    const uint32_t magnitude = bits & kMagnitude;
    found |= static_cast<uint32_t>(nan_too ? magnitude >= kInfinity : magnitude == kInfinity);
  }
  return found != 0;
}

void checkPoints(const PointCloud& cloud, const std::string& what) {
  const bool organized = cloud.isOrganized();
  if (!anyNonFinite(cloud.points, !organized)) return;
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3f& point = cloud.points[i];
    if (point.allFinite()) continue;
    // NaN marks an invalid pixel of an organized cloud; inf is never a measurement.
    if (organized && isInvalidPixel(point) && !point.array().isInf().any()) continue;
    fail(what, "point " + std::to_string(i) + " is not finite " + describePoint(point) +
                   (organized ? " (an organized cloud may only mark invalid pixels with NaN)"
                              : " (NaN points are only allowed in organized clouds)"));
  }
}

void checkNormals(const PointCloud& cloud, const std::string& what) {
  if (cloud.normals.empty()) return;
  if (cloud.normals.size() != cloud.points.size()) {
    fail(what,
         std::to_string(cloud.normals.size()) + " normals for " + std::to_string(cloud.points.size()) + " points");
  }
  for (std::size_t i = 0; i < cloud.normals.size(); ++i) {
    // Invalid pixels carry whatever normal the sensor pipeline left there.
    if (!cloud.points[i].allFinite()) continue;
    if (!cloud.normals[i].allFinite()) {
      fail(what, "normal of point " + std::to_string(i) + " is not finite " + describePoint(cloud.normals[i]));
    }
  }
}

void checkIntensities(const PointCloud& cloud, const std::string& what) {
  if (cloud.intensities.empty()) return;
  if (cloud.intensities.size() != cloud.points.size()) {
    fail(what, std::to_string(cloud.intensities.size()) + " intensities for " + std::to_string(cloud.points.size()) +
                   " points");
  }
  for (std::size_t i = 0; i < cloud.intensities.size(); ++i) {
    // Like normals: invalid pixels carry whatever intensity the sensor pipeline left there.
    if (!cloud.points[i].allFinite()) continue;
    if (!std::isfinite(cloud.intensities[i])) {
      std::string value;
      appendNumber(value, cloud.intensities[i]);
      fail(what, "intensity of point " + std::to_string(i) + " is not finite (" + value + ")");
    }
  }
}

}  // namespace

void validateCloud(const PointCloud& cloud, const std::string& what) {
  checkGrid(cloud, what);
  checkPoints(cloud, what);
  checkNormals(cloud, what);
  checkIntensities(cloud, what);
}

void validateMesh(const TriangleMesh& mesh, const std::string& what) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      fail(what, "vertex " + std::to_string(i) + " is not finite " + describePoint(mesh.vertices[i]));
    }
  }
  const auto vertexCount = static_cast<long long>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      const int index = mesh.triangles[t][corner];
      if (index < 0 || index >= vertexCount) {
        fail(what, "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(index) +
                       " but the mesh has " + std::to_string(vertexCount) + " vertices");
      }
    }
  }
}

namespace detail {

namespace {

// Length of a normal that validateCloud accepted; throws when it has no direction. In double:
// squaring in float overflows for huge components and underflows into denormals for tiny ones
// (a normal of 1e-20 would come out of the division nowhere near unit length).
double directedLength(const PointCloud& cloud, std::size_t i, const std::string& path) {
  const double length = cloud.normals[i].cast<double>().norm();
  // A zero normal has no direction; keeping it would poison every dot product downstream.
  if (!(length > 0.0)) {
    fail(path, "normal of point " + std::to_string(i) + " is zero " + describePoint(cloud.normals[i]));
  }
  return length;
}

}  // namespace

void normaliseNormals(PointCloud& cloud, const std::string& path) {
  // Normals already unit to float precision are kept bit for bit, so binary files round-trip
  // exactly; dividing by a length of 0.99999994 would change their last bits for nothing.
  constexpr double kUnitTolerance = 1e-6;
  for (std::size_t i = 0; i < cloud.normals.size(); ++i) {
    if (!cloud.points[i].allFinite()) continue;
    const double length = directedLength(cloud, i, path);
    if (std::abs(length - 1.0) > kUnitTolerance) {
      cloud.normals[i] = (cloud.normals[i].cast<double>() / length).cast<float>();
    }
  }
}

void requireDirectedNormals(const PointCloud& cloud, const std::string& path) {
  for (std::size_t i = 0; i < cloud.normals.size(); ++i) {
    if (cloud.points[i].allFinite()) directedLength(cloud, i, path);
  }
}

void requireSomeArea(const TriangleMesh& mesh, const std::string& path) {
  for (const Eigen::Vector3i& triangle : mesh.triangles) {
    const Eigen::Vector3f& a = mesh.vertices[triangle[0]];
    const Eigen::Vector3f& b = mesh.vertices[triangle[1]];
    const Eigen::Vector3f& c = mesh.vertices[triangle[2]];
    if ((b - a).cross(c - a).squaredNorm() > 0.0f) return;
  }
  fail(path, "all " + std::to_string(mesh.triangles.size()) + " faces have zero area");
}

}  // namespace detail
}  // namespace binpick::io
