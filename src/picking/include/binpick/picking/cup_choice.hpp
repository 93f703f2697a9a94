#pragma once
// Which suction cup suits a part: an integrator's first question about a new one. A cup seals only
// on faces wider than itself (and on shafts whose curvature it spans within its seal tolerance),
// so a cup too large for a slender part leaves it without a grasp in most of the ways it can
// lie: a shaft on its side, a gear on its rim.
//
// The measure: the share of the part's orientations in which some grasp faces up, i.e. of the
// directions `up` (evenly spread over the sphere, in the model frame) for which some generated
// grasp, under the part's symmetry, approaches within max_tilt_deg of straight down. The choice:
// the gripper's own cup, unless a smaller cup of the series reaches at least `min_gain` more of
// those orientations; then the largest such cup within min_gain of the best. Larger cups hold
// harder, so none larger than the gripper's own is offered.
// Pure functions: thread-safe.
#include <string>
#include <vector>

#include "binpick/io/point_cloud.hpp"
#include "binpick/picking/grasp_generation.hpp"
#include "binpick/picking/gripper.hpp"
#include "binpick/picking/picking.hpp"

namespace binpick::picking {

struct CupChoiceParams {
  // Metres: bellows cups smaller than the gripper's that may stand in for it. A 5 mm cup on a
  // 10 mm shaft seals on the model within its reserve and failed 4 picks in 5 bins of the
  // stepped shaft; a 4 mm cup none.
  std::vector<double> series = {0.004};
  double min_gain = 0.10;      // share of orientations a smaller cup must add, in (0, 1]
  double max_tilt_deg = 60.0;  // as the planner's PickParams::max_tilt_deg
  int directions = 2000;       // up directions sampled over the sphere, >= 10
  int continuous_steps = 36;   // turns about a continuous symmetry axis
  void validate() const;       // throws core::Error naming the field
};

struct CupOption {
  double diameter = 0.0;  // metres
  int grasps = 0;         // generated for this cup
  double upward = 0.0;    // share of orientations with a grasp facing up, [0, 1]
};

struct CupChoice {
  double diameter = 0.0;           // metres: the cup chosen
  std::vector<CupOption> options;  // every cup weighed, the gripper's own first
};

// The share of orientations in which one of `grasps` (model frame) faces up (see above).
double upwardShare(const std::vector<Grasp>& grasps, const PartSymmetry& symmetry, const CupChoiceParams& params);

// "4 mm cup (of 6 mm: 50% of orientations with a grasp facing up, 4 mm: 100%)".
std::string describeCupChoice(const CupChoice& choice);

// The cup for a part given as a closed mesh (metres); `gripper` must be a suction gripper. Throws
// core::Error on invalid params, gripper or mesh, as generateGrasps does.
CupChoice chooseCup(const io::TriangleMesh& model, const GripperParams& gripper, const PartSymmetry& symmetry,
                    const GraspGenerationParams& generation, const CupChoiceParams& params = {});

}  // namespace binpick::picking
