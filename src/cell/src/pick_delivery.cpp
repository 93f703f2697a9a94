#include "pick_delivery.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>

#include "binpick/core/error.hpp"
#include "cell_replies.hpp"

namespace binpick::cell {
namespace {

constexpr double kMillimetresPerMetre = 1000.0;
constexpr int32_t kWidestId = 99;
constexpr std::size_t kLongestLineLength = 4096;  // CodecParams' upper bound

// Whether `reply` goes out as itself rather than as the encoder's bad_message stand-in.
bool encodes(const robot::Reply& reply, const robot::CodecParams& codec) {
  try {
    return robot::encodeReplyIfItFits(reply, codec).has_value();
  } catch (const core::Error&) {  // a pose the encoder refuses (not finite)
    return false;
  }
}

// Rotations whose values are wide in every convention: each Euler angle from a spread of
// magnitudes around the whole turn, negative ones included (a '-' is a character more).
std::vector<Eigen::Matrix3d> spreadOfRotations() {
  constexpr std::array<double, 6> kAnglesDeg = {-179.5, -120.5, -60.5, 60.5, 120.5, 179.5};
  std::vector<Eigen::Matrix3d> rotations;
  for (double a : kAnglesDeg) {
    for (double b : kAnglesDeg) {
      for (double c : kAnglesDeg) {
        const auto radians = [](double deg) { return deg * M_PI / 180.0; };
        rotations.push_back((Eigen::AngleAxisd(radians(a), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(radians(b), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(radians(c), Eigen::Vector3d::UnitX()))
                                .toRotationMatrix());
      }
    }
  }
  return rotations;
}

// NEXT replies as wide as the start-up check allows for.
std::vector<robot::Reply> widestPickReplies(int max_picks) {
  std::vector<robot::Reply> replies;
  for (const Eigen::Matrix3d& rotation : spreadOfRotations()) {
    picking::Pick pick;
    pick.object = kWidestId;
    pick.grasp = kWidestId;
    pick.T_base_grasp.linear() = rotation;
    pick.T_base_grasp.translation().setConstant(-kWidestPickCoordinateMm / kMillimetresPerMetre);
    replies.push_back(nextPickReply(pick, static_cast<std::size_t>(std::max(max_picks - 1, 0))));
  }
  return replies;
}

bool allEncode(const std::vector<robot::Reply>& replies, const robot::CodecParams& codec) {
  for (const robot::Reply& reply : replies) {
    if (!encodes(reply, codec)) return false;
  }
  return true;
}

// The shortest max_line_length that carries every reply (encoding only gets easier with a longer
// line), or nothing when even the longest allowed does not.
std::optional<std::size_t> shortestLineLength(const std::vector<robot::Reply>& replies, robot::CodecParams codec) {
  std::size_t too_short = codec.max_line_length, enough = kLongestLineLength;
  codec.max_line_length = enough;
  if (!allEncode(replies, codec)) return std::nullopt;
  while (enough - too_short > 1) {
    codec.max_line_length = (too_short + enough) / 2;
    (allEncode(replies, codec) ? enough : too_short) = codec.max_line_length;
  }
  return enough;
}

double largestOrientationValue(core::Orientation orientation) {
  double largest = 0.0;
  for (const Eigen::Matrix3d& rotation : spreadOfRotations()) {
    for (double value : core::orientationValues(rotation, orientation)) largest = std::max(largest, std::abs(value));
  }
  return largest;
}

std::string fixed(double value, int decimals) {
  std::ostringstream text;
  text.precision(decimals);
  text << std::fixed << value;
  return text.str();
}

void checkBinaryScales(const robot::CodecParams& codec) {
  const double position_limit = INT32_MAX / kWidestPickCoordinateMm;
  if (codec.position_scale > position_limit) {
    throw core::Error("robot.position_scale must be <= " + fixed(std::floor(position_limit), 0) +
                      " so that a coordinate of " + fixed(kWidestPickCoordinateMm, 2) +
                      " mm fits an int32 field (got " + fixed(codec.position_scale, 1) + ")");
  }
  const double largest = largestOrientationValue(codec.orientation);
  const double orientation_limit = INT32_MAX / largest;
  if (codec.orientation_scale > orientation_limit) {
    throw core::Error("robot.orientation_scale must be <= " + fixed(std::floor(orientation_limit), 0) + " so that " +
                      core::orientationName(codec.orientation) + " values up to " + fixed(largest, 5) +
                      " fit an int32 field (got " + fixed(codec.orientation_scale, 1) + ")");
  }
}

// Why `reply` (a NEXT with a pick) did not encode, for the log.
std::string whyNotEncodable(const robot::Reply& reply, const robot::CodecParams& codec) {
  if (!reply.T_base_tool->matrix().allFinite()) return "its pose is not finite";
  const Eigen::Vector3d mm = reply.T_base_tool->translation() * kMillimetresPerMetre;
  if (codec.framing == robot::Framing::Binary) {
    const double limit = INT32_MAX / codec.position_scale;
    if (mm.cwiseAbs().maxCoeff() > limit) {
      return "a coordinate of (" + fixed(mm.x(), 2) + ", " + fixed(mm.y(), 2) + ", " + fixed(mm.z(), 2) +
             ") mm is beyond the binary int32 range at robot.position_scale " + fixed(codec.position_scale, 1) +
             " (+-" + fixed(limit, 2) + " mm)";
    }
    return "an orientation value is beyond the binary int32 range at robot.orientation_scale " +
           fixed(codec.orientation_scale, 1);
  }
  robot::CodecParams unlimited = codec;
  unlimited.max_line_length = kLongestLineLength;
  const std::size_t length = robot::encodeReply(reply, unlimited).size();
  return "its NEXT reply takes " + std::to_string(length) + " characters at full precision, more than " +
         "robot.max_line_length (" + std::to_string(codec.max_line_length) + ") holds even with fewer decimals";
}

}  // namespace

void checkPickRepliesFit(const robot::CodecParams& codec, int max_picks) {
  if (codec.framing == robot::Framing::Binary) return checkBinaryScales(codec);
  const std::vector<robot::Reply> widest = widestPickReplies(max_picks);
  if (allEncode(widest, codec)) return;
  const std::optional<std::size_t> shortest = shortestLineLength(widest, codec);
  throw core::Error("robot.max_line_length must be >= " +
                    (shortest ? std::to_string(*shortest) : "more than " + std::to_string(kLongestLineLength)) +
                    " to carry a NEXT reply with a pick (" + core::orientationName(codec.orientation) +
                    ", coordinates up to +-" + fixed(kWidestPickCoordinateMm, 2) + " mm) (got " +
                    std::to_string(codec.max_line_length) + ")");
}

DeliverablePicks deliverablePicks(std::vector<picking::Pick> picks, const robot::CodecParams& codec) {
  DeliverablePicks result;
  for (std::size_t i = 0; i < picks.size(); ++i) {
    // The count of the picks remaining is at its largest when none is left out: if the reply fits
    // with it, it fits with any smaller count.
    const robot::Reply reply = nextPickReply(picks[i], picks.size() - i - 1);
    if (encodes(reply, codec)) {
      result.picks.push_back(std::move(picks[i]));
      continue;
    }
    result.problems.push_back("the pick of object " + std::to_string(picks[i].object) + " (grasp " +
                              std::to_string(picks[i].grasp) + ") cannot be sent: " + whyNotEncodable(reply, codec));
  }
  return result;
}

}  // namespace binpick::cell
