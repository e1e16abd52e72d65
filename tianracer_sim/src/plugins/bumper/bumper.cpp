#include "tianracer_sim/plugins/bumper/bumper.h"

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

BumperConfig parseBumperConfig(const SensorSpec& spec, const std::string& model_name,
                               const WarningSink& warn) {
  const std::string what = "contact sensor '" + spec.name + "' of model '" + model_name + "'";
  BumperConfig c;
  c.name = spec.name;
  c.link = spec.link;
  c.update_rate = spec.update_rate;
  const PluginSpec* plugin = nullptr;
  for (const PluginSpec& p : spec.plugins) {
    if (baseName(p.filename) == "libgazebo_ros_bumper.so") {
      plugin = &p;
    } else if (warn) {
      warn(formatLocation(p.source, p.line) + what + ": plugin " + p.filename +
           " is not simulated, ignored");
    }
  }
  if (!plugin) {
    c.topic_name.clear();
    return c;
  }
  PluginReader r(*plugin, what, warn);
  r.text("bumperTopicName", &c.topic_name);
  r.text("frameName", &c.frame_name);
  r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
  r.ignore({"alwaysOn", "updateRate"});  // the sensor's own tags rule
  r.finish();
  if (c.topic_name.empty()) r.fail("<bumperTopicName> is empty");
  if (c.frame_name.empty()) r.fail("<frameName> is empty");
  return c;
}

std::vector<SensorTopic> publishedTopics(const BumperConfig& config) {
  if (config.topic_name.empty()) return {};
  return {{config.topic(), "gazebo_msgs/ContactsState", config.update_rate}};
}

void bumperStates(const std::vector<BumperContact>& contacts, const Eigen::Isometry3d& X_WF,
                  double dt, std::vector<BumperState>* out) {
  out->clear();
  const Eigen::Matrix3d R_FW = X_WF.linear().transpose();
  for (const BumperContact& c : contacts) {
    BumperState* s = nullptr;
    for (BumperState& existing : *out) {
      if (existing.collision1 == c.own && existing.collision2 == c.other) s = &existing;
    }
    if (!s) {
      out->emplace_back();
      s = &out->back();
      s->collision1 = c.own;
      s->collision2 = c.other;
    }
    const Eigen::Vector3d f = R_FW * (c.impulse / dt * c.normal_W);
    s->positions.push_back(R_FW * (c.position_W - X_WF.translation()));
    s->normals.push_back(R_FW * c.normal_W);
    s->forces.push_back(f);
    s->depths.push_back(c.depth);
    s->total_force += f;
  }
}

}  // namespace tianracer_sim
