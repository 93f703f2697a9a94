// The calibration's fit to a capture, per sampled pixel, and its smooth residual field.
//
// Frames as in triangulation_rows.cpp: in the projector frame the camera ray of a pixel is
// C + t d with C the camera centre and d = R (a, b, 1), (a, b) its undistorted normalised
// coordinates, so t is the point's camera z; the projector ray of the decoded (column, row) is
// s (u, v, 1), (u, v) undistorted normalised projector coordinates, s the projector z.
#include "epipolar_residual.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "binpick/reconstruction/pixel_status.hpp"

namespace binpick::reconstruction::detail {
namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();
// Rays closer to parallel than this (the sine of their angle, squared) meet nowhere useful.
constexpr double kMinSineSquared = 1e-12;
// The field's tiles: small enough to follow a calibration's error across the image (it varies
// over hundreds of pixels), large enough that the median of their samples ignores the
// misdecoded pixels of a depth edge or a dark spot.
constexpr int kTilePixels = 32;
constexpr int kMinSamplesPerTile = 8;
constexpr double kReportedShare = 0.95;  // of the tiles, within the reported largest offset

struct PixelFit {
  float epipolar_px = kNaNf;  // signed
  float gap_m = kNaNf;
  int tile = -1;
};

// The decoded (u, v) lies on the camera ray's image in the projector, the epipolar line
// n . (u, v, 1) = 0 with n = C x d, when the rays meet. In pixels (fx u, fy v) the line's normal
// is (nx / fx, ny / fy). Signed: the side of the line (the sign triangulation_rows.cpp uses).
double signedEpipolarPx(const RigFrames& rig, const Eigen::Vector3d& d, const Eigen::Vector3d& w) {
  const Eigen::Vector3d n = rig.c.cross(d);
  const double line = std::hypot(n.x() / rig.projector_fx, n.y() / rig.projector_fy);
  return n.dot(w) / line;
}

// The closest approach of C + t d and s w: NaN unless it lies in front of both devices.
double rayGapMetres(const RigFrames& rig, const Eigen::Vector3d& d, const Eigen::Vector3d& w) {
  const double dd = d.dot(d), dw = d.dot(w), ww = w.dot(w);
  const double dc = d.dot(rig.c), wc = w.dot(rig.c);
  const double denominator = dd * ww - dw * dw;  // |d x w|^2
  if (!(denominator > kMinSineSquared * dd * ww)) return kNaNf;
  const double t = (dw * wc - ww * dc) / denominator;
  const double s = (dd * wc - dw * dc) / denominator;
  if (!(t > 0.0 && s > 0.0)) return kNaNf;
  return (rig.c + t * d - s * w).norm();
}

PixelFit fitOfPixel(const RigFrames& rig, float a, float b, const float uv[2]) {
  PixelFit fit;
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(uv[0]) || !std::isfinite(uv[1])) return fit;
  const Eigen::Vector3d d = rig.r * Eigen::Vector3d(a, b, 1.0);
  const Eigen::Vector3d w(uv[0], uv[1], 1.0);
  fit.epipolar_px = static_cast<float>(signedEpipolarPx(rig, d, w));
  fit.gap_m = static_cast<float>(rayGapMetres(rig, d, w));
  return fit;
}

// The sampled pixels' measures, NaN where a pixel has no decoded column and row inside the
// projector image (the margin triangulation accepts included).
std::vector<PixelFit> fitOfSamples(const RigFrames& rig, const CameraRays& rays, const LookupGrid<2>& undistort,
                                   const DecodedCapture& decoded, const FitSampling& sampling, int tiles_x) {
  const int stride = sampling.stride;
  const int columns = (decoded.width + stride - 1) / stride, rows = (decoded.height + stride - 1) / stride;
  std::vector<PixelFit> fits(static_cast<std::size_t>(columns) * rows);
  const auto grid = undistort.view();
  constexpr auto kValid = static_cast<uint8_t>(PixelStatus::Valid);
#pragma omp parallel for num_threads(sampling.threads) schedule(static)
  for (int j = 0; j < rows; ++j) {
    const int y = j * stride;
    const float* column = decoded.column.ptr<float>(y);
    const float* row = decoded.row.ptr<float>(y);
    const uint8_t* status = decoded.status.ptr<uint8_t>(y);
    // Pixels read along their stripes are coarser than the calibration's residual: not measured.
    const uint8_t* stripe_run = decoded.stripe_run.empty() ? nullptr : decoded.stripe_run.ptr<uint8_t>(y);
    for (int i = 0; i < columns; ++i) {
      const int x = i * stride;
      if (status[x] != kValid || (stripe_run != nullptr && stripe_run[x] != 0)) continue;
      const auto at = grid.locate(column[x], row[x]);  // NaN rows fall outside
      if (!at.inside) continue;
      float uv[2];
      grid.interpolate(at.cell, at.fx, at.fy, uv);
      const std::size_t pixel = static_cast<std::size_t>(y) * decoded.width + x;
      PixelFit& fit = fits[static_cast<std::size_t>(j) * columns + i];
      fit = fitOfPixel(rig, rays.x[pixel], rays.y[pixel], uv);
      fit.tile = (y / kTilePixels) * tiles_x + x / kTilePixels;
    }
  }
  return fits;
}

