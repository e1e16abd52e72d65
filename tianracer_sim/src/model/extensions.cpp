// <gazebo> and <transmission> tags -> plain structs (tinyxml2). Must never crash on any input:
// every failure is a ModelError (this file is the libFuzzer target's code under test).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "model_internal.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

namespace mi = model_internal;
using model_internal::attr;
using tinyxml2::XMLElement;

namespace model_internal {

std::string at(const std::string& source, const XMLElement* e) {
  return formatLocation(source, lineOf(e));
}

XmlReader modelReader(const std::string& source, WarningSink warn) {
  return XmlReader(source, std::move(warn));
}

const XMLElement* parseRobotXml(tinyxml2::XMLDocument& doc, const std::string& text,
                                const std::string& source) {
  if (trimText(text).empty()) throw ModelError(source + ": robot_description is empty");
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    // ErrorStr() reads "Error=NAME ErrorID=N (0xN) Line number=N: detail"; keep name + detail.
    std::string detail = doc.ErrorStr() ? doc.ErrorStr() : "";
    const auto colon = detail.find(": ");
    detail = colon == std::string::npos ? "" : detail.substr(colon + 2);
    std::string msg = formatLocation(source, doc.ErrorLineNum()) + "XML error: " +
                      (doc.ErrorName() ? doc.ErrorName() : "unknown error");
    if (!detail.empty()) msg += " (" + detail + ")";
    throw ModelError(msg);
  }
  const XMLElement* robot = doc.RootElement();
  if (robot == nullptr) throw ModelError(source + ": no root element (expected <robot>)");
  if (std::strcmp(robot->Name(), "robot") != 0)
    throw ModelError(at(source, robot) + "root element is <" + robot->Name() +
                     ">, expected <robot>");
  return robot;
}

}  // namespace model_internal

namespace {

constexpr const char* kRosControl = "libgazebo_ros_control.so";
constexpr const char* kJointStatePublisher = "libgazebo_ros_joint_state_publisher.so";
constexpr const char* kSimpleTransmission = "transmission_interface/SimpleTransmission";

std::string text(const XMLElement* e) { return elementText(e); }

/// Value of <tag value="..."/> (the seed's form) or <tag>...</tag> (Gazebo's form).
std::string valueOf(const XMLElement* e) {
  if (const auto v = mi::attribute(e, "value")) return trimText(*v);
  return text(e);
}

/// A finite number (>= 0 unless `negative_ok`), or a ModelError naming the element and value.
double finiteNumber(const XMLElement* e, const std::string& what, const std::string& source,
                    bool negative_ok) {
  const std::string v = valueOf(e);
  const auto d = parseNumber(v);
  if (!d) throw ModelError(mi::at(source, e) + what + ": <" + e->Name() + "> value '" + v +
                           "' is not a number");
  if (!std::isfinite(*d) || (*d < 0.0 && !negative_ok))
    throw ModelError(mi::at(source, e) + what + ": <" + e->Name() + "> value '" + v +
                     (negative_ok ? "' must be finite" : "' must be finite and >= 0"));
  return *d;
}

double nonNegative(const XMLElement* e, const std::string& what, const std::string& source) {
  return finiteNumber(e, what, source, false);
}

bool toBool(const XMLElement* e, const std::string& what, const std::string& source) {
  const std::string v = valueOf(e);
  if (const auto b = parseBool(v)) return *b;
  throw ModelError(mi::at(source, e) + what + ": <" + e->Name() + "> value '" + v +
                   "' is not a boolean (true/false/1/0)");
}

std::vector<double> numbers(const std::string& s, bool* ok) {
  auto v = parseNumbers(s);
  *ok = v && std::all_of(v->begin(), v->end(), [](double d) { return std::isfinite(d); });
  return *ok ? *v : std::vector<double>();
}

PluginSpec parsePlugin(const XMLElement* e, const std::string& source) {
  PluginSpec p;
  p.name = attr(e, "name");
  p.filename = trimText(attr(e, "filename"));
  p.line = e->GetLineNum();
  p.source = source;
  if (p.filename.empty())
    throw ModelError(mi::at(source, e) + "plugin '" + p.name + "' has no filename");
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
    p.params[c->Name()] = text(c);
  return p;
}

SensorSpec parseSensor(const XMLElement* e, const std::string& link, const std::string& source) {
  SensorSpec s;
  s.name = attr(e, "name");
  s.type = trimText(attr(e, "type"));
  s.link = link;
  s.line = e->GetLineNum();
  s.source = source;
  const std::string what = "sensor '" + s.name + "' on link '" + link + "'";
  if (s.name.empty())
    throw ModelError(mi::at(source, e) + "sensor on link '" + link + "' has no name");
  if (s.type.empty()) throw ModelError(mi::at(source, e) + what + " has no type");
  XmlReader reader(source, WarningSink());
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    // A bad value of the sensor's own tags leaves this sensor out, not the robot. A <sensor> is
    // SDF (gazebo_ros copies it as it is): an empty value keeps its default (XmlReader).
    try {
    if (tag == "pose") {
      s.X_LS = reader.pose(c, what, s.X_LS);
    } else if (tag == "update_rate") {
      if (!XmlReader::keepsDefault(c) || mi::attribute(c, "value"))
        s.update_rate = nonNegative(c, what, source);
    } else if (tag == "always_on") {
      s.always_on = toBool(c, what, source);
    } else if (tag == "plugin") {
      s.plugins.push_back(parsePlugin(c, source));
    }
    } catch (const ModelError& err) {
      if (tag == "plugin") throw;
      if (s.error.empty()) s.error = err.what();
    }
    // Everything else (ray, camera, noise, visualize, ...) belongs to the sensor loaders, which
    // read it from `xml` and report what they do not support.
  }
  XmlReader::Copy copy = XmlReader(source, WarningSink()).printCopy(e);
  s.xml = std::move(copy.xml);
  s.xml_lines = std::move(copy.lines);
  return s;
}

