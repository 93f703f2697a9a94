#include "mass_properties.hpp"

#include <Eigen/Eigenvalues>

namespace binpick::simulation::detail {

MassProperties massProperties(const io::TriangleMesh& mesh) {
  // Sum over the tetrahedra spanned by each triangle and a reference point (a vertex, so that the
  // sums stay small and lose no precision to a far-away origin). For the tetrahedron
  // (0, a, b, c) of signed volume v: integral of x x^T = v / 20 (a a^T + b b^T + c c^T + s s^T),
  // s = a + b + c, and its centroid is s / 4.
  const Eigen::Vector3d reference =
      mesh.vertices.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(mesh.vertices[0].cast<double>());
  double six_volume = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();   // times 24
  Eigen::Matrix3d second_moment = Eigen::Matrix3d::Zero();  // times 120
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>() - reference;
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>() - reference;
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>() - reference;
    const Eigen::Vector3d s = a + b + c;
    const double v6 = a.dot(b.cross(c));
    six_volume += v6;
    first_moment += v6 * s;
    second_moment += v6 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  MassProperties mass;
  mass.volume = six_volume / 6.0;
  if (mass.volume == 0.0) return mass;
  const Eigen::Vector3d centroid_offset = first_moment / (4.0 * six_volume);
  mass.centroid = reference + centroid_offset;
  // Second moment about the centroid, then the inertia tensor trace(C) I - C.
  const Eigen::Matrix3d about_reference = second_moment / 120.0;
  const Eigen::Matrix3d about_centroid = about_reference - mass.volume * centroid_offset * centroid_offset.transpose();
  mass.inertia = about_centroid.trace() * Eigen::Matrix3d::Identity() - about_centroid;
  return mass;
}

PrincipalFrame principalFrame(const MassProperties& mass) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(mass.inertia);
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
  PrincipalFrame frame;
  frame.T_model_body.linear() = axes;
  frame.T_model_body.translation() = mass.centroid;
  frame.moments = solver.eigenvalues();
  frame.volume = mass.volume;
  return frame;
}

}  // namespace binpick::simulation::detail
