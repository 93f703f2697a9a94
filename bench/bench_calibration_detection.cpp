// Board detection time and outcome per kind of view, on the virtual cell's white images at full
// resolution (1280 x 1024): a complete board, no board (the wall alone), a board cut by the image
// border (left, bottom) and a complete board blurred with a Gaussian of --sigma pixels. Each view
// is timed with detectBoard (what `binpick calibrate rig` runs) and, for reference, with the
// classic detector alone as detectBoard ran it before the fast pre-checks
// (cv::findChessboardCorners, ADAPTIVE_THRESH | NORMALIZE_IMAGE). Images of your own (8- or
// 16-bit grey PNGs of the same board) can be timed the same way with --image.
//
//   bench_calibration_detection [--board chessboard|charuco] [--poses 3] [--seed 1] [--sigma 5]
//                               [--repeat 1] [--no-classic] [--image FILE ...]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "binpick/calibration/board_detection.hpp"
#include "binpick/core/error.hpp"
#include "binpick/core/stopwatch.hpp"
#include "binpick/io/image_file.hpp"
#include "binpick/simulation/calibration_sequence.hpp"

namespace {

using namespace binpick;

struct Options {
  std::string board = "chessboard";
  int poses = 3;
  int seed = 1;
  double sigma = 5.0;
  int repeat = 1;
  bool classic = true;
  bool probe = false;
  std::vector<std::string> images;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--no-classic" || flag == "--probe") {
      (flag == "--probe" ? o.probe : o.classic) = flag == "--probe";
      continue;
    }
    if (i + 1 >= argc) throw core::Error("bench_calibration_detection: " + flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--board")
      o.board = value;
    else if (flag == "--poses")
      o.poses = std::stoi(value);
    else if (flag == "--seed")
      o.seed = std::stoi(value);
    else if (flag == "--sigma")
      o.sigma = std::stod(value);
    else if (flag == "--repeat")
      o.repeat = std::stoi(value);
    else if (flag == "--image")
      o.images.push_back(value);
    else
      throw core::Error("bench_calibration_detection: unknown option " + flag);
  }
  if (o.poses < 1 || o.repeat < 1 || !(o.sigma > 0.0)) {
    throw core::Error("bench_calibration_detection: --poses >= 1, --repeat >= 1, --sigma > 0");
  }
  return o;
}

struct View {
  std::string kind;  // "complete", "empty", "partial-left", "partial-bottom", "blurred", "file"
  std::string name;
  cv::Mat image;
  std::vector<simulation::CornerObservation> truth;  // empty for files and board-less views
};

Eigen::Isometry3d moved(Eigen::Isometry3d pose, double dx, double dy) {
  pose.translation() += Eigen::Vector3d(dx, dy, 0.0);
  return pose;
}

// The camera's field reaches x = +-0.40 z and y = +-0.32 z: a board centre put on the edge
// leaves half the board outside.
std::vector<View> renderedViews(const Options& o) {
  simulation::CalibrationSequenceParams params;
  params.board.type = simulation::boardTypeFromName(o.board);
  params.pattern_set.row_codes = false;  // only the white image is rendered
  params.pattern_set.phase_steps = 0;
  params.poses.count = o.poses;
  params.poses.seed = static_cast<uint64_t>(o.seed);
  const simulation::CalibrationBoard board(params.board, params.texel_size);
  const Eigen::Vector2d face_centre = board.printedFace().center();
  std::vector<View> views;
  int index = 0;
  for (const Eigen::Isometry3d& pose : simulation::randomBoardPoses(board, params.rig, params.poses)) {
    const Eigen::Vector3d centre = pose * Eigen::Vector3d(face_centre.x(), face_centre.y(), 0.0);
    const std::string suffix = "_" + std::to_string(index);
    const auto render = [&](const Eigen::Isometry3d& T) {
      return simulation::renderCalibrationWhiteImage(board, T, params, 10 + static_cast<uint64_t>(index));
    };
    View complete{"complete", "complete" + suffix, render(pose), simulation::observeCorners(board, params.rig, pose)};
    View blurred{"blurred", "blurred" + suffix, {}, complete.truth};
    cv::GaussianBlur(complete.image, blurred.image, cv::Size(), o.sigma);
    views.push_back(complete);
    views.push_back(blurred);
    views.push_back({"empty", "empty" + suffix, render(moved(pose, 2.0, 0.0)), {}});
    views.push_back(
        {"partial-left", "partial_left" + suffix, render(moved(pose, -0.40 * centre.z() - centre.x(), 0)), {}});
    views.push_back(
        {"partial-bottom", "partial_bottom" + suffix, render(moved(pose, 0, 0.32 * centre.z() - centre.y())), {}});
    ++index;
  }
  return views;
}

// Median and largest distance of the detected corners from the true ones; "-" without truth.
std::string cornerErrors(const calibration::BoardDetection& detection, const View& view) {
  if (view.truth.empty() || !detection.found()) return "-";
  std::map<int, Eigen::Vector2d> truth;
  for (const simulation::CornerObservation& corner : view.truth) truth[corner.id] = corner.camera_pixel;
  std::vector<double> errors;
  for (std::size_t i = 0; i < detection.ids.size(); ++i) {
    const auto found = truth.find(detection.ids[i]);
    if (found != truth.end()) errors.push_back((detection.pixels[i] - found->second).norm());
  }
  if (errors.empty()) return "-";
  std::sort(errors.begin(), errors.end());
  char text[48];
  std::snprintf(text, sizeof text, "%.3f / %.3f", errors[errors.size() / 2], errors.back());
  return text;
}

