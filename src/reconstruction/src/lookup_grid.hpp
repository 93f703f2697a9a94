#pragma once
// Values sampled on a regular grid over a rectangle of 2D coordinates and read back by bilinear
// interpolation. The lens models are smooth, so a grid a few pixels coarse reproduces them far
// below the decoder's precision, for a few loads instead of a Newton solve per pixel. Nodes are
// stored row-major with their channels interleaved. Immutable once filled: thread-safe.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "binpick/core/error.hpp"
#include "float4.hpp"

namespace binpick::reconstruction::detail {

template <int Channels>
class LookupGrid {
  static_assert(Channels == 2 || Channels == 4, "lookups read four floats at a time");

 public:
  // A grid nothing falls in (its corner is at infinity), with one cell of NaN to interpolate.
  LookupGrid()
      : x_min_(std::numeric_limits<float>::infinity()),
        y_min_(x_min_),
        values_(4 * Channels, std::numeric_limits<float>::quiet_NaN()) {}
  // Nodes at (x_min + i step_x, y_min + j step_y), i < nx, j < ny; values start at zero.
  LookupGrid(double x_min, double y_min, double step_x, double step_y, int nx, int ny)
      : x_min_(static_cast<float>(x_min)),
        y_min_(static_cast<float>(y_min)),
        inv_step_x_(static_cast<float>(1.0 / step_x)),
        inv_step_y_(static_cast<float>(1.0 / step_y)),
        nx_(nx),
        ny_(ny),
        x_min_d_(x_min),
        y_min_d_(y_min),
        step_x_(step_x),
        step_y_(step_y),
        values_(static_cast<std::size_t>(nx) * ny * Channels, 0.0f) {
    // locate() computes node indices in float arithmetic.
    if (static_cast<double>(nx) * ny >= (1 << 24)) throw core::Error("LookupGrid: too many nodes");
  }

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double nodeX(int i) const { return x_min_d_ + i * step_x_; }
  double nodeY(int j) const { return y_min_d_ + j * step_y_; }
  float* node(int i, int j) { return &values_[(static_cast<std::size_t>(j) * nx_ + i) * Channels]; }

  // A copy of what lookups read, to keep in registers across a loop: the compiler must assume
  // that a store through any float pointer may change a member of the grid itself.
  // Lookups come in two steps so that the first vectorises: locate() is branch-free arithmetic,
  // interpolate() the loads (SSE has no gather).
  struct View {
    float x_min, y_min, inv_step_x, inv_step_y, last_x, last_y;
    float row_nodes;  // nx, as a float
    int32_t nx;
    const float* values;

    // The cell a point falls in, as the offset of its first value, and the point's position
    // within it. Outside the grid (or for NaN coordinates) `inside` is false and the cell is
    // the first one, so that interpolating it stays inside the table.
    struct Location {
      int32_t cell;
      float fx, fy;
      bool inside;
    };
    Location locate(float x, float y) const {
      float gx = (x - x_min) * inv_step_x;
      float gy = (y - y_min) * inv_step_y;
      // Written so that NaN fails too; & rather than && keeps it branch-free. The last node
      // row and column are only ever far corners.
      const bool inside = (gx >= 0.0f) & (gx < last_x) & (gy >= 0.0f) & (gy < last_y);
      gx = inside ? gx : 0.0f;
      gy = inside ? gy : 0.0f;
      const auto i = static_cast<float>(static_cast<int32_t>(gx));
      const auto j = static_cast<float>(static_cast<int32_t>(gy));
      // The node index in float arithmetic (exact below 2^24 nodes): SSE2 has no 32-bit
      // integer multiply, and this loop is vectorised.
      const auto node = static_cast<int32_t>(j * row_nodes + i);
      return {node * Channels, gx - i, gy - j, inside};
    }

    // Bilinear interpolation in a located cell, four floats at a time (a node pair of a
    // 2-channel grid, one node of a 4-channel grid), into out[0 .. Channels - 1]. A corner
    // node that holds NaN (a lens model without inverse there) gives NaN, which the callers'
    // checks turn into a verdict.
    void interpolate(int32_t cell, float fx, float fy, float* out) const {
      const float* top = values + cell;
      const float* bottom = top + static_cast<std::ptrdiff_t>(nx) * Channels;
      if constexpr (Channels == 2) {
        const Float4 pair = lerpFloat4(loadFloat4(top), loadFloat4(bottom), fy);  // u0 v0 u1 v1
        const Float4 right = __builtin_shufflevector(pair, pair, 2, 3, 2, 3);
        storeFloat2(out, lerpFloat4(pair, right, fx));
      } else {
        const Float4 left = lerpFloat4(loadFloat4(top), loadFloat4(bottom), fy);
        const Float4 right = lerpFloat4(loadFloat4(top + 4), loadFloat4(bottom + 4), fy);
        storeFloat4(out, lerpFloat4(left, right, fx));
      }
    }
  };

  View view() const {
    return {x_min_,
            y_min_,
            inv_step_x_,
            inv_step_y_,
            static_cast<float>(nx_ - 1),
            static_cast<float>(ny_ - 1),
            static_cast<float>(nx_),
            nx_,
            values_.data()};
  }

 private:
  float x_min_ = 0.0f, y_min_ = 0.0f, inv_step_x_ = 1.0f, inv_step_y_ = 1.0f;
  int nx_ = 2, ny_ = 2;
  double x_min_d_ = 0.0, y_min_d_ = 0.0, step_x_ = 1.0, step_y_ = 1.0;
  std::vector<float> values_;
};

}  // namespace binpick::reconstruction::detail
