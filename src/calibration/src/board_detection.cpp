// Board corners in a camera image (ChArUco or chessboard), refined to sub-pixel, and the pose.
#include "binpick/calibration/board_detection.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "binpick/core/error.hpp"

namespace binpick::calibration {
namespace {

struct Corners {
  std::vector<int> ids;
  std::vector<cv::Point2f> pixels;
};

// The detectors want 8 bits; 16-bit captures hold the sensor value in the high bits.
cv::Mat eightBit(const cv::Mat& image) {
  if (image.depth() == CV_8U) return image;
  cv::Mat converted;
  image.convertTo(converted, CV_8U, 1.0 / 257.0);
  return converted;
}

cv::Ptr<cv::aruco::CharucoBoard> charucoBoard(const BoardLayout& layout) {
  return cv::aruco::CharucoBoard::create(layout.squares_x, layout.squares_y, static_cast<float>(layout.square_size),
                                         static_cast<float>(layout.marker_size),
                                         cv::aruco::getPredefinedDictionary(arucoDictionaryId(layout.dictionary)));
}

std::string findCharuco(const cv::Mat& image8, const BoardLayout& layout, Corners& found) {
  const auto board = charucoBoard(layout);
  std::vector<std::vector<cv::Point2f>> markers;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(image8, board->dictionary, markers, marker_ids);
  if (marker_ids.empty()) return "no ArUco marker of " + layout.dictionary + " in the image";
  cv::aruco::interpolateCornersCharuco(markers, marker_ids, image8, board, found.pixels, found.ids);
  if (found.ids.empty()) return "ArUco markers found but no ChArUco corner between them";
  return {};
}

// Whether the sector-based detector (findChessboardCornersSB) sees the whole pattern, in the
// image scaled to a quarter, a half or full size, cheapest first (10, 40, 100-250 ms at 1280x1024):
// scaled down, a blurred board (sigma 5 px) is sharp enough for it.
bool seesWholeChessboard(const cv::Mat& image8, cv::Size pattern) {
  std::vector<cv::Point2f> corners;
  for (const double scale : {0.25, 0.5}) {
    cv::Mat small;
    cv::resize(image8, small, cv::Size(), scale, scale, cv::INTER_AREA);
    if (cv::findChessboardCornersSB(small, pattern, corners)) return true;
  }
  return cv::findChessboardCornersSB(image8, pattern, corners);
}

// cv::findChessboardCorners without a complete board tries every threshold and dilation it knows:
// 7-28 s on a 1280x1024 view, against a few milliseconds for a complete board. Its own quick check
// (CALIB_CB_FAST_CHECK) rejects empty views at once but passes some boards cut by the image border
// (11-15 s each). So it runs only when the sector-based detector sees the whole pattern; the
// corners still come from it, as before: SB alone gave a false positive on a half-black image
// (the classic search then rejects it, slowly) and missed views blurred with sigma 5 px at full
// size.
bool findChessboardCorners(const cv::Mat& image8, cv::Size pattern, std::vector<cv::Point2f>& pixels) {
  if (!seesWholeChessboard(image8, pattern)) return false;
  return cv::findChessboardCorners(image8, pattern, pixels,
                                   cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE);
}

// Why no board was found: no chessboard at all, or some of one (the quick check still sees a 3x3
// patch of squares: a board cut by the image border or partly covered).
std::string missingChessboardProblem(const cv::Mat& image8, cv::Size pattern) {
  const std::string size = std::to_string(pattern.width) + "x" + std::to_string(pattern.height);
  const std::string squares = std::to_string(pattern.width + 1) + "x" + std::to_string(pattern.height + 1);
  if (!cv::checkChessboard(image8, cv::Size(3, 3)))
    return "no chessboard in the image (looked for " + size + " inner corners, " + squares + " squares)";
  return "no complete " + size +
         " chessboard in the image, only part of one (every inner corner must be visible: is the board cut by the"
         " image border or covered? Or does it have another number of inner corners (looked for " +
         size + ", " + squares + " squares)?)";
}

// Squares and inner corners are easily confused (a board of 9 x 7 inner corners has 10 x 8
// squares): a whole board one corner larger or smaller each way, when there is one.
cv::Size otherChessboardSize(const cv::Mat& image8, cv::Size pattern) {
  for (const int step : {1, -1}) {
    const cv::Size other(pattern.width + step, pattern.height + step);
    if (other.width >= 2 && other.height >= 2 && seesWholeChessboard(image8, other)) return other;
  }
  return {};
}

std::string otherSizeProblem(cv::Size pattern, cv::Size other) {
  const auto size = [](int x, int y) { return std::to_string(x) + "x" + std::to_string(y); };
  return "no " + size(pattern.width, pattern.height) + " chessboard (inner corners; " +
         size(pattern.width + 1, pattern.height + 1) + " squares) in the image, but one of " +
         size(other.width, other.height) + " inner corners (" + size(other.width + 1, other.height + 1) +
         " squares): the board's size is given in the other convention?";
}

// cv::findChessboardCorners lists the corners from either end of a board turned half a turn:
// start from the end nearest the image's top-left so that views agree.
std::string findChessboard(const cv::Mat& image8, const BoardLayout& layout, Corners& found,
                           BoardDetection& detection) {
  const cv::Size pattern(layout.squares_x - 1, layout.squares_y - 1);
  if (!findChessboardCorners(image8, pattern, found.pixels)) {
    const cv::Size other = otherChessboardSize(image8, pattern);
    if (other.empty()) return missingChessboardProblem(image8, pattern);
    detection.seen_inner_x = other.width;
    detection.seen_inner_y = other.height;
    return otherSizeProblem(pattern, other);
  }
  const cv::Point2f first = found.pixels.front(), last = found.pixels.back();
  if (first.x + first.y > last.x + last.y) std::reverse(found.pixels.begin(), found.pixels.end());
  found.ids.resize(found.pixels.size());
  std::iota(found.ids.begin(), found.ids.end(), 0);
  return {};
}

// The side of the smallest squares in the image, pixels: a low percentile of the distances between
// neighbouring corners (the board is foreshortened unevenly). 0 when no two neighbours were found.
double smallSquareSide(const BoardLayout& layout, const Corners& corners) {
  const int columns = layout.squares_x - 1;
  std::map<int, cv::Point2f> by_id;
  for (std::size_t i = 0; i < corners.ids.size(); ++i) by_id[corners.ids[i]] = corners.pixels[i];
  std::vector<double> sides;
  for (const auto& [id, pixel] : by_id) {
    const auto right = by_id.find(id + 1), below = by_id.find(id + columns);
    if (id % columns != columns - 1 && right != by_id.end()) {
      sides.push_back(cv::norm(right->second - pixel));
    }
    if (below != by_id.end()) sides.push_back(cv::norm(below->second - pixel));
  }
  if (sides.empty()) return 0.0;
  const auto low = sides.begin() + static_cast<std::ptrdiff_t>(sides.size() / 10);
  std::nth_element(sides.begin(), low, sides.end());
  return *low;
}

// The refinement window must stay in the white ring between a corner and the nearest ChArUco
// marker (or, on a chessboard, inside the squares): a marker edge in the window pulls the
// saddle point towards it (0.6 px with 25-pixel squares and a 5-pixel half window). A chessboard's
// window grows with its squares: a blurred corner's saddle is as wide as the blur, and a window
// narrower than that left one corner of a view blurred with sigma 5 px 14 px off (the full-size
// virtual views, squares of 46-69 px: a 15-pixel window brings it within 0.4 px).
int refinementHalfWindow(const BoardLayout& layout, const Corners& corners, const BoardDetectionParams& params) {
  const double side = smallSquareSide(layout, corners);
  if (side <= 0.0) return params.subpixel_half_window;
  if (layout.type == BoardType::Chessboard) {
    const int window = static_cast<int>(std::floor(params.chessboard_window_share * side));
    return std::clamp(window, 2, std::max(params.subpixel_half_window, params.chessboard_half_window));
  }
  const double ring = (layout.square_size - layout.marker_size) / (2.0 * layout.square_size);
  const int limit = static_cast<int>(std::floor(ring * side)) - 1;
  return std::clamp(limit, 2, params.subpixel_half_window);
}

// The image divided by its local white level (the white squares' brightness around each pixel):
// the light falling across the board, blurred together with the squares, moves a blurred
// corner's saddle point towards the brighter side (0.3 px median on views blurred with sigma
// 5 px, 0.07 px once flattened). The white level is the largest value within two squares' sides,
// smoothed over one.
cv::Mat flattened(const cv::Mat& image, double side) {
  cv::Mat grey, white;
  image.convertTo(grey, CV_32F);
  if (!(side > 0.0)) return grey;
  const int size = 2 * static_cast<int>(std::ceil(side)) + 1;
  cv::dilate(grey, white, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(size, size)));
  cv::GaussianBlur(white, white, cv::Size(), std::max(1.0, side));
  cv::max(white, 1.0, white);  // no division by a black region's zero
  cv::divide(grey, white, grey);
  return grey;
}

// OpenCV 4.6's ChArUco interpolation leaves corners half a pixel off (opencv/opencv#25539);
// cornerSubPix converges to the saddle point from there whatever the detector's convention.
void refine(const cv::Mat& image, std::vector<cv::Point2f>& pixels, int half_window) {
  cv::Mat grey = image;
  if (image.depth() != CV_8U && image.depth() != CV_32F) image.convertTo(grey, CV_32F);
  cv::cornerSubPix(grey, pixels, cv::Size(half_window, half_window), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
}

// Corners by ascending id, without those too near the border for the refinement window.
void keepInside(const cv::Mat& image, double margin, const Corners& corners, BoardDetection& detection) {
  std::vector<std::size_t> order(corners.ids.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return corners.ids[a] < corners.ids[b]; });
  for (const std::size_t i : order) {
    const cv::Point2f& p = corners.pixels[i];
    if (p.x < margin || p.y < margin || p.x > image.cols - 1 - margin || p.y > image.rows - 1 - margin) {
      continue;
    }
    detection.ids.push_back(corners.ids[i]);
    detection.pixels.emplace_back(p.x, p.y);
  }
}

}  // namespace

