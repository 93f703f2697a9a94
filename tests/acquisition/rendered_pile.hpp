#pragma once
// Test data for the acquisition tests: the pattern images of a small rendered pile (quarter-size
// camera, 320 x 256; column codes only), computed once per test binary.
#include <utility>
#include <vector>

#include "binpick/io/capture.hpp"
#include "binpick/simulation/parts.hpp"
#include "binpick/simulation/pile.hpp"

namespace binpick::acquisition::testing {

struct RenderedPile {
  io::PatternSetSpec patterns;
  std::vector<cv::Mat> images;  // patternSequence order, CV_8UC1
  io::RigCalibration rig;       // the rig that saw them, to reconstruct recordings
};

inline const RenderedPile& renderedPile() {
  static const RenderedPile pile = [] {
    simulation::PileParams params;
    params.objects = 5;
    params.seed = 11;
    params.rig.camera = params.rig.camera.scaled(0.25);
    RenderedPile out;
    out.patterns.projector_width = params.rig.projector.width;
    out.patterns.projector_height = params.rig.projector.height;
    out.patterns.row_codes = false;
    simulation::PhotometryParams photometry;
    photometry.seed = 3;
    simulation::PileCapture capture =
        simulation::generatePileCapture(simulation::makePart("clamp").mesh, params, out.patterns, photometry);
    out.images = std::move(capture.images);
    out.rig = capture.scene.rig;
    return out;
  }();
  return pile;
}

inline bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

}  // namespace binpick::acquisition::testing
