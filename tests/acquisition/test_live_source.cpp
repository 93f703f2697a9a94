// The live source: opens the camera on demand, captures, and after a lost camera reopens it with
// a doubling backoff; a camera that will not open is reported and tried again on the next call.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "backoff.hpp"
#include "binpick/acquisition/capture_source.hpp"
#include "fake_camera.hpp"
#include "rendered_pile.hpp"

namespace binpick::acquisition {
namespace {

using std::chrono::milliseconds;
using testing::FakeRigState;
using testing::identical;
using testing::renderedPile;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Backoffs of a millisecond or two, so that the tests wait them out with a short sleep.
LiveParams fastParams() {
  LiveParams params;
  params.patterns = renderedPile().patterns;
  params.sequencer.settle_us = 0;
  params.reopen_backoff_ms = 1;
  params.max_reopen_backoff_ms = 2;
  return params;
}

struct Live {
  std::shared_ptr<FakeRigState> state = std::make_shared<FakeRigState>();
  std::unique_ptr<CaptureSource> source;

  explicit Live(const LiveParams& params = fastParams()) {
    state->images = renderedPile().images;
    source = makeLiveSource(std::make_unique<testing::FakeCamera>(state),
                            std::make_unique<testing::FakeProjector>(state), params);
  }
};

// After a failure the source refuses at once until its backoff has passed (at most
// max_reopen_backoff_ms of fastParams).
void waitOutTheBackoff() { std::this_thread::sleep_for(milliseconds(3)); }

// The error of next(), and whether it said the connection is lost.
std::string nextError(CaptureSource& source, bool* connection_lost = nullptr) {
  waitOutTheBackoff();
  try {
    source.next();
  } catch (const CaptureError& e) {
    if (connection_lost != nullptr) *connection_lost = e.connectionLost();
    return e.what();
  } catch (const core::Error& e) {
    return e.what();
  }
  return "";
}

bool matchesRendered(const io::Capture& capture) {
  if (capture.images.size() != renderedPile().images.size()) return false;
  for (std::size_t i = 0; i < capture.images.size(); ++i) {
    if (!identical(capture.images[i], renderedPile().images[i])) return false;
  }
  return true;
}

TEST(LiveSource, OpensTheCameraOnceOnDemand) {
  Live live;
  EXPECT_EQ(live.state->opens, 0);  // nothing touched before the first capture
  EXPECT_TRUE(matchesRendered(live.source->next()));
  EXPECT_TRUE(matchesRendered(live.source->next()));
  EXPECT_EQ(live.state->opens, 1);
  EXPECT_TRUE(live.state->started);
  EXPECT_TRUE(contains(live.source->description(), "Fake Vision FV-1 FAKE-0001"));
  live.source.reset();
  EXPECT_FALSE(live.state->open);  // closed with the source
}

TEST(LiveSource, ReopensTheCameraAfterALostConnection) {
  Live live;
  const std::size_t patterns = renderedPile().images.size();
  live.state->lose_connection_at = patterns + 7;  // during the second capture
  ASSERT_TRUE(matchesRendered(live.source->next()));
  bool lost = false;
  const std::string error = nextError(*live.source, &lost);
  EXPECT_TRUE(lost) << error;
  EXPECT_TRUE(contains(error, "pattern 7 (")) << error;
  EXPECT_FALSE(live.state->open);  // closed at once, reopened by the next call
  waitOutTheBackoff();
  EXPECT_TRUE(matchesRendered(live.source->next()));
  EXPECT_EQ(live.state->opens, 2);
}

TEST(LiveSource, WithinTheBackoffACaptureFailsAtOnceWithoutTryingTheCamera) {
  LiveParams params = fastParams();
  params.reopen_backoff_ms = 60000;  // a camera gone for a while: the next try is a minute away
  params.max_reopen_backoff_ms = 60000;
  Live live(params);
  live.state->failing_opens = 1;
  const std::string first = nextError(*live.source);
  EXPECT_TRUE(contains(first, "did not open (attempt 1")) << first;
  bool lost = false;
  const std::string second = nextError(*live.source, &lost);
  EXPECT_TRUE(contains(second, "the next attempt to reopen it is in")) << second;
  EXPECT_TRUE(lost);
  EXPECT_EQ(live.state->open_attempts, 1);  // not tried again, and not waited for either
}

TEST(LiveSource, ACameraThatWillNotOpenIsNamedAndTriedAgain) {
  Live live;
  live.state->failing_opens = 2;
  bool lost = false;
  const std::string first = nextError(*live.source, &lost);
  EXPECT_TRUE(contains(first, "fake camera 'FAKE-0001': not found")) << first;
  EXPECT_TRUE(contains(first, "did not open (attempt 1")) << first;
  EXPECT_TRUE(lost);
  const std::string second = nextError(*live.source);
  EXPECT_TRUE(contains(second, "did not open (attempt 2")) << second;
  waitOutTheBackoff();
  EXPECT_TRUE(matchesRendered(live.source->next()));
  EXPECT_EQ(live.state->open_attempts, 3);
  EXPECT_EQ(live.state->opens, 1);
}

TEST(LiveSource, ALostCameraThatComesBackLaterIsReopened) {
  Live live;
  live.state->lose_connection_at = 3;
  bool lost = false;
  nextError(*live.source, &lost);
  ASSERT_TRUE(lost);
  live.state->failing_opens = 3;  // still unplugged for three attempts
  for (int attempt = 1; attempt <= 3; ++attempt) {
    const std::string error = nextError(*live.source);
    EXPECT_TRUE(contains(error, "did not open (attempt " + std::to_string(attempt))) << error;
  }
  waitOutTheBackoff();
  EXPECT_TRUE(matchesRendered(live.source->next()));
  EXPECT_EQ(live.state->open_attempts, 5);
}

TEST(LiveSource, AFrameLostForGoodKeepsTheCameraStreaming) {
  Live live;
  live.state->failing_pattern = 12;
  bool lost = true;
  const std::string error = nextError(*live.source, &lost);
  EXPECT_TRUE(contains(error, "pattern 12 (gray_col_05)")) << error;
  EXPECT_FALSE(lost);
  EXPECT_TRUE(live.state->open);
  live.state->failing_pattern = -1;
  EXPECT_TRUE(matchesRendered(live.source->next()));
  EXPECT_EQ(live.state->opens, 1);
}

TEST(LiveSource, ParamsAreCheckedNamingTheField) {
  auto error = [](const LiveParams& params) {
    try {
      Live live(params);
    } catch (const core::Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  LiveParams backoff = fastParams();
  backoff.reopen_backoff_ms = 0;
  EXPECT_TRUE(contains(error(backoff), "live params.reopen_backoff_ms")) << error(backoff);
  LiveParams max_backoff = fastParams();
  max_backoff.max_reopen_backoff_ms = 0;
  EXPECT_TRUE(contains(error(max_backoff), "live params.max_reopen_backoff_ms")) << error(max_backoff);
  LiveParams sequencer = fastParams();
  sequencer.sequencer.frame_timeout_ms = -5;
  EXPECT_TRUE(contains(error(sequencer), "sequencer params.frame_timeout_ms")) << error(sequencer);
  EXPECT_THROW(makeLiveSource(nullptr, makeFreeRunningProjector(), fastParams()), core::Error);
}

TEST(Backoff, DoublesUpToTheMaximumAndStartsOverAfterASuccess) {
  Backoff backoff(milliseconds(500), milliseconds(8000));
  const Backoff::Clock::time_point t0{};
  EXPECT_EQ(backoff.delay(), milliseconds(0));
  EXPECT_EQ(backoff.wait(t0), Backoff::Clock::duration::zero());
  backoff.failed(t0);
  EXPECT_EQ(backoff.delay(), milliseconds(500));
  EXPECT_EQ(backoff.wait(t0 + milliseconds(200)), milliseconds(300));
  EXPECT_EQ(backoff.wait(t0 + milliseconds(600)), Backoff::Clock::duration::zero());
  std::string delays;
  for (int i = 0; i < 6; ++i) {
    backoff.failed(t0);
    delays += std::to_string(backoff.delay().count()) + " ";
  }
  EXPECT_EQ(delays, "1000 2000 4000 8000 8000 8000 ");
  backoff.succeeded();
  EXPECT_EQ(backoff.delay(), milliseconds(0));
  EXPECT_EQ(backoff.wait(t0), Backoff::Clock::duration::zero());
}

TEST(Backoff, RefusesNonsense) {
  EXPECT_THROW(Backoff(milliseconds(0), milliseconds(10)), core::Error);
  EXPECT_THROW(Backoff(milliseconds(10), milliseconds(5)), core::Error);
}

}  // namespace
}  // namespace binpick::acquisition
