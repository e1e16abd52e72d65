// model_info: expands a xacro/URDF, loads it as the simulator does and prints its summary.
//   rosrun tianracer_sim model_info [path.xacro|path.urdf] [--no-meshes]
// It reads every mesh file as the simulator would (--no-meshes: neither resolved nor read).
#include <cstdio>
#include <iostream>
#include <set>
#include <string>

#include <ros/package.h>
#include <urdf_model/model.h>

#include "tianracer_sim/model/robot_meshes.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/rigid_tree.h"
#include "tianracer_sim/plugins/model_report.h"
#include "tianracer_sim/plugins/sensor_registry.h"

int main(int argc, char** argv) {
  std::string path;
  bool require_meshes = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--no-meshes") {
      require_meshes = false;
    } else if (arg == "-h" || arg == "--help") {
      std::cout << "usage: model_info [MODEL.xacro|MODEL.urdf] [--no-meshes]\n";
      return 0;
    } else {
      path = arg;
    }
  }
  if (path.empty()) {
    const std::string pkg = ros::package::getPath("tianracer_description");
    if (pkg.empty()) {
      std::cerr << "model_info: no model given and package tianracer_description not found\n";
      return 2;
    }
    path = pkg + "/urdf/tianracer_description.xacro";
  }

  tianracer_sim::LoadOptions options;
  options.require_meshes = require_meshes;
  options.resolver.find_package = [](const std::string& p) { return ros::package::getPath(p); };
  std::set<std::string> warnings;
  options.warn = [&](const std::string& w) {
    if (warnings.insert(w).second) std::cerr << "warning: " << w << "\n";
  };
  try {
    const tianracer_sim::RobotModel model = tianracer_sim::loadRobotModelFile(path, options);
    // The mesh contents too, as the physics and the renderer read them: a file that would stop
    // the simulator (or crash it, before issue 43) stops model_info with the same message.
    if (require_meshes) tianracer_sim::readRobotMeshes(model, options.warn);
    // What the simulator checks when it builds the physics (moving bodies without mass, joint
    // types and axes, inertia), with the same messages and places: model_info accepts no model
    // the simulator refuses.
    tianracer_sim::buildRigidTree(*model.urdf, model.mesh_paths, model.lines, options.warn);
    std::cout << tianracer_sim::describeRobotModel(model) << "\n"
              << tianracer_sim::formatModelReport(
                     model.urdf->getName(), tianracer_sim::modelReport(model, model.urdf->getName()));
  } catch (const std::exception& e) {
    std::cerr << "model_info: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
