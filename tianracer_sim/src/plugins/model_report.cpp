#include "tianracer_sim/plugins/model_report.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include <urdf_model/model.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/plugins/sensor_topics.h"
#include "tianracer_sim/render/camera_intrinsics.h"
#include "tianracer_sim/plugins/camera/camera_config.h"
#include "tianracer_sim/plugins/camera/optical_frame.h"
#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {
namespace {


// Differences of a sensor type (docs/simulator.md, Known differences and limits); a camera's
// by its frame (plugins/camera/optical_frame.h).
std::vector<std::string> typeDifferences(const RobotModel& model, const SensorSpec& s) {
  std::vector<std::string> out;
  if (s.type == "gpu_ray") out.push_back("ray-cast on the CPU (Embree), exactly as type ray");
  if (s.type == "camera" || s.type == "wideanglecamera" || s.type == "depth" ||
      s.type == "multicamera") {
    // The simulator's own decision (sim_camera.cpp), from the settings as it parses them; a
    // camera that does not parse is left out below, with its error.
    bool own = false;
    try {
      if (s.type != "multicamera") {
        const CameraConfig c =
            s.type == "depth" ? parseDepthCameraConfig(s).camera : parseCameraConfig(s);
        own = usesOwnOpticalFrame(model.urdf.get(), c);
      }
    } catch (const std::exception&) {
    }
    if (!own) {
      out.push_back("images are stamped in <frameName>_optical_frame (z forward), not the plain "
                    "frame");
    }
  }
  return out;
}

// Differences of a model plugin the registry simulates, by what it is set to (docs/model_and_sensors.md).
std::vector<std::string> pluginDifferences(const SensorSpec& s) {
  std::vector<std::string> out;
  if (s.plugins.size() != 1) return out;
  const PluginSpec& p = s.plugins.front();
  const auto param = [&](const char* key) {
    const auto it = p.params.find(key);
    return it == p.params.end() ? std::string() : trimText(it->second);
  };
  if (baseName(p.filename) == "libgazebo_ros_diff_drive.so" && param("odometrySource") == "encoder")
    out.push_back("encoder odometry's linear.x is signed (upstream publishes its magnitude)");
  return out;
}

// Fills status, topics and notes of a sensor or plugin the registry may simulate.
void simulate(const RobotModel& model, const SensorSpec& s, const std::string& robot_name,
              const LeftOut& left_out, ReportRow* row) {
  const auto out = left_out.find(s.name);
  if (out != left_out.end()) {
    row->status = ReportRow::Status::kLeftOut;
    row->notes.push_back(out->second);
    return;
  }
  if (!s.error.empty()) {
    row->status = ReportRow::Status::kLeftOut;
    row->notes.push_back(s.error);
    return;
  }
  if (!s.link.empty() && !model.urdf->getLink(s.link)) {
    row->status = ReportRow::Status::kLeftOut;
    row->notes.push_back("link '" + s.link + "' is not a link of the model");
    return;
  }
  const SensorKind* kind = findSensorKind(s);
  if (!kind) {
    row->status = ReportRow::Status::kLeftOut;
    row->notes.push_back("sensor type '" + s.type + "' is not simulated");
    return;
  }
  std::vector<std::string> warnings = typeDifferences(model, s);
  for (const std::string& d : pluginDifferences(s)) warnings.push_back(d);
  try {
    const std::vector<SensorTopic> topics = kind->topics(s, robot_name, [&](const std::string& w) {
      if (std::find(warnings.begin(), warnings.end(), w) == warnings.end()) warnings.push_back(w);
    });
    for (const SensorTopic& t : topics) {
      const bool in = t.msg_type.find("(subscribed)") != std::string::npos;  // a command topic
      // Rate 0 is Gazebo's "as often as it can": every step here.
      const std::string rate = t.rate > 0.0 ? " @ " + formatShort(t.rate) + " Hz" : " every step";
      row->topics.push_back(t.topic + " " + t.msg_type + (in ? "" : rate));
    }
    if (topics.empty()) row->topics.push_back("(no gazebo_ros plugin: nothing published)");
  } catch (const std::exception& e) {
    row->status = ReportRow::Status::kLeftOut;
    row->notes.assign(1, e.what());
    return;
  }
  row->notes = warnings;
  row->status = warnings.empty() ? ReportRow::Status::kSimulated : ReportRow::Status::kDifferences;
}

const char* statusText(ReportRow::Status s) {
  switch (s) {
    case ReportRow::Status::kSimulated: return "simulated";
    case ReportRow::Status::kDifferences: return "simulated, with differences";
    case ReportRow::Status::kLeftOut: return "left out";
  }
  return "";
}

}  // namespace

