// The guided session's requests: answered on the server thread, views taken on the session's.
#include "hand_eye_guided_session.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "binpick/core/error.hpp"

namespace binpick::cli {
namespace {

using robot::Command;
using robot::Reply;
using robot::Status;
using Clock = std::chrono::steady_clock;

enum class SessionState : int32_t { Waiting = 0, TakingView = 1, Done = 2 };

}  // namespace

void GuidedSessionParams::validate() const {
  const std::string owner = "GuidedSessionParams";
  core::requireField(wanted >= 1, owner, "wanted", ">= 1 view", wanted);
  layout.validate();
  camera.validate("camera");
  check.validate();
  core::requireField(final_reply_grace.count() >= 0, owner, "final_reply_grace", ">= 0 ms", final_reply_grace.count());
}

HandEyeGuidedSession::HandEyeGuidedSession(const GuidedSessionParams& params, GuidedViewRecorder& recorder,
                                           ViewCamera& camera, GuidedReplySink sink)
    : params_(params), recorder_(recorder), camera_(camera), sink_(std::move(sink)) {
  params_.validate();
  accepted_ = recorder_.accepted();
  if (accepted_ >= params_.wanted) {  // an earlier session took them all: nobody waits
    completed_at_ = Clock::now();
    final_reply_read_ = true;
  }
  worker_ = std::thread([this] { work(); });
}

HandEyeGuidedSession::~HandEyeGuidedSession() { stop(); }

void HandEyeGuidedSession::handle(robot::ClientId client, const robot::Request& request) {
  std::optional<Reply> reply;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    // A robot is synchronous: a new request means it has read the reply to its last view.
    if (final_client_ == client) final_reply_read_ = true;
    switch (request.command) {
      case Command::Ping: reply = Reply{Command::Ping, Status::Ok}; break;
      case Command::Status: {
        SessionState state = SessionState::Waiting;
        if (taking_ || !jobs_.empty()) state = SessionState::TakingView;
        if (completed_at_) state = SessionState::Done;
        reply = Reply{Command::Status, Status::Ok, {static_cast<int32_t>(state), accepted_, params_.wanted}};
        break;
      }
      case Command::Pose:
        if (!request.T_base_flange) {  // the decoders never hand one over; a caller might
          reply = Reply{Command::Pose, Status::BadMessage};
        } else if (completed_at_ || stopping_) {
          spdlog::info("POSE from client {} not recorded: the session has its {} views", client, params_.wanted);
          reply = poseReply(Status::Busy);
        } else {
          jobs_.push_back({client, *request.T_base_flange});
          wakeup_.notify_one();
        }
        break;
      default: reply = Reply{request.command, Status::UnknownCommand};
    }
  }
  if (reply) sink_(client, *reply);
}

void HandEyeGuidedSession::disconnected(robot::ClientId client) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (final_client_ == client) final_reply_read_ = true;
  // Nobody waits for these any more, and the robot may be moving already: its pose is stale.
  const auto waiting = jobs_.size();
  jobs_.erase(std::remove_if(jobs_.begin(), jobs_.end(), [client](const Job& job) { return job.client == client; }),
              jobs_.end());
  if (jobs_.size() != waiting) {
    spdlog::warn("client {} left before its POSE was served: that view is not taken", client);
  }
}

int HandEyeGuidedSession::accepted() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return accepted_;
}

bool HandEyeGuidedSession::complete() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return completed_at_.has_value();
}

bool HandEyeGuidedSession::finished() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return completed_at_ && (final_reply_read_ || Clock::now() - *completed_at_ >= params_.final_reply_grace);
}

void HandEyeGuidedSession::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wakeup_.notify_all();
  if (worker_.joinable()) worker_.join();
}

Reply HandEyeGuidedSession::poseReply(Status status) const {
  return Reply{Command::Pose, status, {accepted_, params_.wanted}};
}

void HandEyeGuidedSession::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wakeup_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
    if (stopping_) return;
    const Job job = jobs_.front();
    jobs_.pop_front();
    Reply reply = poseReply(Status::Busy);  // a view beyond those wanted is not taken
    if (!completed_at_) {
      taking_ = true;
      lock.unlock();
      const Status status = takeView(job);
      lock.lock();
      taking_ = false;
      if (status == Status::Ok && ++accepted_ >= params_.wanted) noteCompletion(job.client);
      reply = poseReply(status);
    }
    lock.unlock();
    sink_(job.client, reply);
    lock.lock();
  }
}

void HandEyeGuidedSession::noteCompletion(robot::ClientId client) {
  completed_at_ = Clock::now();
  final_client_ = client;
  spdlog::info("all {} views recorded in {}", params_.wanted, recorder_.directory());
}

}  // namespace binpick::cli
