// Byte streams: however they are split, the same messages come out; random bytes are errors,
// never crashes or exceptions; the decoders hold no more than one incomplete message.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::robot {
namespace {

struct Summary {
  bool ok;
  Status error;
  Command command;
  Command requested;
  std::optional<std::string> argument;
  std::optional<Eigen::Vector3d> position;  // POSE's
  bool operator==(const Summary& other) const {
    return ok == other.ok && error == other.error && command == other.command && requested == other.requested &&
           argument == other.argument && position == other.position;
  }
};

Summary summarise(const Decoded& decoded) {
  std::optional<Eigen::Vector3d> position;
  if (decoded.request && decoded.request->T_base_flange) {
    position = decoded.request->T_base_flange->translation();
  }
  return {decoded.request.has_value(),
          decoded.error,
          decoded.command,
          decoded.request ? decoded.request->command : Command::Ping,
          decoded.request ? decoded.request->argument : std::nullopt,
          position};
}

// Feeds `bytes` in pieces of the given sizes (the rest in one), collecting every message.
std::vector<Summary> decodeInPieces(const std::string& bytes, const CodecParams& params,
                                    const std::vector<std::size_t>& pieces) {
  RequestDecoder decoder(params);
  std::vector<Summary> all;
  std::size_t start = 0;
  auto drain = [&] {
    while (std::optional<Decoded> decoded = decoder.next()) all.push_back(summarise(*decoded));
  };
  for (std::size_t piece : pieces) {
    piece = std::min(piece, bytes.size() - start);
    decoder.feed(bytes.data() + start, piece);
    start += piece;
    EXPECT_LE(decoder.buffered(),
              params.framing == Framing::Ascii ? params.max_line_length : kMaxBinaryRequestSize - 1);
    drain();
  }
  decoder.feed(bytes.data() + start, bytes.size() - start);
  drain();
  return all;
}

std::vector<Summary> decodeByteByByte(const std::string& bytes, const CodecParams& params) {
  return decodeInPieces(bytes, params, std::vector<std::size_t>(bytes.size(), 1));
}

TEST(ProtocolStreams, AsciiSplitByteByByteDecodesAsInOnePiece) {
  const std::string stream = "PING\r\nstatus\n\r\nTRIGGER,bolt\r\nFOO\r\nMODEL\r\n" + std::string(300, 'x') +
                             "\r\nNEXT\r\nFAILED,0012\r\nPI" + std::string(1, '\0') + "NG\r\n" + std::string(80, ' ') +
                             "\nPOSE,1,2,3,1,0,0,0\r\n" + "POSE,1,2\r\nNEXT";
  const CodecParams params;
  const std::vector<Summary> whole = decodeInPieces(stream, params, {});
  ASSERT_EQ(whole.size(), 12u);  // the last NEXT has no end yet
  EXPECT_TRUE(whole[10].position);
  EXPECT_EQ(whole[11].error, Status::BadMessage);
  EXPECT_EQ(decodeByteByByte(stream, params), whole);
  std::mt19937 random(51);
  for (int i = 0; i < 200; ++i) {
    std::vector<std::size_t> pieces;
    for (int k = 0; k < 10; ++k) pieces.push_back(random() % 100);
    ASSERT_EQ(decodeInPieces(stream, params, pieces), whole);
  }
}

TEST(ProtocolStreams, BinarySplitByteByByteDecodesAsInOnePiece) {
  CodecParams params;
  params.framing = Framing::Binary;
  Eigen::Isometry3d flange = Eigen::Isometry3d::Identity();
  flange.translation() = Eigen::Vector3d(0.6, 0.0, 0.4);
  const std::vector<Request> requests = {{Command::Ping, std::nullopt},
                                         {Command::Trigger, "7"},
                                         {Command::Pose, std::nullopt, flange},
                                         {Command::SelectModel, "7"},
                                         {Command::Pose, std::nullopt, flange.inverse()},
                                         {Command::PickFailed, "7"}};
  std::string stream;
  for (const Request& request : requests) stream += encodeRequest(request, params);
  stream += std::string("\0\0\0\x63\0\0\0\0", 8) + "abc";
  const std::vector<Summary> whole = decodeInPieces(stream, params, {});
  ASSERT_EQ(whole.size(), 7u);
  EXPECT_EQ(whole[2].requested, Command::Pose);
  EXPECT_EQ(whole[5].requested, Command::PickFailed);
  EXPECT_EQ(whole[6].error, Status::UnknownCommand);
  EXPECT_EQ(decodeByteByByte(stream, params), whole);
  RequestDecoder decoder(params);
  decoder.feed(stream.data(), stream.size());
  EXPECT_EQ(decoder.buffered(), 3u);
}

TEST(ProtocolStreams, RandomBytesAreErrorsNotCrashes) {
  std::mt19937 random(52);
  for (Framing framing : {Framing::Ascii, Framing::Binary}) {
    CodecParams params;
    params.framing = framing;
    for (int i = 0; i < 300; ++i) {
      std::string bytes(random() % 400, '\0');
      for (char& c : bytes) c = static_cast<char>(random() % 4 == 0 ? '\n' : random());
      std::vector<Summary> all;
      ASSERT_NO_THROW(all = decodeInPieces(bytes, params, {random() % 50, random() % 50}));
      for (const Summary& message : all) EXPECT_EQ(message.ok, message.error == Status::Ok);
      ReplyDecoder replies(params);
      replies.feed(bytes.data(), bytes.size());
      for (int k = 0; k < 200; ++k) {
        try {
          if (!replies.next()) break;
        } catch (const core::Error&) {
          // Malformed: expected for random bytes. Anything else would fail the test.
        }
      }
    }
  }
}

// An endless line holds no more than the limit, and counts as one BadMessage.
TEST(ProtocolStreams, AnEndlessLineIsOneBadMessageAndKeepsNoBytes) {
  RequestDecoder decoder(CodecParams{});
  const std::string chunk(1000, 'A');
  for (int i = 0; i < 100; ++i) decoder.feed(chunk.data(), chunk.size());
  EXPECT_EQ(decoder.buffered(), 0u);
  ASSERT_EQ(decoder.next()->error, Status::BadMessage);
  EXPECT_FALSE(decoder.next());
  decoder.feed("\nPING\n", 6);
  EXPECT_EQ(decoder.next()->request->command, Command::Ping);
}

}  // namespace
}  // namespace binpick::robot
