#include "tianracer_sim/plugins/camera/multicamera_config.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include <tinyxml2.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {
namespace {

using tinyxml2::XMLElement;

const char* const kMultiCameraPlugin = "libgazebo_ros_multicamera.so";

// The libgazebo_ros_camera parameters every camera of the multicamera reads (parsed by
// parseCameraConfig); the multicamera's own (frameName, hackBaseline, cameraSuffixes) are
// applied per camera here.
const std::set<std::string> kSharedCameraParams = {
    "robotNamespace", "cameraName",   "imageTopicName", "cameraInfoTopicName", "updateRate",
    "distortionK1",   "distortionK2", "distortionK3",   "distortionT1",        "distortionT2",
    "distortion_k1",  "distortion_k2", "distortion_k3", "distortion_t1",       "distortion_t2",
    "Cx",             "Cy",           "CxPrime",        "focalLength",         "alwaysOn"};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(trimText(item));
  return out;
}

class MultiCameraParser {
 public:
  MultiCameraParser(const SensorSpec& sensor, const std::string& model_name,
                    const WarningSink& warn)
      : sensor_(sensor), model_name_(model_name), warn_(warn),
        xml_(XmlReader::copyOf(sensor.source, sensor.line, context(sensor, model_name) + ": ",
                               warn, sensor.xml_lines)) {}

  // Read from the <sensor>'s printed copy (SensorSpec::xml): every message is placed at the
  // sensor's line of the model file, then names the robot and the sensor.
  static std::string context(const SensorSpec& sensor, const std::string& model_name) {
    std::string c = "robot '" + model_name + "': multicamera sensor '" + sensor.name + "'";
    if (!sensor.link.empty()) c += " on link '" + sensor.link + "'";
    return c;
  }

  [[noreturn]] void fail(const std::string& what) const { xml_.fail(nullptr, what); }
  void warn(const std::string& what) { xml_.warn(nullptr, what); }
  [[noreturn]] void fail(const XMLElement* e, const std::string& what) const { xml_.fail(e, what); }

  MultiCameraConfig parse() {
    MultiCameraConfig m;
    m.name = sensor_.name;
    m.link = sensor_.link;
    m.update_rate = sensor_.update_rate;
    tinyxml2::XMLDocument doc;
    XMLElement* root = xml_.parseCopy(sensor_.xml, &doc);
    const PluginSpec* plugin = findPlugin();
    m.has_plugin = plugin != nullptr;

    // Every <camera> parses as the only camera of a camera sensor; its <pose> is ours.
    std::vector<std::string> names;
    std::vector<Eigen::Isometry3d> poses;
    std::vector<SensorSpec> specs;
    for (XMLElement* cam = root->FirstChildElement("camera"); cam;
         cam = cam->NextSiblingElement("camera")) {
      const std::string name = attributeText(cam, "name");
      if (name.empty()) {
        fail(cam, "<camera> number " + std::to_string(names.size() + 1) +
             " has no name (a multicamera's cameras are told apart by name)");
      }
      for (const std::string& n : names) {
        if (n == name) fail(cam, "two cameras are named '" + name + "'; each needs its own name");
      }
      names.push_back(name);
      Eigen::Isometry3d X_SC = Eigen::Isometry3d::Identity();
      if (XMLElement* pose = cam->FirstChildElement("pose")) {
        X_SC = xml_.pose(pose, "camera '" + name + "'", X_SC);
        cam->DeleteChild(pose);
      }
      poses.push_back(X_SC);
      XmlReader::Copy copy = xml_.printCopy(cam);
      SensorSpec spec = sensor_;
      spec.name = sensor_.name + "/" + name;
      spec.xml = std::move(copy.xml);
      spec.xml_lines = std::move(copy.lines);
      spec.plugins.clear();
      if (plugin) spec.plugins.push_back(cameraPlugin(*plugin));
      specs.push_back(spec);
    }
    for (const XMLElement* c = root->FirstChildElement(); c;
         c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (tag != "camera" && tag != "plugin" && tag != "pose" && tag != "update_rate" &&
          tag != "always_on" && tag != "visualize") {
        xml_.warn(c, "unknown element <" + tag + "> ignored");
      }
    }
    if (names.size() < 2) {
      fail("has " + std::to_string(names.size()) +
           " <camera> element(s); a multicamera needs at least two (use type=\"camera\" for one)");
    }

    std::vector<std::string> suffixes, frames;
    double hack_baseline = 0.0;
    if (plugin) readPlugin(*plugin, names, &suffixes, &frames, &hack_baseline);

    for (std::size_t i = 0; i < specs.size(); ++i) {
      CameraConfig c;
      try {
        c = parseCameraConfig(specs[i], warn_);
      } catch (const CameraError& e) {
        throw CameraError(e.where(), "robot '" + model_name_ + "': " + e.message());
      }
      c.name = names[i];
      c.type = "multicamera";
      c.X_LS = sensor_.X_LS * poses[i];
      c.noise_seed = nameHash(specs[i].name);
      if (plugin) {
        c.plugin_filename = plugin->filename;
        c.camera_name += suffixes[i];
        if (!frames.empty() && !frames[i].empty()) c.frame_name = frames[i];
        c.hack_baseline = names[i].find("right") != std::string::npos ? hack_baseline : 0.0;
      }
      m.cameras.push_back(c);
    }
    return m;
  }

