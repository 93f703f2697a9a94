// normalisedImageBounds and pixelsSeeing: a box's footprint through a distorting lens.
#include "lens_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace binpick::simulation::detail {
namespace {

// Samples per side of a rectangle mapped through the distortion; the curve between samples
// departs from its chord by far less than kPaddingPixels.
constexpr int kSamplesPerSide = 64;
constexpr double kPaddingPixels = 2.0;
// Nearer than this (metres) the box counts as reaching the camera plane.
constexpr double kMinDepth = 1e-6;

Eigen::Vector2d toPixel(const io::LensIntrinsics& lens, const Eigen::Vector2d& normalised) {
  const Eigen::Vector2d d = lens.distort(normalised);
  return {lens.fx * d.x() + lens.cx, lens.fy * d.y() + lens.cy};
}

Eigen::Vector2d fromPixel(const io::LensIntrinsics& lens, const Eigen::Vector2d& pixel) {
  return lens.undistort({(pixel.x() - lens.cx) / lens.fx, (pixel.y() - lens.cy) / lens.fy});
}

// Point `s` in [0, 1) of the way round the rectangle's border.
Eigen::Vector2d alongBorder(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int side, double s) {
  switch (side) {
    case 0: return {lo.x() + s * (hi.x() - lo.x()), lo.y()};
    case 1: return {hi.x(), lo.y() + s * (hi.y() - lo.y())};
    case 2: return {hi.x() - s * (hi.x() - lo.x()), hi.y()};
    default: return {lo.x(), hi.y() - s * (hi.y() - lo.y())};
  }
}

PixelRange wholeImage(const io::LensIntrinsics& lens) { return {0, lens.width, 0, lens.height}; }

}  // namespace

Eigen::AlignedBox2d normalisedImageBounds(const io::LensIntrinsics& lens, double margin) {
  const Eigen::Vector2d lo(-0.5, -0.5), hi(lens.width - 0.5, lens.height - 0.5);
  // Pixel steps along the border: one sample per pixel edge is plenty for a smooth lens.
  const int steps = std::max(lens.width, lens.height);
  Eigen::AlignedBox2d bounds;
  for (int side = 0; side < 4; ++side) {
    for (int i = 0; i < steps; ++i) {
      bounds.extend(fromPixel(lens, alongBorder(lo, hi, side, static_cast<double>(i) / steps)));
    }
  }
  const Eigen::Vector2d grow = margin * bounds.sizes();
  return {bounds.min() - grow, bounds.max() + grow};
}

PixelRange pixelsSeeing(const io::LensIntrinsics& lens, const Eigen::AlignedBox2d& field,
                        const Eigen::AlignedBox3d& box) {
  if (box.isEmpty() || box.max().z() <= 0.0) return {};
  if (box.min().z() <= kMinDepth) return wholeImage(lens);
  // x/z and y/z over a box in front of the camera are extreme at its corners.
  Eigen::AlignedBox2d directions;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner));
    directions.extend(Eigen::Vector2d(p.x() / p.z(), p.y() / p.z()));
  }
  directions = directions.intersection(field);
  if (directions.isEmpty()) return {};
  // The lens maps the rectangle one-to-one, so its image is bounded by the image of its border.
  Eigen::AlignedBox2d pixels;
  const int samples = lens.hasDistortion() ? kSamplesPerSide : 1;
  for (int side = 0; side < 4; ++side) {
    for (int i = 0; i < samples; ++i) {
      const double s = static_cast<double>(i) / samples;
      pixels.extend(toPixel(lens, alongBorder(directions.min(), directions.max(), side, s)));
    }
  }
  const auto clampTo = [](double value, int limit) {
    return static_cast<int>(std::clamp(value, 0.0, static_cast<double>(limit)));
  };
  PixelRange range;
  range.u_begin = clampTo(std::ceil(pixels.min().x() - kPaddingPixels), lens.width);
  range.u_end = clampTo(std::floor(pixels.max().x() + kPaddingPixels) + 1.0, lens.width);
  range.v_begin = clampTo(std::ceil(pixels.min().y() - kPaddingPixels), lens.height);
  range.v_end = clampTo(std::floor(pixels.max().y() + kPaddingPixels) + 1.0, lens.height);
  return range;
}

}  // namespace binpick::simulation::detail
