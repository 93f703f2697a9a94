// Fuzz target for the robot protocol: whatever bytes a robot (or anything else on the port)
// sends, the decoders must neither crash nor throw, and every reply the service writes back must
// respect the framing. Built two ways: with libFuzzer (fuzz/run-libfuzzer.sh) and with the seeded
// driver fuzz/random_input_driver.cpp (test protocol_fuzz_smoke). A broken invariant aborts.
//
// The first input byte picks the codec parameters (paramsFor), the rest is the stream.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/robot/protocol.hpp"

namespace {

using namespace binpick::robot;
namespace core = binpick::core;

// The bytes in C escapes, for the report.
std::string escaped(const std::string& bytes) {
  std::string text;
  char hex[8];
  for (unsigned char c : bytes) {
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      text += static_cast<char>(c);
    } else {
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      text += hex;
    }
  }
  return text;
}

void require(bool ok, const char* invariant, const std::string& bytes = "") {
  if (ok) return;
  std::fprintf(stderr, "robot protocol invariant violated: %s\n", invariant);
  if (!bytes.empty()) std::fprintf(stderr, "  bytes: \"%s\"\n", escaped(bytes).c_str());
  std::abort();
}

CodecParams paramsFor(uint8_t selector, Framing framing) {
  constexpr core::Orientation kOrientations[] = {core::Orientation::Quaternion, core::Orientation::EulerZYX,
                                                 core::Orientation::FixedXYZ, core::Orientation::RotationVector,
                                                 core::Orientation::EulerXYZ};
  constexpr std::size_t kLineLengths[] = {80, 16, 200};
  CodecParams params;
  params.framing = framing;
  params.orientation = kOrientations[selector % 5];
  params.byte_order = (selector / 5) % 2 == 0 ? ByteOrder::Big : ByteOrder::Little;
  params.max_line_length = kLineLengths[(selector / 10) % 3];
  if ((selector / 30) % 2 == 1) {  // finer than the defaults: longer lines, earlier overflows
    params.position_decimals = 4;
    params.orientation_decimals = 7;
    params.position_scale = 1000.0;
    params.orientation_scale = 1e6;
  }
  return params;
}

// Everything `stream` decodes to, fed in the pieces that `cuts` (ascending offsets) make.
std::vector<Decoded> decodeRequests(const std::string& stream, const CodecParams& params,
                                    const std::vector<std::size_t>& cuts) {
  RequestDecoder decoder(params);
  std::vector<Decoded> all;
  std::size_t start = 0;
  for (std::size_t cut : cuts) {
    cut = std::max(start, std::min(cut, stream.size()));
    decoder.feed(stream.data() + start, cut - start);
    start = cut;
    require(decoder.buffered() <= std::max(params.max_line_length, kMaxBinaryRequestSize - 1),
            "a request decoder holds at most one incomplete message");
    while (std::optional<Decoded> decoded = decoder.next()) all.push_back(std::move(*decoded));
  }
  return all;
}

bool sameDecoded(const Decoded& a, const Decoded& b) {
  if (a.error != b.error || a.command != b.command || a.request.has_value() != b.request.has_value()) {
    return false;
  }
  if (!a.request) return true;
  const std::optional<Eigen::Isometry3d>& pa = a.request->T_base_flange;
  const std::optional<Eigen::Isometry3d>& pb = b.request->T_base_flange;
  return a.request->command == b.request->command && a.request->argument == b.request->argument &&
         pa.has_value() == pb.has_value() && (!pa || pa->matrix() == pb->matrix());
}

