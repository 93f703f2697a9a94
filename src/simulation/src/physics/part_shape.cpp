#include "part_shape.hpp"

#include "bullet_units.hpp"
#include "convex_decomposition.hpp"
#include "mass_properties.hpp"

namespace binpick::sim::detail {
namespace {

// Steel. Every part in a pile is a copy of the same one, so the density only scales all masses
// alike and does not change how the pile settles; it is here to keep the numbers physical.
constexpr double kDensity = 7850.0;  // kg/m^3

}  // namespace

PartShape::PartShape(const TriangleMesh& mesh, const PhysicsParams& params) {
  const PrincipalFrame frame = principalFrame(massProperties(mesh));
  T_model_body_ = frame.T_model_body;
  mass_ = kDensity * frame.volume;
  const Eigen::Vector3d inertia = kDensity * kWorldScale * kWorldScale * frame.moments;
  inertia_ = btVector3(static_cast<btScalar>(inertia.x()), static_cast<btScalar>(inertia.y()),
                       static_cast<btScalar>(inertia.z()));

  const ConvexDecomposition decomposition =
      convexDecomposition(mesh, params.decomposition_tolerance, params.max_convex_pieces);
  const Eigen::Isometry3d T_body_model = T_model_body_.inverse();
  compound_ = std::make_unique<btCompoundShape>(true, static_cast<int>(decomposition.pieces.size()));
  for (const ConvexHull& piece : decomposition.pieces) {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const Eigen::Vector3d& vertex : piece.vertices) {
      hull->addPoint(toWorld(T_body_model * vertex), false);
      extreme_points_.push_back(vertex);
    }
    hull->setMargin(static_cast<btScalar>(kWorldScale * params.collision_margin));
    hull->recalcLocalAabb();
    compound_->addChildShape(btTransform::getIdentity(), hull.get());
    hulls_.push_back(std::move(hull));
  }
}

}  // namespace binpick::sim::detail