std::vector<ReportRow> modelReport(const RobotModel& model, const std::string& robot_name,
                                   const LeftOut& left_out) {
  std::vector<ReportRow> rows;
  for (const PluginSpec& p : model.ext.model_plugins) {
    ReportRow row;
    row.kind = "plugin";
    row.name = p.name;
    row.type = baseName(p.filename);
    const SensorSpec as_sensor = modelPluginSensor(p);
    row.link = as_sensor.link;
    if (row.type == "libgazebo_ros_control.so" && model.ext.ros_control) {
      const std::string ns = model.ext.ros_control->robot_namespace.empty()
                                 ? "/" + robot_name
                                 : resolveTopic("", model.ext.ros_control->robot_namespace);
      row.topics.push_back("runs the controllers of the YAML under " + ns);
    } else if (row.type == "libgazebo_ros_joint_state_publisher.so" &&
               model.ext.joint_state_publisher) {
      const auto& jsp = *model.ext.joint_state_publisher;
      row.topics.push_back(resolveTopic(jsp.robot_namespace, "joint_states") +
                           " sensor_msgs/JointState @ " + formatShort(jsp.update_rate) + " Hz");
    } else if (findSensorKind(as_sensor)) {
      simulate(model, as_sensor, robot_name, left_out, &row);
    } else {
      row.status = ReportRow::Status::kLeftOut;
      const std::string why = leftOutPluginReason(row.type);
      row.notes.push_back(why.empty() ? "plugin '" + row.type + "' is not simulated" : why);
    }
    rows.push_back(std::move(row));
  }
  for (const auto& [link, ext] : model.ext.links) {
    for (const SensorSpec& s : ext.sensors) {
      ReportRow row;
      row.kind = "sensor";
      row.name = s.name;
      row.type = s.type;
      row.link = link;
      simulate(model, s, robot_name, left_out, &row);
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

std::string formatModelReport(const std::string& robot_name, const std::vector<ReportRow>& rows) {
  size_t simulated = 0, differences = 0, left = 0;
  std::vector<size_t> width = {4, 4, 4, 4};  // KIND NAME TYPE LINK
  for (const ReportRow& r : rows) {
    simulated += r.status == ReportRow::Status::kSimulated;
    differences += r.status == ReportRow::Status::kDifferences;
    left += r.status == ReportRow::Status::kLeftOut;
    width[0] = std::max(width[0], r.kind.size());
    width[1] = std::max(width[1], r.name.size());
    width[2] = std::max(width[2], r.type.size());
    width[3] = std::max(width[3], std::max<size_t>(1, r.link.size()));
  }
  std::ostringstream out;
  out << "robot '" << robot_name << "': " << rows.size() << " plugins and sensors: " << simulated
      << " simulated, " << differences << " with differences, " << left << " left out\n";
  if (rows.empty()) return out.str();
  const auto line = [&](const std::string& a, const std::string& b, const std::string& c,
                        const std::string& d, const std::string& e) {
    std::string s = "  ";
    const std::string cells[] = {a, b, c, d};
    for (size_t i = 0; i < 4; ++i) s += cells[i] + std::string(width[i] - cells[i].size() + 2, ' ');
    out << s << e << "\n";
  };
  line("KIND", "NAME", "TYPE", "LINK", "STATUS");
  const std::string indent(2 + width[0] + 2, ' ');
  for (const ReportRow& r : rows) {
    line(r.kind, r.name, r.type, r.link.empty() ? "-" : r.link, statusText(r.status));
    for (const std::string& t : r.topics) out << indent << t << "\n";
    const char* label = r.status == ReportRow::Status::kLeftOut ? "why: " : "difference: ";
    for (const std::string& n : r.notes) out << indent << label << n << "\n";
  }
  return out.str();
}

std::string leftOutPluginReason(const std::string& filename) {
  const std::string f = baseName(filename);
  if (f == "libgazebo_ros_force.so")
    return "libgazebo_ros_force (a geometry_msgs/Wrench topic pushing a link) is not simulated: "
           "/gazebo/apply_body_wrench applies the same force and torque to a link";
  if (f == "libgazebo_ros_template.so")
    return "libgazebo_ros_template is gazebo_plugins' empty example (its update does nothing): "
           "there is nothing to simulate";
  return "";
}

const char kDisabledBySensorList[] = "disabled by ~disable_sensors";

bool leavesOutUnasked(const std::vector<ReportRow>& rows) {
  return std::any_of(rows.begin(), rows.end(), [](const ReportRow& r) {
    return r.status == ReportRow::Status::kLeftOut &&
           std::find(r.notes.begin(), r.notes.end(), kDisabledBySensorList) == r.notes.end();
  });
}

}  // namespace tianracer_sim
