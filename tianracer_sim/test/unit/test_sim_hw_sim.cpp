// gazebo_ros_control's DefaultRobotHWSim between the controllers and the joints
// (sim/robot_hw_sim.h; issue 39, point 3): the URDF <limit> and <safety_controller>, the
// joint_limits/<joint> and gazebo_ros_control/pid_gains/<joint> parameters, the e-stop. A
// heavy base with four joints about z (gravity does not load them): a prismatic slider
// (effort interface, soft limits), a continuous spinner (velocity, limited), a revolute hinge
// (position) and a continuous free wheel (velocity, no <limit>).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sim_test_support.h"
#include "tianracer_control/controller_yaml.h"

namespace tianracer_sim {
namespace {

namespace tc = tianracer_control;

const char* const kUrdf = R"(<?xml version="1.0"?>
<robot name="hw">
  <link name="base_link">
    <inertial><mass value="80"/><inertia ixx="2" ixy="0" ixz="0" iyy="2" iyz="0" izz="2"/></inertial>
    <collision><origin xyz="0 0 0.05"/><geometry><box size="0.8 0.8 0.1"/></geometry></collision>
  </link>
  <link name="slider_link">
    <inertial><mass value="1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
  <link name="spinner_link">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="hinge_link">
    <inertial><origin xyz="0.1 0 0"/><mass value="0.5"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.002"/></inertial>
  </link>
  <link name="wheel_link">
    <inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <joint name="slider" type="prismatic">
    <parent link="base_link"/><child link="slider_link"/><origin xyz="0 0 0.2"/><axis xyz="0 1 0"/>
    <limit lower="-0.5" upper="0.5" velocity="1.0" effort="30"/>
    <safety_controller soft_lower_limit="-0.3" soft_upper_limit="0.3" k_position="20" k_velocity="50"/>
  </joint>
  <joint name="spinner" type="continuous">
    <parent link="base_link"/><child link="spinner_link"/><origin xyz="0.3 0 0.2"/><axis xyz="0 0 1"/>
    <limit velocity="4.0" effort="5"/>
  </joint>
  <joint name="hinge" type="revolute">
    <parent link="base_link"/><child link="hinge_link"/><origin xyz="-0.3 0 0.2"/><axis xyz="0 0 1"/>
    <limit lower="-1.0" upper="1.0" velocity="2.0" effort="8"/>
  </joint>
  <joint name="free_wheel" type="continuous">
    <parent link="base_link"/><child link="wheel_link"/><origin xyz="0 0.3 0.2"/><axis xyz="0 0 1"/>
  </joint>
  <transmission name="t1"><type>transmission_interface/SimpleTransmission</type>
    <joint name="slider"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="a1"/></transmission>
  <transmission name="t2"><type>transmission_interface/SimpleTransmission</type>
    <joint name="spinner"><hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint>
    <actuator name="a2"/></transmission>
  <transmission name="t3"><type>transmission_interface/SimpleTransmission</type>
    <joint name="hinge"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
    <actuator name="a3"/></transmission>
  <transmission name="t4"><type>transmission_interface/SimpleTransmission</type>
    <joint name="free_wheel"><hardwareInterface>hardware_interface/VelocityJointInterface</hardwareInterface></joint>
    <actuator name="a4"/></transmission>
  <gazebo>
    <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">
      <robotNamespace>/hw</robotNamespace>
    </plugin>
  </gazebo>
</robot>
)";

const char* const kControllers =
    "hw:\n"
    "  slider_controller: {type: effort_controllers/JointEffortController, joint: slider}\n"
    "  spinner_controller: {type: velocity_controllers/JointVelocityController, joint: spinner}\n"
    "  hinge_controller: {type: position_controllers/JointPositionController, joint: hinge}\n"
    "  wheel_controller: {type: velocity_controllers/JointVelocityController, joint: free_wheel}\n";

using Method = RobotHwSim::Method;
using Limits = RobotHwSim::Limits;

class HwSim : public ::testing::Test {
 protected:
  HwSim() : sim_(PhysicsOptions(), [this](const std::string& w) { warnings_.push_back(w); }) {}

