#pragma once
// Model preparation (sections II-A and III-A): a dense "original" cloud of the part's surface, the
// subsampled model cloud with normals from the dense neighbours, and the PPF hash table of all
// model pairs. A PreparedModel is immutable once built: share it between threads freely.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "binpick/estimation/hash_table.hpp"
#include "binpick/estimation/near_symmetries.hpp"
#include "binpick/estimation/ppf.hpp"
#include "binpick/io/geometry_io.hpp"

namespace binpick::estimation {

struct ModelParams {
  float sampling_ratio = 0.04f;            // tau_d: subsampling step / diam(M) (Table I: 0.04)
  float angle_step_deg = 12.0f;            // feature and alpha quantisation, degrees
  float dense_samples_per_step2 = 25.0f;   // mesh input: dense samples per step^2 of surface
  float normal_radius_ratio = 0.5f;        // plane-fit radius for normals, in subsampling steps
  float normal_cluster_angle_deg = 30.0f;  // one voxel keeps apart points whose normals differ more
  uint32_t max_pairs_per_feature = 2000;   // cap on model pairs per hash key (0: none, as in the
                                           // paper); halves voting for parts with big flat faces
  uint64_t seed = 1;                       // dense surface sampling
  bool reduce_by_symmetry = true;          // mesh models: the model points of one turn of the part's
                                           // symmetry are the table's references (ModelSymmetry)
  void validate() const;                   // throws core::Error naming the field
};

// The turns about one axis through the model origin that map the part onto itself, found from a
// mesh model (io::findSymmetry), and whether it also flips over onto itself (half turns about axes
// across that one). A part turned by one of them explains the same scene points, so every
// equivalent model point would vote for an equivalent pose: only the points of one turn (a sector
// of 360/N degrees about the axis, or a strip along one meridian of a revolved part; its upper half
// when the part flips) are references. Each scene pair still finds its model pair there; the pair
// table, the accumulator and the candidates shrink about N (2N) times, and the votes once split
// over equivalent poses fall on one.
struct BoundaryModel;  // boundary.hpp

struct ModelSymmetry {
  Eigen::Vector3f axis = Eigen::Vector3f::Zero();  // unit; zero when turns == 1
  int turns = 1;                                   // N of an N-fold axis, 0: revolved, 1: none
  bool flips = false;                              // only with an axis
  std::string describe() const;  // "12-fold about (0, 0, 1), flips over", "revolved about ...", "none"
};

struct PreparedModel {
  std::vector<Eigen::Vector3f> points;               // subsampled model cloud, model frame
  std::vector<Eigen::Vector3f> normals;              // unit, pointing out of the part
  float diameter = 0.0f;                             // diam(M), model units
  float step = 0.0f;                                 // d_dist = tau_d * diam(M)
  Eigen::Vector3f centre = Eigen::Vector3f::Zero();  // centroid of `points`
  std::vector<Eigen::Vector3f> fine_points;          // the surface at half the step, for judging a
  std::vector<Eigen::Vector3f> fine_normals;         // refined pose point by point (range_agreement.hpp)
  ModelParams params;
  ModelSymmetry symmetry;           // found from a mesh (params.reduce_by_symmetry), else none
  std::size_t reference_count = 0;  // the first reference_count points are the table's references:
                                    // one turn of `symmetry`, else all of them
  PpfHashTable table;
  NearSymmetries near_symmetries;  // the turned twins (near_symmetries.hpp), model-only work
  // The outline's model side (boundary.hpp) for the default crease angle, also model-only work; a
  // detector set to another crease angle builds its own.
  std::shared_ptr<const BoundaryModel> boundary;
  float boundary_crease_angle_deg = 0.0f;

  PpfQuantizer quantizer() const;
  std::size_t size() const { return points.size(); }
  std::size_t referenceCount() const { return reference_count == 0 ? points.size() : reference_count; }
};

// Mesh input: area-weighted dense samples, normals oriented by the faces. Cloud input: the cloud
// is the original cloud; its normals are used when present, else fitted and oriented away from
// the centroid (right for convex-ish parts: prefer meshes or clouds with normals).
// Throws core::Error for an empty geometry, a mesh without area, or nonsense params.
PreparedModel prepareModel(const io::ModelGeometry& geometry, const ModelParams& params);

}  // namespace binpick::estimation
