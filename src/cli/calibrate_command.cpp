// binpick calibrate rig | hand-eye: which calibration, then its own command.
#include <algorithm>

#include "binpick/core/error.hpp"
#include "commands.hpp"

namespace binpick::cli {

int runCalibrate(const std::vector<std::string>& args) {
  if (args.empty()) throw core::Error("calibrate needs 'rig' or 'hand-eye'");
  const std::string what = args.front();
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (what == "rig") return runCalibrateRig(rest);
  // A guided session listens for the robot; otherwise the poses come from a file.
  const bool guided = std::find(rest.begin(), rest.end(), "--listen") != rest.end();
  if (what == "hand-eye" && guided) return runCalibrateHandEyeGuided(rest);
  if (what == "hand-eye" && !guided) return runCalibrateHandEye(rest);
  throw core::Error("calibrate: unknown calibration '" + what + "' (rig or hand-eye)");
}

}  // namespace binpick::cli