// A deterministic stand-in for the service's answer to `decoded`, drawn from `seed`.
Reply replyFor(const Decoded& decoded, uint64_t seed) {
  if (!decoded.request) return Reply{decoded.command, decoded.error};
  Reply reply{decoded.command, static_cast<Status>(seed % 15)};
  for (std::size_t i = 0; i < (seed >> 4) % 4; ++i) {  // small and large, of either sign
    const auto bits = static_cast<int32_t>(static_cast<uint32_t>(seed >> (8 * i)));
    reply.integers.push_back(bits / (int32_t{1} << (seed % 24)));
  }
  if (reply.command == Command::NextPick && reply.status == Status::Ok) {
    // Positions from 1 mm to 8 km, to reach the precision drops and the fallbacks. Rotations
    // through the library's own conversion: Eigen's would double the harness's build time.
    const double reach = static_cast<double>(1ull << ((seed >> 8) % 24)) * 1e-3;
    std::vector<double> random;
    for (int k = 0; k < 4; ++k) random.push_back(double((seed >> (10 * k)) % 1000) / 500.0 - 1.0);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(random[0], random[1], random[2]) * reach;
    random[1] += 0.01;  // never the zero quaternion
    T.linear() = core::rotationFromValues(random, core::Orientation::Quaternion);
    reply.T_base_tool = T;
  }
  return reply;
}

void checkReplyBytes(const std::string& bytes, const CodecParams& params) {
  if (params.framing == Framing::Binary) {
    require(bytes.size() == kBinaryReplySize, "a binary reply is kBinaryReplySize bytes", bytes);
    return;
  }
  require(bytes.size() <= params.max_line_length, "an ASCII reply fits max_line_length", bytes);
  require(bytes.size() >= 2 && bytes.compare(bytes.size() - 2, 2, "\r\n") == 0, "an ASCII reply ends with CRLF", bytes);
  require(bytes.find_first_of("\r\n") == bytes.size() - 2, "an ASCII reply is one line", bytes);
}

// The reply the robot reads back is the one sent, or its BadMessage stand-in.
void checkReplyReadsBack(const Reply& sent, const std::string& bytes, const CodecParams& params) {
  ReplyDecoder decoder(params);
  decoder.feed(bytes.data(), bytes.size());
  std::optional<Reply> read;
  try {
    read = decoder.next();
  } catch (const binpick::core::Error& error) {
    std::fprintf(stderr, "%s\n", error.what());
    require(false, "every encoded reply decodes", bytes);
  }
  require(read.has_value() && !decoder.next(), "an encoded reply is exactly one message", bytes);
  require(read->command == sent.command, "a reply keeps its command", bytes);
  std::vector<int32_t> integers = sent.integers;
  if (params.framing == Framing::Binary) integers.resize(kMaxReplyIntegers, 0);
  const bool stoodIn = read->status == Status::BadMessage && !read->T_base_tool &&
                       (read->integers.empty() || read->integers == std::vector<int32_t>(3, 0));
  require(read->status == sent.status || stoodIn, "only BadMessage replaces a status", bytes);
  require(read->integers == integers || stoodIn, "a reply keeps its integers", bytes);
  if (read->status != sent.status) return;
  if (sent.T_base_tool) {
    const Eigen::Isometry3d& T = *sent.T_base_tool;
    require(read->T_base_tool.has_value(), "a pick keeps its pose", bytes);
    // At worst one position decimal dropped: 0.05 mm per axis.
    const double millimetres = (read->T_base_tool->translation() - T.translation()).norm() * 1e3;
    require(millimetres <= 0.087 + 1e-12 * T.translation().norm() * 1e3, "a pick's position survives", bytes);
    const std::vector<double> turn = core::orientationValues(read->T_base_tool->linear().transpose() * T.linear(),
                                                             core::Orientation::RotationVector);
    const double radians = Eigen::Vector3d(turn[0], turn[1], turn[2]).norm();
    require(radians <= 0.004, "a pick's orientation survives", bytes);
  }
}

// A POSE read back from its encoding is the pose sent, at the codec's resolution: positions
// within half a unit per axis (relative double precision for huge ones), rotations within
// 0.02 degrees (binary quaternions at 1e-4 reach 0.01).
void checkPoseReadsBack(const Eigen::Isometry3d& sent, const Eigen::Isometry3d& read, const std::string& bytes) {
  const double millimetres = (read.translation() - sent.translation()).norm() * 1e3;
  require(millimetres <= 0.0087 + 1e-12 * sent.translation().norm() * 1e3, "a POSE's position survives encoding",
          bytes);
  const std::vector<double> turn =
      core::orientationValues(read.linear().transpose() * sent.linear(), core::Orientation::RotationVector);
  require(Eigen::Vector3d(turn[0], turn[1], turn[2]).norm() <= 3.5e-4, "a POSE's orientation survives encoding", bytes);
}

