// The per-view table and the totals of a rig calibration.
#include "calibrate_rig_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace binpick::cli {
namespace {

constexpr double kDegreesPerRadian = 180.0 / 3.14159265358979323846;

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

std::string rms(double value) { return std::isfinite(value) ? format("%.3f", value) : "-"; }

std::string status(const io::RigViewQuality& view) {
  if (view.used) return "used";
  return view.problem.empty() ? "not used" : view.problem;
}

void printViews(std::ostream& out, const io::RigCalibrationQuality& quality) {
  int width = 4;
  for (const io::RigViewQuality& view : quality.views) {
    width = std::max(width, static_cast<int>(view.name.size()));
  }
  char line[512];
  std::snprintf(line, sizeof line, "%-*s  %7s %9s  %7s %9s\n", width, "", "camera", "projector", "camera", "projector");
  out << line;
  std::snprintf(line, sizeof line, "%-*s  %7s %9s  %7s %9s  %7s\n", width, "view", "corners", "corners", "RMS px",
                "RMS px", "outlier");
  out << line;
  for (const io::RigViewQuality& view : quality.views) {
    std::snprintf(line, sizeof line, "%-*s  %7d %9d  %7s %9s  %7s  ", width, view.name.c_str(), view.camera_corners,
                  view.projector_corners, rms(view.camera_rms_px).c_str(), rms(view.projector_rms_px).c_str(),
                  view.outlier ? "yes" : "no");
    out << line << status(view) << "\n";
  }
}

void printLens(std::ostream& out, const char* device, const io::LensIntrinsics& lens) {
  char line[256];
  std::snprintf(line, sizeof line,
                "%-9s %dx%d  fx %.2f  fy %.2f  cx %.2f  cy %.2f  k1 %.4f k2 %.4f p1 %.5f p2 %.5f"
                " k3 %.4f\n",
                device, lens.width, lens.height, lens.fx, lens.fy, lens.cx, lens.cy, lens.distortion[0],
                lens.distortion[1], lens.distortion[2], lens.distortion[3], lens.distortion[4]);
  out << line;
}

std::string termValue(int term, const calibration::TermResidual& residual) {
  char text[96];
  if (term == 2) {
    std::snprintf(text, sizeof text, "p1 %.5f +- %.5f, p2 %.5f +- %.5f", residual.value[0], residual.sd[0],
                  residual.value[1], residual.sd[1]);
  } else {
    std::snprintf(text, sizeof text, "%s %.4f +- %.4f", calibration::kDistortionTermNames[term], residual.value[0],
                  residual.sd[0]);
  }
  return text;
}

// "camera    terms k1,k2,p1,p2: own solve RMS 0.055 px", the fitted terms' standard deviations,
// then per term the RMS with it fitted and held and its value where fitted: whether a term is
// warranted shows in both.
void printLensFit(std::ostream& out, const char* device, const calibration::LensFitReport& fit) {
  char line[320];
  const io::LensIntrinsics& own = fit.lens;
  std::snprintf(line, sizeof line, "%-9s terms %s: own solve RMS %.3f px  fx %.2f  fy %.2f  cx %.2f  cy %.2f\n", device,
                fit.terms.text().c_str(), fit.rms_px, own.fx, own.fy, own.cx, own.cy);
  out << line;
  if (!fit.restarted_from.empty()) {
    // Honest about the local minimum: what the solve from zero distortion gave.
    std::snprintf(line, sizeof line,
                  "%-9s from zero distortion the solve stopped at RMS %.3f px, above the fit holding %s: restarted"
                  " from that fit\n",
                  "", fit.scratch_rms_px, fit.restarted_from.c_str());
    out << line;
  }
  std::snprintf(line, sizeof line,
                "%-9s std dev  fx %.2f  fy %.2f  cx %.2f  cy %.2f  k1 %.4f k2 %.4f p1 %.5f p2 %.5f k3 %.4f\n", "",
                fit.sd[0], fit.sd[1], fit.sd[2], fit.sd[3], fit.sd[4], fit.sd[5], fit.sd[6], fit.sd[7], fit.sd[8]);
  out << line;
  for (int term = 0; term < calibration::kDistortionTermCount; ++term) {
    const calibration::TermResidual& residual = fit.per_term[static_cast<std::size_t>(term)];
    std::snprintf(line, sizeof line, "%-9s %-5s %-6s RMS fitted %.3f px, held %.3f px; fitted: %s\n", "",
                  calibration::kDistortionTermNames[term], residual.chosen ? "chosen" : "held", residual.rms_fitted_px,
                  residual.rms_held_px, termValue(term, residual).c_str());
    out << line;
  }
}

}  // namespace

void printRigReport(std::ostream& out, const calibration::RigCalibrationResult& result) {
  const io::RigCalibrationQuality& quality = result.quality;
  printViews(out, quality);
  char line[256];
  std::snprintf(line, sizeof line, "%d of %zu views used; RMS camera %.3f px, projector %.3f px, stereo %.3f px\n",
                quality.viewsUsed(), quality.views.size(), quality.camera_rms_px, quality.projector_rms_px,
                quality.stereo_rms_px);
  out << line;
  printLens(out, "camera", result.rig.camera);
  printLens(out, "projector", result.rig.projector);
  printLensFit(out, "camera", result.camera_fit);
  printLensFit(out, "projector", result.projector_fit);
  const Eigen::Isometry3d T_camera_projector = result.rig.T_projector_camera.inverse();
  const Eigen::Vector3d centre = T_camera_projector.translation() * 1e3;
  const double angle = Eigen::AngleAxisd(T_camera_projector.linear()).angle() * kDegreesPerRadian;
  std::snprintf(line, sizeof line,
                "projector centre in the camera frame (%.2f, %.2f, %.2f) mm, baseline %.2f mm,"
                " turned %.3f deg\n",
                centre.x(), centre.y(), centre.z(), centre.norm(), angle);
  out << line;
}

}  // namespace binpick::cli