void BoardDetectionParams::validate() const {
  core::requireField(subpixel_half_window >= 2, "BoardDetectionParams", "subpixel_half_window", ">= 2",
                     subpixel_half_window);
  core::requireField(chessboard_half_window >= 2, "BoardDetectionParams", "chessboard_half_window", ">= 2",
                     chessboard_half_window);
  core::requireField(
      std::isfinite(chessboard_window_share) && chessboard_window_share > 0.0 && chessboard_window_share < 0.5,
      "BoardDetectionParams", "chessboard_window_share", "in (0, 0.5)", chessboard_window_share);
  core::requireField(min_corners >= 4, "BoardDetectionParams", "min_corners", ">= 4", min_corners);
  core::requireField(std::isfinite(border_margin) && border_margin >= 0.0, "BoardDetectionParams", "border_margin",
                     ">= 0", border_margin);
}

BoardDetection detectBoard(const cv::Mat& image, const BoardLayout& layout, const BoardDetectionParams& params) {
  params.validate();
  layout.validate();
  if (image.empty() || image.channels() != 1 || (image.depth() != CV_8U && image.depth() != CV_16U)) {
    throw core::Error("board detection needs a non-empty 8- or 16-bit single-channel image");
  }
  BoardDetection detection;
  detection.expected = layout.cornerCount();
  const cv::Mat image8 = eightBit(image);
  Corners corners;
  detection.problem = layout.type == BoardType::Charuco ? findCharuco(image8, layout, corners)
                                                        : findChessboard(image8, layout, corners, detection);
  if (!detection.found()) return detection;
  const int window = refinementHalfWindow(layout, corners, params);
  if (layout.type == BoardType::Chessboard && params.flatten_chessboard) {
    refine(flattened(image, smallSquareSide(layout, corners)), corners.pixels, window);
  } else {
    refine(image, corners.pixels, window);
  }
  keepInside(image, params.border_margin, corners, detection);
  if (static_cast<int>(detection.ids.size()) < params.min_corners) {
    detection.problem = "only " + std::to_string(detection.ids.size()) + " of " + std::to_string(detection.expected) +
                        " board corners found (at least " + std::to_string(params.min_corners) + " needed)";
  }
  return detection;
}

}  // namespace binpick::calibration
