// The hand-eye command's tables, printed with fixed columns so that scripts can read them.
#include "hand_eye_report.hpp"

#include <cstdio>
#include <ostream>

#include "binpick/core/orientation.hpp"

namespace binpick::cli {
namespace {

std::string printed(const char* format, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, format, a, b, c, d);
  return text;
}

const calibration::HandEyeResidual* residualOf(const calibration::HandEyeResult* result, const std::string& view) {
  if (result == nullptr) return nullptr;
  for (const calibration::HandEyeResidual& r : result->residuals) {
    if (r.name == view) return &r;
  }
  return nullptr;
}

void printPose(std::ostream& out, const std::string& name, const Eigen::Isometry3d& T) {
  const Eigen::Vector3d t = T.translation() * 1000.0;
  const std::vector<double> q = core::orientationValues(T.linear(), core::Orientation::Quaternion);
  out << name << ": translation " << printed("[%.3f, %.3f, %.3f] mm", t.x(), t.y(), t.z())
      << ", rotation (quaternion w x y z) " << printed("[%.6f, %.6f, %.6f, %.6f]", q[0], q[1], q[2], q[3]) << "\n";
}

}  // namespace

void printViewTable(std::ostream& out, const std::vector<calibration::MeasuredView>& views,
                    const calibration::HandEyeResult* result) {
  out << "view                 corners  board px  residual mm  residual deg\n";
  for (const calibration::MeasuredView& v : views) {
    char name[64];
    std::snprintf(name, sizeof name, "%-20s %3d/%-3d", v.name.c_str(), v.corners, v.expected);
    out << name;
    if (!v.usable()) {
      out << "  left out: " << v.problem << "\n";
      continue;
    }
    out << printed("  %8.3f", v.rms_px);
    if (const calibration::HandEyeResidual* r = residualOf(result, v.name)) {
      out << printed("  %11.3f  %12.4f", r->translation_mm, r->rotation_deg)
          << (r->dropped   ? "  dropped"
              : r->outlier ? "  outlier"
                           : "");
    }
    out << "\n";
  }
}

void printHandEyeResult(std::ostream& out, const calibration::HandEyeResult& result) {
  out << calibration::handEyeSetupName(result.setup) << ", method " << calibration::handEyeMethodDescription(result)
      << ", " << result.residuals.size() - result.dropped.size() << " views: residual RMS "
      << printed("%.3f mm, %.4f deg", result.rms_mm, result.rms_deg) << "\n";
  printPose(out, calibration::cameraTransformName(result.setup), result.T_mount_camera);
  printPose(out, calibration::boardTransformName(result.setup), result.T_mount_board);
}

void printHandEyeWarnings(std::ostream& out, const std::vector<calibration::MeasuredView>& views,
                          const calibration::HandEyeResult* result) {
  for (const calibration::MeasuredView& v : views) {
    if (!v.usable()) out << "warning: view " << v.name << " left out: " << v.problem << "\n";
    if (!v.note.empty()) out << "warning: view " << v.name << ": " << v.note << "\n";
  }
  if (result == nullptr) return;
  for (const std::string& warning : result->warnings) out << "warning: " << warning << "\n";
}

}  // namespace binpick::cli
