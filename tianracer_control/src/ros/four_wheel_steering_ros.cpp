// The ROS side of four_wheel_steering_controller/FourWheelSteeringController (ros_controllers
// noetic-devel, four_wheel_steering_controller/src/four_wheel_steering_controller.cpp: init(),
// cmdVelCallback(), cmdFourWheelSteeringCallback(), setOdomPubFields(), updateOdometry()'s
// publications):
//   <controller>/cmd_vel                  geometry_msgs/Twist, queue 1: linear.x, linear.y, angular.z;
//   <controller>/cmd_four_wheel_steering  four_wheel_steering_msgs/FourWheelSteering, queue 1;
//   <controller>/odom                     nav_msgs/Odometry "odom" -> base_frame_id at publish_rate
//                                         (linear.x, linear.y, angular.z);
//   <controller>/odom_steer               four_wheel_steering_msgs/FourWheelSteeringStamped, "odom":
//                                         speed, acceleration, jerk, the axles' angles and rates;
//   /tf                                   "odom" -> base_frame_id (enable_odom_tf).
// Upstream's odom frame is "odom" whatever odom_frame_id says.
#include <mutex>
#include <optional>

#include <four_wheel_steering_msgs/FourWheelSteering.h>
#include <four_wheel_steering_msgs/FourWheelSteeringStamped.h>
#include <geometry_msgs/Twist.h>
#include <ros/console.h>
#include <ros/publisher.h>
#include <ros/subscriber.h>

#include "tianracer_control/controllers/four_wheel_steering_controller.h"
#include "tianracer_control/ros/controller_ros.h"
#include "tianracer_control/ros/odom_tf_publisher.h"

namespace tianracer_control {

namespace {

class FourWheelSteeringRos : public ControllerRosSide {
 public:
  static std::unique_ptr<ControllerRosSide> create(RosSideContext& context) {
    return std::make_unique<FourWheelSteeringRos>(context);
  }

  explicit FourWheelSteeringRos(RosSideContext& context)
      : controller_(dynamic_cast<FourWheelSteeringController&>(context.controller)),
        set_(context.set),
        odom_("odom", controller_.common()) {
    const FourWheelSteeringController::Params& g = controller_.params();
    ROS_INFO_STREAM_NAMED(controller_.name(), "controller '" << controller_.name() << "': Odometry params : track "
                          << g.track << ", wheel radius " << g.wheel_radius << ", wheel base " << g.wheel_base
                          << ", wheel steering offset " << g.wheel_steering_y_offset);
    ros::NodeHandle& nh = context.controller_nh;
    // init() writes back what it took from the URDF.
    nh.setParam("track", g.track);
    nh.setParam("wheel_steering_y_offset", g.wheel_steering_y_offset);
    nh.setParam("wheel_radius", g.wheel_radius);
    nh.setParam("wheel_base", g.wheel_base);
    odom_.advertise(nh, context.root_nh);
    steer_pub_ = nh.advertise<four_wheel_steering_msgs::FourWheelSteeringStamped>("odom_steer", 100);
    steer_.header.frame_id = "odom";
    twist_sub_ = nh.subscribe<geometry_msgs::Twist>("cmd_vel", 1, [this](const geometry_msgs::Twist::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      twist_ = *m;
    });
    four_ws_sub_ = nh.subscribe<four_wheel_steering_msgs::FourWheelSteering>(
        "cmd_four_wheel_steering", 1, [this](const four_wheel_steering_msgs::FourWheelSteering::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          four_ws_ = *m;
        });
  }

  void apply() override {
    std::optional<geometry_msgs::Twist> twist;
    std::optional<four_wheel_steering_msgs::FourWheelSteering> four_ws;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      twist.swap(twist_);
      four_ws.swap(four_ws_);
    }
    if (!twist && !four_ws) return;
    if (!set_.isRunning(controller_)) {
      ROS_ERROR_NAMED(controller_.name(), "Can't accept new commands. Controller is not running.");
      return;
    }
    if (twist && !controller_.setTwist(twist->linear.x, twist->linear.y, twist->angular.z)) {
      nan_.warn("controller '" + controller_.name() + "': Received NaN in geometry_msgs::Twist. Ignoring command.");
    }
    if (four_ws &&
        !controller_.setFourWheelSteering(four_ws->front_steering_angle, four_ws->rear_steering_angle, four_ws->speed)) {
      nan_.warn("controller '" + controller_.name() +
                "': Received NaN in four_wheel_steering_msgs::FourWheelSteering. Ignoring command.");
    }
  }

  void publish(double) override {
    for (const FourWheelSteeringController::OdomSample& s : controller_.takeOdom()) {
      odom_.publishOdom(s.t, s.x, s.y, s.heading, s.linear_x, s.linear_y, s.angular);
      steer_.header.stamp = ros::Time(s.t);
      steer_.data.speed = s.speed;
      steer_.data.acceleration = s.acceleration;
      steer_.data.jerk = s.jerk;
      steer_.data.front_steering_angle = s.front_steering;
      steer_.data.front_steering_angle_velocity = s.front_steering_velocity;
      steer_.data.rear_steering_angle = s.rear_steering;
      steer_.data.rear_steering_angle_velocity = s.rear_steering_velocity;
      steer_pub_.publish(steer_);
      if (s.tf) odom_.publishTf(s.t, s.x, s.y, s.heading);
    }
  }

  void clear() override {
    std::lock_guard<std::mutex> lock(mutex_);
    twist_.reset();
    four_ws_.reset();
  }
  std::vector<std::string> commandTopics() const override {
    return {twist_sub_.getTopic(), four_ws_sub_.getTopic()};
  }

 private:
  FourWheelSteeringController& controller_;
  const ControllerSet& set_;
  ros::Subscriber twist_sub_, four_ws_sub_;
  OdomTfPublisher odom_;
  ros::Publisher steer_pub_;
  four_wheel_steering_msgs::FourWheelSteeringStamped steer_;
  std::mutex mutex_;
  std::optional<geometry_msgs::Twist> twist_;
  std::optional<four_wheel_steering_msgs::FourWheelSteering> four_ws_;
  ThrottledWarning nan_;
};

}  // namespace

TIANRACER_CONTROLLER_ROS_SIDE(FourWheelSteeringController::kType, FourWheelSteeringRos::create);

}  // namespace tianracer_control
