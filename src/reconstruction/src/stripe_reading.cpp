// readAlongStripes: candidates, the stripe's direction per block, then every bit summed along it.
#include "stripe_reading.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <tuple>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "axis_resolution.hpp"
#include "binpick/reconstruction/pixel_status.hpp"

namespace binpick::reconstruction::detail {
namespace {

constexpr int kBlock = 16;              // pixels per side of the blocks the direction is searched for
constexpr int kDirections = 32;         // 5.6 degrees apart: the ends of an 8 px reach within 0.4 px
constexpr int kCoarseStep = 4;          // the search tries every 4th direction first (22.5 degrees apart)
constexpr int kSearchReach = 8;         // pixels each side along a direction tried
constexpr int kEnergyBits = 4;          // the finest bits, whose sums depend most on the direction
constexpr int kSearchStride = 4;        // every 4th pixel of a block, both ways, takes part in the search
constexpr double kCredibleMass = 0.95;  // of the codes' likelihood, in the run a member is placed in
constexpr int kAreaSide = 5;            // pixels: the neighbourhood that tells a dark area from a line, keepDarkAreas
constexpr float kMaxContrastInMargins = 4.0f;  // white - black over a pixel's noise margin, lightOf
constexpr float kZScale = 25.0f;               // Member::z per unit: up to 10.2, beyond any uncertain bit

// The pixels of the segment t u, |t| <= reach, for one direction u: as steps and as row-major
// offsets in an image `width` wide.
struct Segment {
  int reach = 0;
  std::vector<cv::Point> steps;
  std::vector<std::ptrdiff_t> offsets;
};

Segment segmentAlong(double angle, int reach, int width) {
  Segment segment{reach, {}, {}};
  for (int t = -reach; t <= reach; ++t) {
    const cv::Point step(static_cast<int>(std::lround(t * std::cos(angle))),
                         static_cast<int>(std::lround(t * std::sin(angle))));
    segment.steps.push_back(step);
    segment.offsets.push_back(static_cast<std::ptrdiff_t>(step.y) * width + step.x);
  }
  return segment;
}

std::vector<Segment> segmentsOfEveryDirection(int reach, int width) {
  std::vector<Segment> segments;
  for (int k = 0; k < kDirections; ++k) segments.push_back(segmentAlong(M_PI * k / kDirections, reach, width));
  return segments;
}

// What every bit's sums need (pattern - inverse is made per bit when the bit is read, differenceOf).
struct Light {
  cv::Mat variance;  // bit_noise_sigmas^2 var(pattern - inverse): the squared margin the noise sets
  cv::Mat member;    // CV_8U: non-zero for the pixels read along their stripes
};

cv::Mat asFloat(const cv::Mat& image) {
  cv::Mat converted;
  image.convertTo(converted, CV_32F);
  return converted;
}

// pattern - inverse of one Gray bit, into `difference` (its buffer reused from bit to bit: fresh
// pages cost more than the subtraction).
void differenceOf(const io::Capture& capture, const AxisLayout& axis, int bit, cv::Mat& difference) {
  cv::subtract(capture.images[static_cast<std::size_t>(axis.bit_images[static_cast<std::size_t>(bit)])],
               capture.images[static_cast<std::size_t>(axis.inverse_images[static_cast<std::size_t>(bit)])], difference,
               cv::noArray(), CV_32F);
}

// Keeps the dark pixels (CV_8U, 0 or 255) with at least half of their kAreaSide x kAreaSide
// neighbourhood dark: a dark surface. A thin dark line between bright pixels is a crease or a
// depth step, whose pixels mix two stripes, and along which the direction search would follow
// the line across the stripes.
void keepDarkAreas(cv::Mat& dark) {
  cv::Mat around;
  cv::boxFilter(dark / 255, around, CV_16U, cv::Size(kAreaSide, kAreaSide), cv::Point(-1, -1), false,
                cv::BORDER_CONSTANT);
  dark &= around >= (kAreaSide * kAreaSide + 1) / 2;
}

// The members: pixels that failed alone for lack of signal (Unlit, UncertainCode), unclipped, in
// dark areas, with some light of the projector's beyond the noise margin (a pixel in shadow sums
// to noise alone) but at most kMaxContrastInMargins margins. A brighter pixel failed alone for
// another reason than the noise (a mixed pixel at a depth edge, interreflections), which summing
// does not cure: on the virtual cell's defocused Gray-code capture, the brighter pixels read
// along their stripes were 0.7% wrong (by more than their run), the darker ones none.
Light lightOf(const io::Capture& capture, const DecodePlan& plan, const DecodedCapture& decoded) {
  const DecodeThresholds& t = plan.thresholds;
  const cv::Mat white = asFloat(capture.images[static_cast<std::size_t>(plan.layout.white)]);
  const cv::Mat black = asFloat(capture.images[static_cast<std::size_t>(plan.layout.black)]);
  Light light;
  light.variance = t.noise_floor + t.noise_slope * (white + black);
  const cv::Mat contrast = white - black;
  const cv::Mat contrast_sq = contrast.mul(contrast);
  const cv::Mat brightest_sq = kMaxContrastInMargins * kMaxContrastInMargins * light.variance;
  cv::Mat dark = (contrast_sq > light.variance) & (contrast_sq < brightest_sq) & (white < t.saturation);
  keepDarkAreas(dark);
  const cv::Mat failed = (decoded.status == static_cast<int>(PixelStatus::Unlit)) |
                         (decoded.status == static_cast<int>(PixelStatus::UncertainCode));
  light.member = dark & failed;
  return light;
}

// Sums of `values` over the members on the segment through (x, y): before the pixel (t < 0), the
// pixel itself and after it (t > 0); and how many members in all.
struct HalfSums {
  float before = 0.0f;
  float centre = 0.0f;
  float after = 0.0f;
  int count = 0;
  float total() const { return before + centre + after; }
};

HalfSums sumHalves(const cv::Mat& values, const cv::Mat& member, int x, int y, const Segment& segment) {
  const int reach = segment.reach;
  const bool inside = x >= reach && y >= reach && x + reach < values.cols && y + reach < values.rows;
  const std::ptrdiff_t centre = static_cast<std::ptrdiff_t>(y) * values.cols + x;
  const float* value = values.ptr<float>(0) + centre;
  const uint8_t* in = member.ptr<uint8_t>(0) + centre;
  HalfSums sums;
  for (std::size_t i = 0; i < segment.steps.size(); ++i) {
    if (!inside) {
      const cv::Point& step = segment.steps[i];
      if (x + step.x < 0 || y + step.y < 0 || x + step.x >= values.cols || y + step.y >= values.rows) continue;
    }
    const std::ptrdiff_t offset = segment.offsets[i];
    if (in[offset] == 0) continue;
    const int t = static_cast<int>(i) - reach;
    (t < 0 ? sums.before : t == 0 ? sums.centre : sums.after) += value[offset];
    ++sums.count;
  }
  return sums;
}

float sumAlong(const cv::Mat& values, const cv::Mat& member, int x, int y, const Segment& segment) {
  return sumHalves(values, member, x, y, segment).total();
}

// The energy of the finest bits' sums along direction k over a block's members on the search
// grid; negative when it has none there.
double energyAlong(const std::vector<cv::Mat>& finest, const cv::Mat& member, int x0, int y0, const Segment& segment) {
  double energy = -1.0;
  for (int y = y0; y < std::min(y0 + kBlock, member.rows); y += kSearchStride) {
    for (int x = x0; x < std::min(x0 + kBlock, member.cols); x += kSearchStride) {
      if (member.at<uint8_t>(y, x) == 0) continue;
      energy = std::max(energy, 0.0);
      for (const cv::Mat& difference : finest) {
        const double sum = sumAlong(difference, member, x, y, segment);
        energy += sum * sum;
      }
    }
  }
  return energy;
}

// Per block, the direction (index into `search`) along which the finest bits' sums over the
// block's members carry the most energy; -1 for blocks without members on the search's grid.
// Coarse to fine: every kCoarseStep-th direction, then the neighbours of the best, halving.
std::vector<int> stripeDirections(const io::Capture& capture, const AxisLayout& axis, const Light& light,
                                  const std::vector<Segment>& search, int threads) {
  const int blocks_x = (light.member.cols + kBlock - 1) / kBlock;
  const int blocks_y = (light.member.rows + kBlock - 1) / kBlock;
  std::vector<cv::Mat> finest;
  for (int bit = std::max(0, axis.bits() - kEnergyBits); bit < axis.bits(); ++bit) {
    differenceOf(capture, axis, bit, finest.emplace_back());
  }
  std::vector<int> direction(static_cast<std::size_t>(blocks_x) * static_cast<std::size_t>(blocks_y), -1);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 8)
  for (int block = 0; block < blocks_x * blocks_y; ++block) {
    const int x0 = (block % blocks_x) * kBlock;
    const int y0 = (block / blocks_x) * kBlock;
    const auto energy = [&](int k) {
      return energyAlong(finest, light.member, x0, y0,
                         search[static_cast<std::size_t>((k + kDirections) % kDirections)]);
    };
    int best = -1;
    double most = -1.0;
    for (int k = 0; k < kDirections; k += kCoarseStep) {
      const double e = energy(k);
      if (e > most) std::tie(best, most) = std::make_tuple(k, e);
    }
    if (best < 0) continue;
    for (int step = kCoarseStep / 2; step >= 1; step /= 2) {
      const int centre = best;
      for (const int k : {centre - step, centre + step}) {
        const double e = energy(k);
        if (e > most) std::tie(best, most) = std::make_tuple((k + kDirections) % kDirections, e);
      }
    }
    direction[static_cast<std::size_t>(block)] = best;
  }
  return direction;
}

// Whether two parts of a segment's sums each clear their noise with opposite signs.
bool disagree(const HalfSums& sums, const HalfSums& variance) {
  const float part[3] = {sums.before, sums.centre, sums.after};
  const float noise[3] = {variance.before, variance.centre, variance.after};
  bool positive = false, negative = false;
  for (int i = 0; i < 3; ++i) {
    if (part[i] * part[i] <= noise[i]) continue;
    (part[i] > 0.0f ? positive : negative) = true;
  }
  return positive && negative;
}

struct Member {
  int x = 0;
  int y = 0;
  const Segment* segment = nullptr;  // along its block's stripe direction
  HalfSums variance;                 // bit_noise_sigmas^2 times the sums' variance
  // Two of the segment's parts (before the pixel, the pixel, after it) read a bit differently,
  // each beyond its noise: the segment crosses from one stripe into another (a depth edge, or a
  // stripe more curved than the segment is straight).
  bool mixed = false;
  uint16_t code = 0;  // as TileAxis: Gray code read, uncertain bits, most significant first
  uint16_t uncertain = 0;
  // Per bit of `code` (index 0: least significant), |sum| / sigma in steps of 1/kZScale.
  std::array<uint8_t, 16> z{};
};

// The members of one axis with enough of the segment to sum over (at least half of it), in
// row-major order.
std::vector<Member> membersAlong(const Light& light, const std::vector<int>& direction,
                                 const std::vector<Segment>& segments, int reach, int threads) {
  const int blocks_x = (light.member.cols + kBlock - 1) / kBlock;
  std::vector<Member> members(static_cast<std::size_t>(cv::countNonZero(light.member)));
  std::vector<std::size_t> row_start(static_cast<std::size_t>(light.member.rows) + 1, 0);
  for (int y = 0; y < light.member.rows; ++y) {
    row_start[static_cast<std::size_t>(y) + 1] =
        row_start[static_cast<std::size_t>(y)] + static_cast<std::size_t>(cv::countNonZero(light.member.row(y)));
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int y = 0; y < light.member.rows; ++y) {
    const uint8_t* in = light.member.ptr<uint8_t>(y);
    std::size_t next = row_start[static_cast<std::size_t>(y)];
    for (int x = 0; x < light.member.cols; ++x) {
      if (in[x] == 0) continue;
      Member& member = members[next++];
      member.x = x;
      member.y = y;
      const int k = direction[static_cast<std::size_t>((y / kBlock) * blocks_x + x / kBlock)];
      if (k < 0) continue;  // no member of its block on the search's grid: too few to read
      const HalfSums variance = sumHalves(light.variance, light.member, x, y, segments[static_cast<std::size_t>(k)]);
      if (variance.count < reach + 1) continue;
      member.segment = &segments[static_cast<std::size_t>(k)];
      member.variance = variance;
    }
  }
  members.erase(std::remove_if(members.begin(), members.end(), [](const Member& m) { return m.segment == nullptr; }),
                members.end());
  return members;
}

// Every bit of the axis summed along each member's segment and classified. No margin of the
// contrast, unlike a pixel read alone: what interreflections bias are the wide stripes' bits, and
// a pixel lit mostly by interreflections has its fine bits washed out, so its run stays too long.
void readBits(const io::Capture& capture, const AxisLayout& axis, const Light& light, const DecodeParams& params,
              int threads, std::vector<Member>& members) {
  const auto sigmas = static_cast<float>(params.bit_noise_sigmas);
  cv::Mat difference;
  for (int bit = 0; bit < axis.bits(); ++bit) {
    differenceOf(capture, axis, bit, difference);
    const auto position = static_cast<std::size_t>(axis.bits() - 1 - bit);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::size_t i = 0; i < members.size(); ++i) {
      Member& m = members[i];
      const HalfSums parts = sumHalves(difference, light.member, m.x, m.y, *m.segment);
      const float sum = parts.total();
      const bool certain = sum * sum > m.variance.total();
      m.mixed |= disagree(parts, m.variance);
      m.code = static_cast<uint16_t>((m.code << 1) | static_cast<uint16_t>(sum > 0.0f));
      m.uncertain = static_cast<uint16_t>((m.uncertain << 1) | static_cast<uint16_t>(!certain));
      const float z = sigmas * std::fabs(sum) / std::sqrt(m.variance.total());  // |sum| / sigma
      m.z[position] = static_cast<uint8_t>(std::min(255.0f, z * kZScale + 0.5f));
    }
  }
}

