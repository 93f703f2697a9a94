#pragma once
// The triangle setup and scan conversion behind renderDepth, exposed inside the library so that
// the pile generator can render one object into just the pixels it covers.
// Internal to binpick::simulation. Pure functions: thread-safe.
#include <cstdint>
#include <vector>

#include "binpick/simulation/depth_renderer.hpp"

namespace binpick::simulation::detail {

// A triangle ready for scan conversion. Pixel centres sit at integer (u, v).
struct ScreenTriangle {
  // Edge functions a*u + b*v + c, all >= 0 inside. A shared edge gets bit-identical
  // coefficients (negated) in both triangles, so meshes render without cracks or gaps.
  double edge_a[3], edge_b[3], edge_c[3];
  // Plane of the triangle in the camera frame, normal . X = offset: the depth along the pixel
  // ray r = ((u - cx)/fx, (v - cy)/fy, 1) is offset / (normal . r), exact at every pixel.
  Eigen::Vector3d normal;
  double offset;
  int u_min, u_max, v_min, v_max;  // pixel bounding box, clipped to the image
  int32_t id;
};

// Triangles nearer than this (metres, camera z) are skipped rather than mis-projected.
constexpr double kNearPlane = 1e-3;

// Triangles of all objects in their order, skipping those that touch the near plane, are edge-on
// or fall outside the image. Throws core::Error on a missing or invalid mesh.
std::vector<ScreenTriangle> setupTriangles(const PinholeCamera& camera, const std::vector<RenderObject>& objects);

// Rows and columns [u0, u0 + width) x [v0, v0 + height) of the image.
struct PixelWindow {
  int u0 = 0, v0 = 0, width = 0, height = 0;
};

// Z-buffers `triangles` into a window-sized depth/instance buffer pair (row-major over the
// window; +inf / -1 where nothing was drawn before). The nearest surface wins; on an exact tie
// the earlier triangle keeps the pixel, so the result does not depend on how the image is split
// into windows.
void rasterize(const PinholeCamera& camera, const std::vector<ScreenTriangle>& triangles, const PixelWindow& window,
               float* depth, int32_t* instance);

}  // namespace binpick::simulation::detail
