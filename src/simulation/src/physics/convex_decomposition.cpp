#include "convex_decomposition.hpp"

#include <algorithm>
#include <cmath>

#include "cut_choice.hpp"
#include "hull_fit.hpp"
#include "piece_merging.hpp"

namespace binpick::simulation::detail {
namespace {

// The grid's cells are half the tolerance, up to this many: beyond it the cells grow with the
// part (and the tolerance with them) to bound memory and time.
constexpr double kMaxCells = 4.0e6;
// Cutting may go this far beyond max_pieces before joining brings the count back down.
constexpr int kCutBudgetFactor = 2;

double cellSizeFor(const io::TriangleMesh& mesh, double tolerance) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v.cast<double>());
  const Eigen::Vector3d padded = box.sizes().array() + 2.0 * tolerance;
  const double smallest = std::cbrt(padded.prod() / kMaxCells);
  return std::max(0.5 * tolerance, smallest);
}

struct OpenPiece {
  BoxPiece piece;
  double excess = 0.0;  // hull volume beyond the solid
};

}  // namespace

ConvexDecomposition convexDecomposition(const io::TriangleMesh& mesh, double tolerance, int max_pieces) {
  ConvexDecomposition result;
  result.cell_size = cellSizeFor(mesh, tolerance);
  result.far_distance = std::max(tolerance, 2.0 * result.cell_size);
  const CellGrid grid = gridAroundMesh(mesh, result.cell_size, result.far_distance);
  const MeshColumns columns(mesh, grid);
  const SolidGrid solid(mesh, columns, grid, result.far_distance);

  std::vector<ConvexHull> done;
  std::vector<OpenPiece> open;
  const double cell_volume = std::pow(result.cell_size, 3);
  const auto add = [&](BoxPiece piece) {
    if (piece.hull.vertices.empty()) return;  // no solid in this box
    if (hullFits(solid, piece.hull)) {
      done.push_back(std::move(piece.hull));
    } else {
      const double excess = piece.hull.volume - cell_volume * solid.insideCells(piece.box);
      open.push_back({std::move(piece), excess});
    }
  };
  add(makeBoxPiece({Eigen::Vector3i::Zero(), grid.size}, meshPolygons(mesh), grid, columns));
  // Worst piece first, so that a budget running out leaves the error spread evenly.
  const int budget = kCutBudgetFactor * max_pieces;
  while (!open.empty() && static_cast<int>(done.size() + open.size()) < budget) {
    const auto worst =
        std::max_element(open.begin(), open.end(), [](const auto& p, const auto& q) { return p.excess < q.excess; });
    OpenPiece piece = std::move(*worst);
    open.erase(worst);
    std::optional<BoxSplit> split = bestSplit(piece.piece, solid, columns);
    if (!split) {
      done.push_back(std::move(piece.piece.hull));  // cannot be cut any finer
      continue;
    }
    add(std::move(split->below));
    add(std::move(split->above));
  }
  for (auto& piece : open) done.push_back(std::move(piece.piece.hull));
  result.pieces = mergePieces(std::move(done), solid, max_pieces);
  result.fits =
      std::all_of(result.pieces.begin(), result.pieces.end(), [&](const ConvexHull& p) { return hullFits(solid, p); });
  return result;
}

}  // namespace binpick::simulation::detail
