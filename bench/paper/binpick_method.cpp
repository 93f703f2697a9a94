#include "binpick_method.hpp"

#include "binpick/core/error.hpp"
#include "binpick/estimation/config.hpp"

namespace binpick::bench {

BinpickMethod::BinpickMethod(std::string name, const MethodSetup& setup, estimation::DetectorParams params)
    : name_(std::move(name)), detector_(*setup.model, [&] {
        params.selection.max_objects = setup.max_objects;
        params.threads = setup.threads;
        return params;
      }()) {}

estimation::DetectionResult BinpickMethod::detectWithDetails(const MethodInput& input) const {
  return detector_.detect(*input.cloud, input.crop);
}

std::vector<Eigen::Isometry3f> BinpickMethod::detect(const MethodInput& input) const {
  std::vector<Eigen::Isometry3f> poses;
  for (const estimation::Detection& d : detectWithDetails(input).detections) poses.push_back(d.T_camera_model);
  return poses;
}

bool isBinpickMethod(const std::string& name) { return name == "binpick" || name == "ppf1" || name == "ppf5"; }

std::unique_ptr<BinpickMethod> makeBinpickMethod(const std::string& name, const MethodSetup& setup) {
  // Table I: every method subsamples at tau_d = 0.04 (the model's own step). PPF1 takes every
  // scene point as a reference, PPF5 every fifth; both pair each with all scene points.
  if (name == "binpick") {
    const estimation::DetectorParams params = setup.binpick_settings.empty()
                                                  ? estimation::DetectorParams{}
                                                  : estimation::loadEstimationConfig(setup.binpick_settings).detector;
    return std::make_unique<BinpickMethod>(name, setup, params);
  }
  if (name == "ppf1") return std::make_unique<BinpickMethod>(name, setup, estimation::DetectorParams::drost(1.0f));
  if (name == "ppf5") return std::make_unique<BinpickMethod>(name, setup, estimation::DetectorParams::drost(0.2f));
  throw core::Error("bench: '" + name + "' is not one of binpick's methods (binpick, ppf1, ppf5)");
}

}  // namespace binpick::bench