// The upper median: half the values are at most it.
float median(std::vector<float> values) {
  if (values.empty()) return kNaNf;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// Each tile's own median where it has enough samples, then the median of each measured tile's
// 3 x 3 neighbourhood (a tile of mostly misdecoded pixels does not bend the field), then the
// tiles without samples filled from their measured neighbours, wave by wave.
std::vector<float> tileMedians(const std::vector<PixelFit>& fits, int tiles_x, int tiles_y) {
  std::vector<std::vector<float>> samples(static_cast<std::size_t>(tiles_x) * tiles_y);
  for (const PixelFit& fit : fits) {
    if (fit.tile >= 0 && !std::isnan(fit.epipolar_px)) samples[fit.tile].push_back(fit.epipolar_px);
  }
  std::vector<float> own(samples.size(), kNaNf);
  for (std::size_t t = 0; t < samples.size(); ++t) {
    if (samples[t].size() >= kMinSamplesPerTile) own[t] = median(std::move(samples[t]));
  }
  std::vector<float> field(own.size(), kNaNf);
  for (int ty = 0; ty < tiles_y; ++ty) {
    for (int tx = 0; tx < tiles_x; ++tx) {
      if (std::isnan(own[ty * tiles_x + tx])) continue;
      std::vector<float> around;
      for (int j = std::max(0, ty - 1); j <= std::min(tiles_y - 1, ty + 1); ++j) {
        for (int i = std::max(0, tx - 1); i <= std::min(tiles_x - 1, tx + 1); ++i) {
          if (!std::isnan(own[j * tiles_x + i])) around.push_back(own[j * tiles_x + i]);
        }
      }
      field[ty * tiles_x + tx] = median(std::move(around));
    }
  }
  return field;
}

void fillUnmeasuredTiles(std::vector<float>& field, int tiles_x, int tiles_y) {
  for (bool missing = true; missing;) {
    missing = false;
    std::vector<float> next = field;
    bool filled = false;
    for (int ty = 0; ty < tiles_y; ++ty) {
      for (int tx = 0; tx < tiles_x; ++tx) {
        if (!std::isnan(field[ty * tiles_x + tx])) continue;
        double sum = 0.0;
        int count = 0;
        for (int j = std::max(0, ty - 1); j <= std::min(tiles_y - 1, ty + 1); ++j) {
          for (int i = std::max(0, tx - 1); i <= std::min(tiles_x - 1, tx + 1); ++i) {
            if (!std::isnan(field[j * tiles_x + i])) sum += field[j * tiles_x + i], ++count;
          }
        }
        if (count > 0)
          next[ty * tiles_x + tx] = static_cast<float>(sum / count), filled = true;
        else
          missing = true;
      }
    }
    field.swap(next);
    if (missing && !filled) return;  // no tile measured at all
  }
}

EpipolarResidualField residualField(const std::vector<PixelFit>& fits, const DecodedCapture& decoded,
                                    double max_residual_px, CalibrationFit& fit) {
  EpipolarResidualField field;
  field.tile = kTilePixels;
  field.tiles_x = (decoded.width + kTilePixels - 1) / kTilePixels;
  field.tiles_y = (decoded.height + kTilePixels - 1) / kTilePixels;
  field.offset_px = tileMedians(fits, field.tiles_x, field.tiles_y);
  fillUnmeasuredTiles(field.offset_px, field.tiles_x, field.tiles_y);
  if (std::isnan(field.offset_px.front())) return {};
  std::vector<float> sizes;
  const auto limit = static_cast<float>(max_residual_px);
  for (float& offset : field.offset_px) {
    sizes.push_back(std::abs(offset));
    offset = std::clamp(offset, -limit, limit);  // beyond it: not a calibration's residual
  }
  // The largest but for a few tiles: those of a region decoded all wrong (a dark or shadowed
  // corner whose codes are noise) would name hundreds of pixels.
  const auto upper = sizes.begin() + static_cast<std::ptrdiff_t>(kReportedShare * (sizes.size() - 1));
  std::nth_element(sizes.begin(), upper, sizes.end());
  fit.largest_residual_px = *upper;
  return field;
}

// The field at a sample's tile (its value at the tile's centre; triangulation interpolates
// between centres): close enough for a summary.
float fieldAt(const EpipolarResidualField& field, int tile) {
  return field.offset_px.empty() ? 0.0f : field.offset_px[static_cast<std::size_t>(tile)];
}

void summarise(const std::vector<PixelFit>& fits, const EpipolarResidualField* field, double limit_px,
               CalibrationFit& fit) {
  std::vector<float> epipolar, off_field, gaps;
  std::size_t beyond = 0;
  for (const PixelFit& sample : fits) {
    if (std::isnan(sample.epipolar_px)) continue;
    epipolar.push_back(std::abs(sample.epipolar_px));
    const float judged = field ? std::abs(sample.epipolar_px - fieldAt(*field, sample.tile)) : epipolar.back();
    if (field) off_field.push_back(judged);
    beyond += judged > limit_px ? 1 : 0;
    if (!std::isnan(sample.gap_m)) gaps.push_back(sample.gap_m);
  }
  fit.epipolar_limit_px = limit_px;
  fit.pixels = epipolar.size();
  fit.pixels_with_gap = gaps.size();
  fit.beyond_limit_share = epipolar.empty() ? 0.0 : static_cast<double>(beyond) / epipolar.size();
  fit.median_epipolar_px = median(std::move(epipolar));
  fit.median_off_residual_px = median(std::move(off_field));
  fit.median_gap_mm = 1000.0 * median(std::move(gaps));
}

}  // namespace

