// Names of the hand-eye setups, methods and transforms, as the CLI and the result file show them.
#include <array>
#include <utility>

#include "binpick/calibration/hand_eye.hpp"
#include "binpick/io/error.hpp"

namespace binpick::calibration {
namespace {

const std::array<std::pair<HandEyeMethod, const char*>, 7> kMethods = {{
    {HandEyeMethod::Shah, "shah"},
    {HandEyeMethod::Li, "li"},
    {HandEyeMethod::Tsai, "tsai"},
    {HandEyeMethod::Park, "park"},
    {HandEyeMethod::Horaud, "horaud"},
    {HandEyeMethod::Andreff, "andreff"},
    {HandEyeMethod::Daniilidis, "daniilidis"},
}};

}  // namespace

std::string handEyeSetupName(HandEyeSetup setup) {
  return setup == HandEyeSetup::EyeToHand ? "eye-to-hand" : "eye-in-hand";
}

HandEyeSetup handEyeSetupFromName(const std::string& name) {
  if (name == "eye-to-hand") return HandEyeSetup::EyeToHand;
  if (name == "eye-in-hand") return HandEyeSetup::EyeInHand;
  throw Error("unknown hand-eye setup '" + name +
              "' (eye-to-hand: fixed camera, board on the flange; eye-in-hand: camera on the "
              "flange, board fixed)");
}

std::string cameraTransformName(HandEyeSetup setup) {
  return setup == HandEyeSetup::EyeToHand ? "T_base_camera" : "T_flange_camera";
}

std::string boardTransformName(HandEyeSetup setup) {
  return setup == HandEyeSetup::EyeToHand ? "T_flange_board" : "T_base_board";
}

std::string handEyeMethodName(HandEyeMethod method) {
  for (const auto& [value, name] : kMethods) {
    if (value == method) return name;
  }
  throw Error("handEyeMethodName: unknown method");
}

HandEyeMethod handEyeMethodFromName(const std::string& name) {
  std::string names;
  for (const auto& [value, known] : kMethods) {
    if (name == known) return value;
    names += (names.empty() ? "" : ", ") + std::string(known);
  }
  throw Error("unknown hand-eye method '" + name + "' (" + names + ")");
}

std::vector<HandEyeMethod> allHandEyeMethods() {
  std::vector<HandEyeMethod> methods;
  for (const auto& entry : kMethods) methods.push_back(entry.first);
  return methods;
}

}  // namespace binpick::calibration