template <typename Run>
double bestOfMs(int repeat, Run run) {
  double best = INFINITY;
  for (int r = 0; r < repeat; ++r) {
    const binpick::core::Stopwatch watch;
    run();
    best = std::min(best, watch.elapsedMs());
  }
  return best;
}

// OpenCV's chessboard detectors one by one, at full resolution and scaled down: what a faster
// detection can be built from.
void probe(const View& view, const calibration::BoardLayout& layout, const Options& o) {
  cv::Mat image8 = view.image;
  if (image8.depth() != CV_8U) view.image.convertTo(image8, CV_8U, 1.0 / 257.0);
  const cv::Size pattern(layout.squares_x - 1, layout.squares_y - 1);
  for (const double scale : {1.0, 0.5, 0.25}) {
    cv::Mat small = image8;
    if (scale < 1.0) cv::resize(image8, small, cv::Size(), scale, scale, cv::INTER_AREA);
    std::vector<cv::Point2f> corners;
    bool check = false, sb = false, classic = false, fast = false;
    const double check_ms = bestOfMs(o.repeat, [&] { check = cv::checkChessboard(small, pattern); });
    const double sb_ms = bestOfMs(o.repeat, [&] { sb = cv::findChessboardCornersSB(small, pattern, corners); });
    const double fast_ms = bestOfMs(o.repeat, [&] {
      fast = cv::findChessboardCorners(
          small, pattern, corners,
          cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_FAST_CHECK);
    });
    double classic_ms = NAN;
    if (scale < 1.0) {
      classic_ms = bestOfMs(o.repeat, [&] {
        classic = cv::findChessboardCorners(small, pattern, corners,
                                            cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
      });
    }
    std::printf(
        "    x%.2f: checkChessboard %d %5.0f ms | SB %d %5.0f ms | classic+FAST_CHECK %d %6.0f ms | classic %d %6.0f "
        "ms\n",
        scale, check, check_ms, sb, sb_ms, fast, fast_ms, classic, classic_ms);
  }
}

void measure(const View& view, const calibration::BoardLayout& layout, const Options& o,
             std::map<std::string, std::vector<double>>& times) {
  calibration::BoardDetection detection;
  const double ms = bestOfMs(o.repeat, [&] { detection = calibration::detectBoard(view.image, layout); });
  times[view.kind].push_back(ms);
  std::string classic = "-";
  if (o.classic && layout.type == calibration::BoardType::Chessboard) {
    cv::Mat image8 = view.image;
    if (image8.depth() != CV_8U) view.image.convertTo(image8, CV_8U, 1.0 / 257.0);
    std::vector<cv::Point2f> corners;
    bool found = false;
    const double classic_ms = bestOfMs(o.repeat, [&] {
      found = cv::findChessboardCorners(image8, {layout.squares_x - 1, layout.squares_y - 1}, corners,
                                        cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
    });
    times[view.kind + " (classic)"].push_back(classic_ms);
    char text[64];
    std::snprintf(text, sizeof text, "%8.0f ms %-5s", classic_ms, found ? "found" : "no");
    classic = text;
  }
  if (o.probe) probe(view, layout, o);
  std::printf("%-18s %8.0f ms  %-5s %2zu/%2d corners  err median/max %13s px | classic %s | %s\n", view.name.c_str(),
              ms, detection.found() ? "found" : "no", detection.ids.size(), detection.expected,
              cornerErrors(detection, view).c_str(), classic.c_str(),
              detection.found() ? "" : detection.problem.c_str());
  std::fflush(stdout);
}

void run(const Options& o) {
  calibration::BoardLayout layout = simulation::BoardSpec{}.layout();
  layout.type = calibration::boardTypeFromName(o.board);
  std::vector<View> views;
  for (const std::string& path : o.images) {
    const cv::Mat image = io::readImageFile(path);
    if (image.empty()) throw core::Error("bench_calibration_detection: cannot read " + path);
    views.push_back({"file", path, image, {}});
  }
  if (o.images.empty()) views = renderedViews(o);
  std::printf("bench_calibration_detection: %s, %zu views, blur sigma %.1f px, best of %d\n", o.board.c_str(),
              views.size(), o.sigma, o.repeat);
  std::printf("%-18s %11s  %-5s %14s  %16s | %-22s\n", "view", "detectBoard", "", "", "", "classic alone");
  std::map<std::string, std::vector<double>> times;
  for (const View& view : views) measure(view, layout, o, times);
  std::printf("\nmean time per view kind:\n");
  for (const auto& [kind, ms] : times) {
    double sum = 0.0;
    for (const double t : ms) sum += t;
    std::printf("  %-26s %8.0f ms (%zu views)\n", kind.c_str(), sum / static_cast<double>(ms.size()), ms.size());
  }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    run(parse(argc, argv));
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
