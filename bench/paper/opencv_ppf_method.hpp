#pragma once
// OpenCV contrib's point pair feature detector (cv::ppf_match_3d::PPF3DDetector, Drost et al. 2010
// as implemented by T. Birdal) followed by its own ICP (cv::ppf_match_3d::ICP), as a PoseMethod.
// The detector is trained on binpick's prepared model points and set to binpick's resolution; the
// .cpp explains how the absolute step becomes the relative values OpenCV expects.
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "pose_method.hpp"

namespace binpick::bench {

struct OpenCvPpfParams {
  // Share of the subsampled scene points used as reference points: match() takes every
  // (int)(1 / fraction)-th point. The paper's PPF5 baseline refers 20% of the scene.
  double reference_fraction = 0.2;
  // Subdivisions of 360 degrees for the feature angles: 30 gives 12 degrees, binpick's angle step.
  // (OpenCV spreads its alpha bins over [-2 pi, 2 pi], so alpha itself gets 24-degree bins.)
  int num_angles = 30;
  // Pose clustering (setSearchParams): poses join a cluster when translations differ by less
  // than this share of diam(M) and rotation angles by less than this many degrees; binpick's
  // Drost clustering uses the same 0.1 and 12. OpenCV's defaults are unusable in metres (.cpp).
  double cluster_translation_ratio = 0.1;
  double cluster_rotation_deg = 12.0;
  // Vote-weighted cluster averages, as binpick's clustering (OpenCV's default is plain means).
  bool weighted_clustering = true;
  // Scene pre-sampling before normals, in model steps d_dist: a voxel grid at half the step keeps
  // about four points per step-sized cell for OpenCV's own quantisation to average while
  // computeNormalsPC3d runs on a few tens of thousands of points instead of the full cloud.
  // 0 turns the pre-sampling off (normals on every cropped point).
  double normal_voxel_ratio = 0.5;
  // Neighbours of computeNormalsPC3d's plane fit: on the half-step grid, 10 neighbours span a disc
  // of radius about one step, the support binpick's normals have.
  int normal_neighbours = 10;
  // ICP (cv::ppf_match_3d::ICP): at most 30 iterations, as binpick's ICP; stop when the error
  // changes by less than 0.5% (OpenCV's sample's value); reject correspondences beyond 2.5 robust
  // sigmas (OpenCV's default). One pyramid level: on the 20-part l_bracket pile (seed 1) OpenCV's
  // pyramid made things worse (found 6/20 with 1 level, 4-5/20 with 2 or 4, 5/20 without ICP),
  // its coarse levels fitting an eighth of a model half of which the camera cannot see.
  int icp_iterations = 30;  // 0: no ICP (the raw clustered poses)
  float icp_tolerance = 0.005f;
  float icp_rejection_scale = 2.5f;
  int icp_levels = 1;
  // Final order: false keeps OpenCV's order (cluster votes), true sorts the refined poses by ICP
  // residual. Votes: on the 20-part pile the residual order found the same parts but put more
  // wrong poses in the first 10 (7 vs 4); the residual also mixes point and normal differences
  // and is OpenCV's 1e10 sentinel both for a perfect fit and for no correspondences.
  bool order_by_residual = false;
  void validate() const;  // throws core::Error naming the field
};

class OpenCvPpfMethod : public PoseMethod {
 public:
  // Trains the detector on setup.model's points and normals (model frame). Throws core::Error
  // without a model or with bad params.
  explicit OpenCvPpfMethod(const MethodSetup& setup, OpenCvPpfParams params = {});
  ~OpenCvPpfMethod() override;
  OpenCvPpfMethod(const OpenCvPpfMethod&) = delete;
  OpenCvPpfMethod& operator=(const OpenCvPpfMethod&) = delete;

  std::string name() const override;  // "opencv_ppf"
  // Normals, match(), ICP on the best setup.max_objects clusters. Calls are serialised: match()
  // writes the detector's state, and cv::setNumThreads is process-wide.
  std::vector<Eigen::Isometry3f> detect(const MethodInput& input) const override;

  struct Timing {  // milliseconds of the last detect()
    double normals = 0, match = 0, icp = 0;
    std::size_t normal_points = 0;  // points given to computeNormalsPC3d and match()
  };
  Timing lastTiming() const;

 private:
  struct Trained;  // OpenCV's detector and model matrix, kept out of this header
  MethodSetup setup_;
  OpenCvPpfParams params_;
  std::unique_ptr<Trained> trained_;
  mutable std::mutex mutex_;
  mutable Timing timing_;
};

}  // namespace binpick::bench
