// Per-image-row triangulation passes: table loads, then ray intersection arithmetic.
//
// Frames: the camera ray of a pixel is (a, b, 1) in the camera frame (undistorted normalised
// coordinates), so the point at ray parameter t has camera z = t. In the projector frame the
// ray is X(t) = C + t d, with C the camera centre and d = R (a, b, 1). (u, v) are undistorted
// normalised projector coordinates: the projector ray (u, v, 1).
//
// Both modes reduce to the same last step: a projector ray in the camera ray's epipolar plane,
// which the camera ray meets exactly. With projector rows decoded it is the foot of the decoded
// (u, v) on the ray's epipolar line; with columns only, where the column's light crosses the
// epipolar plane, read from a table over (column, plane).
#include "triangulation_rows.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/reconstruction/pixel_status.hpp"
#include "float4.hpp"
#include "simd_dispatch.hpp"

// The image-row passes are compiled for SSE2 and AVX2 + FMA, picked at load time
// (simd_dispatch.hpp): about a third faster on AVX2 machines.
namespace binpick::reconstruction::detail {
namespace {

// A pixel's verdict while its image row is processed: the status it will get, or kSkipped.
enum Code : int32_t {
  kSolved = static_cast<int32_t>(PixelStatus::Valid),
  kInconsistent = static_cast<int32_t>(PixelStatus::Inconsistent),
  kNoIntersection = static_cast<int32_t>(PixelStatus::NoIntersection),
  kOutOfRange = static_cast<int32_t>(PixelStatus::CodeOutOfRange),
  kSkipped = 255,  // the decoder already gave the pixel another status: it keeps it
};

// Rays that meet farther than this many baselines from the camera are within 0.06 degrees of
// parallel: such a point means nothing, and the division would only amplify noise and rounding.
constexpr double kMaxDepthInBaselines = 1000.0;

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

struct Direction {
  float x, y, z;
};

inline Direction rayInProjector(const RigGeometry& g, float a, float b) {
  return {g.r[0] * a + g.r[1] * b + g.r[2], g.r[3] * a + g.r[4] * b + g.r[5], g.r[6] * a + g.r[7] * b + g.r[8]};
}

struct Solution {
  float depth;
  float depth_per_px;  // camera z per projector pixel along the ray's epipolar line
  bool no_point;
};

// The camera ray meets the projector ray w = (wu, wv, wz) (homogeneous: any positive scale) of
// its epipolar plane. t minimises |(wz X_x - wu X_z, wz X_y - wv X_z)| = |A + t B| (zero for
// coplanar rays; least squares keeps either component from being ill-conditioned alone). No
// point where the rays meet behind either device or (nearly parallel) beyond max_depth.
inline Solution intersectRays(const RigGeometry& g, const Direction& d, float wu, float wv, float wz) {
  const float* c = g.c;
  const float ax = wz * c[0] - wu * c[2], ay = wz * c[1] - wv * c[2];
  const float bx = wz * d.x - wu * d.z, by = wz * d.y - wv * d.z;
  const float t = -(ax * bx + ay * by) / (bx * bx + by * by);
  const float z_projector = c[2] + t * d.z;
  // The point's image moves along the line at d(u, v)/dt = (d_xy c_z - c_xy d_z) / z_projector^2
  // (normalised units per metre of t): its inverse, in pixels, is the depth one projector pixel
  // spans there.
  const float speed_u = g.fx * (d.x * c[2] - c[0] * d.z), speed_v = g.fy * (d.y * c[2] - c[1] * d.z);
  const float depth_per_px = z_projector * z_projector / std::sqrt(speed_u * speed_u + speed_v * speed_v);
  // NaN (parallel or degenerate rays) fails these comparisons too.
  return {t, depth_per_px, !((t > 0.0f) & (t < g.max_depth) & (z_projector > 0.0f))};
}

// Decoded projector column and row: the point of the ray whose projection is nearest the decoded
// (u, v) in the undistorted projector image, in pixel units. The ray projects onto its epipolar
// line, n . (u, v, 1) = 0 with n = C x d; the nearest point is the foot of (u, v) on the line.
// The epipolar error is the foot's distance, measured in the undistorted image: the projector's
// distortion scales lengths by 1 + O(k1 r^2) (a few per cent at the corners of real lenses),
// which does not matter for a tolerance, while projecting through the distortion would cost
// more than the rest of the solve. It is judged from `expected`, the calibration's residual at
// the pixel (normalised units, signed as s / sqrt(line)).
inline int32_t solveWithProjectorRow(const RigGeometry& g, float a, float b, float u, float v, float expected,
                                     float limit_scale_sq, Solution& solution) {
  const Direction d = rayInProjector(g, a, b);
  const float* c = g.c;
  const float nx = c[1] * d.z - c[2] * d.y;
  const float ny = c[2] * d.x - c[0] * d.z;
  const float nz = c[0] * d.y - c[1] * d.x;
  const float s = nx * u + ny * v + nz;
  // In pixels (fx u, fy v) the line's normal is (nx / fx, ny / fy): with q = fx / fy,
  // |normal|^2 = line / fx^2 and (u, v) lies |s| fx / sqrt(line) pixels from the line.
  const float qny = g.aspect_sq * ny;
  const float line = nx * nx + qny * ny;
  const float off_residual = s - expected * std::sqrt(line);
  const bool inconsistent = off_residual * off_residual > g.max_error_sq * limit_scale_sq * line;
  // The foot (u, v) - (s / line) (nx, q^2 ny), kept homogeneous (times `line`): one division
  // fewer, and divisions are what this loop waits on.
  solution = intersectRays(g, d, u * line - s * nx, v * line - s * qny, line);
  return solution.no_point ? kNoIntersection : (inconsistent ? kInconsistent : kSolved);
}

inline float epipolarLabel(const RigGeometry& g, float a, float b) {
  return (g.q3[0] * a + g.q3[1] * b + g.q3[2]) / (g.q2[0] * a + g.q2[1] * b + g.q2[2]);
}

// The passes over an image row, each a function of its own: GCC honours __restrict only on
// parameters, and would not vectorise the loops that store through several pointers without it.

// Which table cell each decoded point (x, y) falls in. Columns outside [min_column, max_column]
// are CodeOutOfRange; a point otherwise outside the table gets `outside`.
template <class View>
BINPICK_SIMD_PASS void locateCells(const View& grid, int n, const float* __restrict xs, const float* __restrict ys,
                                   const uint8_t* __restrict status, float min_column, float max_column,
                                   int32_t outside, int32_t* __restrict cell, float* __restrict fx,
                                   float* __restrict fy, int32_t* __restrict code) {
  for (int x = 0; x < n; ++x) {
    const auto at = grid.locate(xs[x], ys[x]);
    cell[x] = at.cell;
    fx[x] = at.fx;
    fy[x] = at.fy;
    const bool in_image = (xs[x] >= min_column) & (xs[x] <= max_column);
    const int32_t decoded = status[x];  // loaded unconditionally: the selects vectorise
    code[x] = decoded != kSolved ? kSkipped : !in_image ? kOutOfRange : at.inside ? kSolved : outside;
  }
}

// Projector rows decoded: the undistorted (u, v) of each decoded projector pixel, interleaved.
// Unsolved pixels interpolate the first cell: no branch, and their values are never used.
BINPICK_SIMD_PASS void undistortCells(const LookupGrid<2>::View& grid, int n, const int32_t* __restrict cell,
                                      const float* __restrict fx, const float* __restrict fy, float* __restrict uv) {
  for (int x = 0; x < n; ++x) grid.interpolate(cell[x], fx[x], fy[x], uv + 2 * x);
}

// Columns only: (u, v, distorted projector row, unused) where the column's light crosses the ray's
// epipolar plane, interleaved.
BINPICK_SIMD_PASS void crossColumnLight(const LookupGrid<4>::View& grid, int n, const int32_t* __restrict cell,
                                        const float* __restrict fx, const float* __restrict fy,
                                        float* __restrict light) {
  for (int x = 0; x < n; ++x) grid.interpolate(cell[x], fx[x], fy[x], light + 4 * x);
}

BINPICK_SIMD_PASS void epipolarLabels(const RigGeometry& rig, int n, const float* __restrict ray_x,
                                      const float* __restrict ray_y, float* __restrict label) {
  for (int x = 0; x < n; ++x) label[x] = epipolarLabel(rig, ray_x[x], ray_y[x]);
}

// The solves write camera-frame points, NaN unless solved: x, y in px, py, and z (= t) in pz;
// and the depth a projector pixel spans in depth_per_px. The SIMD passes take them as separate
// __restrict parameters (see above); the helpers around them pass them as one.
struct ImageRowPoints {
  float* px;
  float* py;
  float* pz;
  float* depth_per_px;
};

BINPICK_SIMD_PASS void solveWithProjectorRows(const RigGeometry& rig, int n, const float* __restrict ray_x,
                                              const float* __restrict ray_y, const float* __restrict uv,
                                              const float* __restrict expected_px,
                                              const float* __restrict limit_scale_sq, int32_t* __restrict code,
                                              float* __restrict px, float* __restrict py, float* __restrict pz,
                                              float* __restrict depth_per_px) {
  const float inv_fx = 1.0f / rig.fx;
  for (int x = 0; x < n; ++x) {
    Solution solution{};
    const int32_t solved = solveWithProjectorRow(rig, ray_x[x], ray_y[x], uv[2 * x], uv[2 * x + 1],
                                                 expected_px[x] * inv_fx, limit_scale_sq[x], solution);
    const int32_t verdict = code[x] == kSolved ? solved : code[x];
    const float z = verdict == kSolved ? solution.depth : kNaNf;
    code[x] = verdict;
    px[x] = z * ray_x[x];
    py[x] = z * ray_y[x];
    pz[x] = z;
    depth_per_px[x] = verdict == kSolved ? solution.depth_per_px : kNaNf;
  }
}

// Where the column's light crosses the ray's plane outside the projector's rows, it never reaches
// the ray.
BINPICK_SIMD_PASS void solveColumnOnly(const RigGeometry& rig, int n, const float* __restrict ray_x,
                                       const float* __restrict ray_y, const float* __restrict light, float min_row,
                                       float max_row, int32_t* __restrict code, float* __restrict px,
                                       float* __restrict py, float* __restrict pz, float* __restrict depth_per_px) {
  for (int x = 0; x < n; ++x) {
    const float* crossing = light + 4 * x;
    const Solution solution =
        intersectRays(rig, rayInProjector(rig, ray_x[x], ray_y[x]), crossing[0], crossing[1], 1.0f);
    const bool in_image = (crossing[2] >= min_row) & (crossing[2] <= max_row);
    const bool no_point = solution.no_point | !in_image;
    const int32_t verdict = (code[x] == kSolved) & no_point ? kNoIntersection : code[x];
    const float z = verdict == kSolved ? solution.depth : kNaNf;
    code[x] = verdict;
    px[x] = z * ray_x[x];
    py[x] = z * ray_y[x];
    pz[x] = z;
    depth_per_px[x] = verdict == kSolved ? solution.depth_per_px : kNaNf;
  }
}

BINPICK_SIMD_PASS void storePoints(int n, const float* __restrict px, const float* __restrict py,
                                   const float* __restrict pz, Eigen::Vector3f* points) {
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "points must be packed floats");
  float* out = points->data();
  int x = 0;
  for (; x + 4 <= n; x += 4) {
    storeInterleaved3(out + 3 * x, loadFloat4(px + x), loadFloat4(py + x), loadFloat4(pz + x));
  }
  for (; x < n; ++x) points[x] = Eigen::Vector3f(px[x], py[x], pz[x]);
}

BINPICK_SIMD_PASS void storeStatuses(int n, const uint8_t* __restrict decoded, const int32_t* __restrict code,
                                     uint8_t* __restrict status) {
  for (int x = 0; x < n; ++x) {
    const int32_t before = decoded[x];  // loaded unconditionally: the select vectorises
    status[x] = static_cast<uint8_t>(code[x] == kSkipped ? before : code[x]);
  }
}

// Columns only, for the pixels of `in` that are still to be solved: the crossing of each ray's
// epipolar plane with its column's light. Writes code and the points.
void solveByColumns(const RigGeometry& rig, const ProjectorTables& tables, const TriangulationImageRowInput& in,
                    TriangulationScratch& s, int32_t* code, ImageRowPoints out) {
  const int n = in.width;
  const auto grid = tables.epipolar.view();
  // Each ray's epipolar plane. Outside the table's labels the plane misses the projector's
  // image: no light reaches the ray.
  epipolarLabels(rig, n, in.ray_x, in.ray_y, s.label.data());
  locateCells(grid, n, in.column, s.label.data(), in.status, tables.min_column, tables.max_column, kNoIntersection,
              s.cell.data(), s.fx.data(), s.fy.data(), code);
  crossColumnLight(grid, n, s.cell.data(), s.fx.data(), s.fy.data(), s.light.data());
  solveColumnOnly(rig, n, in.ray_x, in.ray_y, s.light.data(), tables.min_row, tables.max_row, code, out.px, out.py,
                  out.pz, out.depth_per_px);
}

// The projector row did not decode, or the decoded one lies off the ray's epipolar line (a wrong
// row: the row check cannot tell a wrong column, which lies on the line anyway).
bool columnWithoutProjectorRow(const RigGeometry& rig, const TriangulationImageRowInput& in,
                               const TriangulationScratch& s, int x) {
  return in.status[x] == kSolved &&
         (std::isnan(in.row[x]) || (rig.column_when_inconsistent && s.code[x] == kInconsistent));
}

// A capture with projector rows whose pixels lost the projector row but kept the column: those
// get the column-only solution instead of the CodeOutOfRange the NaN row gave them. Image rows
// without such pixels cost a scan.
void solveMissingProjectorRows(const RigGeometry& rig, const ProjectorTables& tables,
                               const TriangulationImageRowInput& in, TriangulationScratch& s) {
  bool any = false;
  for (int x = 0; x < in.width; ++x) any |= columnWithoutProjectorRow(rig, in, s, x);
  if (!any) return;
  solveByColumns(rig, tables, in, s, s.column_code.data(),
                 {s.column_px.data(), s.column_py.data(), s.column_pz.data(), s.column_depth_per_px.data()});
  for (int x = 0; x < in.width; ++x) {
    if (!columnWithoutProjectorRow(rig, in, s, x)) continue;
    s.code[x] = s.column_code[x];
    s.px[x] = s.column_px[x];
    s.py[x] = s.column_py[x];
    s.pz[x] = s.column_pz[x];
    s.depth_per_px[x] = s.column_depth_per_px[x];
  }
}

// The solved image row into the outputs: the points are in the scratch's px, py, pz.
void writeImageRow(const TriangulationImageRowInput& in, const TriangulationScratch& s,
                   const TriangulationImageRowOutput& out) {
  storePoints(in.width, s.px.data(), s.py.data(), s.pz.data(), out.points);
  storeStatuses(in.width, in.status, s.code.data(), out.status);
  std::copy(s.depth_per_px.begin(), s.depth_per_px.begin() + in.width, out.depth_per_px);
}

}  // namespace

