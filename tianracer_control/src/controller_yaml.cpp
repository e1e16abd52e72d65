#include "tianracer_control/controller_yaml.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <optional>
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

/// A YAML value as the parameter server holds it after `rosparam load` (XmlRpcValue's kinds).
ParamValue toParamValue(const YAML::Node& n) {
  switch (kindOf(n)) {
    case Kind::kDict: {
      ParamValue tree = ParamValue::dict();
      for (const auto& kv : n) tree[kv.first.as<std::string>()] = toParamValue(kv.second);
      return tree;
    }
    case Kind::kList: {
      ParamValue::List items;
      for (const auto& item : n) items.push_back(toParamValue(item));
      return ParamValue::list(std::move(items));
    }
    case Kind::kBool: {
      bool b = false;
      isBool(n.Scalar(), &b);
      return ParamValue(b);
    }
    case Kind::kInt: {
      // XmlRpc ints are 32-bit; a larger one stays a number (rosparam makes it a double).
      const long long v = std::strtoll(n.Scalar().c_str(), nullptr, 10);
      if (v >= INT32_MIN && v <= INT32_MAX) return ParamValue(static_cast<int>(v));
      return ParamValue(static_cast<double>(v));
    }
    case Kind::kDouble: {
      double d = 0.0;
      isNumber(n.Scalar(), &d);
      return ParamValue(d);
    }
    case Kind::kString:
      return ParamValue(n.Scalar());
    case Kind::kNull:
      break;
  }
  return ParamValue::other();
}

/// One controller's entry as the parameter-server adapter (ros/controller_adapter.h) reads it:
/// the whole dictionary, its type taken out by name; the controller class reads the rest and
/// names this file and line in its errors.
ControllerSpec readSpec(const YAML::Node& params, const std::string& source,
                        const std::string& name) {
  const int line = params.Mark().line + 1;
  const std::string pre = "controller '" + name + "': ";
  if (!params.IsMap()) {
    throw ControllerError({source, line, name},
                          pre + "its parameters must be a dictionary, got " + kindName(kindOf(params)));
  }
  ControllerSpec spec;
  spec.name = name;
  spec.source = source;
  spec.line = line;
  spec.params = toParamValue(params);
  if (const YAML::Node type = params["type"]) {
    if (kindOf(type) != Kind::kString) {
      throw ControllerError({source, type.Mark().line + 1, "type"},
                            pre + "type must be a string, got " + kindName(kindOf(type)));
    }
    spec.type = type.Scalar();
  }
  return spec;
}

std::vector<std::string> splitNamespace(const std::string& ns) {
  std::vector<std::string> parts;
  std::stringstream in(ns);
  for (std::string part; std::getline(in, part, '/');) {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

/// What the parameter server could not hold ("" none), with its line in *line: a dictionary key
/// that is not a plain value (`? {a: 1}: x`; rosparam's names are strings), or a tree that
/// aliases expand beyond kMaxYamlValues values (`&a [*a, *a]` nested: each level doubles).
constexpr long kMaxYamlValues = 1000000;
std::string unusableYaml(const YAML::Node& n, long* values, int* line) {
  if (++*values > kMaxYamlValues) {
    *line = n.Mark().line + 1;
    return "aliases expand it to more than " + std::to_string(kMaxYamlValues) + " values";
  }
  if (n.IsMap()) {
    for (const auto& kv : n) {
      if (!kv.first.IsScalar() && !kv.first.IsNull()) {
        *line = kv.first.Mark().line + 1;
        return std::string("a dictionary key must be a string, got ") + kindName(kindOf(kv.first));
      }
      const std::string e = unusableYaml(kv.second, values, line);
      if (!e.empty()) return e;
    }
  } else if (n.IsSequence()) {
    for (const auto& item : n) {
      const std::string e = unusableYaml(item, values, line);
      if (!e.empty()) return e;
    }
  }
  return "";
}

YAML::Node parseYaml(const std::string& yaml, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw ControllerError({source, e.mark.line + 1, ""}, "not valid YAML: " + e.msg);
  }
  long values = 0;
  int line = 0;
  const std::string unusable = unusableYaml(root, &values, &line);
  if (!unusable.empty()) throw ControllerError({source, line, ""}, unusable);
  return root;
}

/// The node at key path `ns` ("" = the root); a null node when a key is missing. *path receives
/// the path walked ("/a/b").
YAML::Node findNamespace(const YAML::Node& root, const std::string& ns, std::string* path) {
  YAML::Node at = root;
  for (const std::string& part : splitNamespace(ns)) {
    *path += "/" + part;
    const YAML::Node& here = at;  // const: operator[] must not add the key
    if (!here.IsMap() || !here[part]) return YAML::Node(YAML::NodeType::Undefined);
    at.reset(here[part]);
  }
  return at;
}

/// Every dictionary with a `type` key under `at`, sorted by name (as the node lists them).
std::vector<std::string> controllerNames(const YAML::Node& at) {
  std::vector<std::string> names;
  for (const auto& kv : at) {
    if (kv.second.IsMap() && kv.second["type"]) names.push_back(kv.first.as<std::string>());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

std::optional<std::vector<std::string>> listControllerYaml(const std::string& yaml,
                                                           const std::string& source,
                                                           const std::string& ns) {
  std::string path;
  const YAML::Node at = findNamespace(parseYaml(yaml, source), ns, &path);
  if (!at.IsDefined()) return std::nullopt;
  return at.IsMap() ? controllerNames(at) : std::vector<std::string>{};
}

std::vector<ControllerSpec> loadControllerYaml(const std::string& yaml, const std::string& source,
                                               const std::string& ns,
                                               const std::vector<std::string>& names) {
  std::string path;
  const YAML::Node at = findNamespace(parseYaml(yaml, source), ns, &path);
  if (!at.IsDefined()) {
    throw ControllerError(source + ": no controllers under " + path +
                          " (the YAML's top key is the controllers' namespace, e.g. tianracer:)");
  }
  if (!at.IsMap()) {
    throw ControllerError(source + ": " + (path.empty() ? std::string("the top level") : path) +
                          " is not a dictionary of controllers");
  }
  const std::vector<std::string> wanted = names.empty() ? controllerNames(at) : names;
  std::vector<ControllerSpec> specs;
  for (const std::string& name : wanted) {
    const YAML::Node& dict = at;
    const YAML::Node params = dict[name];
    if (!params) {
      throw ControllerError("controller '" + name + "': no parameters at " + path + "/" + name +
                            " in " + source);
    }
    specs.push_back(readSpec(params, source, name));
  }
  return specs;
}

ControlConfigKeys readControlConfigKeys(const std::string& file) {
  ControlConfigKeys out;
  out.file = file;
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    out.error = e.what();
    return out;
  }
  if (!root.IsMap()) {
    out.error = "its top level is not a dictionary";
    return out;
  }
  long values = 0;
  int line = 0;
  const std::string unusable = unusableYaml(root, &values, &line);
  if (!unusable.empty()) {
    out.error = "line " + std::to_string(line) + ": " + unusable;
    return out;
  }
  for (const auto& entry : root) {
    const std::string key = entry.first.as<std::string>();
    out.keys.push_back(key);
    if (entry.second.IsMap() && !controllerNames(entry.second).empty()) {
      out.with_controllers.push_back(key);
    }
  }
  return out;
}

std::string readTextFile(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw ControllerError(what + " " + path + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<ControllerSpec> loadControllerYamlFile(const std::string& path, const std::string& ns,
                                                   const std::vector<std::string>& names) {
  return loadControllerYaml(readTextFile(path, "controller YAML"), path, ns, names);
}

}  // namespace tianracer_control
