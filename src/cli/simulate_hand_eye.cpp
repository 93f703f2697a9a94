// binpick simulate --hand-eye: see simulate_hand_eye.hpp.
#include "simulate_hand_eye.hpp"

#include <iostream>

#include "arguments.hpp"
#include "binpick/simulation/hand_eye_session.hpp"

namespace binpick::cli {

CLI::Option* addSimulateHandEyeOptions(CLI::App& simulate) {
  CLI::Option* hand_eye =
      addText(simulate, "--hand-eye", "SETUP", "Render a hand-eye session: eye-to-hand or eye-in-hand");
  addInteger(simulate, "--views", "K", "Robot poses with a view of the board (default 12)")->needs(hand_eye);
  addNumber(simulate, "--robot-noise-mm", "MM", "Noise on the robot's positions (default 0)")->needs(hand_eye);
  addNumber(simulate, "--robot-noise-deg", "DEG", "Noise on the robot's rotations (default 0)")->needs(hand_eye);
  addText(simulate, "--orientation", "NAME", "Orientation convention of poses.txt (default euler_zyx)")
      ->needs(hand_eye);
  return hand_eye;
}

int simulateHandEye(const Arguments& args) {
  simulation::HandEyeSessionParams params;
  params.setup = calibration::handEyeSetupFromName(args.required("--hand-eye"));
  params.views = args.integer("--views").value_or(params.views);
  params.seed = static_cast<uint64_t>(args.integer("--seed").value_or(1));
  params.robot_noise_mm = args.number("--robot-noise-mm").value_or(0.0);
  params.robot_noise_deg = args.number("--robot-noise-deg").value_or(0.0);
  if (const auto name = args.value("--orientation")) {
    params.orientation = core::orientationFromName(*name);
  }
  params.validate();
  const std::string out = args.required("--out");
  const simulation::HandEyeSession session = simulation::writeHandEyeSession(out, params);
  std::cerr << "rendered " << session.views.size() << " " << calibration::handEyeSetupName(params.setup)
            << " views into " << out << " (truth in " << out << "/truth/hand_eye.yaml)\n";
  return 0;
}

}  // namespace binpick::cli