RigGeometry makeRigGeometry(const io::RigCalibration& rig, const EpipolarPencil& pencil, double max_epipolar_error) {
  RigGeometry g;
  const Eigen::Matrix3d r = rig.T_projector_camera.linear();
  const Eigen::Vector3d c = rig.T_projector_camera.translation();
  const Eigen::Vector3d q2 = r.transpose() * pencil.e2.cross(c);
  const Eigen::Vector3d q3 = r.transpose() * pencil.e3.cross(c);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) g.r[3 * i + j] = static_cast<float>(r(i, j));
    g.c[i] = static_cast<float>(c[i]);
    g.q2[i] = static_cast<float>(q2[i]);
    g.q3[i] = static_cast<float>(q3[i]);
  }
  g.fx = static_cast<float>(rig.projector.fx);
  g.fy = static_cast<float>(rig.projector.fy);
  const double aspect = rig.projector.fx / rig.projector.fy;
  g.aspect_sq = static_cast<float>(aspect * aspect);
  const double max_error = max_epipolar_error / rig.projector.fx;
  g.max_error_sq = static_cast<float>(max_error * max_error);
  g.max_depth = static_cast<float>(kMaxDepthInBaselines * c.norm());
  return g;
}

TriangulationScratch::TriangulationScratch(int width)
    : label(width),
      fx(width),
      fy(width),
      px(width),
      py(width),
      pz(width),
      depth_per_px(width),
      light(4 * width),
      code(width),
      cell(width),
      column_px(width),
      column_py(width),
      column_pz(width),
      column_depth_per_px(width),
      column_code(width) {}