// The probability of each code the certain bits allow (inside the projector), from the
// uncertain bits' sums: every sign read right or wrong independently, Phi(|sum| / sigma) for
// right. In code order.
struct CodeLikelihoods {
  std::array<std::pair<unsigned, double>, 1u << kMaxUncertainBits> codes;
  std::size_t size = 0;
};

// Phi(z) for every Member::z.
std::array<float, 256> normalCdfTable() {
  std::array<float, 256> table{};
  for (std::size_t z = 0; z < table.size(); ++z) {
    table[z] = static_cast<float>(0.5 * std::erfc(-static_cast<double>(z) / (kZScale * M_SQRT2)));
  }
  return table;
}

CodeLikelihoods codeLikelihoods(const Member& member, const AxisLayout& axis) {
  static const std::array<float, 256> kPhi = normalCdfTable();
  std::array<double, 16> right{};
  for (uint32_t bits = member.uncertain; bits != 0; bits &= bits - 1) {
    const auto bit = static_cast<std::size_t>(__builtin_ctz(bits));
    right[bit] = kPhi[member.z[bit]];
  }
  const uint32_t certain_bits = member.code & ~member.uncertain;
  CodeLikelihoods likely;
  double total = 0.0;
  for (uint32_t subset = member.uncertain;; subset = (subset - 1) & member.uncertain) {
    const unsigned code = grayDecode(certain_bits | subset);
    if (code < static_cast<unsigned>(axis.size)) {
      double weight = 1.0;
      for (uint32_t bits = member.uncertain; bits != 0; bits &= bits - 1) {
        const int bit = __builtin_ctz(bits);
        const bool as_read = ((subset >> bit) & 1u) == ((member.code >> bit) & 1u);
        weight *= as_read ? right[static_cast<std::size_t>(bit)] : 1.0 - right[static_cast<std::size_t>(bit)];
      }
      likely.codes[likely.size++] = {code, weight};
      total += weight;
    }
    if (subset == 0) break;
  }
  for (std::size_t i = 0; i < likely.size; ++i) likely.codes[i].second /= total;
  std::sort(likely.codes.begin(), likely.codes.begin() + static_cast<std::ptrdiff_t>(likely.size));
  return likely;
}

