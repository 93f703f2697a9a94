// ASCII requests: what each line decodes to, and which lines are refused and how.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "binpick/core/error.hpp"
#include "binpick/robot/protocol.hpp"

namespace binpick::robot {
namespace {

std::vector<Decoded> decodeAll(const std::string& bytes, const CodecParams& params = {}) {
  RequestDecoder decoder(params);
  decoder.feed(bytes.data(), bytes.size());
  std::vector<Decoded> all;
  while (std::optional<Decoded> decoded = decoder.next()) all.push_back(*decoded);
  return all;
}

// The one message of `bytes`.
Decoded decodeOne(const std::string& bytes) {
  const std::vector<Decoded> all = decodeAll(bytes);
  EXPECT_EQ(all.size(), 1u) << bytes;
  return all.empty() ? Decoded{} : all.front();
}

void expectRequest(const std::string& line, Command command,
                   const std::optional<std::string>& argument = std::nullopt) {
  const Decoded decoded = decodeOne(line);
  ASSERT_TRUE(decoded.request) << line << ": " << decoded.detail;
  EXPECT_EQ(decoded.error, Status::Ok);
  EXPECT_EQ(decoded.command, command);
  EXPECT_EQ(decoded.request->command, command);
  EXPECT_EQ(decoded.request->argument, argument) << line;
}

void expectRefused(const std::string& line, Status error, Command command) {
  const Decoded decoded = decodeOne(line);
  EXPECT_FALSE(decoded.request) << line;
  EXPECT_EQ(decoded.error, error) << line;
  EXPECT_EQ(decoded.command, command) << line;
  EXPECT_FALSE(decoded.detail.empty());
}

TEST(ProtocolAsciiRequest, EveryCommandDecodes) {
  expectRequest("PING\r\n", Command::Ping);
  expectRequest("STATUS\n", Command::Status);
  expectRequest("TRIGGER\r\n", Command::Trigger);
  expectRequest("TRIGGER,bolt_m8\r\n", Command::Trigger, "bolt_m8");
  expectRequest("NEXT\r\n", Command::NextPick);
  expectRequest("FAILED\r\n", Command::PickFailed);
  expectRequest("FAILED,12\r\n", Command::PickFailed, "12");
  expectRequest("MODEL,2\r\n", Command::SelectModel, "2");
  expectRequest("MODEL,Flange-A\r\n", Command::SelectModel, "Flange-A");
}

TEST(ProtocolAsciiRequest, KeywordsIgnoreCaseAndSpacesAroundFieldsAreTrimmed) {
  expectRequest("ping\n", Command::Ping);
  expectRequest("  Next  \r\n", Command::NextPick);
  expectRequest(" model , Bolt \r\n", Command::SelectModel, "Bolt");  // argument keeps its case
}

TEST(ProtocolAsciiRequest, FailedTakesAnObjectIdWithoutLeadingZeros) {
  expectRequest("FAILED,007\r\n", Command::PickFailed, "7");
  expectRequest("FAILED,2147483647\r\n", Command::PickFailed, "2147483647");
  expectRefused("FAILED,2147483648\r\n", Status::BadMessage, Command::PickFailed);
  expectRefused("FAILED,-1\r\n", Status::BadMessage, Command::PickFailed);
  expectRefused("FAILED,+1\r\n", Status::BadMessage, Command::PickFailed);
  expectRefused("FAILED,a\r\n", Status::BadMessage, Command::PickFailed);
}

TEST(ProtocolAsciiRequest, BlankLinesAreIgnored) {
  const std::vector<Decoded> all = decodeAll("\r\n\n   \r\nPING\r\n\r\n");
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].request->command, Command::Ping);
}