void triangulateImageRowWithProjectorRows(const RigGeometry& rig, const ProjectorTables& tables,
                                          const TriangulationImageRowInput& in, TriangulationScratch& s,
                                          const TriangulationImageRowOutput& out) {
  const int n = in.width;
  const auto grid = tables.undistort.view();
  // A projector row outside the table names a projector pixel outside the image too.
  locateCells(grid, n, in.column, in.row, in.status, tables.min_column, tables.max_column, kOutOfRange, s.cell.data(),
              s.fx.data(), s.fy.data(), s.code.data());
  undistortCells(grid, n, s.cell.data(), s.fx.data(), s.fy.data(), s.light.data());
  solveWithProjectorRows(rig, n, in.ray_x, in.ray_y, s.light.data(), in.expected_offset, in.limit_scale_sq,
                         s.code.data(), s.px.data(), s.py.data(), s.pz.data(), s.depth_per_px.data());
  solveMissingProjectorRows(rig, tables, in, s);
  writeImageRow(in, s, out);
}

void triangulateImageRowColumnOnly(const RigGeometry& rig, const ProjectorTables& tables,
                                   const TriangulationImageRowInput& in, TriangulationScratch& s,
                                   const TriangulationImageRowOutput& out) {
  solveByColumns(rig, tables, in, s, s.code.data(), {s.px.data(), s.py.data(), s.pz.data(), s.depth_per_px.data()});
  writeImageRow(in, s, out);
}

}  // namespace binpick::reconstruction::detail
