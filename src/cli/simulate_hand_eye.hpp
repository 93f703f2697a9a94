#pragma once
// binpick simulate --hand-eye eye-to-hand|eye-in-hand [--views K] [--seed S]
//                  [--robot-noise-mm M --robot-noise-deg D] [--orientation NAME] --out DIR
// A simulated hand-eye session of the virtual cell written as a views directory
// (binpick/simulation/hand_eye_session.hpp), for `binpick calibrate hand-eye`.
#include <CLI/CLI.hpp>

#include "arguments.hpp"

namespace binpick::cli {

// Declares --hand-eye and the options that need it on `simulate`; returns --hand-eye. --seed and
// --out are simulate's own.
CLI::Option* addSimulateHandEyeOptions(CLI::App& simulate);

int simulateHandEye(const Arguments& args);

}  // namespace binpick::cli