TEST(ProtocolAsciiRequest, UnknownKeywordsAreUnknownCommands) {
  const Decoded decoded = decodeOne("FOO,1\r\n");
  EXPECT_EQ(decoded.error, Status::UnknownCommand);
  EXPECT_FALSE(isKnownCommand(decoded.command));
  EXPECT_EQ(std::string(commandKeyword(decoded.command)), "UNKNOWN");
  EXPECT_NE(decoded.detail.find("FOO"), std::string::npos);
  // What the server answers: the robot hears "UNKNOWN,7".
  EXPECT_EQ(encodeReply(Reply{decoded.command, decoded.error}, CodecParams{}), "UNKNOWN,7\r\n");
}

TEST(ProtocolAsciiRequest, BadArgumentsAreBadMessagesOfThatCommand) {
  expectRefused("MODEL\r\n", Status::BadMessage, Command::SelectModel);
  expectRefused("MODEL,\r\n", Status::BadMessage, Command::SelectModel);
  expectRefused("MODEL,a,b\r\n", Status::BadMessage, Command::SelectModel);
  expectRefused("TRIGGER,,\r\n", Status::BadMessage, Command::Trigger);
  expectRefused("PING,1\r\n", Status::BadMessage, Command::Ping);
  expectRefused("NEXT,1\r\n", Status::BadMessage, Command::NextPick);
  expectRefused("MODEL,two words\r\n", Status::BadMessage, Command::SelectModel);
  expectRequest("MODEL," + std::string(32, 'm') + "\r\n", Command::SelectModel, std::string(32, 'm'));
  expectRefused("MODEL," + std::string(33, 'm') + "\r\n", Status::BadMessage, Command::SelectModel);
  expectRefused(",PING\r\n", Status::BadMessage, Command::Unreadable);
}

TEST(ProtocolAsciiRequest, ControlAndNonAsciiBytesAreBadMessages) {
  expectRefused(std::string("PI\0NG\r\n", 7), Status::BadMessage, Command::Unreadable);
  expectRefused("PING\t\r\n", Status::BadMessage, Command::Ping);
  expectRefused("PING\r\r\n", Status::BadMessage, Command::Ping);
  expectRefused("TRIGGER,b\x7f\r\n", Status::BadMessage, Command::Trigger);
  expectRefused("MODEL,\xc3\xa4\r\n", Status::BadMessage, Command::SelectModel);
  expectRefused("\xff\xfe\r\n", Status::BadMessage, Command::Unreadable);
}

// The reply to what the server decodes from `line`.
std::string answerTo(const std::string& line) {
  const Decoded decoded = decodeOne(line);
  EXPECT_FALSE(decoded.request) << line;
  return encodeReply(Reply{decoded.command, decoded.error}, CodecParams{});
}

// A robot matching replies to requests must never read a reply naming a command it did not send.
TEST(ProtocolAsciiRequest, LinesWithoutAReadableKeywordAreAnsweredError) {
  EXPECT_EQ(answerTo(",,,\r\n"), "ERROR,8\r\n");
  EXPECT_EQ(answerTo("\x01\x02\r\n"), "ERROR,8\r\n");
  EXPECT_EQ(answerTo(std::string("\0\r\n", 3)), "ERROR,8\r\n");
  EXPECT_EQ(answerTo(std::string("NE\0XT\r\n", 7)), "ERROR,8\r\n");
  EXPECT_EQ(answerTo(std::string("HELLO\0\r\n", 8)), "ERROR,8\r\n");   // cut short: no keyword read
  EXPECT_EQ(answerTo(std::string(100, 'A') + "\r\n"), "ERROR,8\r\n");  // over the line limit
  EXPECT_EQ(answerTo("HELLO," + std::string(100, 'A') + "\r\n"), "ERROR,8\r\n");
  // A known keyword ended by a garbage byte was that command, garbled: it keeps its keyword.
  EXPECT_EQ(answerTo(std::string("NEXT\0\r\n", 7)), "NEXT,8\r\n");
  EXPECT_EQ(answerTo("TRIGGER\xff\r\n"), "TRIGGER,8\r\n");
  EXPECT_EQ(answerTo(" next \x01 \r\n"), "NEXT,8\r\n");
  EXPECT_EQ(answerTo("NEXT\x01" + std::string(100, 'A') + "\r\n"), "NEXT,8\r\n");  // over the limit
  // A readable keyword naming no command stays an unknown command.
  EXPECT_EQ(answerTo("HELLO\r\n"), "UNKNOWN,7\r\n");
  EXPECT_EQ(answerTo("HELLO,\x01\r\n"), "UNKNOWN,7\r\n");
}

