#include "tianracer_sim/simulator/robot_setup.h"

#include <urdf_model/model.h>

#include "tianracer_sim/common/text.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

YamlControlParams::YamlControlParams(std::string file) : file_(std::move(file)) {
  if (file_.empty()) return;
  text_ = tc::readTextFile(file_, "controller YAML");
  tc::listControllerYaml(text_, file_, "");  // a file that does not parse fails here, once
}

std::vector<std::string> YamlControlParams::list(const std::string& ns) const {
  if (file_.empty()) return {};
  return tc::listControllerYaml(text_, file_, ns).value_or(std::vector<std::string>{});
}

std::vector<tc::ControllerSpec> YamlControlParams::load(const std::string& ns,
                                                        const std::vector<std::string>& names) const {
  if (names.empty()) return {};
  // A name with nothing under it is the parameter server's error, whether the namespace is
  // missing or only the controller.
  if (file_.empty() || !tc::listControllerYaml(text_, file_, ns)) {
    throw tc::ControllerError("controller '" + names.front() + "': no parameters at " +
                              resolve(ns) + "/" + names.front() +
                              (file_.empty() ? " (no controller YAML given)" : " in " + file_));
  }
  return tc::loadControllerYaml(text_, file_, ns, names);
}

std::string YamlControlParams::resolve(const std::string& ns) const {
  return "/" + trimSlashes(ns);
}

std::string chooseControlNamespace(const std::string& robot_ns, bool robot_ns_has_controllers,
                                   const ControlConfigKeys& config) {
  if (robot_ns_has_controllers || config.with_controllers.size() != 1) return robot_ns;
  return config.with_controllers.front();
}

std::string noControllersWarning(const std::string& robot, const std::string& searched,
                                 const ControlConfigKeys& config) {
  std::string text = "robot '" + robot + "' has gazebo_ros_control but no controller: none is " +
                     "defined under " + searched + " (a dictionary with a 'type' key)";
  if (config.file.empty()) {
    return text + "; load the controller YAML (rosparam load) under " + searched +
           ", or give ~control_namespace";
  }
  if (!config.error.empty()) {
    return text + "; control_config " + config.file + " could not be read: " + config.error;
  }
  std::string keys;
  for (const std::string& k : config.keys) keys += (keys.empty() ? "" : ", ") + k;
  text += "; control_config " + config.file + " has the top-level keys [" + keys + "]";
  if (!config.with_controllers.empty()) {
    text += ": pass control_key:=" + config.with_controllers.front() +
            " (or key the YAML by the robot's namespace)";
  }
  return text;
}

RobotSetup setUpRobot(const RobotModel& model, const RobotSetupRequest& request,
                      const ControlParams& params) {
  RobotSetup out;
  const std::string model_ns =
      trimSlashes(model.ext.ros_control ? model.ext.ros_control->robot_namespace : "");
  out.name = request.spawn_name;
  if (out.name.empty()) {
    out.name = request.robot_name.empty() ? model_ns : request.robot_name;
    if (!model_ns.empty() && out.name != model_ns) {
      // robot_state_publisher and the control nodes of the launch files follow robot_name.
      out.warnings.push_back(
          "robot '" + out.name + "': ~robot_name is '" + out.name + "' but the model's " +
          "gazebo_ros_control robotNamespace is '/" + model_ns + "': its controllers and " +
          "joint_states are under /" + model_ns + ", not /" + out.name + " (give the model its " +
          "namespace, e.g. model_args:=robot_namespace=/" + out.name + ", or robot_name:=" +
          model_ns + ")");
    }
  }
  if (out.name.empty()) out.name = model.urdf->getName();
  // robotNamespace "/" is the root namespace in gazebo_ros_control (NodeHandle("/")); only an
  // absent or empty one means the model's name.
  const bool root_ns = model.ext.ros_control && !model.ext.ros_control->robot_namespace.empty() &&
                       model_ns.empty();
  out.ns = root_ns ? "/" : "/" + trimSlashes(model_ns.empty() ? out.name : model_ns);

  ControlConfigKeys config;
  std::string control_ns;
  if (request.control_namespace) {
    control_ns = *request.control_namespace;
  } else {
    if (!request.control_config.empty()) config = readControlConfigKeys(request.control_config);
    control_ns = chooseControlNamespace(out.ns, !params.list(out.ns).empty(), config);
    if (control_ns != out.ns) {
      out.notes.push_back("controllers of " + out.ns + " read from " + params.resolve(control_ns) +
                          ", the one key of " + config.file + " that defines controllers (none " +
                          "are defined under " + out.ns + "; control_key:= picks another)");
    }
  }
  out.control_ns = params.resolve(control_ns);

  std::vector<std::string> names;
  if (request.controllers) {
    names = *request.controllers;
  } else if (!request.waits_for_spawner) {
    names = params.list(control_ns);
    if (names.empty() && model.ext.ros_control) {
      out.warnings.push_back(noControllersWarning(out.name, out.control_ns, config));
    }
  }
  out.controllers = params.load(control_ns, names);
  return out;
}

}  // namespace tianracer_sim
