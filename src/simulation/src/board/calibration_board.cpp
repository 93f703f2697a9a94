// CalibrationBoard: the board's box, its corners and its print as a texture.
#include "binpick/simulation/calibration_board.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "binpick/core/error.hpp"
#include "board_print.hpp"
#include "mesh_geometry.hpp"

namespace binpick::simulation {
namespace {

// A box over `face` from z = 0 (the print, normal -z) to z = thickness, outward winding.
io::TriangleMesh boardBox(const Eigen::AlignedBox2d& face, double thickness) {
  io::TriangleMesh mesh;
  detail::appendBox(mesh, Eigen::Vector3d(face.min().x(), face.min().y(), 0.0).cast<float>(),
                    Eigen::Vector3d(face.max().x(), face.max().y(), thickness).cast<float>());
  return mesh;
}

}  // namespace

CalibrationBoard::CalibrationBoard(const BoardSpec& spec, double texel_size) : spec_(spec) {
  spec_.validate();
  if (!std::isfinite(texel_size) || texel_size <= 0.0) {
    std::ostringstream message;
    message << "CalibrationBoard texel_size must be positive (got " << texel_size << ")";
    throw core::Error(message.str());
  }
  squares_origin_ = detail::squaresOrigin(spec_);
  const Eigen::Vector2d squares(spec_.squares_x * spec_.square_size, spec_.squares_y * spec_.square_size);
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(spec_.margin);
  face_ = Eigen::AlignedBox2d(squares_origin_ - margin, squares_origin_ + squares + margin);
  mesh_ = boardBox(face_, spec_.thickness);
  corners_ = detail::boardCornerPoints(spec_);

  texels_per_square_ = static_cast<int>(std::ceil(spec_.square_size / texel_size - 1e-9));
  const cv::Mat print = detail::drawBoardPrint(spec_, texels_per_square_);
  texture_width_ = print.cols;
  texture_height_ = print.rows;
  texture_.resize(static_cast<std::size_t>(print.cols) * print.rows);
  for (int row = 0; row < print.rows; ++row) {
    std::copy_n(print.ptr<uint8_t>(row), print.cols, texture_.begin() + row * print.cols);
  }
}

double CalibrationBoard::texelSize() const { return spec_.square_size / texels_per_square_; }

float CalibrationBoard::albedo(const Eigen::Vector2d& xy) const {
  // Texture coordinates with texel centres at half-integers, so that an edge between two texels
  // stays where the print has it.
  const Eigen::Vector2d t = (xy - squares_origin_) * (texels_per_square_ / spec_.square_size);
  const auto white = static_cast<float>(spec_.white_albedo);
  if (!(t.x() >= 0.0 && t.y() >= 0.0 && t.x() <= texture_width_ && t.y() <= texture_height_)) {
    return white;  // margin (or off the board)
  }
  const double ax = t.x() - 0.5, ay = t.y() - 0.5;
  const int x0 = static_cast<int>(std::floor(ax)), y0 = static_cast<int>(std::floor(ay));
  const double fx = ax - x0, fy = ay - y0;
  auto texel = [&](int x, int y) {  // clamped to the edge: the last half texel repeats
    x = std::clamp(x, 0, texture_width_ - 1);
    y = std::clamp(y, 0, texture_height_ - 1);
    return static_cast<double>(texture_[static_cast<std::size_t>(y) * texture_width_ + x]);
  };
  const double value = (1.0 - fy) * ((1.0 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
                       fy * ((1.0 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
  const double black = spec_.black_albedo;
  return static_cast<float>(black + (spec_.white_albedo - black) * value / 255.0);
}

float CalibrationBoard::meanAlbedo(const Eigen::Vector2d& centre, const Eigen::Matrix2d& footprint, int samples) const {
  if (samples <= 1) return albedo(centre);
  double sum = 0.0;
  for (int j = 0; j < samples; ++j) {
    for (int i = 0; i < samples; ++i) {
      // Midpoints of a samples x samples grid over [-1/2, 1/2]^2.
      const Eigen::Vector2d offset((i + 0.5) / samples - 0.5, (j + 0.5) / samples - 0.5);
      sum += albedo(centre + footprint * offset);
    }
  }
  return static_cast<float>(sum / (samples * samples));
}

}  // namespace binpick::simulation