  void add(const RobotHwSimParams& params = RobotHwSimParams()) {
    RobotConfig config;
    config.name = "hw";
    config.model = loadRobotModel(kUrdf, "hw.urdf", LoadOptions());
    config.drop_to_ground = true;
    config.controllers = tc::loadControllerYaml(kControllers, "hw.yaml", "hw");
    config.hw_sim = params;
    robot_ = &sim_.addRobot(std::move(config));
  }
  size_t handle(const std::string& joint) const {
    for (size_t k = 0; k < robot_->handles.size(); ++k)
      if (robot_->handles[k].name == joint) return k;
    ADD_FAILURE() << "no handle " << joint;
    return 0;
  }
  const RobotHwSim::Joint& joint(const std::string& name) const {
    return robot_->hw_sim.joints()[handle(name)];
  }
  double position(const std::string& name) {
    PhysicsRobot& pr = sim_.physics().robot(robot_->id);
    return pr.jointPosition(pr.jointIndex(name));
  }
  double velocity(const std::string& name) {
    PhysicsRobot& pr = sim_.physics().robot(robot_->id);
    return pr.jointVelocity(pr.jointIndex(name));
  }
  void command(const std::string& controller, double value) {
    tc::Controller* c = robot_->controllers.find(controller);
    ASSERT_NE(c, nullptr) << controller;
    ASSERT_TRUE(c->setCommand(value));
  }
  void run(double seconds) {
    const auto n = static_cast<long>(std::lround(seconds / sim_.dt()));
    for (long i = 0; i < n; ++i) sim_.step();
  }
  bool warned(const std::string& part) const {
    for (const std::string& w : warnings_)
      if (w.find(part) != std::string::npos) return true;
    return false;
  }
  std::string allWarnings() const {
    std::string s;
    for (const std::string& w : warnings_) s += w + "\n";
    return s;
  }

