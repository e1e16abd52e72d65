#include "tianracer_sim/plugins/sensor_registry.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <stdexcept>
#include <sstream>

#include <urdf_model/model.h>

#include "tianracer_sim/common/text.h"

namespace tianracer_sim {
namespace {


bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

}  // namespace

namespace {

/// The kinds as registered (library load order), before the check.
std::vector<SensorKind>& registeredKinds() {
  static std::vector<SensorKind> kinds;
  return kinds;
}

bool shareType(const SensorKind& a, const SensorKind& b) {
  for (const std::string& t : a.sensor_types) {
    if (contains(b.sensor_types, t)) return true;
  }
  return a.sensor_types.empty() && b.sensor_types.empty();  // model plugins: by filename alone
}

}  // namespace

bool registerSensorKind(const SensorKind& kind) {
  registeredKinds().push_back(kind);
  return true;
}

std::vector<std::string> sensorKindProblems(const std::vector<SensorKind>& kinds) {
  std::vector<std::string> problems;
  std::map<std::string, std::vector<const SensorKind*>> by_type;
  for (size_t i = 0; i < kinds.size(); ++i) {
    const SensorKind& k = kinds[i];
    if (k.id.empty()) problems.push_back("a sensor kind has no id");
    if (k.plugins.empty() && k.sensor_types.empty())
      problems.push_back("sensor kind '" + k.id + "' has neither sensor types nor plugins");
    if (!k.topics || !k.make) problems.push_back("sensor kind '" + k.id + "' lacks its topics or make function");
    for (const std::string& t : k.sensor_types) by_type[t].push_back(&k);
    for (size_t j = 0; j < i; ++j) {
      const SensorKind& o = kinds[j];
      if (o.id == k.id) problems.push_back("sensor kind '" + k.id + "' is registered twice");
      if (!shareType(o, k)) continue;
      for (const std::string& p : k.plugins) {
        if (contains(o.plugins, p))
          problems.push_back("plugin '" + p + "' is claimed by sensor kinds '" + o.id + "' and '" + k.id + "'");
      }
    }
  }
  for (const auto& [type, of_type] : by_type) {
    if (of_type.size() < 2) continue;
    std::string ids;
    int defaults = 0;
    for (const SensorKind* k : of_type) {
      ids += (ids.empty() ? "" : ", ") + k->id;
      defaults += k->type_default ? 1 : 0;
    }
    if (defaults != 1)
      problems.push_back("sensor type '" + type + "' is shared by kinds " + ids + ", of which " +
                         std::to_string(defaults) + " (not 1) is its type_default");
  }
  return problems;
}

const std::vector<SensorKind>& sensorKinds() {
  static const std::vector<SensorKind> kinds = [] {
    std::vector<SensorKind> sorted = registeredKinds();
    std::stable_sort(sorted.begin(), sorted.end(),
                     [](const SensorKind& a, const SensorKind& b) { return a.id < b.id; });
    const std::vector<std::string> problems = sensorKindProblems(sorted);
    if (!problems.empty()) {
      std::string text = "the registered sensor kinds disagree:";
      for (const std::string& p : problems) text += "\n  " + p;
      throw std::logic_error(text);
    }
    return sorted;
  }();
  return kinds;
}

const SensorKind* findSensorKind(const SensorSpec& sensor) {
  if (sensor.type.empty()) {
    for (const SensorKind& kind : sensorKinds()) {
      if (!kind.sensor_types.empty() || sensor.plugins.size() != 1) continue;
      if (contains(kind.plugins, baseName(sensor.plugins.front().filename))) return &kind;
    }
    return nullptr;
  }
  const SensorKind* only = nullptr;
  const SensorKind* by_default = nullptr;
  int of_type = 0;
  for (const SensorKind& kind : sensorKinds()) {
    if (!contains(kind.sensor_types, sensor.type)) continue;
    for (const PluginSpec& p : sensor.plugins) {
      if (contains(kind.plugins, baseName(p.filename))) return &kind;
    }
    ++of_type;
    only = &kind;
    if (kind.type_default) by_default = &kind;
  }
  return of_type == 1 ? only : by_default;
}

const SensorKind* findPluginKind(const std::string& sensor_type, const std::string& filename) {
  for (const SensorKind& kind : sensorKinds()) {
    if (contains(kind.sensor_types, sensor_type) && contains(kind.plugins, baseName(filename)))
      return &kind;
  }
  return nullptr;
}

std::vector<SensorTopic> sensorTopics(const SensorSpec& sensor, const std::string& model_name,
                                      const WarningSink& warn) {
  const SensorKind* kind = findSensorKind(sensor);
  return kind ? kind->topics(sensor, model_name, warn) : std::vector<SensorTopic>{};
}

SensorSpec modelPluginSensor(const PluginSpec& plugin) {
  SensorSpec s;
  s.name = plugin.name;
  const auto body = plugin.params.find("bodyName");
  if (body != plugin.params.end()) {
    s.link = body->second;
    s.link.erase(0, s.link.find_first_not_of(" \t\r\n"));
    s.link.erase(s.link.find_last_not_of(" \t\r\n") + 1);
  }
  s.plugins.push_back(plugin);
  s.source = plugin.source;
  s.line = plugin.line;
  return s;
}

std::string describeRobotModel(const RobotModel& model) {
  std::ostringstream out;
  const urdf::ModelInterface& urdf = *model.urdf;
  double total_mass = 0.0;
  for (const auto& [name, link] : urdf.links_) {
    if (link->inertial) total_mass += link->inertial->mass;
  }
  out << "robot '" << urdf.getName() << "' from " << model.source << ": " << urdf.links_.size()
      << " links, " << urdf.joints_.size() << " joints, total mass " << formatShort(total_mass)
      << " kg\n\nlink/joint tree (mass; joint type, axis, limits):\n";

  std::function<void(const urdf::LinkConstSharedPtr&, const std::string&)> walk =
      [&](const urdf::LinkConstSharedPtr& link, const std::string& indent) {
        out << indent << link->name;
        if (link->inertial) {
          out << "  [" << formatShort(link->inertial->mass) << " kg]";
        } else {
          out << "  [massless]";
        }
        out << "\n";
        for (const urdf::JointSharedPtr& joint : link->child_joints) {
          static const char* kTypes[] = {"unknown", "revolute", "continuous", "prismatic",
                                         "floating", "planar", "fixed"};
          out << indent << "  +- " << joint->name << " (" << kTypes[joint->type];
          if (joint->type != urdf::Joint::FIXED) {
            out << ", axis " << formatShort(joint->axis.x) << " " << formatShort(joint->axis.y) << " "
                << formatShort(joint->axis.z);
          }
          if (joint->limits && (joint->type == urdf::Joint::REVOLUTE ||
                                joint->type == urdf::Joint::PRISMATIC)) {
            out << ", limits [" << formatShort(joint->limits->lower) << ", " << formatShort(joint->limits->upper)
                << "]";
          }
          if (joint->limits && joint->type != urdf::Joint::FIXED) {
            out << ", effort " << formatShort(joint->limits->effort) << ", velocity "
                << formatShort(joint->limits->velocity);
          }
          out << ")\n";
          walk(urdf.getLink(joint->child_link_name), indent + "  |  ");
        }
      };
  walk(urdf.getRoot(), "  ");

  out << "\ntransmissions:\n";
  if (model.ext.transmissions.empty()) out << "  (none)\n";
  for (const TransmissionSpec& t : model.ext.transmissions) {
    out << "  " << t.name << ": " << t.type << ", joint " << t.joint << " [";
    for (size_t i = 0; i < t.joint_interfaces.size(); ++i) {
      out << (i ? ", " : "") << toString(t.joint_interfaces[i]);
    }
    out << "], actuator " << t.actuator << ", reduction " << formatShort(t.mechanical_reduction) << "\n";
  }

  // What the simulator publishes for a sensor, or why it leaves it out.
  const auto printTopics = [&](const SensorSpec& s) {
    if (!s.error.empty()) {
      out << "    left out: " << s.error << "\n";
      return;
    }
    const SensorKind* kind = findSensorKind(s);
    if (!kind) {
      out << "    left out: sensor type '" << s.type << "' is not simulated\n";
      return;
    }
    try {
      const std::vector<SensorTopic> topics = kind->topics(s, urdf.getName(), {});
      if (topics.empty()) out << "    (no gazebo_ros plugin: nothing published)\n";
      for (const SensorTopic& t : topics) {
        out << "    " << t.topic << "  " << t.msg_type << " @ " << formatShort(t.rate) << " Hz\n";
      }
    } catch (const std::exception& e) {
      out << "    left out: " << e.what() << "\n";
    }
  };
  out << "\nmodel plugins:\n";
  if (model.ext.model_plugins.empty()) out << "  (none)\n";
  for (const PluginSpec& p : model.ext.model_plugins) {
    out << "  " << p.name << " (" << p.filename << ")\n";
    const SensorSpec as_sensor = modelPluginSensor(p);
    if (findSensorKind(as_sensor)) printTopics(as_sensor);
  }
  if (model.ext.ros_control) {
    out << "  ros_control: namespace " << model.ext.ros_control->robot_namespace << ", robotParam "
        << model.ext.ros_control->robot_param << "\n";
  }
  if (const auto& jsp = model.ext.joint_state_publisher) {
    out << "  joint_state_publisher: "
        << resolveTopic(jsp->robot_namespace, "joint_states") << " at "
        << formatShort(jsp->update_rate) << " Hz, joints:";
    for (const std::string& j : jsp->joint_names) out << " " << j;
    out << "\n";
  }

  out << "\nsensors:\n";
  bool any = false;
  for (const auto& [link, ext] : model.ext.links) {
    for (const SensorSpec& s : ext.sensors) {
      any = true;
      out << "  " << s.name << " (" << s.type << ") on link " << link << ", "
          << formatShort(s.update_rate) << " Hz\n";
      printTopics(s);
    }
  }
  if (!any) out << "  (none)\n";
  return out.str();
}

}  // namespace tianracer_sim