void parseLinkExtension(const XMLElement* g, const std::string& link, LinkExtension& ext,
                        const std::string& source, XmlReader& warner) {
  const std::string what = "<gazebo reference='" + link + "'>";
  for (const XMLElement* c = g->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "mu1") {  // a negative mu is no limit (toSurface), as in Gazebo
      ext.mu1 = finiteNumber(c, what, source, true);
    } else if (tag == "mu2") {
      ext.mu2 = finiteNumber(c, what, source, true);
    } else if (tag == "kp") {
      ext.kp = nonNegative(c, what, source);
    } else if (tag == "kd") {
      ext.kd = nonNegative(c, what, source);
    } else if (tag == "maxVel") {
      ext.max_vel = nonNegative(c, what, source);
    } else if (tag == "minDepth") {
      ext.min_depth = nonNegative(c, what, source);
    } else if (tag == "fdir1") {
      bool ok = false;
      const std::string v = valueOf(c);
      const auto n = numbers(v, &ok);
      if (!ok || n.size() != 3)
        throw ModelError(mi::at(source, c) + what + ": <fdir1> value '" + v +
                         "' is not 3 finite numbers \"x y z\"");
      ext.fdir1 = Eigen::Vector3d(n[0], n[1], n[2]);
    } else if (tag == "material") {
      ext.material = valueOf(c);
    } else if (tag == "selfCollide") {
      ext.self_collide = toBool(c, what, source);
    } else if (tag == "gravity") {
      ext.gravity = toBool(c, what, source);
    } else if (tag == "turnGravityOff") {
      ext.gravity = !toBool(c, what, source);
    } else if (tag == "sensor") {
      ext.sensors.push_back(parseSensor(c, link, source));
    } else {
      warner.warnOnce("gazebo-link:" + tag, mi::at(source, c) + what + ": unknown element <" +
                                                tag + "> ignored");
    }
  }
}

