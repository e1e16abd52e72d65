// Helpers shared by the model loader's translation units. Private to src/model.
#ifndef TIANRACER_SIM_SRC_MODEL_MODEL_INTERNAL_H
#define TIANRACER_SIM_SRC_MODEL_MODEL_INTERNAL_H

#include <optional>
#include <set>
#include <string>

#include <tinyxml2.h>

#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {
namespace model_internal {

/// Forwards each warning once: once per key (e.g. one unknown tag reported at its first line) and
/// once per distinct message.
class Warner {
 public:
  explicit Warner(WarningSink sink) : sink_(std::move(sink)) {}
  void warn(const std::string& message) { warnOnce(message, message); }
  void warnOnce(const std::string& key, const std::string& message) {
    if (!keys_.insert(key).second) return;
    if (!messages_.insert(message).second) return;
    if (sink_) sink_(message);
  }

 private:
  WarningSink sink_;
  std::set<std::string> keys_;
  std::set<std::string> messages_;
};

std::string trim(const std::string& s);

/// "<source>: line N: " for an element (line omitted when unknown).
std::string at(const std::string& source, const tinyxml2::XMLElement* e);

/// Parses a whole (trimmed) string as a double, locale-independent; nullopt on any junk.
/// "nan"/"inf" parse (and are rejected by the callers' finiteness checks).
std::optional<double> toDouble(const std::string& text);

/// Parses `text` into a document; throws ModelError "<source>: XML error at line N: ..." on a
/// syntax error, "<source>: robot_description is empty" for empty input, and requires <robot>.
const tinyxml2::XMLElement* parseRobotXml(tinyxml2::XMLDocument& doc, const std::string& text,
                                          const std::string& source);

/// Extension parsing over an already parsed <robot> element (shared by loadRobotModel and
/// parseExtensions). Never throws anything but ModelError.
RobotExtensions parseExtensionsXml(const tinyxml2::XMLElement* robot, const std::string& source,
                                   Warner& warner);

}  // namespace model_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_MODEL_MODEL_INTERNAL_H
