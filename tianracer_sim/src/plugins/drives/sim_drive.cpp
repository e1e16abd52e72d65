#include "tianracer_sim/plugins/drives/sim_drive.h"

#include <stdexcept>

#include <tianracer_control/naming.h>

#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

std::unique_ptr<SimSensor> makeDrive(const SimSensorSetup& setup) {
  return std::make_unique<SimDrive>(setup, parseDriveConfig(*setup.spec, setup.model_name, setup.warn));
}

}  // namespace

const SensorKind& driveKind() {
  static const SensorKind kind = {"drive", {},
       {"libgazebo_ros_diff_drive.so", "libgazebo_ros_skid_steer_drive.so",
        "libgazebo_ros_planar_move.so"},
       &topicsOf<parseDriveConfig>, &makeDrive};
  return kind;
}
TIANRACER_SENSOR_KIND(driveKind);

SimDrive::SimDrive(const SimSensorSetup& setup, DriveConfig config)
    : SimSensor("drive", config.name, setup.linkRef(""), setup.model_name), core_(std::move(config)) {
  const DriveConfig& c = core_.config();
  if (!setup.world) throw std::logic_error("SimDrive needs the simulation");
  const std::string what = c.filename + " plugin '" + c.name + "' of model '" +
                           setup.model_name + "'";
  static const char* kDiffTags[] = {"leftJoint", "rightJoint"};
  static const char* kSkidTags[] = {"leftFrontJoint", "rightFrontJoint", "leftRearJoint",
                                    "rightRearJoint"};
  for (std::size_t k = 0; k < c.joints.size(); ++k) {
    std::string parent, child;
    const int i = setup.world->jointIndex(setup.model, c.joints[k], &parent, &child);
    if (i < 0) {
      const char* tag = c.kind == DriveKind::kDiffDrive ? kDiffTags[k] : kSkidTags[k];
      setup.fail(what + ": <" + tag + "> '" + c.joints[k] +
                 "' is not a movable joint of the model (Gazebo does not load the plugin)");
    }
    joints_.push_back(i);
    parent_links_.push_back(parent);
    child_links_.push_back(child);
    wheel_tf_.push_back({resolveFrame(setup.tf_prefix, parent),
                         resolveFrame(setup.tf_prefix, child), Eigen::Isometry3d::Identity()});
  }
  if (c.kind == DriveKind::kPlanarMove &&
      !setup.world->setModelVelocity(setup.model, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero())) {
    setup.fail(what + ": the model is static: there is nothing to move");
  }
  omega_.assign(joints_.size(), 0.0);
  positions_.assign(joints_.size(), 0.0);
  odom_frame_ = resolveFrame(setup.tf_prefix, c.odometry_frame);
  base_frame_ = resolveFrame(setup.tf_prefix, c.robot_base_frame);
  stat().name = c.name;
  stat().target = c.update_rate;
}

SensorOutputs SimDrive::update(double t, SensorWorld& world) {
  const DriveConfig& c = config();
  const ModelId id = link().model;
  t_ = t;
  const LinkState model = world.modelFrameState(id);
  if (!started_) {
    // Load: the motors hold the wheels (vel 0) with fmax = the torque.
    for (int j : joints_) world.setJointVelocity(id, j, 0.0, c.wheel_torque);
    started_ = true;
  }
  if (restart_) {
    core_.restart(restart_t_, model);
    restart_ = false;
  }
  for (std::size_t k = 0; k < joints_.size(); ++k) omega_[k] = world.jointVelocity(id, joints_[k]);
  const DriveCore::Step& step = core_.update(t, model, omega_);
  if (step.set_wheels) {
    for (std::size_t k = 0; k < joints_.size(); ++k)
      world.setJointVelocity(id, joints_[k], step.wheel_omega[k], c.wheel_torque);
  }
  if (step.set_twist) world.setModelVelocity(id, step.linear_W, step.angular_W);
  if (!step.due) return 0;
  SensorOutputs due = 0;
  if (c.kind == DriveKind::kPlanarMove || c.publish_odometry) due |= kOdometry;
  if (c.publish_wheel_tf) due |= kWheelTf;
  if (c.publish_wheel_joint_state) due |= kJointState;
  return due;
}

void SimDrive::sample(SensorOutputs outputs, SensorWorld& world) {
  const ModelId id = link().model;
  if (outputs & kJointState) {
    for (std::size_t k = 0; k < joints_.size(); ++k) positions_[k] = world.jointPosition(id, joints_[k]);
  }
  if (outputs & kWheelTf) {
    for (std::size_t k = 0; k < joints_.size(); ++k) {
      wheel_tf_[k].X_PC = world.linkPose(LinkRef{id, parent_links_[k]}).inverse() *
                          world.linkPose(LinkRef{id, child_links_[k]});
    }
  }
}

void SimDrive::restart(double t) {
  // reset_simulation cleared the motors: they hold the wheels again until the first update.
  started_ = false;
  restart_ = true;
  restart_t_ = t;
}

}  // namespace tianracer_sim
