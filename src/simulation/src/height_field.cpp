#include "height_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace binpick::sim::detail {

HeightField::HeightField(double length, double width, double cell_size)
    : half_length_(0.5 * length),
      half_width_(0.5 * width),
      cells_per_metre_(1.0 / cell_size),
      columns_(std::max(1, static_cast<int>(std::ceil(length / cell_size)))),
      rows_(std::max(1, static_cast<int>(std::ceil(width / cell_size)))),
      top_(static_cast<std::size_t>(columns_) * rows_, 0.0f) {}

// Points are kept inside the bin by the caller; clamping only guards against rounding at the rim.
int HeightField::column(float x) const {
  const int c = static_cast<int>(std::floor((x + half_length_) * cells_per_metre_));
  return std::clamp(c, 0, columns_ - 1);
}

int HeightField::row(float y) const {
  const int r = static_cast<int>(std::floor((y + half_width_) * cells_per_metre_));
  return std::clamp(r, 0, rows_ - 1);
}

CellColumns HeightField::columnsOf(const std::vector<Eigen::Vector3f>& points) const {
  CellColumns part;
  if (points.empty()) return part;
  // Cell of each point computed once: this runs over ~10^5 samples per dropped part.
  std::vector<Eigen::Vector2i> cells(points.size());
  Eigen::Vector2i lo(columns_, rows_), hi(-1, -1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    cells[i] = {column(points[i].x()), row(points[i].y())};
    lo = lo.cwiseMin(cells[i]);
    hi = hi.cwiseMax(cells[i]);
  }
  part.column0 = lo.x();
  part.row0 = lo.y();
  part.columns = hi.x() - lo.x() + 1;
  part.rows = hi.y() - lo.y() + 1;
  const std::size_t count = static_cast<std::size_t>(part.columns) * part.rows;
  part.low.assign(count, std::numeric_limits<float>::infinity());
  part.high.assign(count, -std::numeric_limits<float>::infinity());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t cell = static_cast<std::size_t>(cells[i].y() - part.row0) * part.columns +
                             static_cast<std::size_t>(cells[i].x() - part.column0);
    part.low[cell] = std::min(part.low[cell], points[i].z());
    part.high[cell] = std::max(part.high[cell], points[i].z());
  }
  return part;
}

double HeightField::restingLift(const CellColumns& part) const {
  double lift = -std::numeric_limits<double>::infinity();
  for (int r = 0; r < part.rows; ++r) {
    for (int c = 0; c < part.columns; ++c) {
      const float low = part.low[static_cast<std::size_t>(r) * part.columns + c];
      if (!std::isfinite(low)) continue;  // the part does not reach this cell
      lift = std::max(lift, static_cast<double>(top(part.column0 + c, part.row0 + r)) - low);
    }
  }
  return lift;
}

void HeightField::raise(const CellColumns& part, float lift) {
  for (int r = 0; r < part.rows; ++r) {
    for (int c = 0; c < part.columns; ++c) {
      const float high = part.high[static_cast<std::size_t>(r) * part.columns + c];
      if (!std::isfinite(high)) continue;
      const int column_here = part.column0 + c, row_here = part.row0 + r;
      for (int rr = std::max(0, row_here - 1); rr <= std::min(rows_ - 1, row_here + 1); ++rr) {
        for (int cc = std::max(0, column_here - 1); cc <= std::min(columns_ - 1, column_here + 1);
             ++cc) {
          top(cc, rr) = std::max(top(cc, rr), high + lift);
        }
      }
    }
  }
}

}  // namespace binpick::sim::detail