struct Placement {
  float position = 0.0f;  // codes
  unsigned run = 0;       // codes the position may be off by up to half of
};

// The shortest run of codes that holds kCredibleMass of the likelihood, when it is at most
// `longest_run` long: the member lies at the run's weighted mean. A bit summing to nothing
// splits its run evenly (the centre of a run of two: a stripe edge); a weak but clear one leans
// to its sign, which a run of the certain bits alone would throw away.
std::optional<Placement> placeInRun(const Member& member, const AxisLayout& axis, int longest_run) {
  if (member.mixed || __builtin_popcount(member.uncertain) > kMaxUncertainBits) return std::nullopt;
  const CodeLikelihoods likely = codeLikelihoods(member, axis);
  const auto& codes = likely.codes;
  std::optional<Placement> best;
  std::size_t last = 0;
  double mass = 0.0;
  for (std::size_t first = 0; first < likely.size; ++first) {
    for (; last < likely.size && mass < kCredibleMass; ++last) mass += codes[last].second;
    if (mass < kCredibleMass) break;
    const unsigned run = codes[last - 1].first - codes[first].first + 1;
    if (run <= static_cast<unsigned>(longest_run) && (!best || run < best->run)) {
      double weighted = 0.0;
      for (std::size_t i = first; i < last; ++i) weighted += codes[i].first * codes[i].second;
      best = Placement{static_cast<float>(weighted / mass), run};
    }
    mass -= codes[first].second;
  }
  return best;
}

