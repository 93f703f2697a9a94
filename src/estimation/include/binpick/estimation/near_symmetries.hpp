#pragma once
// A model's near-symmetries. A part turned over, or turned a quarter about its long axis, often
// shows a face of nearly the same outline (a housing lying on its side with its profile mirrored,
// an L-bracket upside down, a plate with its off-centre bulge on the other side): a pose and its
// turned twin explain almost the same scene points, and eq. 4 cannot tell them apart. The
// detector refines both and keeps the one that contradicts less of what the camera saw.
#include <Eigen/Geometry>
#include <vector>

namespace binpick::estimation {

// Rigid transforms S of the model frame (pose * S is the turned pose) under which the model
// overlaps itself for the most part but not wholly. Turns under which the part is truly symmetric
// are left out: they cannot change what a pose explains; so are twins that differ from one kept
// by one of the part's own turns (ModelSymmetry): a revolved plate flipped over about any axis
// across it is one twin, not one per box turn.
struct NearSymmetries {
  // The turns that map the model's principal box onto itself (quarter and half turns about the
  // axes, half turns about face diagonals, third turns about body diagonals) about its centroid,
  // each registered onto the model (ICP of the model onto itself). A twin of these replaces the
  // pick when the range prefers it.
  std::vector<Eigen::Isometry3f> turned;
  // The same turns slid first over the principal box to where most turned points land on the
  // model facing the same way, then registered; those not already in `turned`. A long bracket
  // turned end for end lies on its own long leg only once slid by tens of millimetres, which ICP
  // from the centroid never finds. They only weigh on the pick's twin margin (is it sure?): letting
  // them replace the pick made more wrong detections sure on piles in clutter (docs/estimation.md).
  std::vector<Eigen::Isometry3f> slid;
};

struct PreparedModel;
// Depends on the model alone: computed once by prepareModel and kept in the model cache.
NearSymmetries nearSymmetries(const PreparedModel& model);

}  // namespace binpick::estimation
