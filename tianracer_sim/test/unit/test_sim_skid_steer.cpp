// A four-wheeled skid-steer robot (test/data/urdf/skid_jackal.urdf: Clearpath Jackal's chassis,
// masses, wheel cylinders and wheel surfaces) on Gazebo's ground plane, its wheels driven by
// velocity motors with no effort cap (VelocityJointInterface without limits: Gazebo's fmax is
// DBL_MAX), as diff_drive_controller drives Jackal. Issue 39 point 6: turning on the spot the
// body's yaw rate built up over ~3 s and the robot crept forwards. With SDF's cone_model
// (FrictionModel::kCone) a sliding wheel's friction is Coulomb's, opposite to its slip; the
// default keeps Bullet's fixed basis (docs/physics.md, Friction). Sim time only; each test
// prints the measured figures.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/sim/robot_physics.h"

namespace tianracer_sim {
namespace {

constexpr double kRadius = 0.098;          // wheel radius
constexpr double kHalfBase = 0.262 / 2;    // a: axle to the centre
constexpr double kHalfTrack = 0.37559 / 2; // b: wheel to the centre line
constexpr double kSpawnZ = 0.0635;         // chassis_link above the ground, wheels touching

const RobotModel& skidJackal() {
  static const RobotModel model =
      loadRobotModelFile(std::string(TEST_DATA_DIR) + "/urdf/skid_jackal.urdf", LoadOptions());
  return model;
}

/// The steady yaw rate of a rigid four-wheeled body turning on the spot with wheel surface speeds
/// -v (left) and +v (right) when every wheel slides with an isotropic Coulomb force mu N opposite
/// to its slip: the yaw moments balance (wheels at (+-a, +-b), equal loads) when
/// b (v - W b) = W a^2, i.e. W = v b / (a^2 + b^2). It does not depend on mu or on the loads.
double coulombYawRate(double v) {
  return v * kHalfTrack / (kHalfBase * kHalfBase + kHalfTrack * kHalfTrack);
}

double yawOf(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d R = X.linear();
  return std::atan2(R(1, 0), R(0, 0));
}

PhysicsOptions coneModel() {
  PhysicsOptions o;
  o.friction_model = FrictionModel::kCone;
  return o;
}

struct Skid {
  std::unique_ptr<PhysicsWorld> world;
  PhysicsRobot* robot = nullptr;
  int fl, fr, rl, rr;