// Per pixel (row-major), the axis's position (NaN: not read) and the length of its run.
struct AxisReading {
  std::vector<float> position;
  std::vector<uint8_t> run;
};

AxisReading readAxis(const io::Capture& capture, const AxisLayout& axis, const Light& light, const DecodeParams& params,
                     int threads) {
  const int width = light.member.cols;
  const std::vector<int> direction =
      stripeDirections(capture, axis, light, segmentsOfEveryDirection(kSearchReach, width), threads);
  const std::vector<Segment> segments = segmentsOfEveryDirection(params.stripe_reach, width);
  std::vector<Member> members = membersAlong(light, direction, segments, params.stripe_reach, threads);
  readBits(capture, axis, light, params, threads, members);
  AxisReading reading{std::vector<float>(light.member.total(), std::numeric_limits<float>::quiet_NaN()),
                      std::vector<uint8_t>(light.member.total(), 0)};
#pragma omp parallel for num_threads(threads) schedule(static)
  for (const Member& member : members) {
    const std::optional<Placement> placed = placeInRun(member, axis, params.max_code_run_along_stripe);
    if (!placed) continue;
    const std::size_t pixel = static_cast<std::size_t>(member.y) * static_cast<std::size_t>(width) + member.x;
    reading.position[pixel] = placed->position;
    reading.run[pixel] = static_cast<uint8_t>(placed->run);
  }
  return reading;
}

}  // namespace

