#include "binpick/estimation/model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>

#include "binpick/core/error.hpp"
#include "binpick/io/mesh_surface.hpp"
#include "binpick/io/mesh_symmetry.hpp"
#include "boundary.hpp"
#include "kdtree.hpp"
#include "point_ops.hpp"

namespace binpick::estimation {
namespace {

constexpr float kDegToRad = static_cast<float>(M_PI / 180.0);
constexpr float kTwoPi = static_cast<float>(2.0 * M_PI);
// One turn's references reach this far (in d_dist, along the circle about the axis) past the
// turn's end: a scene point whose equivalent lies at the sector's edge finds a sample on either
// side. A revolved part's strip is this wide in all: a voxel-subsampled profile has a point per
// step along every meridian strip that wide.
constexpr float kSectorMarginSteps = 0.5f;
constexpr float kRevolvedStripSteps = 2.0f;

// The original (dense) cloud with a reference normal per point used only for orientation.
struct DenseCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> orientation;
  bool has_exact_normals = false;  // a cloud file's own normals are kept as they are
};

DenseCloud denseFromMesh(const io::TriangleMesh& mesh, const ModelParams& params) {
  io::validateMesh(mesh, "model mesh");
  const double area = io::surfaceArea(mesh);
  const float diameter = approximateDiameter(mesh.vertices);
  if (!(area > 0.0) || !(diameter > 0.0f)) throw core::Error("model mesh has no surface area");
  const double step = params.sampling_ratio * diameter;
  const auto count = static_cast<std::size_t>(std::ceil(area / (step * step) * params.dense_samples_per_step2));
  if (count > 20'000'000)
    throw core::Error("model: sampling would need " + std::to_string(count) + " points; raise sampling_ratio");
  io::SurfaceSamples samples = io::sampleSurface(mesh, count, params.seed);
  return {std::move(samples.points), std::move(samples.face_normals), false};
}

DenseCloud denseFromCloud(const io::PointCloud& cloud) {
  DenseCloud dense;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite()) continue;  // an organized model scan may hold NaN pixels
    dense.points.push_back(cloud.points[i]);
    if (cloud.hasNormals()) dense.orientation.push_back(cloud.normals[i]);
  }
  if (dense.points.size() < 10) throw core::Error("model cloud has fewer than 10 valid points");
  dense.has_exact_normals = cloud.hasNormals();
  if (!dense.has_exact_normals) {
    Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
    for (const auto& p : dense.points) centroid += p;
    centroid /= static_cast<float>(dense.points.size());
    for (const auto& p : dense.points) dense.orientation.push_back((p - centroid).normalized());
  }
  return dense;
}

// Section III-A: normals from the neighbours in the original cloud, not the subsampled one.
std::vector<Eigen::Vector3f> fitNormals(const DenseCloud& dense, const KdTree& tree, float radius) {
  std::vector<Eigen::Vector3f> normals(dense.points.size());
  std::vector<uint32_t> neighbours;
  for (std::size_t i = 0; i < dense.points.size(); ++i) {
    tree.withinRadius(dense.points[i], radius, neighbours);
    PlaneFit fit;
    for (uint32_t j : neighbours) fit.add(dense.points[j]);
    Eigen::Vector3f n = fit.normal(5).value_or(dense.orientation[i]);
    normals[i] = n.dot(dense.orientation[i]) < 0.0f ? Eigen::Vector3f(-n) : n;
  }
  return normals;
}

ModelSymmetry symmetryOf(const io::TriangleMesh& mesh) {
  const io::FoundSymmetry found = io::findSymmetry(mesh);
  ModelSymmetry symmetry;
  if (found.turns == 1) return symmetry;
  symmetry.axis = found.axis.cast<float>().normalized();
  symmetry.turns = found.turns;
  symmetry.flips = found.flips;
  return symmetry;
}

// Puts the model points of one turn of its symmetry first, keeping their order; returns how many.
std::size_t referencesFirst(PreparedModel& model) {
  const ModelSymmetry& symmetry = model.symmetry;
  if (symmetry.turns == 1) return model.size();
  const Eigen::Vector3f u = symmetry.axis.unitOrthogonal(), v = symmetry.axis.cross(u);
  const float turn = symmetry.turns == 0 ? 0.0f : kTwoPi / static_cast<float>(symmetry.turns);
  const float reach = (symmetry.turns == 0 ? kRevolvedStripSteps : kSectorMarginSteps) * model.step;
  const float flip_margin = kSectorMarginSteps * model.step;
  const auto inFirstTurn = [&](const Eigen::Vector3f& p) {
    // A part that flips over shows its lower half as its upper half flipped: the upper half (and
    // half a step below the plane across the axis) is enough.
    if (symmetry.flips && p.dot(symmetry.axis) < -flip_margin) return false;
    const float radius = std::hypot(p.dot(u), p.dot(v));
    float azimuth = std::atan2(p.dot(v), p.dot(u));
    if (azimuth < 0.0f) azimuth += kTwoPi;
    return radius * (azimuth - turn) < reach;  // the arc past the turn's end
  };
  std::vector<uint32_t> order(model.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto first_other =
      std::stable_partition(order.begin(), order.end(), [&](uint32_t i) { return inFirstTurn(model.points[i]); });
  std::vector<Eigen::Vector3f> points, normals;
  for (uint32_t i : order) points.push_back(model.points[i]), normals.push_back(model.normals[i]);
  model.points = std::move(points);
  model.normals = std::move(normals);
  return static_cast<std::size_t>(first_other - order.begin());
}

}  // namespace

