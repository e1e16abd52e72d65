// Sensor specs as the model loader gives them, built in the test from a <sensor> element so that
// the sensor tests need no model file, and the kind the registry finds for one.
#ifndef TIANRACER_SIM_TEST_SENSOR_TEST_SUPPORT_H
#define TIANRACER_SIM_TEST_SENSOR_TEST_SUPPORT_H

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tinyxml2.h>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {
namespace test {

/// What the model loader makes of a <sensor> element on `link`, read from `source` at `line`:
/// name, type, <update_rate> (when given), the element's text and its plugins with their
/// parameters.
inline SensorSpec specFromXml(const std::string& xml, const std::string& link,
                              const std::string& source, int line) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS) << xml;
  const tinyxml2::XMLElement* root = doc.RootElement();
  SensorSpec spec;
  spec.name = root->Attribute("name");
  spec.type = root->Attribute("type");
  spec.link = link;
  spec.xml = xml;
  spec.source = source;
  spec.line = line;
  if (const auto* rate = root->FirstChildElement("update_rate")) {
    spec.update_rate = std::stod(rate->GetText());
  }
  for (const auto* c = root->FirstChildElement("plugin"); c; c = c->NextSiblingElement("plugin")) {
    PluginSpec p;
    p.name = c->Attribute("name");
    p.filename = c->Attribute("filename");
    for (const auto* param = c->FirstChildElement(); param; param = param->NextSiblingElement()) {
      p.params[param->Name()] = param->GetText() ? param->GetText() : "";
    }
    spec.plugins.push_back(p);
  }
  return spec;
}

/// The names of `topics` in order, to compare a sensor's whole list of topics at once.
inline std::vector<std::string> topicNames(const std::vector<SensorTopic>& topics) {
  std::vector<std::string> names;
  for (const SensorTopic& t : topics) names.push_back(t.topic);
  return names;
}

/// The id of the registered sensor kind that serves `spec` ("" when none does).
inline std::string kindOf(const SensorSpec& spec) {
  const SensorKind* kind = findSensorKind(spec);
  return kind ? kind->id : std::string();
}

}  // namespace test
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_TEST_SENSOR_TEST_SUPPORT_H
