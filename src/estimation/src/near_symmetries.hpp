#pragma once
// Internal: a model's near-symmetries. A part turned over, or turned a quarter about its long axis,
// often shows a face of nearly the same outline (a housing lying on its side with its profile
// mirrored, an L-bracket upside down, a plate with its off-centre bulge on the other side): a pose
// and its turned twin explain almost the same scene points, and eq. 4 cannot tell them apart. The
// detector refines both and keeps the one that contradicts less of what the camera saw.
#include <Eigen/Geometry>
#include <vector>

#include "binpick/estimation/model.hpp"

namespace binpick::estimation {

// Rigid transforms S of the model frame (pose * S is the turned pose) under which the model
// overlaps itself for the most part but not wholly: the turns that map its principal box onto
// itself (quarter and half turns about the axes, half turns about face diagonals, third turns about
// body diagonals), each registered onto the model (ICP of the model onto itself) so that the turned
// outline lands on the original one. Turns under which the part is truly symmetric are left out:
// they cannot change what a pose explains.
std::vector<Eigen::Isometry3f> nearSymmetries(const PreparedModel& model);

}  // namespace binpick::estimation