void checkRequestRoundTrip(const Request& request, const CodecParams& params) {
  std::string bytes;
  try {
    bytes = encodeRequest(request, params);
  } catch (const binpick::core::Error& error) {
    // A line that arrived with a bare "\n" may be one too long to send back with "\r\n"; a POSE
    // typed with fewer digits than the codec writes may be longer at its precision.
    const std::string message = error.what();
    const bool tooLong =
        message.find("max_line_length") != std::string::npos || message.find("too far out") != std::string::npos;
    const std::size_t longestRequest = std::string("TRIGGER,\r\n").size() + 32;
    require(tooLong && params.framing == Framing::Ascii &&
                (request.command == Command::Pose || params.max_line_length < longestRequest),
            "a decoded request encodes");
    return;
  }
  const std::vector<Decoded> back = decodeRequests(bytes, params, {bytes.size()});
  require(back.size() == 1 && back[0].request && back[0].request->command == request.command &&
              back[0].request->argument == request.argument &&
              back[0].request->T_base_flange.has_value() == request.T_base_flange.has_value(),
          "a decoded request round-trips through encodeRequest", bytes);
  if (request.T_base_flange) {
    checkPoseReadsBack(*request.T_base_flange, *back[0].request->T_base_flange, bytes);
  }
}

// Round trips and replies for the first messages of an input only: a binary stream holds a
// request every 8 bytes (POSE: 32), and checking them all would slow the fuzzer down more than it
// finds.
constexpr std::size_t kMessagesCheckedInDepth = 8;

void fuzzRequests(const std::string& stream, const CodecParams& params, uint64_t seed) {
  const std::vector<Decoded> whole = decodeRequests(stream, params, {stream.size()});
  const std::vector<Decoded> pieces = decodeRequests(
      stream, params, {seed % 7, stream.size() / 3, stream.size() / 2 + seed % 5, stream.size() - 1, stream.size()});
  require(whole.size() == pieces.size(), "splitting a stream keeps its messages");
  for (std::size_t i = 0; i < whole.size(); ++i) {
    const Decoded& decoded = whole[i];
    require(sameDecoded(decoded, pieces[i]), "splitting a stream keeps its messages");
    require(decoded.request.has_value() == (decoded.error == Status::Ok), "request xor error");
    require(
        decoded.error == Status::Ok || decoded.error == Status::BadMessage || decoded.error == Status::UnknownCommand,
        "a decoder reports only BadMessage or UnknownCommand");
    if (i >= kMessagesCheckedInDepth) continue;
    if (decoded.request) checkRequestRoundTrip(*decoded.request, params);
    const Reply reply = replyFor(decoded, seed * 6364136223846793005ull + i);
    const std::string bytes = encodeReply(reply, params);
    checkReplyBytes(bytes, params);
    checkReplyReadsBack(reply, bytes, params);
  }
}

// Malformed replies throw, and throwing is slow: the first few messages of an input (including
// what follows a malformed one) exercise the decoder as well as all of them would.
constexpr int kRepliesPerInput = 8;

void fuzzReplies(const std::string& stream, const CodecParams& params) {
  ReplyDecoder decoder(params);
  decoder.feed(stream.data(), stream.size());
  for (int i = 0; i < kRepliesPerInput; ++i) {
    try {
      if (!decoder.next()) return;
    } catch (const binpick::core::Error&) {
      // Malformed: the expected outcome for most inputs.
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string stream(reinterpret_cast<const char*>(data) + 1, size - 1);
  uint64_t seed = 1469598103934665603ull;  // FNV-1a: replies vary with the input, reproducibly
  for (std::size_t i = 0; i < size; ++i) seed = (seed ^ data[i]) * 1099511628211ull;
  for (Framing framing : {Framing::Ascii, Framing::Binary}) {
    const CodecParams params = paramsFor(data[0], framing);
    fuzzRequests(stream, params, seed);
    fuzzReplies(stream, params);
  }
  return 0;
}