/// The reader of a model plugin's parameters: "<file>:<line>: plugin 'name' (file): ...".
PluginReader modelPluginReader(const PluginSpec& p, XmlReader& warner) {
  return PluginReader(p, "plugin '" + p.name + "' (" + p.filename + ")",
                      [&warner](const std::string& m) { warner.warn(m); });
}

RosControlSpec rosControl(const PluginSpec& p, XmlReader& warner) {
  PluginReader r = modelPluginReader(p, warner);
  RosControlSpec s;
  r.robotNamespace(NamespaceRule::kAsGiven, &s.robot_namespace);
  if (const auto param = r.text("robotParam"); param && !param->empty()) s.robot_param = *param;
  r.number("controlPeriod", &s.control_period, true);
  if (const auto type = r.text("robotSimType")) {
    if (*type == "gazebo_ros_control/DefaultRobotHWSim" ||
        *type == "steer_bot_hardware_gazebo/SteerBotHardwareGazebo")  // sim/steer_bot_hw_sim.h
      s.robot_sim_type = *type;
    else
      r.warn("robotSimType '" + *type +
             "' is not supported; the built-in DefaultRobotHWSim behaviour is used");
  }
  r.text("eStopTopic", &s.e_stop_topic);
  r.ignore({"legacyModeNS"});
  r.finish();
  return s;
}

JointStatePublisherSpec jointStatePublisher(const PluginSpec& p,
                                            const std::map<std::string, int>& joints,
                                            XmlReader& warner) {
  PluginReader r = modelPluginReader(p, warner);
  JointStatePublisherSpec s;
  const auto list = r.text("jointName");
  if (!list) r.fail("no <jointName>");
  // Comma separated; whitespace anywhere inside a name is dropped (the seed writes
  // "left_ front_wheel_joint" for left_front_wheel_joint).
  std::string name;
  auto flush = [&]() {
    if (name.empty()) return;
    if (!joints.count(name)) r.fail("unknown joint '" + name + "'");
    s.joint_names.push_back(name);
    name.clear();
  };
  for (char ch : *list) {
    if (ch == ',') {
      flush();
    } else if (!std::isspace(static_cast<unsigned char>(ch))) {
      name += ch;
    }
  }
  flush();
  if (s.joint_names.empty()) r.fail("<jointName> lists no joints");
  r.number("updateRate", &s.update_rate, true);
  r.robotNamespace(NamespaceRule::kAsGiven, &s.robot_namespace);
  r.ignore({"alwaysOn"});
  r.finish();
  return s;
}

std::vector<JointInterface> interfaces(const XMLElement* e, const std::string& what,
                                       const std::string& source) {
  std::vector<JointInterface> out;
  for (const XMLElement* h = e->FirstChildElement("hardwareInterface"); h;
       h = h->NextSiblingElement("hardwareInterface")) {
    const auto iface = parseJointInterface(text(h));
    if (!iface)
      throw ModelError(mi::at(source, h) + what + ": unknown hardwareInterface '" + text(h) +
                       "' (expected EffortJointInterface, VelocityJointInterface or "
                       "PositionJointInterface, optionally prefixed hardware_interface/)");
    out.push_back(*iface);
  }
  return out;
}

