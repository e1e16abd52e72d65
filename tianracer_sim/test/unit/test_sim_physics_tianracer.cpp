// Physics regression on the shipped tianracer (xacro + generated meshes), on Gazebo's ground plane,
// driven the way its controllers drive it: rear wheels by velocity motors (VelocityJointInterface),
// steering hinges by a PID through joint efforts (effort_controllers/JointPositionController).
// Sim time only; each test prints the measured figures.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <array>
#include <iomanip>
#include <iostream>
#include <memory>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/sim/robot_physics.h"

namespace tianracer_sim {
namespace {

const std::string kDescription = TIANRACER_DESCRIPTION_DIR;

// Geometry from the seed's joint origins.
constexpr double kWheelRadius = 0.032;                  // generated wheel meshes
constexpr double kWheelbase = 0.5 * (0.1237 + 0.12626) + 0.5 * (0.12626 + 0.1237);  // 0.24996
constexpr double kHingeTrack = 0.070647 + 0.065953;     // T, between steering hinges
constexpr double kRearTrack = 0.081602 + 0.086296;      // between rear wheel centres
constexpr double kSpawnZ = 0.0095;                      // base_link above ground, wheels touching

// Hinge gains chosen by SteeringStep (effort_controllers semantics, see HingePid).
constexpr double kHingeP = 20.0, kHingeI = 0.0, kHingeD = 0.2;

const RobotModel& tianracer() {
  static const RobotModel model = [] {
    // xacro resolves $(find tianracer_description) through ROS_PACKAGE_PATH.
    const std::string root = kDescription.substr(0, kDescription.rfind('/'));
    const char* old = std::getenv("ROS_PACKAGE_PATH");
    setenv("ROS_PACKAGE_PATH", (root + (old ? ":" + std::string(old) : "")).c_str(), 1);
    LoadOptions options;
    options.resolver.find_package = [](const std::string& pkg) {
      return pkg == "tianracer_description" ? kDescription : std::string();
    };
    return loadRobotModelFile(kDescription + "/urdf/tianracer_description.xacro", options);
  }();
  return model;
}

/// effort_controllers/JointPositionController's PID: effort = p e + i sum(e dt) + d de/dt,
/// derivative on the error, zero on the first update (as tianracer_control::Pid).
struct HingePid {
  double p = kHingeP, i = kHingeI, d = kHingeD;
  double integral = 0.0, prev = 0.0;
  bool first = true;
  double update(double e, double dt) {
    integral += e * dt;
    const double de = first ? 0.0 : (e - prev) / dt;
    first = false;
    prev = e;
    return p * e + i * integral + d * de;
  }
};

/// The car plus its controllers, stepped at 1 kHz (controllers every step, as
/// gazebo_ros_control with no controlPeriod).
struct Car {
  std::unique_ptr<PhysicsWorld> world;
  PhysicsRobot* robot = nullptr;
  int lr, rr, lh, rh, lf, rf;
  HingePid pid_l, pid_r;
  double steer_l = 0.0, steer_r = 0.0;  // hinge targets (rad)
  double omega_l = 0.0, omega_r = 0.0;  // rear wheel targets (rad/s)

