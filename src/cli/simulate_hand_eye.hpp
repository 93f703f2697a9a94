#pragma once
// binpick simulate --hand-eye eye-to-hand|eye-in-hand [--views K] [--seed S]
//                  [--robot-noise-mm M --robot-noise-deg D] [--orientation NAME] --out DIR
// A simulated hand-eye session of the virtual cell written as a views directory
// (binpick/simulation/hand_eye_session.hpp), for `binpick calibrate hand-eye`.
#include <string>
#include <vector>

namespace binpick::cli {

int runSimulateHandEye(const std::vector<std::string>& args);

}  // namespace binpick::cli
