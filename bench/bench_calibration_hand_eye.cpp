// Hand-eye benchmark on the virtual cell: for both setups, robot pose noise levels and every
// OpenCV method, the error of the recovered camera transform (T_base_camera or T_flange_camera)
// against the truth, over several seeds. The board poses come from rendered images (detection
// and PnP, so the image noise is in), rendered once per setup and seed; the noise levels only
// change the reported robot poses.
//
//   bench_calibration_hand_eye [--views 12] [--seeds 5] [--seed 1]
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "binpick/calibration/board_detection.hpp"
#include "binpick/calibration/hand_eye.hpp"
#include "binpick/core/error.hpp"
#include "binpick/simulation/hand_eye_session.hpp"

namespace {

using namespace binpick;
using calibration::HandEyeMethod;
using calibration::HandEyeSetup;

struct Options {
  int views = 12;
  int seeds = 5;
  uint64_t seed = 1;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) throw core::Error("bench_calibration_hand_eye: " + flag + " needs a value");
    const std::string value = argv[++i];
    if (flag == "--views")
      o.views = std::stoi(value);
    else if (flag == "--seeds")
      o.seeds = std::stoi(value);
    else if (flag == "--seed")
      o.seed = std::stoull(value);
    else
      throw core::Error("bench_calibration_hand_eye: unknown option " + flag);
  }
  if (o.views < 6 || o.seeds < 1) throw core::Error("bench_calibration_hand_eye: --views >= 6, --seeds >= 1");
  return o;
}

struct NoiseLevel {
  double mm, deg;
};
const std::vector<NoiseLevel> kNoiseLevels = {{0.0, 0.0}, {0.1, 0.05}, {0.5, 0.2}};

// A method alone, or refined (HandEyeParams::refine); auto is the default.
struct Variant {
  HandEyeMethod method;
  bool refine;
  std::string name() const {
    return method == HandEyeMethod::Auto ? "auto" : calibration::handEyeMethodName(method) + (refine ? "+refine" : "");
  }
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const HandEyeMethod m : calibration::allHandEyeMethods()) out.push_back({m, false});
  out.push_back({HandEyeMethod::Shah, true});
  out.push_back({HandEyeMethod::Tsai, true});  // does the refinement recover a poor start?
  out.push_back({HandEyeMethod::Auto, true});
  return out;
}

// Per setup, seed: the board poses PnP measures in the rendered images, by view name.
std::vector<std::pair<std::string, Eigen::Isometry3d>> measuredBoards(const simulation::HandEyeSessionParams& params) {
  const simulation::HandEyeSession session = simulation::simulateHandEyeSession(params);
  const simulation::CalibrationBoard board(params.board);
  const calibration::BoardLayout layout = params.board.layout();
  std::vector<std::pair<std::string, Eigen::Isometry3d>> boards;
  uint64_t noise_seed = params.seed * 1000;
  for (const simulation::HandEyeSessionView& view : session.views) {
    const cv::Mat image = simulation::renderHandEyeImage(board, view.T_camera_board, params, ++noise_seed);
    const auto pose =
        calibration::estimateBoardPose(calibration::detectBoard(image, layout), layout, params.rig.camera);
    if (pose) boards.emplace_back(view.name, pose->T_camera_board);
  }
  return boards;
}

struct Tally {
  double sum_mm = 0.0, max_mm = 0.0, sum_deg = 0.0, max_deg = 0.0;
  int solved = 0, failed = 0;
  void add(const calibration::PoseDifference& d) {
    sum_mm += d.translation_mm;
    sum_deg += d.rotation_deg;
    max_mm = std::max(max_mm, d.translation_mm);
    max_deg = std::max(max_deg, d.rotation_deg);
    ++solved;
  }
};

void runSetup(HandEyeSetup setup, const Options& o) {
  const std::vector<Variant> methods = variants();
  std::vector<std::vector<Tally>> tallies(kNoiseLevels.size(), std::vector<Tally>(methods.size()));
  for (int s = 0; s < o.seeds; ++s) {
    simulation::HandEyeSessionParams params;
    params.setup = setup;
    params.views = o.views;
    params.seed = o.seed + static_cast<uint64_t>(s);
    const auto boards = measuredBoards(params);
    for (std::size_t n = 0; n < kNoiseLevels.size(); ++n) {
      params.robot_noise_mm = kNoiseLevels[n].mm;
      params.robot_noise_deg = kNoiseLevels[n].deg;
      const simulation::HandEyeSession session = simulation::simulateHandEyeSession(params);
      std::vector<calibration::HandEyeView> views;
      for (const auto& [name, T_camera_board] : boards) {
        const int index = std::stoi(name.substr(name.find('_') + 1));
        views.push_back({name, session.views[static_cast<std::size_t>(index)].T_base_flange, T_camera_board});
      }
      for (std::size_t m = 0; m < methods.size(); ++m) {
        calibration::HandEyeParams solver;
        solver.setup = setup;
        solver.method = methods[m].method;
        solver.refine = methods[m].refine;
        try {
          const calibration::HandEyeResult r = calibration::solveHandEye(views, solver);
          tallies[n][m].add(calibration::poseDifference(r.T_mount_camera, session.T_mount_camera));
          if (!r.ok()) ++tallies[n][m].failed;
        } catch (const core::Error&) {
          ++tallies[n][m].failed;
        }
      }
    }
  }
  std::printf("\n%s, %d views, %d seeds from %llu: error of %s\n", calibration::handEyeSetupName(setup).c_str(),
              o.views, o.seeds, static_cast<unsigned long long>(o.seed),
              calibration::cameraTransformName(setup).c_str());
  std::printf("| robot noise        | method          | mean mm | max mm | mean deg | max deg | rejected |\n");
  std::printf("|--------------------|-----------------|--------:|-------:|---------:|--------:|---------:|\n");
  for (std::size_t n = 0; n < kNoiseLevels.size(); ++n) {
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const Tally& t = tallies[n][m];
      const double k = std::max(t.solved, 1);
      std::printf("| %4.1f mm, %4.2f deg | %-15s | %7.3f | %6.3f | %8.4f | %7.4f | %8d |\n", kNoiseLevels[n].mm,
                  kNoiseLevels[n].deg, methods[m].name().c_str(), t.sum_mm / k, t.max_mm, t.sum_deg / k, t.max_deg,
                  t.failed);
    }
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parse(argc, argv);
    for (const HandEyeSetup setup : {HandEyeSetup::EyeToHand, HandEyeSetup::EyeInHand}) runSetup(setup, options);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
