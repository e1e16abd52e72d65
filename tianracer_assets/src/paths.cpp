#include "tianracer_assets/paths.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include <tinyxml2.h>

namespace tianracer_assets {

namespace {

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

std::string join(const std::string& dir, const std::string& rest) {
  if (dir.empty()) return rest;
  if (dir.back() == '/') return dir + rest;
  return dir + "/" + rest;
}

std::vector<std::string> splitPath(const char* env) {
  std::vector<std::string> dirs;
  if (!env) return dirs;
  std::stringstream ss(env);
  std::string d;
  while (std::getline(ss, d, ':'))
    if (!d.empty()) dirs.push_back(d);
  return dirs;
}

}  // namespace

std::vector<std::string> gazeboModelPath() { return splitPath(std::getenv("GAZEBO_MODEL_PATH")); }

std::string userModelDir() {
  const char* home = std::getenv("HOME");
  return home ? join(home, ".gazebo/models") : std::string();
}

std::vector<std::string> rosExportedModelPaths() {
  static std::mutex mutex;
  static std::map<std::string, std::vector<std::string>> cache;
  const char* env = std::getenv("ROS_PACKAGE_PATH");
  const std::string key = env ? env : "";
  std::lock_guard<std::mutex> lock(mutex);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  std::vector<std::string> out;
  namespace fs = std::filesystem;
  std::function<void(const fs::path&, int)> crawl = [&](const fs::path& dir, int depth) {
    std::error_code ec;
    if (fs::exists(dir / "package.xml", ec)) {
      tinyxml2::XMLDocument doc;
      if (doc.LoadFile((dir / "package.xml").c_str()) != tinyxml2::XML_SUCCESS) return;
      const tinyxml2::XMLElement* pkg = doc.RootElement();
      const tinyxml2::XMLElement* exp = pkg ? pkg->FirstChildElement("export") : nullptr;
      for (const tinyxml2::XMLElement* g = exp ? exp->FirstChildElement("gazebo_ros") : nullptr; g;
           g = g->NextSiblingElement("gazebo_ros")) {
        const char* attr = g->Attribute("gazebo_model_path");
        if (!attr) continue;
        std::string path = attr;
        const auto p = path.find("${prefix}");
        if (p != std::string::npos) path.replace(p, 9, dir.string());
        out.push_back(path);
      }
      return;
    }
    if (depth > 8 || fs::exists(dir / "CATKIN_IGNORE", ec)) return;
    std::vector<fs::path> subs;
    for (fs::directory_iterator d(dir, ec), end; !ec && d != end; d.increment(ec)) {
      if (d->is_directory(ec) && d->path().filename().string()[0] != '.') subs.push_back(d->path());
    }
    std::sort(subs.begin(), subs.end());  // same order on every run
    for (const fs::path& sub : subs) crawl(sub, depth + 1);
  };
  for (const std::string& root : splitPath(env)) crawl(root, 0);
  cache[key] = out;
  return out;
}

std::string UriResolver::resolve(const std::string& uri) const {
  if (uri.empty()) throw ResourceError("empty mesh URI");
  if (startsWith(uri, "model://")) {
    const std::string rest = uri.substr(8);
    const auto slash = rest.find('/');
    if (rest.empty() || slash == 0 || slash == std::string::npos || slash + 1 >= rest.size())
      throw ResourceError("mesh URI '" + uri + "' is not model://<model>/<path>");
    std::vector<std::string> dirs = model_paths;
    if (dirs.empty()) {
      dirs = gazeboModelPath();
      const std::string user = userModelDir();
      if (!user.empty()) dirs.push_back(user);
    }
    std::string searched;
    for (const std::string& dir : dirs) {
      const std::string candidate = join(dir, rest);
      if (std::ifstream(candidate).good()) return candidate;
      searched += (searched.empty() ? "" : ", ") + dir;
    }
    throw ResourceError("mesh URI '" + uri + "' not found in the model path (GAZEBO_MODEL_PATH): " +
                        (searched.empty() ? std::string("no folder to search") : "searched " + searched));
  }
  if (startsWith(uri, "package://")) {
    const std::string rest = uri.substr(10);
    const auto slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    if (package.empty() || slash == std::string::npos || slash + 1 >= rest.size())
      throw ResourceError("mesh URI '" + uri + "' is not package://<package>/<path>");
    if (!find_package)
      throw ResourceError("mesh URI '" + uri + "': no package lookup configured to find '" +
                          package + "'");
    const std::string dir = find_package(package);
    if (dir.empty())
      throw ResourceError("mesh URI '" + uri + "': package '" + package + "' not found");
    return join(dir, rest.substr(slash + 1));
  }
  std::string path = uri;
  if (startsWith(uri, "file://")) {
    path = uri.substr(7);
    if (path.empty()) throw ResourceError("mesh URI '" + uri + "' has no path");
  } else if (uri.find("://") != std::string::npos) {
    throw ResourceError("mesh URI '" + uri +
                        "': unsupported scheme (use package://, file:// or a file path)");
  }
  if (path[0] == '/') return path;
  if (base_dir.empty())
    throw ResourceError("mesh URI '" + uri +
                        "' is relative but the model has no folder to resolve it against (give the "
                        "node ~model_dir, or the model file as ~model)");
  return join(base_dir, path);
}

}  // namespace tianracer_assets
