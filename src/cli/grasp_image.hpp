#pragma once
// A picture of generated grasps for an integrator to check at a glance: the model shaded from four
// views (above, below and two opposite corners), each grasp drawn where it is seen from the front
// (a suction cup as its disc and approach arrow, parallel jaws as their two finger pads and the
// approach arrow), numbered by rank. Stateless: thread-safe.
#include <string>
#include <vector>

#include "binpick/io/geometry_io.hpp"
#include "binpick/picking/gripper.hpp"
#include "binpick/picking/picking.hpp"

namespace binpick::cli {

// Throws core::Error naming the file when it cannot be written.
void writeGraspImage(const std::string& path, const io::ModelGeometry& model, const std::vector<picking::Grasp>& grasps,
                     const picking::GripperParams& gripper);

}  // namespace binpick::cli
