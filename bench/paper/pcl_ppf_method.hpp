#pragma once
// PCL 1.13's point pair feature registration (pcl::PPFRegistration, Drost et al. 2010 as
// implemented by A.-E. Ichim) as a benchmark peer, configured at binpick's resolution.
//
// PCL's align() returns ONE pose per call (the best pose cluster). A bin holds many parts, so
// detect() is our loop around PCL: align, refine with PCL's ICP, accept, remove the scene points
// the posed part explains, align again on what remains. See pcl_ppf_method.cpp for what PCL does
// inside and why each value below is what it is.
//
// PCL's headers stay in the .cpp (pimpl): they cost seconds of compile time per translation unit.
#include <memory>
#include <string>
#include <vector>

#include "pose_method.hpp"

namespace binpick::bench {

// Lengths are in model subsampling steps (d_dist = setup.model->step = 0.04 diam(M)) or in
// diam(M), so one set of values serves every part.
struct PclPpfParams {
  // Scene reference points: binpick votes from 10% of the scene points. PCL takes every k-th
  // point of the scene cloud (in cloud order) as a reference, so k = round(1 / fraction) = 10.
  // (The paper's PPF5 baseline uses 20%.)
  float reference_fraction = 0.10f;
  // Feature quantisation, as binpick: angles 12 degrees, distances one step. PCL's features are
  // PFH's Darboux-frame triple (one angle in [-pi, pi], two cosines in [-1, 1]) plus the distance;
  // the angle step quantises all three and the rotation angle alpha (see the .cpp). PCL's alpha
  // accumulator overflows by one column for some float steps, 12 degrees among them; the nearest
  // safe step is used instead: 360 / 29 = 12.41 degrees for 12 (accumulatorSafeAngleStep).
  float angle_step_deg = 12.0f;
  float distance_step_ratio = 1.0f;  // in steps
  // Scene subsampling: a pcl::VoxelGrid with the model's step as leaf, as binpick subsamples the
  // scene at d_dist (PCL keeps each voxel's centroid, binpick a point of it).
  float voxel_ratio = 1.0f;  // in steps
  // Scene normals (pcl::NormalEstimationOMP): binpick fits a plane to the full-resolution
  // neighbours within 0.5 step of each kept point (ModelParams::normal_radius_ratio); we search
  // the full cropped cloud with the same radius. Normals are turned towards the camera.
  float normal_radius_ratio = 0.5f;  // in steps
  // Pose clustering: PCL's defaults (1 cm, 20 degrees) are absolute and part-blind; binpick's
  // Drost baseline clusters within diam/10 and 12 degrees (ClusteringParams), so do we.
  float cluster_translation_ratio = 0.10f;  // in diam(M)
  float cluster_rotation_deg = 12.0f;
  // Refinement: the paper refined every method with ICP. Symmetric point-to-plane (PCL's
  // IterativeClosestPointWithNormals) from the model points facing the camera to the remaining
  // scene points, a handful of iterations, correspondences within 2 steps (what the coarse pose
  // of a 12-degree, one-step quantisation can be off by).
  int icp_iterations = 10;
  float icp_max_distance_ratio = 2.0f;  // in steps
  // Acceptance of a refined pose: its support is the share of ALL model points with a remaining
  // scene point within support_distance_ratio steps. A part seen from one side shows well under
  // half its points; below min_support (10%) the best cluster explains almost nothing, which
  // means the remaining points hold no more parts PCL can find: the loop stops (PCL would return
  // the same pose again on the same points).
  float support_distance_ratio = 1.0f;  // in steps
  float min_support = 0.10f;
  // After accepting a pose, scene points within this distance of its model points are removed
  // (one step of quantisation plus half a step of noise and pose error).
  float removal_radius_ratio = 1.5f;  // in steps
  // PCL_INFO prints five lines per align() to stdout. true lowers PCL's console verbosity to
  // errors, process-wide (pcl::console has one global level), when the method is built.
  bool quiet_pcl = true;
  void validate() const;  // throws core::Error naming the field
};

// Wall-clock milliseconds of one detect() call, for the benchmark's stage breakdown.
struct PclPpfTimings {
  double normals = 0;  // crop, voxel grid, normal estimation
  double align = 0;    // all PPFRegistration::align calls
  double icp = 0;      // all ICP refinements
  double removal = 0;  // support checks and point removal
  int align_calls = 0;
  std::size_t scene_points = 0;  // after subsampling, with a normal
};

class PclPpfMethod : public PoseMethod {
 public:
  // Builds the PPFEstimation features of all pairs of setup.model->points / normals (N^2 of
  // them) and PCL's PPFHashMapSearch over them: minutes for a ~900-point model, as PCL's hash
  // spreads the pairs over a few hundred buckets. setup.model must outlive the method.
  explicit PclPpfMethod(const MethodSetup& setup, PclPpfParams params = {});
  ~PclPpfMethod() override;
  PclPpfMethod(const PclPpfMethod&) = delete;
  PclPpfMethod& operator=(const PclPpfMethod&) = delete;

  std::string name() const override;  // "pcl_ppf"
  // Thread-safe: each call owns its PCL registration objects; the hash map is only read.
  std::vector<Eigen::Isometry3f> detect(const MethodInput& input) const override;
  std::vector<Eigen::Isometry3f> detect(const MethodInput& input, PclPpfTimings* timings) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace binpick::bench