TEST(ProtocolAsciiRequest, ErrorIsAReplyNeverARequest) {
  EXPECT_FALSE(isKnownCommand(Command::Unreadable));
  EXPECT_EQ(std::string(commandKeyword(Command::Unreadable)), "ERROR");
  EXPECT_EQ(decodeOne("ERROR\r\n").error, Status::UnknownCommand);
  EXPECT_THROW(encodeRequest(Request{Command::Unreadable, std::nullopt}, CodecParams{}), core::Error);
  EXPECT_THROW(encodeReply(Reply{Command::Unreadable, Status::Ok}, CodecParams{}), core::Error);
}

// 80 characters including "\r\n" or "\n" pass; 81 are one BadMessage, then the next line counts.
TEST(ProtocolAsciiRequest, LinesLongerThanTheLimitAreOneBadMessage) {
  expectRequest("PING" + std::string(74, ' ') + "\r\n", Command::Ping);
  expectRequest("PING" + std::string(75, ' ') + "\n", Command::Ping);
  // The keyword counts when its end (a comma, a control byte such as '\r') came within the limit.
  expectRefused("PING" + std::string(75, ' ') + "\r\n", Status::BadMessage, Command::Ping);
  expectRefused("PING" + std::string(76, ' ') + "\n", Status::BadMessage, Command::Unreadable);
  const std::vector<Decoded> all = decodeAll("TRIGGER," + std::string(5000, 'x') + "\r\nNEXT\r\n");
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].error, Status::BadMessage);
  EXPECT_EQ(all[0].command, Command::Trigger);  // its comma came within the limit
  EXPECT_EQ(all[1].request->command, Command::NextPick);
}

TEST(ProtocolAsciiRequest, TheLimitFollowsMaxLineLength) {
  CodecParams params;
  params.max_line_length = 16;
  EXPECT_EQ(decodeAll("TRIGGER,12345\r\n", params).at(0).error, Status::Ok);   // 15
  EXPECT_EQ(decodeAll("TRIGGER,123456\r\n", params).at(0).error, Status::Ok);  // 16
  EXPECT_EQ(decodeAll("TRIGGER,1234567\r\n", params).at(0).error, Status::BadMessage);
}

TEST(ProtocolAsciiRequest, EncodedRequestsAreTheExpectedLinesAndDecodeBack) {
  const CodecParams params;
  EXPECT_EQ(encodeRequest(Request{Command::Ping, std::nullopt}, params), "PING\r\n");
  EXPECT_EQ(encodeRequest(Request{Command::Trigger, "bolt"}, params), "TRIGGER,bolt\r\n");
  EXPECT_EQ(encodeRequest(Request{Command::PickFailed, "3"}, params), "FAILED,3\r\n");
  const std::vector<Request> requests = {
      {Command::Ping, std::nullopt},     {Command::Status, std::nullopt},
      {Command::Trigger, std::nullopt},  {Command::Trigger, "gear_12"},
      {Command::NextPick, std::nullopt}, {Command::PickFailed, std::nullopt},
      {Command::PickFailed, "41"},       {Command::SelectModel, std::string(32, 'z')}};
  for (const Request& request : requests) {
    const Decoded decoded = decodeOne(encodeRequest(request, params));
    ASSERT_TRUE(decoded.request);
    EXPECT_EQ(decoded.request->command, request.command);
    EXPECT_EQ(decoded.request->argument, request.argument);
  }
}

}  // namespace
}  // namespace binpick::robot
