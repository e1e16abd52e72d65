#include "tianracer_sim/sim/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "tianracer_sim/mesh/mesh_loader.h"
#include "tianracer_sim/physics/rigid_tree.h"
#include "tianracer_sim/sim/robot_physics.h"

namespace tianracer_sim {

namespace {
double controlPeriod(const SimRobot& robot) {
  return robot.model.ext.ros_control ? robot.model.ext.ros_control->control_period : 0.0;
}
}  // namespace

namespace tc = tianracer_control;

namespace {

tc::JointHandle::Interface toHandleInterface(JointInterface iface) {
  switch (iface) {
    case JointInterface::kEffort: return tc::JointHandle::Interface::kEffort;
    case JointInterface::kVelocity: return tc::JointHandle::Interface::kVelocity;
    case JointInterface::kPosition: return tc::JointHandle::Interface::kPosition;
  }
  return tc::JointHandle::Interface::kEffort;
}

}  // namespace

void buildJointHandles(const RobotModel& model, const PhysicsRobot& robot,
                       std::vector<tc::JointHandle>* handles, std::vector<int>* handle_joint) {
  handles->clear();
  handle_joint->clear();
  for (const TransmissionSpec& t : model.ext.transmissions) {
    const int j = robot.jointIndex(t.joint);
    if (j < 0) {
      throw ModelError(model.source + ": transmission '" + t.name + "': joint '" + t.joint +
                       "' is not a movable joint of robot '" + robot.name() + "'");
    }
    if (t.joint_interfaces.empty()) {
      throw ModelError(model.source + ": transmission '" + t.name + "': joint '" + t.joint +
                       "' has no hardwareInterface");
    }
    const JointInfo& info = robot.joints()[j];
    handles->push_back(
        makeJointHandle(info.name, toHandleInterface(t.joint_interfaces.front()), &info));
    handle_joint->push_back(j);
  }
}

double depthBelowBase(const RobotModel& model, const Eigen::Matrix3d& R_WB) {
  const RigidTree tree = buildRigidTree(*model.urdf, model.mesh_paths, model.lines);
  // Body poses in the root body's frame at q = 0 (parents precede children).
  std::vector<Eigen::Isometry3d> X_RB(tree.bodies.size(), Eigen::Isometry3d::Identity());
  for (size_t b = 1; b < tree.bodies.size(); ++b) {
    X_RB[b] = X_RB[tree.bodies[b].parent] * tree.bodies[b].X_PB;
  }
  // The root body frame is base_link's frame.
  Eigen::Isometry3d X_WR = Eigen::Isometry3d::Identity();
  X_WR.linear() = R_WB;
  double lowest = 0.0;
  bool any = false;
  for (size_t b = 0; b < tree.bodies.size(); ++b) {
    for (const CollisionGeometry& g : tree.bodies[b].collisions) {
      const Eigen::Isometry3d X_WG = X_WR * X_RB[b] * g.X_BG;
      const Eigen::Vector3d c = X_WG.translation();
      double z = c.z();
      switch (g.shape.type) {
        case ShapeType::kBox: {
          const Eigen::Vector3d h = 0.5 * g.shape.size;
          z -= (X_WG.linear().row(2).cwiseAbs().transpose().cwiseProduct(h)).sum();
          break;
        }
        case ShapeType::kSphere:
          z -= g.shape.radius;
          break;
        case ShapeType::kCylinder: {
          const double az = std::min(1.0, std::fabs(X_WG.linear()(2, 2)));
          z -= 0.5 * g.shape.length * az + g.shape.radius * std::sqrt(1.0 - az * az);
          break;
        }
        case ShapeType::kPlane:
          break;  // never on a robot (the rigid tree holds URDF geometry only)
        case ShapeType::kMesh: {
          const auto mesh = meshOf(g.shape);
          double m = std::numeric_limits<double>::infinity();
          for (const Eigen::Vector3f& v : mesh->vertices) {
            m = std::min(m, (X_WG * v.cast<double>()).z());
          }
          z = m;
          break;
        }
      }
      lowest = any ? std::min(lowest, z) : z;
      any = true;
    }
  }
  return any ? -lowest : 0.0;
}

namespace {

/// A hardware's drive onto physics joint j.
void applyDrive(PhysicsRobot& pr, int j, const JointDrive& d) {
  switch (d.mode) {
    case JointDrive::Mode::kEffort:
      pr.setJointEffort(j, d.value);
      break;
    case JointDrive::Mode::kVelocity:
      // A velocity motor limited by the effort limit.
      pr.setJointVelocityTarget(j, d.value, d.max_effort);
      break;
    case JointDrive::Mode::kPosition: {
      // DefaultRobotHWSim's writeSim without PID gains: SetPosition(0, command, true), the
      // joint put at the command (within its limits: Joint::SetPositionMaximal) with the
      // world velocities kept, so the joint's velocity stays as the physics left it. No
      // motor: a servo capped at the effort limit limit-cycled around the target (upstream's
      // steer bot: +-0.25 rad about a 0.314 rad steer, docs/ros_controllers.md).
      const JointInfo& info = pr.joints()[j];
      const double q = info.has_position_limits ? std::clamp(d.value, info.lower, info.upper) : d.value;
      pr.clearJointCommand(j);
      pr.setJointState(j, q, pr.jointVelocity(j));
      break;
    }
    case JointDrive::Mode::kSetVelocity:
      // Gazebo's Joint::SetVelocity (ODE: SetVelocityMaximal): the child link's velocity set
      // relative to its parent's; no motor, no force limit.
      pr.clearJointCommand(j);
      pr.setJointState(j, pr.jointPosition(j), d.value);
      break;
  }
}

}  // namespace

Simulation::Simulation(const PhysicsOptions& options, WarningSink warn)
    : physics_(options),
      warn_(std::move(warn)),
      controllers_(physics_, warn_, [this](SimRobot& robot) { read(robot); }) {}

SimRobot& Simulation::addRobot(RobotConfig config) {
  if (findRobot(config.name)) {
    throw ModelError("robot '" + config.name + "' exists already: robot names must be unique");
  }
  auto robot = std::make_unique<SimRobot>();
  robot->name = config.name;
  robot->model = std::move(config.model);

  if (config.drop_to_ground) {
    config.X_WB_spawn.translation().z() = depthBelowBase(robot->model, config.X_WB_spawn.linear());
  }
  robot->id = addRobotModel(&physics_, robot->model, config.X_WB_spawn, config.name, warn_);
  PhysicsRobot& physics_robot = physics_.robot(robot->id);
  try {
    const auto& rc = robot->model.ext.ros_control;
    if (rc && rc->robot_sim_type == kSteerBotHardwareGazebo) {
      robot->steer_bot.emplace();
      robot->steer_bot->init(robot->model, physics_robot, config.hw_sim, warn_, &robot->handles,
                             &robot->handle_joint);
    } else {
      buildJointHandles(robot->model, physics_robot, &robot->handles, &robot->handle_joint);
    }
    // gazebo_ros_control's controlPeriod: controllers run every N physics steps.
    const double period = controlPeriod(*robot);
    if (period > 0.0) {
      robot->control_every = std::max(1, static_cast<int>(std::lround(period / physics_.dt())));
      if (std::fabs(robot->control_every * physics_.dt() - period) > 1e-9 && warn_) {
        warn_("robot '" + config.name + "': controlPeriod " + std::to_string(period) +
              " s is not a multiple of the physics step; using " +
              std::to_string(robot->control_every * physics_.dt()) + " s");
      }
    }
    // A velocity or position joint without an effort limit gets an unbounded motor, as
    // DefaultRobotHWSim's SetParam("fmax", DBL_MAX) (sim/robot_hw_sim.h).
    if (!robot->steer_bot) robot->hw_sim.init(robot->model, robot->handles, config.hw_sim, warn_);
    controllers_.attach(*robot, config.controllers);
  } catch (...) {
    physics_.removeRobot(robot->id);  // nothing of a robot that failed stays
    throw;
  }
  robots_.push_back(std::move(robot));
  return *robots_.back();
}

void Simulation::removeRobot(const std::string& name) {
  const auto it = std::find_if(robots_.begin(), robots_.end(),
                               [&](const std::unique_ptr<SimRobot>& r) { return r->name == name; });
  if (it == robots_.end()) throw ModelError("no robot named '" + name + "'");
  physics_.removeRobot((*it)->id);
  robots_.erase(it);
}

SimRobot* Simulation::findRobot(const std::string& name) {
  for (auto& r : robots_) {
    if (r->name == name) return r.get();
  }
  return nullptr;
}

void Simulation::read(SimRobot& robot) {
  const PhysicsRobot& pr = physics_.robot(robot.id);
  for (size_t k = 0; k < robot.handles.size(); ++k) {
    tc::JointHandle& h = robot.handles[k];
    const int j = robot.handle_joint[k];
    if (j < 0) continue;  // SteerBotHardwareGazebo's rear_wheel and front_steer
    h.position = pr.jointPosition(j);
    h.velocity = pr.jointVelocity(j);
    h.effort = pr.jointEffort(j);
  }
  if (robot.steer_bot) robot.steer_bot->read(robot.handles);
}

void Simulation::write(SimRobot& robot) {
  PhysicsRobot& pr = physics_.robot(robot.id);
  const double period = robot.control_every * physics_.dt();
  if (robot.steer_bot) {
    // SteerBotHardwareGazebo writeSim (sim/steer_bot_hw_sim.h): every step, claimed or not.
    for (const auto& [j, d] : robot.steer_bot->write(robot.handles)) applyDrive(pr, j, d);
    return;
  }
  // DefaultRobotHWSim writeSim (sim/robot_hw_sim.h): the e-stop's hold, the joint limits, the
  // PID gains; then the command to the joint.
  robot.hw_sim.beginWrite(robot.handles);
  for (size_t k = 0; k < robot.handles.size(); ++k) {
    tc::JointHandle& h = robot.handles[k];
    const int j = robot.handle_joint[k];
    // NaN never reaches the hardware or Bullet. An infinite command (a PID's output overflowing)
    // goes to the hardware, whose saturation bounds it as DefaultRobotHWSim's would; whatever
    // is still not finite after it is not applied.
    if (!robot.claimed[k] || std::isnan(h.command)) continue;
    const JointDrive d = robot.hw_sim.write(k, h, period);
    if (!std::isfinite(d.value)) continue;
    applyDrive(pr, j, d);
  }
}

void Simulation::step() {
  const std::uint64_t n = physics_.stepCount();
  {
    StepProfile::Scope timed(profile_, controllers_row_);
    for (auto& robot : robots_) {
      if (n % static_cast<std::uint64_t>(robot->control_every) != 0) continue;
      read(*robot);
      // gazebo_ros_control: the controllers are reset on the first update after an e-stop.
      if (robot->hw_sim.takeEStopReleased()) robot->controllers.reset(physics_.time());
      controllers_.update(*robot);
      write(*robot);
    }
  }
  StepProfile::Scope timed(profile_, bullet_row_);
  physics_.step();
}

void Simulation::setProfile(StepProfile* profile) {
  profile_ = profile;
  controllers_row_ = profileRow(profile, StepProfile::kControllers);
  bullet_row_ = profileRow(profile, StepProfile::kBullet);
}

void Simulation::restartControllers(SimRobot& robot) {
  controllers_.restart(robot);
  write(robot);
}

void Simulation::setTimeStep(double dt) {
  physics_.setTimeStep(dt);
  for (auto& robot : robots_) {
    const double period = controlPeriod(*robot);
    robot->control_every = period > 0.0 ? std::max(1, static_cast<int>(std::lround(period / dt))) : 1;
  }
}

void Simulation::resetSimulation() {
  physics_.resetTime();
  resetWorld();
}

void Simulation::resetWorld() {
  for (auto& robot : robots_) {
    physics_.robot(robot->id).resetToSpawn();
    robot->hw_sim.reset();
    restartControllers(*robot);
  }
  // The world's free bodies back to their poses in the world file.
  for (int i = 0; i < physics_.freeBodyCount(); ++i)
    if (physics_.hasFreeBody(i)) physics_.freeBody(i).resetToSpawn();
}

const PhysicsRobot* Simulation::findModel(const std::string& name) const {
  for (const auto& r : robots_) {
    if (r->name == name) return &physics_.robot(r->id);
  }
  const int i = physics_.freeBodyIndex(name);
  return i >= 0 ? &physics_.freeBody(i) : nullptr;
}

std::string checkModelState(const Eigen::Isometry3d& X_WB, const Twist& V_WB) {
  if (!X_WB.matrix().allFinite()) return "pose is not finite";
  if (!V_WB.linear.allFinite() || !V_WB.angular.allFinite()) return "twist is not finite";
  const char* axes[3] = {"x", "y", "z"};
  auto fmt = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", v);
    return std::string(buf);
  };
  struct Check {
    const char* what;
    Eigen::Vector3d v;
    double bound;
    const char* unit;
  };
  for (const Check& c : {Check{"position", X_WB.translation(), kMaxModelPosition, "m"},
                         Check{"linear velocity", V_WB.linear, kMaxModelLinearVelocity, "m/s"},
                         Check{"angular velocity", V_WB.angular, kMaxModelAngularVelocity, "rad/s"}})
    for (int i = 0; i < 3; ++i)
      if (std::abs(c.v[i]) > c.bound)
        return std::string(c.what) + " " + axes[i] + " " + fmt(c.v[i]) + " is out of range (|" +
               axes[i] + "| <= " + fmt(c.bound) + " " + c.unit + ")";
  return "";
}

}  // namespace tianracer_sim