  std::vector<std::string> warnings_;
  Simulation sim_;
  SimRobot* robot_ = nullptr;
};

tc::ParamValue dict(std::initializer_list<std::pair<const char*, tc::ParamValue>> members) {
  tc::ParamValue d = tc::ParamValue::dict();
  for (const auto& m : members) d[m.first] = m.second;
  return d;
}

TEST_F(HwSim, TheUrdfLimitsRegisterSoftLimitsOrSaturationHandles) {
  add();
  EXPECT_EQ(joint("slider").limits_kind, Limits::kSoftLimits);  // <safety_controller>
  EXPECT_EQ(joint("spinner").limits_kind, Limits::kSaturation);
  EXPECT_EQ(joint("hinge").limits_kind, Limits::kSaturation);
  EXPECT_EQ(joint("free_wheel").limits_kind, Limits::kNone);  // no <limit>
  EXPECT_DOUBLE_EQ(joint("spinner").limits.max_velocity, 4.0);
  EXPECT_FALSE(joint("spinner").limits.has_position_limits);  // continuous
  EXPECT_DOUBLE_EQ(joint("hinge").effortLimit(), 8.0);
  EXPECT_EQ(joint("free_wheel").effortLimit(), std::numeric_limits<double>::max());  // DRS: unbounded
  EXPECT_DOUBLE_EQ(joint("slider").soft.max_position, 0.3);
  EXPECT_DOUBLE_EQ(joint("slider").soft.k_velocity, 50.0);
  EXPECT_EQ(joint("hinge").method, Method::kPosition);  // no pid_gains
}

TEST_F(HwSim, SoftLimitsStopAnEffortJointNearTheSoftLimit) {
  add();
  command("slider_controller", 30.0);  // the whole effort limit, outwards
  run(3.0);
  const double x = position("slider");
  std::cout << "slider at " << x << " m under 30 N (soft limit 0.3, hard 0.5)\n";
  EXPECT_GT(x, 0.25);
  EXPECT_LT(x, 0.31);
  // the command the joint got: what the soft-limits handle left (written back to the handle)
  EXPECT_LT(robot_->handles[handle("slider")].command, 30.0);
}

TEST_F(HwSim, AJointLimitsParameterOverridesTheUrdf) {
  RobotHwSimParams p;
  p.ns = "/hw";
  p.joint_limits = tc::ParamValue::dict();
  p.joint_limits["hinge"] =
      dict({{"has_position_limits", true}, {"min_position", -0.3}, {"max_position", 0.3}});
  p.joint_limits["spinner"] =
      dict({{"has_acceleration_limits", true}, {"max_acceleration", 2}});  // an int is a double
  add(p);
  EXPECT_DOUBLE_EQ(joint("hinge").limits.max_position, 0.3);
  EXPECT_DOUBLE_EQ(joint("hinge").limits.max_velocity, 2.0);  // still the URDF's
  EXPECT_DOUBLE_EQ(joint("spinner").limits.max_acceleration, 2.0);

  command("hinge_controller", 0.9);  // within the URDF's 1.0, past the parameter's 0.3
  command("spinner_controller", 3.0);
  run(0.5);
  // 2 rad/s^2 for 0.5 s from 0: the spinner's command has reached 1 rad/s
  EXPECT_NEAR(robot_->handles[handle("spinner")].command, 1.0, 0.01);
  EXPECT_NEAR(velocity("spinner"), 1.0, 0.05);
  run(1.5);
  EXPECT_DOUBLE_EQ(robot_->handles[handle("hinge")].command, 0.3);
  EXPECT_NEAR(position("hinge"), 0.3, 2e-3);
  EXPECT_NEAR(velocity("spinner"), 3.0, 0.05);
  EXPECT_TRUE(warnings_.empty() || !warned("joint_limits")) << allWarnings();
}

// The controllers pass commands past the joint's limits on as they are (as upstream's); the
// hardware's saturation handles limit them, as DefaultRobotHWSim's do.
TEST_F(HwSim, CommandsPastTheUrdfLimitsAreLimitedByTheHardwareNotTheControllers) {
  add();
  command("spinner_controller", 1e9);  // URDF velocity 4
  command("hinge_controller", 5.0);    // URDF upper 1
  run(0.002);
  const tc::Controller* spinner = robot_->controllers.find("spinner_controller");
  ASSERT_NE(spinner, nullptr);
  EXPECT_DOUBLE_EQ(spinner->command(), 1e9);  // the controller's own command: raw
  EXPECT_DOUBLE_EQ(robot_->handles[handle("spinner")].command, 4.0);
  // PositionJointSaturationHandle: within the URDF velocity (2 rad/s) of its last command
  EXPECT_NEAR(robot_->handles[handle("hinge")].command, 2.0 * 0.002, 1e-12);
  run(2.0);
  EXPECT_DOUBLE_EQ(robot_->handles[handle("hinge")].command, 1.0);  // then the position limit
  EXPECT_NEAR(velocity("spinner"), 4.0, 0.05);
  EXPECT_NEAR(position("hinge"), 1.0, 2e-3);
}

TEST(RobotHwSimWrite, AVelocityCommandIsSaturatedAtTheUrdfVelocity) {
  // (our velocity controllers clamp too; the hardware does it whatever the controller)
  RobotModel model = loadRobotModel(kUrdf, "hw.urdf", LoadOptions());
  tc::JointHandle spinner;
  spinner.name = "spinner";
  spinner.interface = tc::JointHandle::Interface::kVelocity;
  RobotHwSim hw;
  hw.init(model, {spinner}, RobotHwSimParams(), WarningSink());
  spinner.command = 10.0;
  const JointDrive d = hw.write(0, spinner, 0.001);
  EXPECT_EQ(d.mode, JointDrive::Mode::kVelocity);
  EXPECT_DOUBLE_EQ(d.value, 4.0);
  EXPECT_DOUBLE_EQ(d.max_effort, 5.0);  // the motor's cap: the effort limit
  EXPECT_DOUBLE_EQ(spinner.command, 4.0);  // written back, as the handle does
  spinner.command = -10.0;
  EXPECT_DOUBLE_EQ(hw.write(0, spinner, 0.001).value, -4.0);
}

TEST_F(HwSim, BadParametersAreWarnedWithTheirNameAndLeftOut) {
  RobotHwSimParams p;
  p.ns = "/hw";
  p.joint_limits = tc::ParamValue::dict();
  p.joint_limits["hinge"] = dict({{"has_position_limits", true}, {"min_position", -0.3},
                                  {"max_position", "far"}});
  p.joint_limits["spinner"] = dict({{"has_velocity_limits", false}});
  p.joint_limits["slider"] = tc::ParamValue(3.0);
  p.pid_gains = tc::ParamValue::dict();
  p.pid_gains["hinge"] = dict({{"i", 1.0}});
  p.pid_gains["free_wheel"] = dict({{"p", 1.0}, {"i_clamp_min", 2.0}, {"i_clamp_max", 1.0}});
  add(p);
  EXPECT_TRUE(warned("/hw/joint_limits/hinge/max_position is a string, not a number; ignored"))
      << allWarnings();
  EXPECT_DOUBLE_EQ(joint("hinge").limits.max_position, 1.0);  // the URDF's stays
  EXPECT_TRUE(warned("/hw/joint_limits/spinner: cannot enforce limits for joint 'spinner'. It "
                     "has no velocity limits specification"))
      << allWarnings();
  EXPECT_EQ(joint("spinner").limits_kind, Limits::kNone);
  EXPECT_TRUE(warned("/hw/joint_limits/slider: is a double, not a dictionary; ignored"))
      << allWarnings();
  EXPECT_EQ(joint("slider").limits_kind, Limits::kSoftLimits);
  EXPECT_TRUE(warned("/hw/gazebo_ros_control/pid_gains/hinge: no p gain specified"))
      << allWarnings();
  EXPECT_EQ(joint("hinge").method, Method::kPosition);
  EXPECT_TRUE(warned("/hw/gazebo_ros_control/pid_gains/free_wheel: ")) << allWarnings();
  EXPECT_TRUE(warned("i_clamp_min (2) is greater than")) << allWarnings();
  EXPECT_EQ(joint("free_wheel").method, Method::kVelocity);
  // and the robot runs
  command("hinge_controller", 0.5);
  run(1.0);
  EXPECT_NEAR(position("hinge"), 0.5, 2e-3);
}

TEST_F(HwSim, PidGainsDriveAPositionJointByEffort) {
  RobotHwSimParams p;
  p.ns = "/hw";
  p.pid_gains = tc::ParamValue::dict();
  p.pid_gains["hinge"] = dict({{"p", 20.0}, {"d", 1.0}});
  p.pid_gains["spinner"] = dict({{"p", 2.0}});
  add(p);
  EXPECT_EQ(joint("hinge").method, Method::kPositionPid);
  EXPECT_EQ(joint("spinner").method, Method::kVelocityPid);
  EXPECT_EQ(joint("slider").method, Method::kEffort);  // effort joints take no gains
  command("hinge_controller", 0.5);
  command("spinner_controller", 3.0);
  run(0.05);
  // the hinge's first write: 20 * 0.5 = 10 N m, clamped to the effort limit 8
  EXPECT_GT(velocity("hinge"), 0.0);
  run(3.0);
  std::cout << "hinge at " << position("hinge") << " rad, spinner at " << velocity("spinner")
            << " rad/s under PID\n";
  EXPECT_NEAR(position("hinge"), 0.5, 0.01);
  EXPECT_NEAR(velocity("spinner"), 3.0, 0.05);
}

TEST(RobotHwSimWrite, APidCommandIsClampedToTheEffortLimit) {
  RobotModel model = loadRobotModel(kUrdf, "hw.urdf", LoadOptions());
  tc::JointHandle hinge;
  hinge.name = "hinge";
  hinge.interface = tc::JointHandle::Interface::kPosition;
  RobotHwSimParams p;
  p.pid_gains = tc::ParamValue::dict();
  p.pid_gains["hinge"] = dict({{"p", 1e6}});
  RobotHwSim hw;
  hw.init(model, {hinge}, p, WarningSink());
  hinge.command = 0.5;
  JointDrive d = hw.write(0, hinge, 0.001);
  EXPECT_EQ(d.mode, JointDrive::Mode::kEffort);
  EXPECT_DOUBLE_EQ(d.value, 8.0);
  // the saturation handle first: 2 rad/s * 1 ms from the position 0
  EXPECT_DOUBLE_EQ(hinge.command, 0.002);
  hinge.position = 0.3;
  hinge.command = -0.5;
  d = hw.write(0, hinge, 0.001);
  EXPECT_DOUBLE_EQ(hinge.command, 0.0);  // 2 mm/ms below the previous command
  EXPECT_DOUBLE_EQ(d.value, -8.0);
}

TEST(RobotHwSimWrite, AMotorWithoutAnEffortLimitIsUnbounded) {
  // DRS: SetParam("fmax", 0, DBL_MAX) for a joint with no effort limit (not our old 10 N m)
  RobotModel model = loadRobotModel(kUrdf, "hw.urdf", LoadOptions());
  tc::JointHandle wheel;
  wheel.name = "free_wheel";
  wheel.interface = tc::JointHandle::Interface::kVelocity;
  RobotHwSim hw;
  hw.init(model, {wheel}, RobotHwSimParams(), WarningSink());
  wheel.command = 100.0;
  const JointDrive d = hw.write(0, wheel, 0.001);
  EXPECT_DOUBLE_EQ(d.value, 100.0);  // no velocity limit either
  EXPECT_EQ(d.max_effort, std::numeric_limits<double>::max());
}

TEST_F(HwSim, AWheelWithoutAnEffortLimitFollowsItsCommandAtOnce) {
  add();
  command("wheel_controller", 50.0);
  run(0.01);
  // 50 rad/s in 10 ms of a 0.01 kg m^2 wheel takes 50 N m: beyond the old 10 N m cap
  EXPECT_NEAR(velocity("free_wheel"), 50.0, 0.5);
}

TEST_F(HwSim, APositionJointWithoutGainsIsPutAtItsCommandAsDefaultRobotHwSimSetsIt) {
  // DRS writeSim: SetPosition(0, command, true), no motor. The command goes through the
  // saturation handle (2 rad/s from the previous command), so the hinge ramps at 2 rad/s and
  // then sits exactly on 0.5, never past it. The servo it replaced (a velocity motor capped at
  // the effort limit) overshot and circled the target by up to its stopping distance.
  add();
  command("hinge_controller", 0.5);
  double highest = -1.0;
  for (int i = 0; i < 1000; ++i) {  // 1 s
    run(0.001);
    highest = std::max(highest, position("hinge"));
    if (i == 99) {
      EXPECT_NEAR(position("hinge"), 0.2, 0.003) << "ramp at 2 rad/s";
    }
  }
  EXPECT_LE(highest, 0.5 + 1e-6);
  EXPECT_NEAR(position("hinge"), 0.5, 1e-6);
  EXPECT_NEAR(velocity("hinge"), 0.0, 1e-4);  // the base under it settles
  // beyond the URDF limit (1.0): the saturation handle clamps, the joint sits on the limit
  command("hinge_controller", 3.0);
  run(1.0);
  EXPECT_NEAR(position("hinge"), 1.0, 1e-6);
}

TEST(RobotHwSimWrite, TheEStopWritesNoEffortAndNoVelocity) {
  RobotModel model = loadRobotModel(kUrdf, "hw.urdf", LoadOptions());
  tc::JointHandle slider, spinner;
  slider.name = "slider";
  slider.interface = tc::JointHandle::Interface::kEffort;
  spinner.name = "spinner";
  spinner.interface = tc::JointHandle::Interface::kVelocity;
  RobotHwSim hw;
  hw.init(model, {slider, spinner}, RobotHwSimParams(), WarningSink());
  slider.command = 5.0;
  spinner.command = 3.0;
  EXPECT_DOUBLE_EQ(hw.write(0, slider, 0.001).value, 5.0);
  EXPECT_DOUBLE_EQ(hw.write(1, spinner, 0.001).value, 3.0);
  hw.setEStop(true);
  hw.beginWrite({slider, spinner});
  EXPECT_DOUBLE_EQ(hw.write(0, slider, 0.001).value, 0.0);
  EXPECT_DOUBLE_EQ(hw.write(1, spinner, 0.001).value, 0.0);
  EXPECT_FALSE(hw.takeEStopReleased());
  hw.setEStop(false);
  EXPECT_TRUE(hw.takeEStopReleased());  // once
  EXPECT_FALSE(hw.takeEStopReleased());
  EXPECT_DOUBLE_EQ(hw.write(0, slider, 0.001).value, 5.0);
}

TEST(RobotHwSimWrite, PositionPidErrors) {
  RobotHwSim::Joint continuous;
  continuous.type = RobotHwSim::Joint::Type::kContinuous;
  EXPECT_NEAR(positionPidError(continuous, 3.0, -3.0), 2.0 * M_PI - 6.0, 1e-12);
  RobotHwSim::Joint revolute;
  revolute.type = RobotHwSim::Joint::Type::kRevolute;
  revolute.limits.has_position_limits = true;
  revolute.limits.min_position = -3.1;
  revolute.limits.max_position = 3.1;
  // within the limits the way round through pi is closed: the plain difference
  EXPECT_NEAR(positionPidError(revolute, 3.0, -3.0), -6.0, 1e-12);
  RobotHwSim::Joint prismatic;
  EXPECT_NEAR(positionPidError(prismatic, 3.0, -3.0), -6.0, 1e-12);
}

TEST_F(HwSim, TheEStopHoldsPositionsStopsVelocityAndEffortAndResetsControllersOnRelease) {
  add();
  command("hinge_controller", 0.8);
  command("spinner_controller", 3.0);
  command("wheel_controller", 2.0);
  run(0.2);  // the hinge on its way (2 rad/s)
  robot_->hw_sim.setEStop(true);
  run(0.002);
  const double held = position("hinge");
  EXPECT_GT(held, 0.2);
  EXPECT_LT(held, 0.7);
  run(1.0);
  EXPECT_NEAR(position("hinge"), held, 5e-3);
  EXPECT_NEAR(robot_->handles[handle("hinge")].command, held, 5e-3);
  EXPECT_NEAR(velocity("spinner"), 0.0, 0.05);
  EXPECT_NEAR(velocity("free_wheel"), 0.0, 0.05);

  // released: the controllers restart (a position controller holds where the joint is, the
  // velocity ones command 0) until new commands come
  robot_->hw_sim.setEStop(false);
  run(1.0);
  EXPECT_NEAR(position("hinge"), held, 5e-3);
  EXPECT_NEAR(velocity("spinner"), 0.0, 0.05);
  command("hinge_controller", 0.0);
  run(1.0);
  EXPECT_NEAR(position("hinge"), 0.0, 2e-3);
}

}  // namespace
}  // namespace tianracer_sim