void EpipolarResidualField::rowOffsets(int y, int width, float* out) const {
  if (offset_px.empty()) {
    std::fill(out, out + width, 0.0f);
    return;
  }
  // Tile centres at (i + 0.5) tile; clamped at the image's border tiles.
  const float gy = std::clamp((y + 0.5f) / tile - 0.5f, 0.0f, static_cast<float>(tiles_y - 1));
  const int j0 = static_cast<int>(gy), j1 = std::min(j0 + 1, tiles_y - 1);
  const float wy = gy - j0;
  const float* upper = &offset_px[static_cast<std::size_t>(j0) * tiles_x];
  const float* lower = &offset_px[static_cast<std::size_t>(j1) * tiles_x];
  for (int x = 0; x < width; ++x) {
    const float gx = std::clamp((x + 0.5f) / tile - 0.5f, 0.0f, static_cast<float>(tiles_x - 1));
    const int i0 = static_cast<int>(gx), i1 = std::min(i0 + 1, tiles_x - 1);
    const float wx = gx - i0;
    const float top = upper[i0] + wx * (upper[i1] - upper[i0]);
    const float bottom = lower[i0] + wx * (lower[i1] - lower[i0]);
    out[x] = top + wy * (bottom - top);
  }
}

RigFrames rigFrames(const io::RigCalibration& rig) {
  return {rig.T_projector_camera.linear(), rig.T_projector_camera.translation(), rig.projector.fx, rig.projector.fy};
}

FitMeasurement measureFit(const RigFrames& rig, const CameraRays& rays, const LookupGrid<2>& undistort,
                          const DecodedCapture& decoded, const FitSampling& sampling) {
  FitMeasurement result;
  const int tiles_x = (decoded.width + kTilePixels - 1) / kTilePixels;
  const std::vector<PixelFit> fits = fitOfSamples(rig, rays, undistort, decoded, sampling, tiles_x);
  if (sampling.max_residual_px > 0.0) result.field = residualField(fits, decoded, sampling.max_residual_px, result.fit);
  const bool followed = !result.field.offset_px.empty();
  summarise(fits, followed ? &result.field : nullptr, sampling.limit_px, result.fit);
  result.fit.residual_limit_px = sampling.max_residual_px;
  return result;
}

}  // namespace binpick::reconstruction::detail
