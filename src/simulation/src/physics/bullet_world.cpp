#include "bullet_world.hpp"

#include <cmath>

#include "../bin.hpp"
#include "bullet_units.hpp"

namespace binpick::simulation::detail {
namespace {

constexpr double kGravity = 9.81;  // m/s^2
// Floor slab below z = 0, reaching this far beyond the walls: a part that falls out of the bin
// lands on it and comes to rest, so that it can be found and dropped again.
constexpr double kApron = 0.5;            // metres
constexpr double kFloorThickness = 0.05;  // metres: thick, so that nothing falls through
// Twice Bullet's default: piles a dozen parts deep jitter and creep with fewer, and then take much
// longer (in simulated time) to come to rest than the extra iterations cost.
constexpr int kSolverIterations = 20;

}  // namespace

BulletWorld::BulletWorld(const BinInterior& bin, const PhysicsParams& params)
    : params_(params),
      configuration_(std::make_unique<btDefaultCollisionConfiguration>()),
      dispatcher_(std::make_unique<btCollisionDispatcher>(configuration_.get())),
      broadphase_(std::make_unique<btDbvtBroadphase>()),
      solver_(std::make_unique<btSequentialImpulseConstraintSolver>()),
      world_(std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                       configuration_.get())) {
  btContactSolverInfo& solver = world_->getSolverInfo();
  solver.m_numIterations = kSolverIterations;
  // Friction along two directions at every contact: with one, resting parts creep down slopes.
  solver.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
  world_->setGravity(toWorld(Eigen::Vector3d(0.0, 0.0, -kGravity)));
  const double hl = 0.5 * bin.length, hw = 0.5 * bin.width, h = bin.wall_height;
  const double t = kBinWallThickness, reach = t + kApron;
  addStaticBox({-hl - reach, -hw - reach, -kFloorThickness}, {hl + reach, hw + reach, 0.0});
  addStaticBox({-hl - t, -hw - t, 0.0}, {-hl, hw + t, h});
  addStaticBox({hl, -hw - t, 0.0}, {hl + t, hw + t, h});
  addStaticBox({-hl, -hw - t, 0.0}, {hl, -hw, h});
  addStaticBox({-hl, hw, 0.0}, {hl, hw + t, h});
}

BulletWorld::~BulletWorld() {
  for (auto& body : bodies_) world_->removeRigidBody(body.get());
}

void BulletWorld::addStaticBox(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  auto box = std::make_unique<btBoxShape>(toWorld(0.5 * (max - min)));
  btRigidBody::btRigidBodyConstructionInfo info(0.0, nullptr, box.get());
  info.m_startWorldTransform.setIdentity();
  info.m_startWorldTransform.setOrigin(toWorld(0.5 * (min + max)));
  // Bullet combines two bodies' coefficients by multiplying them: square roots make every contact
  // (part-part and part-bin) get exactly the configured values.
  info.m_friction = static_cast<btScalar>(std::sqrt(params_.friction));
  info.m_restitution = static_cast<btScalar>(std::sqrt(params_.restitution));
  info.m_rollingFriction = info.m_spinningFriction = rollingFriction();
  bodies_.push_back(std::make_unique<btRigidBody>(info));
  world_->addRigidBody(bodies_.back().get());
  boxes_.push_back(std::move(box));
}

// Bullet combines rolling (and spinning) friction r with sliding friction f over a contact as
// r_a f_b + r_b f_a. With f = sqrt(friction) and this r on every body, bin included, each contact
// gets rolling_resistance.
btScalar BulletWorld::rollingFriction() const {
  if (params_.friction <= 0.0) return 0.0;
  return static_cast<btScalar>(kWorldScale * params_.rolling_resistance / (2.0 * std::sqrt(params_.friction)));
}

btRigidBody* BulletWorld::addPart(const PartShape& part, const Eigen::Isometry3d& T_bin_model) {
  btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(part.mass()), nullptr, part.shape(),
                                                part.inertia());
  info.m_startWorldTransform = toWorld(T_bin_model * part.T_model_body());
  info.m_friction = static_cast<btScalar>(std::sqrt(params_.friction));
  info.m_restitution = static_cast<btScalar>(std::sqrt(params_.restitution));
  info.m_linearSleepingThreshold = static_cast<btScalar>(kWorldScale * params_.settle_linear_velocity);
  info.m_angularSleepingThreshold = static_cast<btScalar>(params_.settle_angular_velocity);
  info.m_rollingFriction = info.m_spinningFriction = rollingFriction();
  bodies_.push_back(std::make_unique<btRigidBody>(info));
  world_->addRigidBody(bodies_.back().get());
  return bodies_.back().get();
}

void BulletWorld::removePart(btRigidBody* body) {
  world_->removeRigidBody(body);
  for (auto it = bodies_.begin(); it != bodies_.end(); ++it) {
    if (it->get() == body) {
      bodies_.erase(it);
      return;
    }
  }
}

void BulletWorld::step(double seconds) {
  // No internal substepping: one step of exactly `seconds`, so that steps are counted here.
  world_->stepSimulation(static_cast<btScalar>(seconds), 0);
}

}  // namespace binpick::simulation::detail
