#include "tianracer_control/controller_params.h"

#include <cmath>
#include <sstream>

namespace tianracer_control {

ParamValue ParamValue::list(List items) {
  ParamValue v;
  v.kind_ = Kind::kList;
  v.list_ = std::move(items);
  return v;
}

ParamValue ParamValue::dict() {
  ParamValue v;
  v.kind_ = Kind::kDict;
  return v;
}

ParamValue ParamValue::other() {
  ParamValue v;
  v.kind_ = Kind::kOther;
  return v;
}

ParamValue& ParamValue::operator[](const std::string& key) {
  if (kind_ == Kind::kNone) kind_ = Kind::kDict;
  return dict_[key];
}

const ParamValue* ParamValue::find(const std::string& key) const {
  if (kind_ != Kind::kDict) return nullptr;
  const auto it = dict_.find(key);
  return it == dict_.end() ? nullptr : &it->second;
}

std::optional<double> ParamValue::asNumber() const {
  if (kind_ == Kind::kDouble) return double_;
  if (kind_ == Kind::kInt) return int_;
  return std::nullopt;
}

std::string finiteNumberProblem(const ParamValue& v) {
  const std::optional<double> x = v.asNumber();
  if (!x) return std::string("is ") + v.typeName() + ", not a number";
  if (!std::isfinite(*x)) return "is " + numberText(*x) + ", not a finite number";
  return "";
}

const char* ParamValue::typeName() const {
  // Indexed by Kind; kNone and kOther are what a YAML reader cannot give as a parameter.
  static const char* const kNames[] = {"an unsupported value", "a bool", "an int", "a double",
                                       "a string", "a list", "a dictionary",
                                       "an unsupported value"};
  return kNames[static_cast<int>(kind_)];
}

std::string controllerPrefix(const std::string& name) { return "controller '" + name + "': "; }

// The place first, as in every located message (diagnostic.h): "c.yaml:7: controller 'x': ".
std::string ControllerParams::prefix() const {
  return formatLocation(spec_.source, spec_.line) + controllerPrefix(spec_.name);
}

const ParamValue* ControllerParams::lookup(const std::string& key) {
  const ParamValue* node = &spec_.params;
  std::string path;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = key.find('/', start);
    const std::string part = key.substr(start, slash == std::string::npos ? slash : slash - start);
    if (node->kind() != ParamValue::Kind::kDict) {
      // The parent of `part` is there but is no dictionary ("pid: 1.0" and pid/p asked for).
      throw ControllerError(prefix() + path + " must be a dictionary, got " + node->typeName());
    }
    node = node->find(part);
    if (!node) return nullptr;
    path += (path.empty() ? "" : "/") + part;
    read_.insert(path);
    if (slash == std::string::npos) return node;
    start = slash + 1;
  }
}

std::string numberText(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

double ControllerParams::positiveNumber(const std::string& key, double fallback) {
  const double x = number(key).value_or(fallback);
  if (!(x > 0.0) || !std::isfinite(x)) {
    throw ControllerError(prefix() + key + " must be a positive number, got " + numberText(x));
  }
  return x;
}

std::optional<double> ControllerParams::number(const std::string& key) {
  const ParamValue* v = lookup(key);
  if (!v) return std::nullopt;
  if (const std::optional<double> x = v->asNumber()) return x;
  throw ControllerError(prefix() + key + " must be a number, got " + v->typeName());
}

std::optional<std::string> ControllerParams::text(const std::string& key) {
  const ParamValue* v = lookup(key);
  if (!v) return std::nullopt;
  if (v->kind() == ParamValue::Kind::kString) return v->asString();
  throw ControllerError(prefix() + key + " must be a string, got " + v->typeName());
}

std::optional<bool> ControllerParams::boolean(const std::string& key) {
  const ParamValue* v = lookup(key);
  if (!v) return std::nullopt;
  if (v->kind() == ParamValue::Kind::kBool) return v->asBool();
  throw ControllerError(prefix() + key + " must be true or false, got " + v->typeName());
}

std::optional<std::vector<std::string>> ControllerParams::textList(const std::string& key) {
  const ParamValue* v = lookup(key);
  if (!v) return std::nullopt;
  if (v->kind() != ParamValue::Kind::kList) {
    throw ControllerError(prefix() + key + " must be a list of strings, got " + v->typeName());
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < v->items().size(); ++i) {
    const ParamValue& item = v->items()[i];
    if (item.kind() != ParamValue::Kind::kString) {
      throw ControllerError(prefix() + key + " must be a list of strings, item " +
                            std::to_string(i) + " is " + item.typeName());
    }
    out.push_back(item.asString());
  }
  return out;
}

namespace {

void collectUnread(const ParamValue& tree, const std::string& path,
                   const std::set<std::string>& read, std::vector<std::string>* out) {
  for (const auto& [key, value] : tree.members()) {
    const std::string sub = path.empty() ? key : path + "/" + key;
    if (sub == "type") continue;
    if (read.count(sub) == 0) {
      out->push_back(sub);
    } else if (value.kind() == ParamValue::Kind::kDict) {
      collectUnread(value, sub, read, out);
    }
  }
}

}  // namespace

std::vector<std::string> ControllerParams::unread() const {
  std::vector<std::string> out;
  collectUnread(spec_.params, "", read_, &out);
  return out;
}

}  // namespace tianracer_control
