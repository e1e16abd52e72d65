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

std::vector<std::string> modelSearchPath(const std::vector<std::string>& extra) {
  std::vector<std::string> dirs;
  const std::string user = userModelDir();
  if (!user.empty()) dirs.push_back(user);
  for (const std::string& d : gazeboModelPath()) dirs.push_back(d);
  for (const std::string& d : rosExportedModelPaths()) dirs.push_back(d);
  dirs.insert(dirs.end(), extra.begin(), extra.end());
  // Each folder once, at its first place (SystemPaths::InsertUnique; messages list each once).
  std::vector<std::string> unique;
  for (const std::string& d : dirs) {
    if (std::find(unique.begin(), unique.end(), d) == unique.end()) unique.push_back(d);
  }
  return unique;
}

namespace {

bool existsAs(const std::string& path, UriResolver::Want want) {
  std::error_code ec;
  switch (want) {
    case UriResolver::Want::kFolder:
      return std::filesystem::is_directory(path, ec);
    case UriResolver::Want::kAny:
      return std::filesystem::exists(path, ec);
    default:  // a file of any kind but a folder: a device is found, and refused by its reader
      return std::filesystem::exists(path, ec) && !std::filesystem::is_directory(path, ec);
  }
}

/// model://<model>/<path> -> "<model>/<path>"; throws for a URI without both parts. Slashes
/// after the scheme are dropped: gazebo/common/SystemPaths.cc FindFileURI appends the rest to
/// each model folder with boost::filesystem's operator/, which appends "/x" too, so
/// model:///table_marble/meshes/... (osrf/gazebo_models' table_marble) is found.
std::string modelRest(const std::string& uri, UriResolver::Want want) {
  std::string rest = uri.substr(8);
  rest.erase(0, std::min(rest.size(), rest.find_first_not_of('/')));
  const auto slash = rest.find('/');
  const bool folder = want != UriResolver::Want::kFile;
  if (rest.empty() || slash == 0 ||
      (!folder && (slash == std::string::npos || slash + 1 >= rest.size())))
    throw ResourceError("mesh URI '" + uri + "' is not model://<model>/<path>");
  return rest;
}

}  // namespace

UriResolver::Found UriResolver::find(const std::string& uri, Want want) const {
  if (uri.empty()) throw ResourceError("empty mesh URI");
  Found found;
  if (startsWith(uri, "model://")) {
    const std::string rest = modelRest(uri, want);
    for (const std::string& dir : modelSearchPath(model_paths)) {
      found.tried.push_back(join(dir, rest));
      if (existsAs(found.tried.back(), want)) {
        found.path = found.tried.back();
        break;
      }
    }
    return found;
  }
  found.tried.push_back(direct(uri));
  if (existsAs(found.tried.back(), want)) found.path = found.tried.back();
  return found;
}

std::string UriResolver::resolve(const std::string& uri) const {
  if (uri.empty()) throw ResourceError("empty mesh URI");
  if (!startsWith(uri, "model://")) return direct(uri);
  const Found found = find(uri, Want::kFile);
  if (!found.path.empty()) return found.path;
  std::string searched;
  for (const std::string& dir : modelSearchPath(model_paths))
    searched += (searched.empty() ? "" : ", ") + dir;
  throw ResourceError("mesh URI '" + uri + "' not found in the model path (GAZEBO_MODEL_PATH): " +
                      (searched.empty() ? std::string("no folder to search") : "searched " + searched));
}

std::string UriResolver::direct(const std::string& uri) const {
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