TransmissionSpec parseTransmission(const XMLElement* t, const std::string& source,
                                   const std::map<std::string, int>& joints,
                                   XmlReader& warner) {
  TransmissionSpec s;
  s.name = attr(t, "name");
  s.line = t->GetLineNum();
  const std::string what = "transmission '" + s.name + "'";
  if (s.name.empty()) throw ModelError(mi::at(source, t) + "transmission without a name");

  // <type> child (current format) or type attribute (pre-Indigo format).
  const XMLElement* type = t->FirstChildElement("type");
  s.type = type ? text(type) : trimText(attr(t, "type"));
  if (s.type.empty()) throw ModelError(mi::at(source, t) + what + ": no <type>");
  // gazebo_ros_control reads <type> as any text (DefaultRobotHWSim treats every one-joint
  // transmission as simple); ros_controllers' test robots write it without the namespace.
  if (s.type == "SimpleTransmission") s.type = kSimpleTransmission;
  if (s.type != kSimpleTransmission)
    throw ModelError(mi::at(source, type ? type : t) + what + ": unsupported type '" + s.type +
                     "' (only " + kSimpleTransmission + ", or SimpleTransmission)");

  const XMLElement* joint = nullptr;
  const XMLElement* actuator = nullptr;
  for (const XMLElement* c = t->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "type") continue;
    if (tag == "joint" || tag == "actuator") {
      const XMLElement*& slot = tag == "joint" ? joint : actuator;
      if (slot)
        throw ModelError(mi::at(source, c) + what + ": a SimpleTransmission has exactly one <" +
                         tag + ">");
      slot = c;
      continue;
    }
    warner.warnOnce("transmission:" + tag,
                    mi::at(source, c) + what + ": unknown element <" + tag + "> ignored");
  }
  if (!joint) throw ModelError(mi::at(source, t) + what + ": no <joint>");
  if (!actuator) throw ModelError(mi::at(source, t) + what + ": no <actuator>");

  s.joint = trimText(attr(joint, "name"));
  if (s.joint.empty()) throw ModelError(mi::at(source, joint) + what + ": <joint> has no name");
  if (!joints.count(s.joint))
    throw ModelError(mi::at(source, joint) + what + ": unknown joint '" + s.joint + "'");
  s.joint_interfaces = interfaces(joint, what + ": joint '" + s.joint + "'", source);
  for (const XMLElement* c = joint->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag != "hardwareInterface")
      warner.warnOnce("transmission-joint:" + tag,
                      mi::at(source, c) + what + ": joint '" + s.joint + "': unknown element <" +
                          tag + "> ignored");
  }

  s.actuator = trimText(attr(actuator, "name"));
  if (s.actuator.empty())
    throw ModelError(mi::at(source, actuator) + what + ": <actuator> has no name");
  const std::string awhat = what + ": actuator '" + s.actuator + "'";
  s.actuator_interfaces = interfaces(actuator, awhat, source);
  for (const XMLElement* c = actuator->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "hardwareInterface") continue;
    if (tag == "mechanicalReduction") {
      const std::string v = text(c);
      const auto d = parseNumber(v);
      if (!d || !std::isfinite(*d) || *d == 0.0)
        throw ModelError(mi::at(source, c) + awhat + ": mechanicalReduction '" + v +
                         "' must be a finite non-zero number");
      s.mechanical_reduction = *d;
      continue;
    }
    warner.warnOnce("transmission-actuator:" + tag,
                    mi::at(source, c) + awhat + ": unknown element <" + tag + "> ignored");
  }

  if (s.joint_interfaces.empty()) {
    // gazebo_ros_control's fallback for old files: the actuator's interfaces, with a warning.
    if (s.actuator_interfaces.empty())
      throw ModelError(mi::at(source, joint) + what + ": joint '" + s.joint +
                       "' has no <hardwareInterface>");
    s.joint_interfaces = s.actuator_interfaces;
    warner.warn(mi::at(source, joint) + what + ": joint '" + s.joint +
                "' has no <hardwareInterface>; using the actuator's (deprecated format)");
  }
  return s;
}

}  // namespace

std::optional<JointInterface> parseJointInterface(const std::string& text) {
  std::string t = trimText(text);
  const std::string prefix = "hardware_interface/";
  if (t.compare(0, prefix.size(), prefix) == 0) t.erase(0, prefix.size());
  if (t == "EffortJointInterface") return JointInterface::kEffort;
  if (t == "VelocityJointInterface") return JointInterface::kVelocity;
  if (t == "PositionJointInterface") return JointInterface::kPosition;
  return std::nullopt;
}

const char* toString(JointInterface iface) {
  switch (iface) {
    case JointInterface::kEffort:
      return "hardware_interface/EffortJointInterface";
    case JointInterface::kVelocity:
      return "hardware_interface/VelocityJointInterface";
    case JointInterface::kPosition:
      return "hardware_interface/PositionJointInterface";
  }
  return "unknown";
}

