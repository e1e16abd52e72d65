#include "tianracer_control/controller_yaml.h"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace tianracer_control {

namespace {

enum class Kind { kNull, kBool, kInt, kDouble, kString, kList, kDict };

bool isBool(const std::string& s, bool* value) {
  // YAML 1.1 booleans, as rosparam (PyYAML) reads them.
  static const char* yes[] = {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"};
  static const char* no[] = {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"};
  for (const char* y : yes) {
    if (s == y) return *value = true, true;
  }
  for (const char* n : no) {
    if (s == n) return *value = false, true;
  }
  return false;
}

bool isInt(const std::string& s) {
  if (s.empty()) return false;
  errno = 0;
  char* end = nullptr;
  std::strtoll(s.c_str(), &end, 10);
  return errno == 0 && end == s.c_str() + s.size();
}

bool isNumber(const std::string& s, double* value) {
  if (s.empty()) return false;
  if (s == ".inf" || s == "+.inf" || s == ".Inf" || s == ".INF") return *value = HUGE_VAL, true;
  if (s == "-.inf" || s == "-.Inf" || s == "-.INF") return *value = -HUGE_VAL, true;
  if (s == ".nan" || s == ".NaN" || s == ".NAN") return *value = NAN, true;
  char* end = nullptr;
  *value = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && s.find_first_of("xXnNiI") == std::string::npos;
}

Kind kindOf(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Sequence: return Kind::kList;
    case YAML::NodeType::Map: return Kind::kDict;
    case YAML::NodeType::Scalar: break;
    default: return Kind::kNull;
  }
  if (n.Tag() == "!") return Kind::kString;  // quoted
  const std::string& s = n.Scalar();
  bool b;
  double d;
  if (isBool(s, &b)) return Kind::kBool;
  if (isInt(s)) return Kind::kInt;
  if (isNumber(s, &d)) return Kind::kDouble;
  return Kind::kString;
}

const char* kindName(Kind k) {
  switch (k) {
    case Kind::kNull: return "nothing";
    case Kind::kBool: return "a bool";
    case Kind::kInt: return "an int";
    case Kind::kDouble: return "a double";
    case Kind::kString: return "a string";
    case Kind::kList: return "a list";
    case Kind::kDict: return "a dictionary";
  }
  return "?";
}

/// Reads one controller's dictionary; messages as the parameter-server adapter's, plus where.
class Reader {
 public:
  Reader(std::string source, std::string name) : source_(std::move(source)), name_(std::move(name)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& what) const {
    throw ControllerError("controller '" + name_ + "': " + what + " (" + source_ + ", line " +
                          std::to_string(at.Mark().line + 1) + ")");
  }
  double number(const YAML::Node& n, const std::string& key) const {
    const Kind k = kindOf(n);
    double d = 0.0;
    if ((k == Kind::kInt || k == Kind::kDouble) && isNumber(n.Scalar(), &d)) return d;
    fail(n, key + " must be a number, got " + kindName(k));
  }
  std::string text(const YAML::Node& n, const std::string& key) const {
    const Kind k = kindOf(n);
    if (k == Kind::kString) return n.Scalar();
    fail(n, key + " must be a string, got " + kindName(k));
  }
  bool boolean(const YAML::Node& n, const std::string& key) const {
    bool b = false;
    if (kindOf(n) == Kind::kBool && isBool(n.Scalar(), &b)) return b;
    fail(n, key + " must be true or false, got " + kindName(kindOf(n)));
  }

  // The same keys and rules as toControllerSpec() of ros/controller_adapter.h.
  ControllerSpec spec(const YAML::Node& params) const {
    if (!params.IsMap()) fail(params, std::string("its parameters must be a dictionary, got ") +
                                          kindName(kindOf(params)));
    ControllerSpec spec;
    spec.name = name_;
    spec.line = params.Mark().line + 1;
    for (const auto& kv : params) {
      const std::string key = kv.first.as<std::string>();
      const YAML::Node& value = kv.second;
      spec.keys.push_back(key);
      if (key == "type") {
        spec.type = text(value, key);
      } else if (key == "joint") {
        spec.joint = text(value, key);
      } else if (key == "publish_rate") {
        spec.publish_rate = number(value, key);
      } else if (key == "pid") {
        if (!value.IsMap()) fail(value, "pid must be a dictionary, got " + std::string(kindName(kindOf(value))));
        PidParams pid;
        for (const auto& p : value) {
          const std::string sub = "pid/" + p.first.as<std::string>();
          spec.keys.push_back(sub);
          const YAML::Node& v = p.second;
          if (sub == "pid/p") pid.p = number(v, sub);
          else if (sub == "pid/i") pid.i = number(v, sub);
          else if (sub == "pid/d") pid.d = number(v, sub);
          else if (sub == "pid/i_clamp") pid.i_clamp = number(v, sub);
          else if (sub == "pid/i_clamp_min") pid.i_clamp_min = number(v, sub);
          else if (sub == "pid/i_clamp_max") pid.i_clamp_max = number(v, sub);
          else if (sub == "pid/antiwindup") pid.antiwindup = boolean(v, sub);
          // other keys stay in spec.keys and are reported by makeController()
        }
        spec.pid = pid;
      }
    }
    std::sort(spec.keys.begin(), spec.keys.end());  // as the parameter server lists them
    return spec;
  }

 private:
  std::string source_, name_;
};

std::vector<std::string> splitNamespace(const std::string& ns) {
  std::vector<std::string> parts;
  std::stringstream in(ns);
  for (std::string part; std::getline(in, part, '/');) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

}  // namespace

std::vector<ControllerSpec> loadControllerYaml(const std::string& yaml, const std::string& source,
                                               const std::string& ns,
                                               const std::vector<std::string>& names) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw ControllerError(source + ": not valid YAML: " + e.msg + " (line " +
                          std::to_string(e.mark.line + 1) + ")");
  }
  YAML::Node at = root;
  std::string path;
  for (const std::string& part : splitNamespace(ns)) {
    path += "/" + part;
    const YAML::Node& here = at;  // const: operator[] must not add the key
    if (!here.IsMap() || !here[part]) {
      throw ControllerError(source + ": no controllers under " + path +
                            " (the YAML's top key is the controllers' namespace, e.g. tianracer:)");
    }
    at.reset(here[part]);
  }
  if (!at.IsMap()) {
    throw ControllerError(source + ": " + (path.empty() ? std::string("the top level") : path) +
                          " is not a dictionary of controllers");
  }
  std::vector<std::string> wanted = names;
  if (wanted.empty()) {
    for (const auto& kv : at) {
      if (kv.second.IsMap() && kv.second["type"]) wanted.push_back(kv.first.as<std::string>());
    }
    std::sort(wanted.begin(), wanted.end());
  }
  std::vector<ControllerSpec> specs;
  for (const std::string& name : wanted) {
    const YAML::Node& dict = at;
    const YAML::Node params = dict[name];
    if (!params) {
      throw ControllerError("controller '" + name + "': no parameters at " + path + "/" + name +
                            " in " + source);
    }
    specs.push_back(Reader(source, name).spec(params));
  }
  return specs;
}

std::vector<ControllerSpec> loadControllerYamlFile(const std::string& path, const std::string& ns,
                                                   const std::vector<std::string>& names) {
  std::ifstream in(path);
  if (!in) throw ControllerError("controller YAML " + path + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return loadControllerYaml(text.str(), path, ns, names);
}

}  // namespace tianracer_control