  explicit Skid(double yaw, const PhysicsOptions& options = coneModel()) {
    world = std::make_unique<PhysicsWorld>(options);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    X.translation() = Eigen::Vector3d(0.0, 0.0, kSpawnZ);
    robot = &world->robot(addRobotModel(world.get(), skidJackal(), X, "skid_jackal"));
    fl = robot->jointIndex("front_left_wheel");
    fr = robot->jointIndex("front_right_wheel");
    rl = robot->jointIndex("rear_left_wheel");
    rr = robot->jointIndex("rear_right_wheel");
  }
  /// Left and right wheel speeds (rad/s), no effort cap.
  void drive(double left, double right) {
    constexpr double kNoCap = 1e30;
    robot->setJointVelocityTarget(fl, left, kNoCap);
    robot->setJointVelocityTarget(rl, left, kNoCap);
    robot->setJointVelocityTarget(fr, right, kNoCap);
    robot->setJointVelocityTarget(rr, right, kNoCap);
  }
  void run(double seconds) {
    const int n = static_cast<int>(std::lround(seconds / world->dt()));
    for (int i = 0; i < n; ++i) world->step();
  }
};

struct SpotTurn {
  double w05, w1, w3;        // yaw rate (rad/s) 0.5, 1 and 3 s after the command
  double t90;                // s until the yaw rate first reaches 90 % of coulombYawRate
  double yaw3;               // rad turned in 3 s
  double creep;              // m, the base's horizontal travel in 3 s
  double centre_offset;      // m, base origin to the turn's centre at 3 s
  double centre_drift;       // m, how far the turn's centre moved from 0.5 to 3 s
};

/// The instantaneous centre of the planar motion: v = W z x (p - c).
Eigen::Vector2d turnCentre(const PhysicsRobot& robot) {
  const Twist t = robot.baseTwist();
  const Eigen::Vector3d p = robot.basePose().translation();
  const double w = t.angular.z();
  return Eigen::Vector2d(p.x() - t.linear.y() / w, p.y() + t.linear.x() / w);
}

/// Parks the robot for 0.5 s (wheels held at 0), then turns it on the spot with wheel speeds
/// -omega / +omega for 3 s.
SpotTurn spotTurn(double spawn_yaw, double omega) {
  Skid s(spawn_yaw);
  s.drive(0.0, 0.0);
  s.run(0.5);
  const Eigen::Vector3d p0 = s.robot->basePose().translation();
  const double yaw0 = yawOf(s.robot->basePose());
  const double target = coulombYawRate(omega * kRadius);
  s.drive(-omega, omega);
  SpotTurn r{};
  r.t90 = -1.0;
  double unwrapped = 0.0, last = yaw0;
  Eigen::Vector2d c05 = Eigen::Vector2d::Zero();
  for (int i = 1; i <= 3000; ++i) {
    s.world->step();
    const double yaw = yawOf(s.robot->basePose());
    unwrapped += std::remainder(yaw - last, 2.0 * M_PI);
    last = yaw;
    const double w = s.robot->baseTwist().angular.z();
    if (r.t90 < 0.0 && w >= 0.9 * target) r.t90 = i * s.world->dt();
    if (i == 500) {
      r.w05 = w;
      c05 = turnCentre(*s.robot);
    }
    if (i == 1000) r.w1 = w;
    if (i == 3000) r.w3 = w;
  }
  r.yaw3 = unwrapped;
  const Eigen::Vector3d d = s.robot->basePose().translation() - p0;
  r.creep = std::hypot(d.x(), d.y());
  const Eigen::Vector2d c3 = turnCentre(*s.robot);
  r.centre_offset = (c3 - s.robot->basePose().translation().head<2>()).norm();
  r.centre_drift = (c3 - c05).norm();
  std::cout << std::fixed << std::setprecision(4) << "spawn yaw " << spawn_yaw << ", wheels -+"
            << omega << " rad/s: yaw rate " << r.w05 << " / " << r.w1 << " / " << r.w3
            << " rad/s at 0.5 / 1 / 3 s (Coulomb balance " << target << "), 90 % after " << r.t90
            << " s, " << r.yaw3 << " rad in 3 s, creep " << r.creep << " m, centre " << r.centre_offset
            << " m from the base, moved " << r.centre_drift << " m from 0.5 to 3 s\n";
  return r;
}

// Jackal's case: diff_drive_controller with wheel_separation_multiplier 1.5 turns 0.5 rad/s
// into wheel speeds of +-1.44 rad/s. Coulomb friction turns the body at 0.50 rad/s within a few
// ms (its yaw moment, 4 mu N (b - a^2 b / (a^2 + b^2)) ~ 10 N m on ~0.6 kg m^2, is large): 0.3 s
// leaves the wheel motors and the tyres' sink their time. Tolerance 10 %: the four loads are
// not equal (the chassis' COM is 12 mm ahead of the axles' centre: the front wheels carry 55 %)
// and the cylinders' contact points are not exactly below the axles; both move the balance by a
// few per cent. The unequal loads also put the turn's centre a few cm off the base's origin
// (the base then circles it: 3 cm off gives up to 6 cm of travel), but a turn on the spot has a
// fixed centre: it may not walk away (it crept 0.16-0.21 m forwards in jackal_gazebo.py).
TEST(SkidSteer, TurnsOnTheSpotAtTheCoulombRateAtOnce) {
  const double omega = 0.5 * 1.5 * 0.37559 / 2 / kRadius;  // 1.437 rad/s
  const double target = coulombYawRate(omega * kRadius);
  EXPECT_NEAR(target, 0.505, 0.005);
  const SpotTurn r = spotTurn(0.0, omega);
  EXPECT_GT(r.t90, 0.0);
  EXPECT_LT(r.t90, 0.3);
  EXPECT_NEAR(r.w05, target, 0.1 * target);
  EXPECT_NEAR(r.w1, target, 0.1 * target);
  EXPECT_NEAR(r.w3, target, 0.1 * target);
  EXPECT_NEAR(r.yaw3, 3.0 * target, 0.1 * 3.0 * target);
  EXPECT_LT(r.centre_offset, 0.05);
  EXPECT_LT(r.centre_drift, 0.005);
  EXPECT_LT(r.creep, 0.1);
}

// The friction does not depend on where the robot faces: spawned at 45 degrees (where the
// ground's tangent basis, world x and y, is diagonal to the wheels) it turns as at 0.
TEST(SkidSteer, TurnsOnTheSpotTheSameWhicheverWayItFaces) {
  const double omega = 1.437;
  const SpotTurn a = spotTurn(0.0, omega);
  const SpotTurn b = spotTurn(M_PI / 4, omega);
  EXPECT_NEAR(b.w05, a.w05, 0.03 * a.w05);
  EXPECT_NEAR(b.w3, a.w3, 0.03 * a.w3);
  EXPECT_NEAR(b.yaw3, a.yaw3, 0.03 * a.yaw3);
}

}  // namespace
}  // namespace tianracer_sim