namespace model_internal {

RobotExtensions parseExtensionsXml(const XMLElement* robot, const std::string& source,
                                   XmlReader& warner) {
  std::map<std::string, int> links, joints;
  for (const XMLElement* e = robot->FirstChildElement("link"); e;
       e = e->NextSiblingElement("link"))
    links.emplace(attr(e, "name"), e->GetLineNum());
  for (const XMLElement* e = robot->FirstChildElement("joint"); e;
       e = e->NextSiblingElement("joint"))
    joints.emplace(attr(e, "name"), e->GetLineNum());

  RobotExtensions ext;
  const XMLElement* ros_control_element = nullptr;
  const XMLElement* jsp_element = nullptr;
  std::map<std::string, std::string> transmission_of_joint;
  for (const XMLElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "link" || tag == "joint" || tag == "material") continue;
    if (tag == "transmission") {
      TransmissionSpec t = parseTransmission(e, source, joints, warner);
      const auto ins = transmission_of_joint.emplace(t.joint, t.name);
      if (!ins.second)
        throw ModelError(at(source, e) + "transmission '" + t.name + "': joint '" + t.joint +
                         "' already has transmission '" + ins.first->second + "'");
      ext.transmissions.push_back(std::move(t));
      continue;
    }
    if (tag != "gazebo") {
      warner.warnOnce("robot:" + tag, at(source, e) + "unknown element <" + tag + "> ignored");
      continue;
    }
    if (const auto ref = mi::attribute(e, "reference")) {
      const std::string link = trimText(*ref);
      if (links.count(link)) {
        parseLinkExtension(e, link, ext.links[link], source, warner);
      } else if (joints.count(link)) {
        warner.warnOnce("gazebo-joint:" + link,
                        at(source, e) + "<gazebo reference='" + link +
                            "'> names a joint; joint extensions are not supported, ignored");
      } else {
        warner.warnOnce("gazebo-ref:" + link,
                        at(source, e) + "<gazebo reference='" + link + "'>: no link named '" +
                            link + "' (Gazebo ignores it)");
      }
      continue;
    }
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string ctag = c->Name();
      if (ctag != "plugin") {
        warner.warnOnce("gazebo-model:" + ctag,
                        at(source, c) + "<gazebo>: unknown element <" + ctag + "> ignored");
        continue;
      }
      PluginSpec p = parsePlugin(c, source);
      if (p.filename == kRosControl) {
        if (ros_control_element)
          throw ModelError(at(source, c) + "second " + kRosControl + " plugin (the first is at line " +
                           std::to_string(ros_control_element->GetLineNum()) + ")");
        ros_control_element = c;
        ext.ros_control = rosControl(p, warner);
      } else if (p.filename == kJointStatePublisher) {
        if (jsp_element)
          throw ModelError(at(source, c) + "second " + kJointStatePublisher +
                           " plugin (the first is at line " +
                           std::to_string(jsp_element->GetLineNum()) + ")");
        jsp_element = c;
        ext.joint_state_publisher = jointStatePublisher(p, joints, warner);
      }
      // Other plugins (IMU, p3d, ...) are the sensor registry's to judge, which this layer
      // cannot see: the start-up table names each one simulated or left out.
      ext.model_plugins.push_back(std::move(p));
    }
  }
  return ext;
}

}  // namespace model_internal

SensorSpec parseSensorElement(const XMLElement* sensor, const std::string& link,
                              const std::string& source) {
  return parseSensor(sensor, link, source);
}

PluginSpec parsePluginElement(const XMLElement* plugin, const std::string& source) {
  return parsePlugin(plugin, source);
}

RobotExtensions parseExtensions(const std::string& urdf_xml, const std::string& source,
                                const WarningSink& warn) {
  tinyxml2::XMLDocument doc;
  const XMLElement* robot = mi::parseRobotXml(doc, urdf_xml, source);
  XmlReader warner = mi::modelReader(source, warn);
  return mi::parseExtensionsXml(robot, source, warner);
}

}  // namespace tianracer_sim
