// Mesh URI -> file path, the way resource_retriever / Gazebo resolve them. ROS-free: the package
// lookup is injected (rospack in the node, a lambda in tests).
#include "tianracer_sim/model/robot_model.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>

namespace tianracer_sim {

namespace {

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

std::string join(const std::string& dir, const std::string& rest) {
  if (dir.empty()) return rest;
  if (dir.back() == '/') return dir + rest;
  return dir + "/" + rest;
}

std::vector<std::string> gazeboModelPaths() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("GAZEBO_MODEL_PATH")) {
    std::string all = env;
    for (std::size_t at = 0; at <= all.size();) {
      const std::size_t colon = std::min(all.find(':', at), all.size());
      if (colon > at) dirs.push_back(all.substr(at, colon - at));
      at = colon + 1;
    }
  }
  if (const char* home = std::getenv("HOME")) dirs.push_back(std::string(home) + "/.gazebo/models");
  return dirs;
}

}  // namespace

std::string MeshResolver::resolve(const std::string& uri) const {
  if (uri.empty()) throw ModelError("empty mesh URI");
  if (startsWith(uri, "model://")) {
    const std::string rest = uri.substr(8);
    const auto slash = rest.find('/');
    if (rest.empty() || slash == 0 || slash == std::string::npos || slash + 1 >= rest.size())
      throw ModelError("mesh URI '" + uri + "' is not model://<model>/<path>");
    const std::vector<std::string> dirs = model_paths.empty() ? gazeboModelPaths() : model_paths;
    std::string searched;
    for (const std::string& dir : dirs) {
      const std::string candidate = join(dir, rest);
      if (std::ifstream(candidate).good()) return candidate;
      searched += (searched.empty() ? "" : ", ") + dir;
    }
    throw ModelError("mesh URI '" + uri + "' not found in the model path (GAZEBO_MODEL_PATH): " +
                     (searched.empty() ? std::string("no folder to search") : "searched " + searched));
  }
  if (startsWith(uri, "package://")) {
    const std::string rest = uri.substr(10);
    const auto slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    if (package.empty() || slash == std::string::npos || slash + 1 >= rest.size())
      throw ModelError("mesh URI '" + uri + "' is not package://<package>/<path>");
    if (!find_package)
      throw ModelError("mesh URI '" + uri + "': no package lookup configured to find '" +
                       package + "'");
    const std::string dir = find_package(package);
    if (dir.empty())
      throw ModelError("mesh URI '" + uri + "': package '" + package + "' not found");
    return join(dir, rest.substr(slash + 1));
  }
  std::string path = uri;
  if (startsWith(uri, "file://")) {
    path = uri.substr(7);
    if (path.empty()) throw ModelError("mesh URI '" + uri + "' has no path");
  } else if (uri.find("://") != std::string::npos) {
    throw ModelError("mesh URI '" + uri +
                     "': unsupported scheme (use package://, file:// or a file path)");
  }
  if (path[0] == '/') return path;
  if (base_dir.empty())
    throw ModelError("mesh URI '" + uri +
                     "' is relative but the model has no folder to resolve it against (give the "
                     "node ~model_dir, or the model file as ~model)");
  return join(base_dir, path);
}

}  // namespace tianracer_sim
