// Helpers shared by the model loader's translation units. Private to src/model.
#ifndef TIANRACER_SIM_SRC_MODEL_MODEL_INTERNAL_H
#define TIANRACER_SIM_SRC_MODEL_MODEL_INTERNAL_H

#include <optional>
#include <set>
#include <string>

#include <tinyxml2.h>

#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {
namespace model_internal {

/// The model loader's reader: warnings once, ModelErrors, places as "<source>:<line>: ".
XmlReader modelReader(const std::string& source, WarningSink warn);

/// An attribute's value as written (not trimmed: URDF names are taken as they are, and a
/// message quotes a value as written); nullopt when absent or `e` is null. The model loader's
/// one tinyxml2 attribute read: XmlReader's attributeText() cannot tell an absent attribute from
/// an empty one, and the URDF checks must (urdfdom fails each its own way).
inline std::optional<std::string> attribute(const tinyxml2::XMLElement* e, const char* name) {
  const char* v = e ? e->Attribute(name) : nullptr;
  return v ? std::optional<std::string>(v) : std::nullopt;
}

/// attribute(), "" when absent.
inline std::string attr(const tinyxml2::XMLElement* e, const char* name) {
  return attribute(e, name).value_or("");
}

/// "<source>:<line>: " for an element ("<source>: " when its line is unknown).
std::string at(const std::string& source, const tinyxml2::XMLElement* e);

/// Parses `text` into a document; throws ModelError "<source>:<line>: XML error: ..." on a
/// syntax error, "<source>: robot_description is empty" for empty input, and requires <robot>.
const tinyxml2::XMLElement* parseRobotXml(tinyxml2::XMLDocument& doc, const std::string& text,
                                          const std::string& source);

/// Extension parsing over an already parsed <robot> element (shared by loadRobotModel and
/// parseExtensions). Never throws anything but ModelError.
RobotExtensions parseExtensionsXml(const tinyxml2::XMLElement* robot, const std::string& source,
                                   XmlReader& warner);

}  // namespace model_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_MODEL_MODEL_INTERNAL_H
