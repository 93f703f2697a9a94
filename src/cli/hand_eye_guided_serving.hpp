#pragma once
// Serving a guided hand-eye session to the robot: the robot server on its own thread, the
// session behind it, and the wait for the last view or a stop signal.
#include <signal.h>

#include <string>

#include "binpick/robot/robot_server.hpp"
#include "hand_eye_guided_session.hpp"

namespace binpick::cli {

struct GuidedServerOptions {
  robot::RobotServerParams server;  // port, codec (framing, orientation, byte order), limits
  std::string port_file;            // the bound port is written here once listening; "" none
};

// SIGINT and SIGTERM: they end the session. Block them in every thread before serving.
sigset_t stopSignals();

// Serves until the session is finished (true) or a stop signal arrives first (false); either
// way every view taken is recorded. Throws core::Error when the port cannot be bound or the
// port file written, and when the server fails (after stopping the session).
bool serveGuidedSession(const GuidedSessionParams& params, const GuidedServerOptions& options,
                        GuidedViewRecorder& recorder, ViewCamera& camera);

}  // namespace binpick::cli
