#include "rasterizer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/core/error.hpp"

namespace binpick::simulation::detail {
namespace {

struct ProjectedVertex {
  Eigen::Vector3d camera;  // position in the camera frame
  Eigen::Vector2d pixel;   // (u, v); meaningful only when camera.z() > kNearPlane
};

std::vector<ProjectedVertex> projectVertices(const PinholeCamera& camera, const RenderObject& object) {
  std::vector<ProjectedVertex> projected;
  projected.reserve(object.mesh->vertices.size());
  for (const auto& v : object.mesh->vertices) {
    const Eigen::Vector3d p = object.T_camera_object * v.cast<double>();
    const double z = std::max(p.z(), kNearPlane);
    projected.push_back({p, {camera.fx * p.x() / z + camera.cx, camera.fy * p.y() / z + camera.cy}});
  }
  return projected;
}

bool lexicographicallyLess(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
}

// Edge function of the line a->b, oriented so that the triangle interior is >= 0. The line is
// always evaluated from its lexicographically smaller end so that two triangles sharing the edge
// compute the very same numbers and disagree only in sign.
void setEdge(ScreenTriangle& triangle, int k, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
             double interior_sign) {
  const bool swapped = lexicographicallyLess(b, a);
  const Eigen::Vector2d& from = swapped ? b : a;
  const Eigen::Vector2d& to = swapped ? a : b;
  const double sign = swapped ? -interior_sign : interior_sign;
  // cross(to - from, p - from) = a*u + b*v + c
  const double coef_a = -(to.y() - from.y());
  const double coef_b = to.x() - from.x();
  const double coef_c = -(coef_a * from.x() + coef_b * from.y());
  triangle.edge_a[k] = sign * coef_a;
  triangle.edge_b[k] = sign * coef_b;
  triangle.edge_c[k] = sign * coef_c;
}

// Returns false when the triangle cannot be drawn (behind the near plane, edge-on, off-image).
bool setupTriangle(const PinholeCamera& camera, const ProjectedVertex& v0, const ProjectedVertex& v1,
                   const ProjectedVertex& v2, int32_t id, ScreenTriangle& out) {
  const bool reaches_near_plane =
      v0.camera.z() <= kNearPlane || v1.camera.z() <= kNearPlane || v2.camera.z() <= kNearPlane;
  if (reaches_near_plane) return false;
  const Eigen::Vector2d e1 = v1.pixel - v0.pixel, e2 = v2.pixel - v0.pixel;
  const double twice_area = e1.x() * e2.y() - e1.y() * e2.x();
  if (!(std::abs(twice_area) > 1e-12)) return false;  // edge-on (or NaN): covers no pixel centre
  const Eigen::Vector2d lo = v0.pixel.cwiseMin(v1.pixel).cwiseMin(v2.pixel);
  const Eigen::Vector2d hi = v0.pixel.cwiseMax(v1.pixel).cwiseMax(v2.pixel);
  // Clamp in double before converting: a vertex close to the near plane projects far away.
  out.u_min = static_cast<int>(std::max(0.0, std::ceil(lo.x())));
  out.v_min = static_cast<int>(std::max(0.0, std::ceil(lo.y())));
  out.u_max = static_cast<int>(std::min(camera.width - 1.0, std::floor(hi.x())));
  out.v_max = static_cast<int>(std::min(camera.height - 1.0, std::floor(hi.y())));
  if (out.u_min > out.u_max || out.v_min > out.v_max) return false;
  const double interior_sign = twice_area > 0.0 ? 1.0 : -1.0;
  setEdge(out, 0, v0.pixel, v1.pixel, interior_sign);
  setEdge(out, 1, v1.pixel, v2.pixel, interior_sign);
  setEdge(out, 2, v2.pixel, v0.pixel, interior_sign);
  out.normal = (v1.camera - v0.camera).cross(v2.camera - v0.camera);
  out.offset = out.normal.dot(v0.camera);
  out.id = id;
  return true;
}

// Columns of row v where all edge functions could be >= 0, widened by one pixel so that the
// exact per-pixel test, not this division, decides the boundary pixels.
bool rowSpan(const ScreenTriangle& t, int v, int& u_first, int& u_last) {
  double lo = t.u_min, hi = t.u_max;
  for (int k = 0; k < 3; ++k) {
    const double rest = t.edge_b[k] * v + t.edge_c[k];  // edge_a * u + rest >= 0
    if (t.edge_a[k] > 0.0) {
      lo = std::max(lo, std::ceil(-rest / t.edge_a[k]) - 1.0);
    } else if (t.edge_a[k] < 0.0) {
      hi = std::min(hi, std::floor(-rest / t.edge_a[k]) + 1.0);
    } else if (rest < 0.0) {
      return false;
    }
  }
  u_first = static_cast<int>(lo);
  u_last = static_cast<int>(hi);
  return u_first <= u_last;
}

bool insideTriangle(const ScreenTriangle& t, double u, double v) {
  for (int k = 0; k < 3; ++k) {
    if (t.edge_a[k] * u + t.edge_b[k] * v + t.edge_c[k] < 0.0) return false;
  }
  return true;
}

void rasterizeTriangle(const PinholeCamera& camera, const ScreenTriangle& t, const PixelWindow& window, float* depth,
                       int32_t* instance) {
  const int v_begin = std::max(t.v_min, window.v0);
  const int v_end = std::min(t.v_max, window.v0 + window.height - 1);
  for (int v = v_begin; v <= v_end; ++v) {
    int u_first = 0, u_last = -1;
    if (!rowSpan(t, v, u_first, u_last)) continue;
    u_first = std::max(u_first, window.u0);
    u_last = std::min(u_last, window.u0 + window.width - 1);
    const double ray_y = (v - camera.cy) / camera.fy;
    const double partial = t.normal.y() * ray_y + t.normal.z();
    const std::size_t row = static_cast<std::size_t>(v - window.v0) * window.width;
    for (int u = u_first; u <= u_last; ++u) {
      if (!insideTriangle(t, u, v)) continue;
      const double z = t.offset / (t.normal.x() * ((u - camera.cx) / camera.fx) + partial);
      const std::size_t pixel = row + (u - window.u0);
      const float zf = static_cast<float>(z);
      if (z > kNearPlane && zf < depth[pixel]) {
        depth[pixel] = zf;
        instance[pixel] = t.id;
      }
    }
  }
}

}  // namespace

std::vector<ScreenTriangle> setupTriangles(const PinholeCamera& camera, const std::vector<RenderObject>& objects) {
  std::vector<ScreenTriangle> triangles;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const RenderObject& object = objects[i];
    if (object.mesh == nullptr) {
      throw core::Error("renderDepth: object " + std::to_string(i) + " has no mesh");
    }
    io::validateMesh(*object.mesh, "renderDepth object " + std::to_string(i));
    const std::vector<ProjectedVertex> projected = projectVertices(camera, object);
    for (const auto& tri : object.mesh->triangles) {
      ScreenTriangle screen;
      if (setupTriangle(camera, projected[tri[0]], projected[tri[1]], projected[tri[2]], object.id, screen)) {
        triangles.push_back(screen);
      }
    }
  }
  return triangles;
}

void rasterize(const PinholeCamera& camera, const std::vector<ScreenTriangle>& triangles, const PixelWindow& window,
               float* depth, int32_t* instance) {
  for (const auto& t : triangles) {
    const bool overlaps = t.v_max >= window.v0 && t.v_min < window.v0 + window.height && t.u_max >= window.u0 &&
                          t.u_min < window.u0 + window.width;
    if (overlaps) rasterizeTriangle(camera, t, window, depth, instance);
  }
}

}  // namespace binpick::simulation::detail