void readAlongStripes(const io::Capture& capture, const DecodePlan& plan, const DecodeParams& params, int threads,
                      DecodedCapture& decoded) {
  const CaptureLayout& layout = plan.layout;
  if (params.stripe_reach == 0 || layout.columns.hasPhase() || layout.rows.hasPhase()) return;
  if (!std::isfinite(plan.thresholds.noise_floor)) return;  // the capture's noise was not measured
  const Light light = lightOf(capture, plan, decoded);
  const AxisReading column = readAxis(capture, layout.columns, light, params, threads);
  AxisReading row;
  if (layout.rows.present) row = readAxis(capture, layout.rows, light, params, threads);
  decoded.stripe_run = cv::Mat::zeros(decoded.status.size(), CV_8UC1);
  for (std::size_t pixel = 0; pixel < column.position.size(); ++pixel) {
    if (std::isnan(column.position[pixel])) continue;
    const bool row_read = row.position.empty() || !std::isnan(row.position[pixel]);
    if (!row_read && !params.keep_column_without_row) continue;
    decoded.status.ptr<uint8_t>(0)[pixel] = static_cast<uint8_t>(PixelStatus::Valid);
    decoded.column.ptr<float>(0)[pixel] = column.position[pixel];
    if (!row.position.empty()) decoded.row.ptr<float>(0)[pixel] = row.position[pixel];
    decoded.stripe_run.ptr<uint8_t>(0)[pixel] =
        row.run.empty() ? column.run[pixel] : std::max(column.run[pixel], row.run[pixel]);
  }
}

}  // namespace binpick::reconstruction::detail
