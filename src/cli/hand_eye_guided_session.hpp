#pragma once
// A guided hand-eye session on the robot protocol (docs/hand-eye.md, "Guided session"): the robot
// moves to a pose, holds still and sends POSE with its flange pose; the session takes an image,
// checks the board in it as the file mode will (measureView), records the view and answers
//   ok               the view was recorded: integers views accepted, views wanted
//   board_not_found  no usable board in the image (kept in rejected/): the same integers
//   no_image         the camera gave no image: the same integers
//   calibration_missing  the image does not match the camera calibration's size
//   busy             the session already has its views: nothing recorded
//   internal_error   the view could not be written (the log says why)
// PING is answered ok, STATUS ok with {state (0 waiting, 1 taking a view, 2 done), views accepted,
// views wanted}; other commands unknown_command. A failed view never ends the session.
//
// Thread-safety: handle() and disconnected() run on the robot server's thread and never wait for
// a view: views are taken on the session's own thread, which replies through the sink. The other
// members may be called from any thread.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

#include "binpick/calibration/board_layout.hpp"
#include "binpick/calibration/hand_eye_views.hpp"
#include "binpick/io/lens.hpp"
#include "binpick/robot/robot_server.hpp"
#include "hand_eye_guided_camera.hpp"
#include "hand_eye_guided_recorder.hpp"

namespace binpick::cli {

struct GuidedSessionParams {
  int wanted = 12;  // views to accept (--count), those recorded before included
  calibration::BoardLayout layout;
  io::LensIntrinsics camera;           // the board pose check needs the intrinsics
  calibration::BoardViewParams check;  // what makes a view usable: the file mode's own rule
  // Once the last view is accepted, how long the robot has to read its reply (it shows it has by
  // disconnecting or sending anything) before the session counts as finished.
  std::chrono::milliseconds final_reply_grace{2000};
  void validate() const;  // throws core::Error naming the field
};

using GuidedReplySink = std::function<void(robot::ClientId, const robot::Reply&)>;

class HandEyeGuidedSession : public robot::RequestHandler {
 public:
  // The recorder and camera must outlive the session.
  HandEyeGuidedSession(const GuidedSessionParams& params, GuidedViewRecorder& recorder, ViewCamera& camera,
                       GuidedReplySink sink);
  ~HandEyeGuidedSession() override;  // stop()
  HandEyeGuidedSession(const HandEyeGuidedSession&) = delete;
  HandEyeGuidedSession& operator=(const HandEyeGuidedSession&) = delete;

  void handle(robot::ClientId client, const robot::Request& request) override;
  void disconnected(robot::ClientId client) override;

  int accepted() const;
  bool complete() const;  // all views accepted
  // Complete, and the robot read the last reply (or final_reply_grace passed): time to calibrate.
  bool finished() const;
  // Takes no more views: the one being taken is finished and recorded, waiting ones are dropped
  // unanswered (the server is stopping). Idempotent.
  void stop();

 private:
  struct Job {
    robot::ClientId client;
    Eigen::Isometry3d T_base_flange;
  };
  void work();
  // Records, grabs, checks and files one view (hand_eye_guided_view.cpp); never throws.
  robot::Status takeView(const Job& job);
  robot::Reply poseReply(robot::Status status) const;  // call with mutex_ held
  void noteCompletion(robot::ClientId client);

  GuidedSessionParams params_;
  GuidedViewRecorder& recorder_;
  ViewCamera& camera_;
  GuidedReplySink sink_;

  mutable std::mutex mutex_;
  std::condition_variable wakeup_;
  std::deque<Job> jobs_;
  int accepted_ = 0;
  bool taking_ = false;  // a view is being taken
  bool stopping_ = false;
  std::optional<std::chrono::steady_clock::time_point> completed_at_;
  std::optional<robot::ClientId> final_client_;  // who sent the last view
  bool final_reply_read_ = false;
  std::thread worker_;
};

}  // namespace binpick::cli