std::string ModelSymmetry::describe() const {
  if (turns == 1) return "none";
  char axis_text[64];
  const auto shown = [](float c) { return std::abs(c) < 5e-4f ? 0.0 : static_cast<double>(c); };  // no "-0"
  std::snprintf(axis_text, sizeof(axis_text), "(%.3g, %.3g, %.3g)", shown(axis.x()), shown(axis.y()), shown(axis.z()));
  return (turns == 0 ? std::string("revolved") : std::to_string(turns) + "-fold") + " about " + axis_text +
         (flips ? ", flips over" : "");
}

void ModelParams::validate() const {
  const char* owner = "model";
  core::requireField(sampling_ratio > 0.005f && sampling_ratio <= 0.5f, owner, "sampling_ratio", "in (0.005, 0.5]",
                     sampling_ratio);
  core::requireField(angle_step_deg >= 1.0f && angle_step_deg <= 90.0f, owner, "angle_step_deg", "in [1, 90]",
                     angle_step_deg);
  core::requireField(dense_samples_per_step2 >= 1.0f && dense_samples_per_step2 <= 1000.0f, owner,
                     "dense_samples_per_step2", "in [1, 1000]", dense_samples_per_step2);
  core::requireField(normal_radius_ratio > 0.05f && normal_radius_ratio <= 5.0f, owner, "normal_radius_ratio",
                     "in (0.05, 5]", normal_radius_ratio);
  core::requireField(normal_cluster_angle_deg >= 0.0f && normal_cluster_angle_deg <= 180.0f, owner,
                     "normal_cluster_angle_deg", "in [0, 180]", normal_cluster_angle_deg);
}

PpfQuantizer PreparedModel::quantizer() const {
  return PpfQuantizer(step, params.angle_step_deg * kDegToRad, diameter);
}

PreparedModel prepareModel(const io::ModelGeometry& geometry, const ModelParams& params) {
  params.validate();
  const DenseCloud dense = geometry.hasMesh() ? denseFromMesh(geometry.mesh, params) : denseFromCloud(geometry.cloud);
  PreparedModel model;
  model.params = params;
  model.diameter = approximateDiameter(dense.points);
  if (!(model.diameter > 0.0f)) throw core::Error("model has zero extent");
  model.step = params.sampling_ratio * model.diameter;

  const KdTree tree(dense.points);
  const std::vector<Eigen::Vector3f> dense_normals =
      dense.has_exact_normals ? dense.orientation : fitNormals(dense, tree, params.normal_radius_ratio * model.step);
  const std::vector<uint32_t> kept =
      voxelSubsample(dense.points, &dense_normals, model.step, params.normal_cluster_angle_deg * kDegToRad);
  for (uint32_t i : kept) {
    model.points.push_back(dense.points[i]);
    model.normals.push_back(dense_normals[i]);
    model.centre += dense.points[i];
  }
  if (model.points.size() < 4) throw core::Error("model: fewer than 4 points after subsampling");
  if (model.points.size() > 20000) {
    throw core::Error("model: " + std::to_string(model.points.size()) +
                      " points after subsampling is too many for the pair table; raise sampling_ratio");
  }
  model.centre /= static_cast<float>(model.points.size());
  for (uint32_t i :
       voxelSubsample(dense.points, &dense_normals, 0.5f * model.step, params.normal_cluster_angle_deg * kDegToRad)) {
    model.fine_points.push_back(dense.points[i]);
    model.fine_normals.push_back(dense_normals[i]);
  }
  if (params.reduce_by_symmetry && geometry.hasMesh()) model.symmetry = symmetryOf(geometry.mesh);
  model.reference_count = referencesFirst(model);
  model.table =
      PpfHashTable(model.points, model.normals, model.quantizer(), params.max_pairs_per_feature, model.reference_count);
  model.near_symmetries = nearSymmetries(model);
  const BoundaryParams outline;
  model.boundary = std::make_shared<const BoundaryModel>(prepareBoundaryModel(model, outline));
  model.boundary_crease_angle_deg = outline.crease_angle_deg;
  return model;
}

}  // namespace binpick::estimation
