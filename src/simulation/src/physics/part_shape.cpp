#include "part_shape.hpp"

#include "bullet_units.hpp"
#include "convex_decomposition.hpp"
#include "hull_simplification.hpp"
#include "mass_properties.hpp"

namespace binpick::simulation::detail {
namespace {

// Steel. Every part in a pile is a copy of the same one, so the density only scales all masses
// alike and does not change how the pile settles; it is here to keep the numbers physical.
constexpr double kDensity = 7850.0;  // kg/m^3
// The principal frame must shrink the bounding box by this factor to be preferred over the model's
// own axes, so that a part drawn along its axes keeps them despite rounding.
constexpr double kTighterBy = 0.9;
// Pieces with more vertices are simplified (hull_simplification.hpp).
constexpr std::size_t kMaxVertices = 48;

// The decomposition cuts along the axes of its frame: the model's own axes when the part is drawn
// along them (a prism extruded along z), else its principal axes, whichever box is tighter. A part
// drawn at a slant would otherwise be cut into needlessly many pieces.
Eigen::Isometry3d decompositionFrame(const io::TriangleMesh& mesh, const Eigen::Isometry3d& T_model_body) {
  const auto boxVolume = [&](const Eigen::Isometry3d& T_frame_model) {
    Eigen::AlignedBox3d box;
    for (const auto& v : mesh.vertices) box.extend(T_frame_model * v.cast<double>());
    return box.volume();
  };
  const bool principal_is_tighter =
      boxVolume(T_model_body.inverse()) < kTighterBy * boxVolume(Eigen::Isometry3d::Identity());
  return principal_is_tighter ? T_model_body : Eigen::Isometry3d::Identity();
}

io::TriangleMesh transformed(io::TriangleMesh mesh, const Eigen::Isometry3d& T_frame_model) {
  for (auto& v : mesh.vertices) v = (T_frame_model * v.cast<double>()).cast<float>();
  return mesh;
}

}  // namespace

PartShape::PartShape(const io::TriangleMesh& mesh, const PhysicsParams& params) {
  const PrincipalFrame frame = principalFrame(massProperties(mesh));
  T_model_body_ = frame.T_model_body;
  mass_ = kDensity * frame.volume;
  const Eigen::Vector3d inertia = kDensity * kWorldScale * kWorldScale * frame.moments;
  inertia_ = btVector3(static_cast<btScalar>(inertia.x()), static_cast<btScalar>(inertia.y()),
                       static_cast<btScalar>(inertia.z()));

  const Eigen::Isometry3d T_model_cut = decompositionFrame(mesh, T_model_body_);
  const ConvexDecomposition decomposition = convexDecomposition(
      transformed(mesh, T_model_cut.inverse()), params.decomposition_tolerance, params.max_convex_pieces);
  const Eigen::Isometry3d T_body_cut = T_model_body_.inverse() * T_model_cut;
  compound_ = std::make_unique<btCompoundShape>(true, static_cast<int>(decomposition.pieces.size()));
  std::vector<Eigen::Vector3d> corners;
  for (const ConvexHull& piece : decomposition.pieces) {
    auto hull = std::make_unique<btConvexHullShape>();
    // Within half the margin of the piece: the margin still covers the whole of it.
    const double tolerance = 0.5 * params.collision_margin;
    for (const Eigen::Vector3d& vertex : simplifiedHullVertices(piece, tolerance, kMaxVertices)) {
      hull->addPoint(toWorld(T_body_cut * vertex), false);
    }
    for (const Eigen::Vector3d& vertex : piece.vertices) corners.push_back(T_model_cut * vertex);
    hull->setMargin(static_cast<btScalar>(kWorldScale * params.collision_margin));
    hull->recalcLocalAabb();
    compound_->addChildShape(btTransform::getIdentity(), hull.get());
    hulls_.push_back(std::move(hull));
  }
  extreme_points_ = convexHull(corners).vertices;
}

}  // namespace binpick::simulation::detail
