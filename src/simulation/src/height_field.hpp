#pragma once
// The top surface of what lies in the bin, on a grid of square cells over the bin's inner area:
// the floor at first, then every part dropped so far. Internal to binpick::simulation.
// A plain value: not synchronised.
#include <Eigen/Core>
#include <vector>

namespace binpick::sim::detail {

// A part's points binned on the height-field grid: per cell its lowest and highest point, over
// the rectangle of cells its footprint covers (+inf / -inf in cells it does not reach).
struct CellColumns {
  int column0 = 0, row0 = 0, columns = 0, rows = 0;
  std::vector<float> low, high;  // row-major over the rectangle
};

class HeightField {
 public:
  // Covers x in [-length/2, length/2], y in [-width/2, width/2] (bin frame), all at height 0.
  HeightField(double length, double width, double cell_size);

  CellColumns columnsOf(const std::vector<Eigen::Vector3f>& points) const;

  // How far the part must be raised (possibly a negative amount: lowered) so that in no cell its
  // lowest point is below the field's top: where a part dropped from above first touches.
  double restingLift(const CellColumns& part) const;

  // Raises the field to the part's highest points. Each cell also raises its 8 neighbours: a
  // later part's point near a cell border may fall in the neighbour of the sample that marks
  // this surface, and the margin keeps the interpenetration below the sample spacing.
  void raise(const CellColumns& part, float lift);

 private:
  int column(float x) const;
  int row(float y) const;
  float& top(int column, int row) {
    return top_[static_cast<std::size_t>(row) * columns_ + column];
  }
  float top(int column, int row) const {
    return top_[static_cast<std::size_t>(row) * columns_ + column];
  }

  double half_length_, half_width_, cells_per_metre_;
  int columns_, rows_;
  std::vector<float> top_;  // row-major, rows along y
};

}  // namespace binpick::sim::detail
