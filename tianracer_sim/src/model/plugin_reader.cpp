#include "tianracer_sim/model/plugin_reader.h"

#include <cmath>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/common/xml_reader.h"

namespace tianracer_sim {

PluginReader::PluginReader(const PluginSpec& plugin, std::string context, WarningSink warn)
    : plugin_(plugin), context_(std::move(context)), warn_(std::move(warn)) {}

std::string PluginReader::fileName() const { return baseName(plugin_.filename); }

bool PluginReader::has(const std::string& key) {
  read_.insert(key);
  return plugin_.params.count(key) > 0;
}

std::optional<std::string> PluginReader::text(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return trimText(plugin_.params.at(key));
}

bool PluginReader::text(const std::string& key, std::string* out) {
  const auto v = text(key);
  if (v) *out = *v;
  return v.has_value();
}

std::string PluginReader::frame(const std::string& key, const std::string& fallback) {
  std::string f = text(key).value_or("");
  while (!f.empty() && f.front() == '/') f.erase(f.begin());
  return f.empty() ? fallback : f;
}

bool PluginReader::number(const std::string& key, double* out, bool non_negative) {
  const auto t = text(key);
  if (!t) return false;
  const auto v = parseNumber(*t);
  if (!v) fail("<" + key + "> '" + *t + "' is not a number");
  if (!std::isfinite(*v)) fail("<" + key + "> " + *t + " is not finite");
  if (non_negative && *v < 0.0) fail("<" + key + "> " + *t + " must be >= 0");
  *out = *v;
  return true;
}

bool PluginReader::vector3(const std::string& key, Eigen::Vector3d* out) {
  const auto t = text(key);
  if (!t) return false;
  const auto v = parseNumbers(*t);
  if (!v || v->size() != 3) fail("<" + key + "> '" + *t + "' is not 3 numbers");
  for (double x : *v) {
    if (!std::isfinite(x)) fail("<" + key + "> '" + *t + "' is not finite");
  }
  *out = Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]);
  return true;
}

NamespaceFrom PluginReader::robotNamespace(NamespaceRule rule, std::string* ns) {
  const auto v = text("robotNamespace");
  if (!v) return NamespaceFrom::kMissing;
  if (v->empty() && rule == NamespaceRule::kEmptyIsModel) return NamespaceFrom::kModel;
  *ns = *v;
  return NamespaceFrom::kGiven;
}

bool PluginReader::boolean(const std::string& key, bool* out) {
  const auto t = text(key);
  if (!t) return false;
  const auto b = parseBool(lowerCase(*t));
  if (!b) fail("<" + key + "> '" + *t + "' is not a boolean (true, false, 1 or 0)");
  *out = *b;
  return true;
}

void PluginReader::ignore(std::initializer_list<const char*> keys) {
  for (const char* k : keys) read_.insert(k);
}

std::string PluginReader::place() const { return context_.empty() ? "" : context_ + ": "; }

void PluginReader::fail(const std::string& message) const {
  throw InputError(SourceLocation{plugin_.source, plugin_.line, "plugin"}, place() + message);
}

void PluginReader::warn(const std::string& message) {
  warn_(formatLocation(plugin_.source, plugin_.line) + place() + message);
}

void PluginReader::finish() {
  for (const auto& kv : plugin_.params) {
    if (!read_.count(kv.first))
      warn("<" + kv.first + "> is not a parameter of " + fileName() + ", ignored");
  }
}

}  // namespace tianracer_sim