  explicit Car(const PhysicsOptions& options = PhysicsOptions(), double yaw = 0.0) {
    world = std::make_unique<PhysicsWorld>(options);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    X.translation().z() = kSpawnZ;
    robot = &world->robot(addRobotModel(world.get(), tianracer(), X, "tianracer"));
    lr = robot->jointIndex("left_rear_wheel_joint");
    rr = robot->jointIndex("right_rear_wheel_joint");
    lh = robot->jointIndex("left_steering_hinge_joint");
    rh = robot->jointIndex("right_steering_hinge_joint");
    lf = robot->jointIndex("left_front_wheel_joint");
    rf = robot->jointIndex("right_front_wheel_joint");
  }
  void setGains(double p, double i, double d) {
    pid_l = pid_r = HingePid{p, i, d};
  }
  void step() {
    const double dt = world->dt();
    robot->setJointEffort(lh, pid_l.update(steer_l - robot->jointPosition(lh), dt));
    robot->setJointEffort(rh, pid_r.update(steer_r - robot->jointPosition(rh), dt));
    robot->setJointVelocityTarget(lr, omega_l);
    robot->setJointVelocityTarget(rr, omega_r);
    world->step();
  }
  void run(double seconds) {
    const long n = std::lround(seconds / world->dt());
    for (long k = 0; k < n; ++k) step();
  }
  /// Exact Ackermann hinge angles for a bicycle angle delta (cot(delta_i) = cot(delta) -+ T/(2L)),
  /// with per-wheel rear speeds.
  void ackermann(double delta, double v) {
    const double t = std::tan(delta);
    steer_l = std::atan(kWheelbase * t / (kWheelbase - 0.5 * kHingeTrack * t));
    steer_r = std::atan(kWheelbase * t / (kWheelbase + 0.5 * kHingeTrack * t));
    omega_l = v * (1.0 - kRearTrack * t / (2.0 * kWheelbase)) / kWheelRadius;
    omega_r = v * (1.0 + kRearTrack * t / (2.0 * kWheelbase)) / kWheelRadius;
  }
  Eigen::Vector3d position() const { return robot->basePose().translation(); }
  double yaw() const {
    const Eigen::Matrix3d R = robot->basePose().rotation();
    return std::atan2(R(1, 0), R(0, 0));
  }
  double planarSpeed() const { return robot->baseTwist().linear.head<2>().norm(); }
  Eigen::Vector3d rearAxle() const {
    return 0.5 * (robot->linkPose("left_rear_wheel").translation() +
                  robot->linkPose("right_rear_wheel").translation());
  }
};

const char* kWheels[] = {"left_front_wheel", "right_front_wheel", "left_rear_wheel",
                         "right_rear_wheel"};

TEST(Tianracer, ModelAsBulletSeesIt) {
  Car car;
  const PhysicsRobot& r = *car.robot;
  EXPECT_EQ(r.joints().size(), 6u);
  EXPECT_EQ(r.tree().bodies.size(), 7u);  // base (+chassis, lidar, camera, real_sense) + 6
  EXPECT_NEAR(r.totalMass(), 5.0 + 2 * 0.34 + 4 * 0.7 + 0.0792224121739075 +
                                 0.0203878842392581 + 0.103311749598955, 1e-12);
  const JointInfo& hinge = r.joints()[car.lh];
  EXPECT_EQ(hinge.type, JointType::kRevolute);
  EXPECT_EQ(hinge.lower, -0.6);
  EXPECT_EQ(hinge.upper, 0.6);
  EXPECT_EQ(hinge.effort_limit, 10.0);
  EXPECT_EQ(r.joints()[car.lr].type, JointType::kContinuous);
  EXPECT_EQ(r.joints()[car.lr].motor_effort, 10.0);  // no URDF limit: documented default
  // Wheels touch the ground at spawn: centre heights = radius (front 1 mm higher in the seed).
  EXPECT_NEAR(r.linkPose("left_rear_wheel").translation().z(), kWheelRadius, 1e-9);
  EXPECT_NEAR(r.linkPose("left_front_wheel").translation().z(), kWheelRadius + 0.001, 1e-9);
}

// (a) Parked: zero wheel velocity, hinges held at 0. 1 s to settle, then 60 s.
TEST(Tianracer, AtRestDoesNotCreep) {
  Car car;
  car.run(1.0);
  const Eigen::Vector3d p0 = car.position();
  const double yaw0 = car.yaw();
  car.run(60.0);
  const double drift = (car.position() - p0).norm();
  std::cout << std::setprecision(4) << "[tianracer (a) at rest] base moved " << drift * 1e3
            << " mm in 60 s (yaw " << (car.yaw() - yaw0) * 180 / M_PI << " deg), settled z "
            << p0.z() * 1e3 << " mm\n";
  EXPECT_LT(drift, 1e-3);
  for (const char* w : kWheels) EXPECT_GT(car.robot->contactCount(w), 0) << w;
}

// (b) Rear wheels at v/r for 1.0 m/s: speed within 1% after 1 s; heading drift < 1 deg over 10 m.
TEST(Tianracer, StraightLineSpeedAndHeading) {
  Car car;
  car.run(0.5);
  car.omega_l = car.omega_r = 1.0 / kWheelRadius;
  car.run(1.0);
  const Eigen::Vector3d p0 = car.position();
  const double yaw0 = car.yaw();
  double vmin = 1e9, vmax = 0.0, wheel_speed = 0.0;
  while ((car.position() - p0).head<2>().norm() < 10.0 && car.world->time() < 20.0) {
    car.step();
    const double v = car.planarSpeed();
    vmin = std::min(vmin, v);
    vmax = std::max(vmax, v);
    wheel_speed = car.robot->jointVelocity(car.lr);
  }
  const double distance = (car.position() - p0).head<2>().norm();
  const double heading_drift = std::abs(car.yaw() - yaw0) * 180 / M_PI;
  const double rolling_radius = car.planarSpeed() / wheel_speed;
  std::cout << std::setprecision(6) << "[tianracer (b) 1.0 m/s] speed after 1 s in [" << vmin
            << ", " << vmax << "] m/s over " << distance << " m, heading drift " << heading_drift
            << " deg, effective rolling radius " << rolling_radius * 1e3 << " mm (mesh "
            << kWheelRadius * 1e3 << ")\n";
  EXPECT_GE(distance, 10.0);
  EXPECT_GT(vmin, 0.99);
  EXPECT_LT(vmax, 1.01);
  EXPECT_LT(heading_drift, 1.0);
  // The margin does not inflate the wheel: rolls on its true radius within 0.1%.
  EXPECT_NEAR(rolling_radius, kWheelRadius, 1e-3 * kWheelRadius);
}

// Why the fitted rounded cylinder: speed error and ride per wheel shape, 3 s at 1 m/s.
TEST(Tianracer, WheelShapeComparison) {
  const std::pair<WheelShape, const char*> shapes[] = {
      {WheelShape::kRoundedCylinder, "rounded cylinder (default)"},
      {WheelShape::kCylinder, "flat cylinder"},
      {WheelShape::kSphere, "sphere"},
      {WheelShape::kMeshHull, "mesh convex hull"}};
  for (const auto& [shape, name] : shapes) {
    PhysicsOptions o;
    o.wheel_shape = shape;
    Car car(o);
    car.run(0.5);
    car.omega_l = car.omega_r = 1.0 / kWheelRadius;
    car.run(1.0);
    const Eigen::Vector3d p0 = car.position();
    const double yaw0 = car.yaw();
    double zmin = 1.0, zmax = 0.0;
    for (int k = 0; k < 2000; ++k) {
      car.step();
      zmin = std::min(zmin, car.position().z());
      zmax = std::max(zmax, car.position().z());
    }
    const double speed = (car.position() - p0).head<2>().norm() / 2.0;
    std::cout << std::setprecision(4) << "[wheel shape] " << std::setw(27) << std::left << name
              << std::right << " speed error " << std::setw(8) << (speed - 1.0) * 100
              << " %, base bounce " << std::setw(7) << (zmax - zmin) * 1e3 << " mm, yaw drift "
              << (car.yaw() - yaw0) * 180 / M_PI << " deg over 2 m\n";
    if (shape == WheelShape::kRoundedCylinder) {
      EXPECT_NEAR(speed, 1.0, 1e-3);
      EXPECT_LT(zmax - zmin, 1e-5);
    }
  }
}

// (c) Hinge step 0 -> 0.4 rad through joint efforts (limit 10 N m), car standing.
struct StepResponse {
  double settle = 0.0, overshoot = 0.0, final_error = 0.0, late_peak_to_peak = 0.0;
};
StepResponse steeringStep(double p, double i, double d) {
  Car car;
  car.setGains(p, i, d);
  car.run(0.5);
  car.steer_l = car.steer_r = 0.4;
  StepResponse s;
  double peak = 0.0, late_min = 1e9, late_max = -1e9;
  for (int k = 1; k <= 1000; ++k) {
    car.step();
    const double q = car.robot->jointPosition(car.lh);
    peak = std::max(peak, q);
    if (std::abs(q - 0.4) > 0.02 * 0.4) s.settle = k * car.world->dt();
    if (k > 500) {
      late_min = std::min(late_min, q);
      late_max = std::max(late_max, q);
    }
  }
  s.overshoot = std::max(0.0, (peak - 0.4) / 0.4);
  s.final_error = car.robot->jointPosition(car.lh) - 0.4;
  s.late_peak_to_peak = late_max - late_min;
  return s;
}

TEST(Tianracer, SteeringStep) {
  std::cout << "[tianracer (c) steering step 0 -> 0.4 rad] p i d: settle(2%) overshoot "
               "final-error late-p2p\n";
  for (const auto& g : {std::array<double, 3>{1.0, 0.0, 0.05}, {5.0, 0.0, 0.1},
                        {10.0, 0.0, 0.15}, {kHingeP, kHingeI, kHingeD}}) {
    const StepResponse s = steeringStep(g[0], g[1], g[2]);
    std::cout << std::setprecision(4) << "  " << g[0] << " " << g[1] << " " << g[2] << ": "
              << s.settle * 1e3 << " ms, " << s.overshoot * 100 << " %, " << s.final_error
              << " rad, " << s.late_peak_to_peak << " rad\n";
  }
  const StepResponse s = steeringStep(kHingeP, kHingeI, kHingeD);
  EXPECT_LT(s.settle, 0.3);
  EXPECT_LT(s.overshoot, 0.10);
  EXPECT_LT(std::abs(s.final_error), 0.02 * 0.4);
  EXPECT_LT(s.late_peak_to_peak, 1e-3);  // no sustained oscillation
}

// Circle at 0.3 rad (bicycle angle), 0.5 m/s, exact Ackermann angles and rear wheel speeds:
// radius of the rear axle's path vs L / tan(0.3).
TEST(Tianracer, AckermannCircleRadius) {
  Car car;
  car.run(0.5);
  const double delta = 0.3, v = 0.5;
  car.ackermann(delta, v);
  car.run(5.0);
  // Kasa least-squares circle fit to the rear axle midpoint, 10 s at 100 Hz.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double hinge_err = 0.0;
  for (int k = 0; k < 10000; ++k) {
    car.step();
    if (k % 10) continue;
    const Eigen::Vector3d p = car.rearAxle();
    const Eigen::Vector3d row(p.x(), p.y(), 1.0);
    A += row * row.transpose();
    b += row * (p.x() * p.x() + p.y() * p.y());
    hinge_err = std::max({hinge_err, std::abs(car.robot->jointPosition(car.lh) - car.steer_l),
                          std::abs(car.robot->jointPosition(car.rh) - car.steer_r)});
  }
  const Eigen::Vector3d s = A.ldlt().solve(b);
  const double cx = 0.5 * s(0), cy = 0.5 * s(1);
  const double radius = std::sqrt(s(2) + cx * cx + cy * cy);
  const double expected = kWheelbase / std::tan(delta);
  std::cout << std::setprecision(5) << "[tianracer circle 0.3 rad, 0.5 m/s] rear-axle radius "
            << radius << " m vs L/tan(0.3) = " << expected << " m: "
            << (radius / expected - 1.0) * 100 << " % (hinges " << car.steer_l << " / "
            << car.steer_r << " rad, max tracking error " << hinge_err << " rad)\n";
  EXPECT_NEAR(radius / expected, 1.0, 0.03);
}

// (d) Full lock +-0.6 rad at 2 m/s for 10 s: all four wheels on the ground, finite, bounded.
TEST(Tianracer, FullLockStaysOnItsWheels) {
  for (double lock : {0.6, -0.6}) {
    Car car;
    car.run(0.5);
    car.steer_l = car.steer_r = lock;
    car.omega_l = car.omega_r = 2.0 / kWheelRadius;
    int lost = 0;
    double z_max = 0.0, ke_max = 0.0, e0 = 0.0;
    for (int k = 0; k < 10000; ++k) {
      car.step();
      for (const char* w : kWheels) {
        if (car.robot->contactCount(w) == 0) ++lost;
        z_max = std::max(z_max, car.robot->linkPose(w).translation().z() -
                                    (std::string(w).find("front") != std::string::npos ? 0.001 : 0.0));
      }
      const double e = car.robot->kineticEnergy();
      ke_max = std::max(ke_max, e);
      if (k == 2000) e0 = e;
      ASSERT_TRUE(car.robot->basePose().matrix().allFinite()) << "step " << k;
    }
    const double ke_end = car.robot->kineticEnergy();
    std::cout << std::setprecision(5) << "[tianracer (d) full lock " << lock
              << " rad, 2 m/s, 10 s] wheel-steps without contact " << lost
              << ", highest wheel centre " << z_max * 1e3 << " mm (r = 32), kinetic energy "
              << e0 << " J at 2 s, " << ke_end << " J at 10 s, max " << ke_max
              << " J, hinges " << car.robot->jointPosition(car.lh) << " / "
              << car.robot->jointPosition(car.rh) << "\n";
    EXPECT_EQ(lost, 0);
    EXPECT_LT(z_max, kWheelRadius + 5e-4);  // no wheel lifts by more than 0.5 mm
    // Bounded: never above the energy of the whole car at 2.5 m/s (translation + wheel spin).
    EXPECT_LT(ke_max, 0.5 * car.robot->totalMass() * 2.5 * 2.5 + 4 * 0.5 * 0.00041226 * std::pow(2.5 / kWheelRadius, 2));
    EXPECT_NEAR(ke_end, e0, 0.05 * e0);  // steady circle: energy steady
  }
}

// Lockstep repeatability: the same command sequence gives the same bits.
TEST(Tianracer, BitIdenticalRepeat) {
  auto run = [] {
    Car car;
    car.run(0.2);
    car.ackermann(0.25, 1.5);
    car.run(1.0);
    car.ackermann(-0.4, 0.8);
    car.run(1.0);
    std::vector<double> out;
    const Eigen::Isometry3d X = car.robot->basePose();
    out.assign(X.data(), X.data() + 16);
    for (int j = 0; j < 6; ++j) out.push_back(car.robot->jointPosition(j));
    return out;
  };
  const std::vector<double> a = run(), b = run();
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;
}

/// Mean normal force on each wheel (kWheels order) and mean longitudinal slip velocity of each
/// rear wheel (r omega minus its centre's speed along the car, m/s) over `seconds`.
struct WheelLoads {
  double load[4] = {0, 0, 0, 0};
  double slip_left = 0.0, slip_right = 0.0;
};
WheelLoads measureLoads(Car& car, double seconds) {
  WheelLoads w;
  const long n = std::lround(seconds / car.world->dt());
  const double dt = car.world->dt();
  Eigen::Vector3d pl = car.robot->linkPose("left_rear_wheel").translation();
  Eigen::Vector3d pr = car.robot->linkPose("right_rear_wheel").translation();
  for (long k = 0; k < n; ++k) {
    car.step();
    for (int i = 0; i < 4; ++i) w.load[i] += car.robot->contactNormalForce(kWheels[i]) / n;
    const Eigen::Vector3d x = car.robot->basePose().rotation().col(0);
    const Eigen::Vector3d ql = car.robot->linkPose("left_rear_wheel").translation();
    const Eigen::Vector3d qr = car.robot->linkPose("right_rear_wheel").translation();
    w.slip_left += (kWheelRadius * car.robot->jointVelocity(car.lr) - (ql - pl).dot(x) / dt) / n;
    w.slip_right += (kWheelRadius * car.robot->jointVelocity(car.rr) - (qr - pr).dot(x) / dt) / n;
    pl = ql;
    pr = qr;
  }
  return w;
}

// Issue 4 (d): in a steady turn all four wheels carry load. The seed's rigid chassis stands on
// a diagonal once steering makes the contact points non-coplanar (world.h, "Tyres"); with the
// seed's stiff contacts alone the outer rear wheel carried 0 N in this turn.
TEST(Tianracer, SteadyTurnSharesTheLoadOverFourWheels) {
  Car car;
  car.run(0.5);
  const WheelLoads straight = measureLoads(car, 0.5);
  double total = 0.0;
  for (double f : straight.load) total += f;
  EXPECT_NEAR(total, car.robot->totalMass() * 9.8, 0.01 * car.robot->totalMass() * 9.8);
  for (double radius : {0.8, -0.8}) {
    Car turning;
    turning.run(0.5);
    turning.ackermann(std::atan(kWheelbase / radius), 0.5);
    turning.run(4.0);
    const WheelLoads w = measureLoads(turning, 4.0);
    std::cout << std::setprecision(4) << "[tianracer turn R " << radius
              << " m, 0.5 m/s] loads LF RF LR RR " << w.load[0] << " " << w.load[1] << " "
              << w.load[2] << " " << w.load[3] << " N (straight " << straight.load[0] << " "
              << straight.load[1] << " " << straight.load[2] << " " << straight.load[3]
              << "); rear slip " << w.slip_left * 1e3 << " / " << w.slip_right * 1e3
              << " mm/s\n";
    for (int i = 0; i < 4; ++i) {
      EXPECT_NEAR(w.load[i], straight.load[i], 0.2 * straight.load[i]) << kWheels[i];
    }
    EXPECT_LT(std::abs(w.slip_left), 1e-3);
    EXPECT_LT(std::abs(w.slip_right), 1e-3);
  }
}

/// tianracer_control's BicycleOdometry, integrated every step: rear wheel speeds and hinge
/// angles, the hinges mapped back to the bicycle angle.
struct WheelOdometry {
  double x = 0.0, y = 0.0, yaw = 0.0;
  void update(const Car& car, double dt) {
    const PhysicsRobot& r = *car.robot;
    const double v = 0.5 * kWheelRadius * (r.jointVelocity(car.lr) + r.jointVelocity(car.rr));
    const double tl = std::tan(r.jointPosition(car.lh)), tr = std::tan(r.jointPosition(car.rh));
    const double dl = std::atan(kWheelbase * tl / (kWheelbase + 0.5 * kHingeTrack * tl));
    const double dr = std::atan(kWheelbase * tr / (kWheelbase - 0.5 * kHingeTrack * tr));
    const double w = v * std::tan(0.5 * (dl + dr)) / kWheelbase;
    x += v * dt * std::cos(yaw + 0.5 * w * dt);
    y += v * dt * std::sin(yaw + 0.5 * w * dt);
    yaw += w * dt;
  }
};

// Issue 4 (d), physics only: figure-eight of 10 m at 0.5 m/s with exact Ackermann angles and
// rear wheel speeds; wheel odometry of the rear axle midpoint vs ground truth.
TEST(Tianracer, FigureEightWheelOdometry) {
  Car car;
  car.run(0.5);
  const double radius = 10.0 / (4.0 * M_PI), v = 0.5, delta = std::atan(kWheelbase / radius);
  const Eigen::Vector3d p0 = car.rearAxle();
  const double yaw0 = car.yaw();
  WheelOdometry odo;
  double travelled = 0.0;
  Eigen::Vector3d p = p0;
  const long lap = std::lround(2.0 * M_PI * radius / v / car.world->dt());
  for (long k = 0; k < 2 * lap + 2000; ++k) {
    if (k == 0) car.ackermann(delta, v);
    if (k == lap) car.ackermann(-delta, v);
    if (k == 2 * lap) car.ackermann(0.0, 0.0);
    car.step();
    odo.update(car, car.world->dt());
    const Eigen::Vector3d q = car.rearAxle();
    travelled += (q - p).head<2>().norm();
    p = q;
  }
  // Truth displacement of the rear axle midpoint in the start frame.
  const Eigen::Vector2d d = Eigen::Rotation2Dd(-yaw0) * (p - p0).head<2>();
  const double yaw_truth = std::remainder(car.yaw() - yaw0, 2.0 * M_PI);
  const double pos_err = std::hypot(odo.x - d.x(), odo.y - d.y());
  const double yaw_err = std::remainder(odo.yaw - yaw_truth, 2.0 * M_PI);
  std::cout << std::setprecision(4) << "[tianracer figure-eight R " << radius << " m, 0.5 m/s] "
            << "travelled " << travelled << " m; truth (" << d.x() << ", " << d.y() << ") m, "
            << yaw_truth * 180 / M_PI << " deg; odometry (" << odo.x << ", " << odo.y << ") m, "
            << odo.yaw * 180 / M_PI << " deg: position error " << 100 * pos_err / travelled
            << " %, heading error " << yaw_err * 180 / M_PI << " deg\n";
  EXPECT_GT(travelled, 9.9);
  EXPECT_LT(pos_err, 0.02 * travelled);
  EXPECT_LT(std::abs(yaw_err), 5.0 * M_PI / 180.0);
}

// Issue 9: spawned straddling a wall (walled_room's north wall: 0.1 m thick, 1 m high, its face
// through base_link). Bullet alone threw the car out at 21 m/s spinning at 460 rad/s; contacts now
// correct at most at max_vel (0.1 m/s, world.h). Along the wall (walled_room at y:=2.0) it is
// pushed out into the room (here, alone with the wall, it ends leaning on it, 2 deg); across it
// (the wall through the chassis) the shortest way out for the chassis is down, into the ground:
// it stays wedged, bounded and still (Bullet alone: 10 km/s).
TEST(Tianracer, SpawnedInAWallIsPushedOutNotThrown) {
  for (const double yaw : {0.0, M_PI / 2}) {
    Car car(PhysicsOptions(), yaw);
    StaticShape wall;
    wall.name = "north_wall";
    wall.shape.size = Eigen::Vector3d(6.2, 0.1, 1.0);
    wall.X_WS.translation() = Eigen::Vector3d(0.0, 0.05, 0.5);  // face y = 0
    car.world->addStaticShape(wall);
    double top = 0.0, top_spin = 0.0;
    bool finite = true;
    for (int k = 0; k < 5000 && finite; ++k) {
      car.step();
      const Twist t = car.robot->baseTwist();
      finite = t.linear.allFinite() && t.angular.allFinite() &&
               car.robot->basePose().matrix().allFinite();
      top = std::max(top, t.linear.norm());
      top_spin = std::max(top_spin, t.angular.norm());
    }
    ASSERT_TRUE(finite) << "yaw " << yaw;
    const Eigen::Vector3d p = car.position();
    const double up = car.robot->basePose().linear()(2, 2);
    std::cout << std::setprecision(4) << "[tianracer spawned in a wall, yaw " << yaw * 180 / M_PI
              << " deg] highest speed " << top << " m/s, spin " << top_spin << " rad/s; after 5 s at ("
              << p.x() << ", " << p.y() << ", " << p.z() * 1e3 << " mm), speed "
              << car.robot->baseTwist().linear.norm() << " m/s, cos(tilt) " << up << "\n";
    EXPECT_LT(top, 0.5);       // was 21 m/s
    EXPECT_LT(top_spin, 5.0);  // was 460 rad/s
    EXPECT_LT((p - Eigen::Vector3d(0, 0, kSpawnZ)).head<2>().norm(), 0.2);  // not thrown
    EXPECT_GT(up, 0.99);
    EXPECT_LT(car.robot->baseTwist().linear.norm(), 0.01);  // settled
    if (yaw == 0.0) {
      EXPECT_LT(p.y(), -0.05);                // out on the room's side, on its wheels
      EXPECT_NEAR(p.z(), kSpawnZ, 2e-3);
    }
  }
}

}  // namespace
}  // namespace tianracer_sim
