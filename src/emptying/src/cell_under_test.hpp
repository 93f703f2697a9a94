#pragma once
// The cell service as binpickd runs it, for the emptying loop: its settings written to a
// binpickd.yaml and read back, the prepared recipe, the CellService behind a RobotServer on the
// loopback interface (its own thread), and the robot's TCP connection to it. The virtual camera
// stands in for the capture source: show() sets the capture the next TRIGGER takes.
// Used by one thread (the loop's); the server and the service run their own threads inside.
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <thread>

#include "binpick/cell/cell_service.hpp"
#include "binpick/emptying/emptying.hpp"
#include "binpick/robot/robot_connection.hpp"
#include "binpick/robot/robot_server.hpp"
#include "binpick/web/log_ring.hpp"
#include "binpick/web/web_server.hpp"

namespace binpick::emptying::detail {

class VirtualCamera;

class CellUnderTest {
 public:
  // Writes DIR/cell/{binpickd.yaml, part.ply, calib.yaml, detection.yaml}, prepares the cell
  // (generating the part's grasps), starts serving and connects the robot.
  CellUnderTest(const simulation::Part& part, const EmptyingParams& params, const Eigen::Isometry3d& T_camera_bin);
  ~CellUnderTest();
  CellUnderTest(const CellUnderTest&) = delete;
  CellUnderTest& operator=(const CellUnderTest&) = delete;

  void show(io::Capture capture);
  robot::Reply request(robot::Command command, const std::string& argument = "");
  cell::CellSnapshot snapshot() const { return service_->snapshot(); }
  const cell::Recipe& recipe() const { return setup_->recipes.front(); }
  const Eigen::Isometry3d& T_base_bin() const { return T_base_bin_; }
  int avoidCycles() const { return setup_->config.limits.avoid_cycles; }

 private:
  void stop();

  Eigen::Isometry3d T_base_bin_;
  std::shared_ptr<const cell::CellSetup> setup_;
  VirtualCamera* camera_ = nullptr;  // owned by the service
  std::unique_ptr<cell::CellService> service_;
  std::unique_ptr<robot::RobotServer> server_;
  std::thread serving_;
  std::unique_ptr<robot::RobotConnection> robot_;
  std::unique_ptr<web::WebServer> web_;  // when the settings have a web: section
};

}  // namespace binpick::emptying::detail
