#pragma once
// binpick's own estimator as a benchmark method: the paper's method with binpick's defaults, or
// the Drost baselines PPF1 and PPF5 of Table I run in the same engine.
#include <memory>
#include <string>
#include <vector>

#include "binpick/estimation/detector.hpp"
#include "pose_method.hpp"

namespace binpick::bench {

class BinpickMethod : public PoseMethod {
 public:
  BinpickMethod(std::string name, const MethodSetup& setup, estimation::DetectorParams params);
  std::string name() const override { return name_; }
  std::vector<Eigen::Isometry3f> detect(const MethodInput& input) const override;
  // The detector's own result (stage timings, candidates), for the sections that look inside.
  estimation::DetectionResult detectWithDetails(const MethodInput& input) const;

 private:
  std::string name_;
  estimation::Detector detector_;
};

// "binpick" (defaults), "ppf1" (Drost, every scene point a reference) or "ppf5" (Drost, 20% of
// them); throws core::Error naming any other.
std::unique_ptr<BinpickMethod> makeBinpickMethod(const std::string& name, const MethodSetup& setup);
bool isBinpickMethod(const std::string& name);

}  // namespace binpick::bench
