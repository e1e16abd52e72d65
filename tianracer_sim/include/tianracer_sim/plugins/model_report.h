// The start-up table of a robot: each plugin and sensor of its model, and whether the simulator
// simulates it, simulates it with named differences from Gazebo, or leaves it out (and why).
// ROS-free: the node logs it, model_info prints it.
#ifndef TIANRACER_SIM_PLUGINS_MODEL_REPORT_H
#define TIANRACER_SIM_PLUGINS_MODEL_REPORT_H

#include <map>
#include <string>
#include <vector>

#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {

/// One plugin or sensor of a model.
struct ReportRow {
  enum class Status { kSimulated, kDifferences, kLeftOut };
  std::string kind;  // "plugin" or "sensor"
  std::string name;
  std::string type;  // the sensor type, or the plugin's filename
  std::string link;  // the sensor's link or the plugin's bodyName; "" for none
  Status status = Status::kSimulated;
  std::vector<std::string> topics;  // what it publishes: "/ns/imu sensor_msgs/Imu @ 100 Hz"
                                    // (for gazebo_ros_control, where its controllers run)
  std::vector<std::string> notes;   // the differences, or why it is left out
};

/// What the node knows beyond the model: sensors it leaves out by name (~disable_sensors or a
/// failure while setting one up, e.g. an unknown link) with the reason.
using LeftOut = std::map<std::string, std::string>;

/// Every model plugin (model order), then every sensor (by link). A sensor or plugin the
/// sensor registry simulates is parsed as the node parses it: an error leaves it out, a
/// warning is a named difference. gazebo_ros_control and joint_state_publisher are simulated;
/// any other plugin is left out as not simulated.
std::vector<ReportRow> modelReport(const RobotModel& model, const std::string& robot_name,
                                   const LeftOut& left_out = {});

/// The table as text:
///   robot 'NAME': N plugins and sensors: S simulated, D with differences, L left out
///     KIND    NAME  TYPE  LINK  STATUS
///             topic / difference / reason lines under their row
std::string formatModelReport(const std::string& robot_name, const std::vector<ReportRow>& rows);

/// Why a gazebo_plugins model plugin we know of is left out (libgazebo_ros_force,
/// libgazebo_ros_template), for the table and the world's log; "" for others.
std::string leftOutPluginReason(const std::string& filename);

/// Why a sensor the user switched off with ~disable_sensors is left out.
extern const char kDisabledBySensorList[];

/// Whether the table is a warning: something is left out that the user did not switch off
/// (the model does less here than in Gazebo).
bool leavesOutUnasked(const std::vector<ReportRow>& rows);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_MODEL_REPORT_H
