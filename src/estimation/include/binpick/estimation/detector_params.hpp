#pragma once
// What a Detector is set with: one params struct per stage of the pipeline (the stages themselves
// are the module's private headers, named beside each struct) and the Detector's own. Each
// validate() throws core::Error naming the settings key that is wrong.
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>

namespace binpick::estimation {

// An oriented box in the camera frame; points outside it are ignored (e.g. the bin's inside
// above its floor).
struct CropBox {
  Eigen::Isometry3f T_camera_box = Eigen::Isometry3f::Identity();  // box centre and axes
  Eigen::Vector3f half_extents = Eigen::Vector3f::Zero();          // model units
  bool contains(const Eigen::Vector3f& p_camera) const;

  // The same test for a whole cloud: the box's inverse pose computed once, not per point.
  struct Test {
    Eigen::Isometry3f T_box_camera = Eigen::Isometry3f::Identity();
    Eigen::Vector3f half_extents = Eigen::Vector3f::Zero();
    bool contains(const Eigen::Vector3f& p_camera) const {
      return ((T_box_camera * p_camera).cwiseAbs().array() <= half_extents.array()).all();
    }
  };
  Test test() const { return {T_camera_box.inverse(), half_extents}; }
};

// Scene preparation (scene.hpp).
struct SceneParams {
  std::optional<CropBox> crop;            // none: keep every finite point
  int min_normal_neighbours = 5;          // fewer full-resolution neighbours: the point is dropped
  int max_window_half_size = 12;          // organized clouds: largest pixel window radius for normals
  float line_of_sight_cell_ratio = 0.5f;  // cell of the line-of-sight map, in steps at the scene's
                                          // median depth (0: no map, no free-space checks)
  void validate() const;                  // throws core::Error naming the field
};

// Sparse voting (voting.hpp).
struct VotingParams {
  float reference_fraction = 0.1f;  // share of scene points used as references (Table I: 10%)
  float referred_fraction = 0.2f;   // share of scene points paired with them (Table I: 20%)
  int poses_per_reference = 5;      // N_p: top local coordinates kept per reference
  float min_relative_votes = 0.0f;  // keep a local coordinate only with >= this share of the
                                    // reference's best vote count (Drost keeps near-peaks)
  uint64_t seed = 1;                // which points are references and referred points
  void validate() const;            // throws core::Error naming the field
};

// Surface-to-boundary pairs (boundary.hpp).
struct BoundaryParams {
  bool enabled = true;             // surface-to-boundary pairs in the voting (organized clouds only)
  float depth_jump_ratio = 1.0f;   // a pixel is a boundary when the next valid pixel beside it lies
                                   // this much farther (in steps)
  float crease_angle_deg = 60.0f;  // model: neighbouring normals turned more than this make a crease
  float min_linearity = 3.0f;      // scene: a boundary point's neighbours spread this many times more along
                                   // its line than across it (corners carry no direction)
  void validate() const;           // throws core::Error naming the field
};

// Voxel verification and the free-space checks (verification.hpp, range_agreement.hpp).
struct VerificationParams {
  float voxel_size_ratio = 0.5f;            // L_voxel in subsampling steps (a model point fits when a scene
                                            // point lies within 1-2 voxels)
  float max_normal_angle_deg = 180.0f;      // a fit also needs the scene normal within this angle of
                                            // the moved model normal (180: off, as in the paper)
  float free_space_tolerance_ratio = 2.0f;  // a model point this far (in steps) in front of the
                                            // measured surface is seen through (candidates: their
                                            // poses are as coarse as an alpha bin)
  float free_space_penalty = 1.0f;          // score points per seen-through model point (0: off,
                                            // the paper's eq. 4)
  float refined_tolerance_ratio = 1.0f;     // the same test after ICP, in steps, on the model's
                                            // fine surface (range_agreement.hpp) ...
  float max_refined_seen_through = 0.15f;   // ... rejects a refined pose when more than this share
                                            // of its visible fine points is seen through (1: off)
  bool compare_turned = true;               // each pick turned by the model's near-symmetries (a
                                            // part turned over) is refined too; the pose that
                                            // contradicts less of what the camera saw is kept
  void validate() const;                    // throws core::Error naming the field
};

// Multiple selection, Algorithm 1 (selection.hpp).
struct SelectionParams {
  int max_objects = 20;                    // stop after this many detections
  float min_score_fraction = 0.05f;        // stop when the best Score_New / N_m falls below this
  float min_coverage = 0.2f;               // a refined pick fitting less of its visible model points is
                                           // refused: ICP found nothing there (0: keep every pick)
  float min_centre_distance_ratio = 0.1f;  // a pose whose model centre lies closer than this
                                           // (times diam(M)) to an accepted one is a repeat
  // A robot acts first on what the range is sure of: detections below either of these come after
  // the others (Detection::sure false), each group in selection order (0 and 0: selection order).
  float sure_twin_margin = 0.04f;  // Detection::twin_margin: the range tells the part from it turned
  float sure_coverage = 0.6f;      // Detection::coverage: the fit explains most of what should be seen
  void validate() const;           // throws core::Error naming the field
};

// ICP on visible points (icp.hpp).
struct IcpParams {
  int max_iterations = 30;
  float initial_max_distance_ratio = 2.0f;      // correspondence gate in steps, first iterations
  float final_max_distance_ratio = 0.75f;       // gate in steps once the pose has settled
  float huber_ratio = 0.25f;                    // Huber threshold on the plane residual, in steps
  float point_weight = 0.1f;                    // weight of the point-to-point distance beside the
                                                // plane residual (0: point-to-plane only)
  float convergence_translation_ratio = 1e-2f;  // stop when a step moves less (in steps: 0.04 mm
                                                // for a 100 mm part) ...
  float convergence_rotation_deg = 0.05f;       // ... and turns less than this
  float fit_distance_ratio = 0.75f;             // final coverage: a visible model point fits when a
                                                // scene point lies this close (in steps)
  float max_normal_angle_deg = 60.0f;           // a correspondence needs the scene normal within this
                                                // angle of the moved model normal (60: cos 0.5)
  bool visible_points_only = true;              // false: use all model points (for comparison)
  void validate() const;                        // throws core::Error naming the field
};

// Pose clustering, Drost only (clustering.hpp).
struct ClusteringParams {
  float max_translation_ratio = 0.1f;  // in diam(M): translations closer than this may join
  float max_rotation_deg = 12.0f;      // and rotations closer than this (both must hold)
  void validate() const;               // throws core::Error naming the field
};

enum class Method {
  LiHashimoto,  // sparse voting, voxel verification, Algorithm 1, ICP (the paper's "Proposed")
  Drost,        // all referred points, pose clustering, ICP (the paper's PPF1 / PPF5)
};
Method methodFromName(const std::string& name);  // "li_hashimoto" | "drost"; throws otherwise
std::string methodName(Method method);

struct DetectorParams {
  Method method = Method::LiHashimoto;
  SceneParams scene;
  VotingParams voting;
  BoundaryParams boundary;  // surface-to-boundary pairs in the voting (boundary.hpp)
  VerificationParams verification;
  SelectionParams selection;
  IcpParams icp;
  ClusteringParams clustering;  // Drost only
  int threads = 0;              // every stage: 0 = all hardware threads

  // The paper's baselines (Table I): PPF1 = all references, PPF5 = 20% of references; both pair
  // each reference with every scene point and cluster poses, from surface pairs only (no outline votes).
  static DetectorParams drost(float reference_fraction);
  void validate() const;  // throws core::Error naming the field
};

}  // namespace binpick::estimation