 private:
  const PluginSpec* findPlugin() const {
    for (const PluginSpec& p : sensor_.plugins) {
      if (endsWith(p.filename, kMultiCameraPlugin)) return &p;
    }
    return nullptr;
  }

  // The multicamera plugin as the libgazebo_ros_camera plugin each camera reads: only the
  // parameters a camera shares; the rest are the multicamera's or unknown.
  PluginSpec cameraPlugin(const PluginSpec& p) const {
    PluginSpec out = p;
    out.filename = "libgazebo_ros_camera.so";
    out.params.clear();
    for (const auto& [key, value] : p.params) {
      if (kSharedCameraParams.count(key)) out.params[key] = value;
    }
    return out;
  }

  void readPlugin(const PluginSpec& p, const std::vector<std::string>& names,
                  std::vector<std::string>* suffixes, std::vector<std::string>* frames,
                  double* hack_baseline) {
    const std::size_t n = names.size();
    PluginReader r(p, context(sensor_, model_name_), warn_);
    r.number("hackBaseline", hack_baseline);
    std::string text;
    // Topic suffixes: the list, else the left/right pair, else each camera's name.
    if (r.text("cameraSuffixes", &text) && !text.empty()) {
      *suffixes = splitList(text);
      if (suffixes->size() != n) {
        r.fail("<cameraSuffixes> '" + text + "' has " + std::to_string(suffixes->size()) +
               " entries for " + std::to_string(n) + " cameras");
      }
    } else if (n == 2 && names[0].find("left") != std::string::npos &&
               names[1].find("right") != std::string::npos) {
      *suffixes = {"/left", "/right"};
    } else if (n == 2 && names[0].find("right") != std::string::npos &&
               names[1].find("left") != std::string::npos) {
      *suffixes = {"/right", "/left"};
    } else {
      for (const std::string& name : names) suffixes->push_back("/" + name);
    }
    if (r.text("frameName", &text) && !text.empty()) {
      *frames = splitList(text);
      if (frames->size() == 1) frames->resize(n, frames->front());
      if (frames->size() != n) {
        r.fail("<frameName> '" + text + "' lists " + std::to_string(frames->size()) +
               " frames for " + std::to_string(n) + " cameras (give one, or one per camera)");
      }
    }
    // The shared ones are read by each camera's own parser (cameraPlugin()).
    for (const std::string& key : kSharedCameraParams) r.has(key);
    r.finish();
  }

  const SensorSpec& sensor_;
  std::string model_name_;
  const WarningSink& warn_;  // for the cameras' own parsers
  XmlReader xml_;
};

}  // namespace

MultiCameraConfig parseMultiCameraConfig(const SensorSpec& sensor, const std::string& model_name,
                                         const WarningSink& warn) {
  MultiCameraConfig config = MultiCameraParser(sensor, model_name, warn).parse();
  // gazebo_ros_multicamera loads a GazeboRosCameraUtils per camera: an empty
  // <robotNamespace/> is the model's name there too.
  for (CameraConfig& c : config.cameras) applyModelNamespace(&c, model_name);
  return config;
}

}  // namespace tianracer_sim
