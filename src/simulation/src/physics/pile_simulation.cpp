#include "pile_simulation.hpp"

#include <algorithm>
#include <cmath>

#include "bullet_units.hpp"

namespace binpick::simulation::detail {
namespace {

// How far a part may reach beyond the inner walls or below the floor and still count as inside:
// room for the collision margin and for the solver's contact slop.
constexpr double kInsideTolerance = 0.0005;  // metres
// A part this far below the floor has fallen off the world (past the apron around the bin).
constexpr double kFallenDepth = 0.2;  // metres

}  // namespace

PileSimulation::PileSimulation(const PartShape& part, const BinInterior& bin, const PhysicsParams& params)
    : part_(part), bin_(bin), params_(params), world_(bin, params) {}

Eigen::Isometry3d PileSimulation::T_bin_model(const btRigidBody* body) const {
  return toMetres(body->getWorldTransform()) * part_.T_model_body().inverse();
}

double PileSimulation::pileTop() const {
  double top = 0.0;
  for (const btRigidBody* body : bodies_) {
    const Eigen::Isometry3d pose = T_bin_model(body);
    for (const auto& p : part_.extremePoints()) top = std::max(top, (pose * p).z());
  }
  return top;
}

void PileSimulation::release(const std::vector<Eigen::Isometry3d>& T_bin_model) {
  for (const auto& pose : T_bin_model) {
    bodies_.push_back(world_.addPart(part_, pose));
    bodies_.back()->setUserIndex(next_serial_++);  // user data only: no influence on the physics
  }
}

bool PileSimulation::atRest(const btRigidBody* body, const btTransform& window_start, double window) const {
  const btTransform& now = body->getWorldTransform();
  const double moved = (now.getOrigin() - window_start.getOrigin()).length() / kWorldScale;
  const double turned = now.getRotation().angleShortestPath(window_start.getRotation());
  return moved < params_.settle_linear_velocity * window && turned < params_.settle_angular_velocity * window;
}

// Compares each part's pose at the end of a window of settle_time with its start: the mean speeds
// over the window, unlike the instantaneous ones, are not kept up by the solver's jitter. The limit
// is counted in whole steps, so that no rounding of a running sum decides when to stop.
bool PileSimulation::settle(int frame_limit) {
  const int window_frames = std::max(1, static_cast<int>(std::ceil(params_.settle_time / params_.time_step - 1e-9)));
  const double window = window_frames * params_.time_step;
  const double step = params_.time_step / params_.substeps;
  std::vector<btTransform> window_start;
  int frames_in_window = 0;
  while (frames_ < frame_limit) {
    if (frames_in_window == 0) {
      window_start.clear();
      for (const btRigidBody* body : bodies_) window_start.push_back(body->getWorldTransform());
    }
    for (int s = 0; s < params_.substeps; ++s) world_.step(step);
    ++frames_;
    if (removeFallen()) {
      frames_in_window = 0;  // the window's bodies changed: start over
      continue;
    }
    if (++frames_in_window < window_frames) continue;
    frames_in_window = 0;
    bool quiet = true;
    for (std::size_t i = 0; i < bodies_.size() && quiet; ++i) quiet = atRest(bodies_[i], window_start[i], window);
    if (quiet) return true;
  }
  return false;
}

void PileSimulation::remove(btRigidBody* body) {
  bodies_.erase(std::find(bodies_.begin(), bodies_.end(), body));
  world_.removePart(body);
}

bool PileSimulation::removeFallen() {
  std::vector<btRigidBody*> fallen;
  for (btRigidBody* body : bodies_) {
    if (toMetres(body->getWorldTransform().getOrigin()).z() < -kFallenDepth) fallen.push_back(body);
  }
  for (btRigidBody* body : fallen) {
    fallen_.push_back(body->getUserIndex());
    remove(body);
  }
  return !fallen.empty();
}

bool PileSimulation::isInsideBin(const btRigidBody* body) const {
  const Eigen::Isometry3d pose = T_bin_model(body);
  const double x_limit = 0.5 * bin_.length + kInsideTolerance;
  const double y_limit = 0.5 * bin_.width + kInsideTolerance;
  return std::all_of(part_.extremePoints().begin(), part_.extremePoints().end(), [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d q = pose * p;
    return std::abs(q.x()) <= x_limit && std::abs(q.y()) <= y_limit && q.z() >= -kInsideTolerance;
  });
}

std::vector<int> PileSimulation::removeEscaped() {
  std::vector<btRigidBody*> outside;
  for (btRigidBody* body : bodies_) {
    if (!isInsideBin(body)) outside.push_back(body);
  }
  std::vector<int> removed;
  removed.swap(fallen_);
  for (btRigidBody* body : outside) {
    removed.push_back(body->getUserIndex());
    remove(body);
  }
  return removed;
}

void PileSimulation::removeAt(int index) {
  remove(bodies_.at(static_cast<std::size_t>(index)));
  // activate(true) also restarts each body's countdown to sleep, so that none dozes off again
  // before its new support has been found.
  for (btRigidBody* body : bodies_) body->activate(true);
}

std::vector<Eigen::Isometry3d> PileSimulation::poses() const {
  std::vector<Eigen::Isometry3d> out;
  for (const btRigidBody* body : bodies_) out.push_back(T_bin_model(body));
  return out;
}

std::vector<int> PileSimulation::serials() const {
  std::vector<int> out;
  for (const btRigidBody* body : bodies_) out.push_back(body->getUserIndex());
  return out;
}

}  // namespace binpick::simulation::detail
