#include "tianracer_sim/plugins/camera/camera_config.h"
#include "tianracer_sim/common/input_limits.h"

#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <vector>

#include <tinyxml2.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {

std::string opticalFrameId(const std::string& frame_name) { return frame_name + "_optical_frame"; }

double CameraConfig::focalLength() const { return width / (2.0 * std::tan(horizontal_fov / 2.0)); }

CameraIntrinsics CameraConfig::intrinsics() const {
  const CameraInfo info = makeCameraInfo(*this);
  CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = info.K[0];
  k.fy = info.K[4];
  k.cx = info.K[2];
  k.cy = info.K[5];
  k.near_clip = near_clip;
  k.far_clip = far_clip;
  return k;
}

const char* imageEncoding(ImageFormat format) {
  switch (format) {
    case ImageFormat::kR8G8B8: return "rgb8";
    case ImageFormat::kB8G8R8: return "bgr8";
    case ImageFormat::kL8: return "mono8";
    case ImageFormat::kL16: return "mono16";
    case ImageFormat::kR16G16B16: return "rgb16";
    case ImageFormat::kBayerRGGB8: return "bayer_rggb8";
    case ImageFormat::kBayerBGGR8: return "bayer_bggr8";
    case ImageFormat::kBayerGBRG8: return "bayer_gbrg8";
    case ImageFormat::kBayerGRBG8: return "bayer_grbg8";
  }
  return "rgb8";
}

int channelCount(ImageFormat format) {
  switch (format) {
    case ImageFormat::kR8G8B8:
    case ImageFormat::kB8G8R8:
    case ImageFormat::kR16G16B16: return 3;
    default: return 1;
  }
}

int bytesPerChannel(ImageFormat format) {
  return format == ImageFormat::kL16 || format == ImageFormat::kR16G16B16 ? 2 : 1;
}

int bytesPerPixel(ImageFormat format) { return channelCount(format) * bytesPerChannel(format); }

int bayerChannel(ImageFormat format, int row, int col) {
  // The 2x2 tile, row by row, as the encoding's name spells it.
  static const char* const kTiles[] = {"RGGB", "BGGR", "GBRG", "GRBG"};
  int tile = -1;
  switch (format) {
    case ImageFormat::kBayerRGGB8: tile = 0; break;
    case ImageFormat::kBayerBGGR8: tile = 1; break;
    case ImageFormat::kBayerGBRG8: tile = 2; break;
    case ImageFormat::kBayerGRBG8: tile = 3; break;
    default: return -1;
  }
  const char c = kTiles[tile][(row & 1) * 2 + (col & 1)];
  return c == 'R' ? 0 : c == 'G' ? 1 : 2;
}

Eigen::Isometry3d CameraConfig::X_LO() const { return X_LS * opticalFromLinkRotation(); }

namespace {

using tinyxml2::XMLElement;

// Text directly inside an element, trimmed ("" when none).
std::string textOf(const XMLElement* e) { return elementText(e); }

class Parser {
 public:
  // The <sensor> is read from its printed copy (SensorSpec::xml): every message is placed at the
  // sensor's line of the model file, then names the sensor.
  Parser(const SensorSpec& sensor, const WarningSink& warn)
      : sensor_(sensor), warn_(warn),
        xml_(XmlReader::copyOf(sensor.source, sensor.line, context(sensor) + ": ", warn, sensor.xml_lines)) {}

  /// What every message names: "camera sensor 'c' on link 'l'".
  static std::string context(const SensorSpec& sensor) {
    std::string c = sensor.type + " sensor '" + sensor.name + "'";
    if (!sensor.link.empty()) c += " on link '" + sensor.link + "'";
    return c;
  }

  [[noreturn]] void fail(const std::string& what) const { xml_.fail(nullptr, what); }
  void warn(const std::string& what) { xml_.warn(nullptr, what); }
  /// At `e`'s own line of the model file (the <sensor>'s when `e` is null).
  [[noreturn]] void fail(const XMLElement* e, const std::string& what) const { xml_.fail(e, what); }
  void warn(const XMLElement* e, const std::string& what) { xml_.warn(e, what); }

  /// `text` (of `e`, where an error is placed) as a finite number.
  double number(const std::string& element, const std::string& text, const XMLElement* e) const {
    const auto v = parseNumber(text);
    if (!v || !std::isfinite(*v)) fail(e, element + " '" + text + "' is not a number");
    return *v;
  }

  int integer(const std::string& element, const std::string& text, const XMLElement* e) const {
    const double v = number(element, text, e);
    if (v != std::floor(v) || std::fabs(v) > 1e9) fail(e, element + " '" + text + "' is not an integer");
    return static_cast<int>(v);
  }

  /// <lens> of a wideanglecamera (sdformat's camera.sdf; CameraLens::Load / SetType in
  /// gazebo/rendering/WideAngleCamera.cc). Unknown types and functions are errors here (Gazebo
  /// logs them and renders something else).
  void parseLens(const XMLElement* lens_element, WideAngleLens* lens) {
    std::string type = "stereographic";
    const XMLElement* custom = nullptr;
    bool scale_to_hfov = true;
    double cutoff = lens->cutoff_angle;
    int env_size = lens->env_texture_size;
    for (const XMLElement* g = lens_element->FirstChildElement(); g; g = g->NextSiblingElement()) {
      const std::string g_name = g->Name(), g_text = textOf(g);
      if (g_name == "type") {
        type = trimText(g_text);
      } else if (g_name == "scale_to_hfov") {
        const std::string b = trimText(g_text);
        if (b == "true" || b == "1") scale_to_hfov = true;
        else if (b == "false" || b == "0") scale_to_hfov = false;
        else fail(g, "<lens><scale_to_hfov> '" + g_text + "' is not a boolean");
      } else if (g_name == "custom_function") {
        custom = g;
      } else if (g_name == "cutoff_angle") {
        cutoff = number("<lens><cutoff_angle>", g_text, g);
      } else if (g_name == "env_texture_size") {
        env_size = integer("<lens><env_texture_size>", g_text, g);
      } else if (g_name == "intrinsics") {
        warn("<lens><intrinsics> ignored: a wideanglecamera stitches its image from six views "
             "(camera.sdf)");
      } else {
        warn("unknown element <lens><" + g_name + "> ignored");
      }
    }
    if (type == "custom") {
      if (custom == nullptr) {
        // CameraLens::Load: gzerr, and the lens becomes stereographic.
        warn("<lens><type> custom without <custom_function>: stereographic, as Gazebo");
        type = "stereographic";
      } else {
        WideAngleLens l;
        l.type = "custom";
        l.c1 = 1.0, l.c2 = 1.0, l.c3 = 0.0, l.f = 1.0, l.fun = WideAngleLens::Fun::kTan;
        for (const XMLElement* g = custom->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          const std::string what = "<lens><custom_function><" + g_name + ">";
          if (g_name == "c1") l.c1 = number(what, g_text, g);
          else if (g_name == "c2") l.c2 = number(what, g_text, g);
          else if (g_name == "c3") l.c3 = number(what, g_text, g);
          else if (g_name == "f") l.f = number(what, g_text, g);
          else if (g_name == "fun") {
            const auto fun = WideAngleLens::funOf(trimText(g_text));
            if (!fun) fail(g, what + " '" + g_text + "' is not a lens function (sin, tan, id)");
            l.fun = *fun;
          } else {
            warn("unknown element " + what + " ignored");
          }
        }
        if (l.c1 == 0.0 || l.c2 == 0.0) {
          fail("<lens><custom_function> c1 " + formatShort(l.c1) + ", c2 " + formatShort(l.c2) +
               ": both must be non-zero");
        }
        if (!(l.f > 0.0)) fail("<lens><custom_function><f> " + formatShort(l.f) + " must be > 0");
        *lens = l;
      }
    }
    if (type != "custom") {
      const auto named = WideAngleLens::ofType(type);
      if (!named) {
        fail("<lens><type> '" + type + "' is not a lens type (gnomonical, stereographic, "
             "equidistant, equisolid_angle, orthographic, custom)");
      }
      *lens = *named;
    }
    lens->scale_to_hfov = scale_to_hfov;
    if (!(cutoff > 0.0 && cutoff <= M_PI)) {
      fail("<lens><cutoff_angle> " + formatShort(cutoff) + " rad outside (0, pi]");
    }
    lens->cutoff_angle = cutoff;
    if (env_size <= 0 || env_size > 4096) {
      fail("<lens><env_texture_size> " + std::to_string(env_size) + " out of range 1..4096 "
           "(the size of each of the cube map's six faces, pixels)");
    }
    lens->env_texture_size = env_size;
  }

  void parseCamera(CameraConfig* c) {
    c->name = sensor_.name;
    c->type = sensor_.type;
    c->link = sensor_.link;
    c->X_LS = sensor_.X_LS;
    c->update_rate = sensor_.update_rate;
    c->line = sensor_.line;
    if (!(c->update_rate >= 0.0) || !std::isfinite(c->update_rate)) {
      fail("<update_rate> " + std::to_string(c->update_rate) + " must be >= 0");
    }
    tinyxml2::XMLDocument doc;
    const XMLElement* root = xml_.parseCopy(sensor_.xml, &doc);
    const XMLElement* cam =
        std::string(root->Name()) == "camera" ? root : root->FirstChildElement("camera");
    if (cam == nullptr) fail("has no <camera> element");
    c->wide_angle = sensor_.type == "wideanglecamera";
    // Where each value checked below was read, so that its error names that line (<camera>'s
    // when the value is the default).
    const XMLElement *width_e = cam, *height_e = cam, *image_e = cam, *fov_e = cam, *near_e = cam,
                     *format_e = cam, *lens_e = cam;
    for (const XMLElement* child = cam->FirstChildElement(); child;
         child = child->NextSiblingElement()) {
      const std::string n = child->Name();
      const std::string child_text = textOf(child);
      if (n == "horizontal_fov") {
        c->horizontal_fov = number("<camera><horizontal_fov>", child_text, child);
        fov_e = child;
      } else if (n == "image") {
        image_e = child;
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          if (g_name == "width") c->width = integer("<image><width>", g_text, width_e = g);
          else if (g_name == "height") c->height = integer("<image><height>", g_text, height_e = g);
          else if (g_name == "format") c->format_name = trimText(g_text), format_e = g;
          else warn(g, "unknown element <camera><image><" + g_name + "> ignored");
        }
      } else if (n == "clip") {
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          if (g_name == "near") c->near_clip = number("<clip><near>", g_text, near_e = g);
          else if (g_name == "far") c->far_clip = number("<clip><far>", g_text, g);
          else warn(g, "unknown element <camera><clip><" + g_name + "> ignored");
        }
      } else if (n == "noise") {
        std::string type = "gaussian";
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          if (g_name == "type") type = trimText(g_text);
          else if (g_name == "mean") c->noise_mean = number("<noise><mean>", g_text, g);
          else if (g_name == "stddev") c->noise_stddev = number("<noise><stddev>", g_text, g);
          else warn(g, "unknown element <camera><noise><" + g_name + "> ignored");
        }
        if (type == "none") {
          c->noise = false;
        } else if (type == "gaussian") {
          c->noise = c->noise_stddev > 0.0 || c->noise_mean != 0.0;
        } else {
          fail(child, "<noise><type> '" + type + "' is not supported (gaussian, none)");
        }
        if (c->noise_stddev < 0.0) fail(child, "<noise><stddev> " + child_text + " must be >= 0");
      } else if (n == "distortion") {
        LensDistortion& d = c->distortion;
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          const std::string what = "<distortion><" + g_name + ">";
          if (g_name == "k1") d.k1 = number(what, g_text, g);
          else if (g_name == "k2") d.k2 = number(what, g_text, g);
          else if (g_name == "k3") d.k3 = number(what, g_text, g);
          else if (g_name == "p1") d.p1 = number(what, g_text, g);
          else if (g_name == "p2") d.p2 = number(what, g_text, g);
          else if (g_name == "center") {
            const auto v = parseNumbers(g_text);
            if (!v || v->size() != 2 || !std::isfinite((*v)[0]) || !std::isfinite((*v)[1]))
              fail(g, what + " '" + g_text + "' is not two numbers");
            d.center_x = (*v)[0];
            d.center_y = (*v)[1];
          } else {
            warn(g, "unknown element <camera><distortion><" + g_name + "> ignored");
          }
        }
      } else if (n == "lens" && c->wide_angle) {
        lens_e = child;
        parseLens(child, &c->lens);
      } else if (n == "save" || n == "depth_camera" || n == "lens" || n == "pose" ||
                 n == "visualize" || n == "triggered" || n == "trigger_topic") {
        warn(child, "<camera><" + n + "> is not supported; ignored");
      } else {
        warn(child, "unknown element <camera><" + n + "> ignored");
      }
    }
    // Validation, each value named.
    auto str = [](double v) {
      std::ostringstream os;
      os << v;
      return os.str();
    };
    if (c->width <= 0 || c->width > 8192) fail(width_e, "<image><width> " + std::to_string(c->width) + " out of range 1..8192");
    if (c->height <= 0 || c->height > 8192) fail(height_e, "<image><height> " + std::to_string(c->height) + " out of range 1..8192");
    // 8192 x 8192 RGBA is 256 MB per image, rendered and copied every update.
    if (static_cast<double>(c->width) * c->height > limits::kImagePixels)
      fail(image_e, "<image> " + std::to_string(c->width) + " x " + std::to_string(c->height) +
           " pixels is out of range (<= " + std::to_string(static_cast<long>(limits::kImagePixels)) +
           " pixels, e.g. 7680 x 4320)");
    if (c->wide_angle) {
      // camera.sdf's range for horizontal_fov; the cube map sees every direction.
      if (!(c->horizontal_fov > 0.0 && c->horizontal_fov <= 2.0 * M_PI)) {
        fail(fov_e, "<horizontal_fov> " + str(c->horizontal_fov) + " rad outside (0, 2 pi]");
      }
      if (c->lens.type == "gnomonical" && c->horizontal_fov > M_PI / 2.0) {
        // WideAngleCamera::Load's gzerr.
        warn("<lens><type> gnomonical with <horizontal_fov> " + str(c->horizontal_fov) +
             " rad: Gazebo recommends a horizontal FOV <= pi/2 for it");
      }
      const double focal = c->lens.focal(c->horizontal_fov);
      if (!(focal > 0.0) || !std::isfinite(focal)) {
        fail(lens_e, "<lens> " + c->lens.type + " with <horizontal_fov> " + str(c->horizontal_fov) +
             " rad has no image (f = 1 / (c1 fun(hfov/2 / c2 + c3)) = " + str(focal) + ")");
      }
      if (c->distortion.enabled()) {
        warn("<camera><distortion> is not applied to a wideanglecamera's images (its <lens> is)");
        c->distortion = LensDistortion();
      }
    } else if (!(c->horizontal_fov > 0.0 && c->horizontal_fov < M_PI)) {
      fail(fov_e, "<horizontal_fov> " + str(c->horizontal_fov) + " rad outside (0, pi)");
    }
    if (!(c->near_clip > 0.0)) fail(near_e, "<clip><near> " + str(c->near_clip) + " must be > 0");
    if (!(c->near_clip < c->far_clip)) {
      fail(near_e, "<clip><near> " + str(c->near_clip) + " must be less than <clip><far> " + str(c->far_clip));
    }
    // Gazebo's names (and its *_INT* aliases), as gazebo_ros_camera_utils.cpp Init maps them;
    // the float formats are Gazebo's too, but not simulated here.
    const std::string& f = c->format_name;
    static const std::pair<const char*, ImageFormat> kFormats[] = {
        {"R8G8B8", ImageFormat::kR8G8B8},          {"RGB_INT8", ImageFormat::kR8G8B8},
        {"B8G8R8", ImageFormat::kB8G8R8},          {"BGR_INT8", ImageFormat::kB8G8R8},
        {"L8", ImageFormat::kL8},                  {"L_INT8", ImageFormat::kL8},
        {"L16", ImageFormat::kL16},                {"L_INT16", ImageFormat::kL16},
        {"R16G16B16", ImageFormat::kR16G16B16},    {"RGB_INT16", ImageFormat::kR16G16B16},
        {"BAYER_RGGB8", ImageFormat::kBayerRGGB8}, {"BAYER_BGGR8", ImageFormat::kBayerBGGR8},
        {"BAYER_GBRG8", ImageFormat::kBayerGBRG8}, {"BAYER_GRBG8", ImageFormat::kBayerGRBG8}};
    static const char* kSupported = "R8G8B8, B8G8R8, L8, L16, R16G16B16, BAYER_RGGB8, "
                                    "BAYER_BGGR8, BAYER_GBRG8, BAYER_GRBG8";
    bool known = false;
    for (const auto& [name, format] : kFormats) {
      if (f == name) {
        c->format = format;
        known = true;
      }
    }
    if (!known) {
      if (f == "R_FLOAT16" || f == "R_FLOAT32") {
        fail(format_e, "<image><format> '" + f + "' is a Gazebo format that is not simulated (supported: " +
             kSupported + "); the camera is left out");
      }
      fail(format_e, "<image><format> '" + f + "' is not a Gazebo image format (supported: " + kSupported +
           ")");
    }
    c->noise_seed = nameHash(sensor_.name);
    c->frame_name = sensor_.link;
  }

  // The sensor's plugin of one of `filenames` (or nullptr).
  const PluginSpec* findPlugin(const std::vector<std::string>& filenames) const {
    for (const PluginSpec& p : sensor_.plugins) {
      for (const auto& f : filenames) {
        if (endsWith(p.filename, f)) return &p;
      }
    }
    return nullptr;
  }

  /// The plugin's parameters, placed at the <plugin> and naming the sensor.
  PluginReader pluginReader(const PluginSpec& p) const {
    return PluginReader(p, context(sensor_), warn_);
  }

  void parseCameraPlugin(PluginReader& r, CameraConfig* c) {
    const PluginSpec& p = r.plugin();
    c->has_plugin = true;
    c->plugin_filename = p.filename;
    c->triggered = endsWith(p.filename, "libgazebo_ros_triggered_camera.so");
    // An empty <robotNamespace/> is the model's name: gazebo_ros_camera_utils.cpp Load calls
    // GetRobotNamespace (gazebo_ros_utils.h), which gives the model's name when the element is
    // there but empty, and "" when it is missing. Resolved by applyModelNamespace().
    c->namespace_from_model =
        r.robotNamespace(NamespaceRule::kEmptyIsModel, &c->robot_namespace) == NamespaceFrom::kModel;
    r.text("cameraName", &c->camera_name);
    r.text("imageTopicName", &c->image_topic);
    r.text("cameraInfoTopicName", &c->camera_info_topic);
    r.text("triggerTopicName", &c->trigger_topic);
    if (c->triggered && c->trigger_topic.empty()) r.fail("<triggerTopicName> is empty");
    std::string frame;
    if (r.text("frameName", &frame) && !frame.empty()) c->frame_name = frame;
    r.number("updateRate", &c->plugin_update_rate);
    r.number("hackBaseline", &c->hack_baseline);
    // gazebo_ros reads the camel-case names; openni examples write distortion_k1: take both.
    for (const auto& k : {std::make_pair("distortionK1", &c->k1), std::make_pair("distortion_k1", &c->k1),
                          std::make_pair("distortionK2", &c->k2), std::make_pair("distortion_k2", &c->k2),
                          std::make_pair("distortionK3", &c->k3), std::make_pair("distortion_k3", &c->k3),
                          std::make_pair("distortionT1", &c->t1), std::make_pair("distortion_t1", &c->t1),
                          std::make_pair("distortionT2", &c->t2), std::make_pair("distortion_t2", &c->t2)}) {
      r.number(k.first, k.second);
    }
    r.boolean("autoDistortion", &c->auto_distortion);
    r.boolean("borderCrop", &c->border_crop);
    if (c->auto_distortion) {
      // gazebo_ros_camera_utils Init: D from the sensor's <distortion>.
      c->k1 = c->distortion.k1;
      c->k2 = c->distortion.k2;
      c->k3 = c->distortion.k3;
      c->t1 = c->distortion.p1;
      c->t2 = c->distortion.p2;
    }
    c->distortion.crop = c->border_crop && c->distortion.k1 < 0.0;
    r.number("Cx", &c->cx_override);
    r.number("Cy", &c->cy_override);
    r.number("focalLength", &c->focal_length_override);
    double unused = 0.0;
    r.number("CxPrime", &unused);
    r.ignore({"alwaysOn"});
    if (c->plugin_update_rate < 0.0) r.fail("<updateRate> must be >= 0");
    const LensDistortion& d = c->distortion;
    if (c->k1 != d.k1 || c->k2 != d.k2 || c->k3 != d.k3 || c->t1 != d.p1 || c->t2 != d.p2) {
      r.warn("camera_info D [" + formatShort(c->k1) + " " + formatShort(c->k2) + " " +
             formatShort(c->t1) + " " + formatShort(c->t2) + " " + formatShort(c->k3) +
             "] differs from the <distortion> applied to the images (k1 k2 p1 p2 k3 = " +
             formatShort(d.k1) + " " + formatShort(d.k2) + " " + formatShort(d.p1) + " " +
             formatShort(d.p2) + " " + formatShort(d.k3) + "): as gazebo_ros, D is the plugin's "
             "distortionK1.. unless <autoDistortion> is true");
    }
    if (c->focal_length_override > 0.0 &&
        std::fabs(c->focal_length_override - c->focalLength()) > 1e-6 * c->focalLength()) {
      r.warn("<focalLength> " + std::to_string(c->focal_length_override) +
             " disagrees with width and hfov (f = " + std::to_string(c->focalLength()) +
             "); camera_info reports it and the images are rendered with it");
    }
  }

  const SensorSpec& sensor() const { return sensor_; }

 private:
  const SensorSpec& sensor_;
  WarningSink warn_;
  XmlReader xml_;
};

const std::vector<std::string> kCameraPlugins = {"libgazebo_ros_camera.so",
                                                  "libgazebo_ros_triggered_camera.so"};
const std::vector<std::string> kDepthPlugins = {"libgazebo_ros_openni_kinect.so",
                                                "libgazebo_ros_depth_camera.so"};

}  // namespace

CameraConfig parseCameraConfig(const SensorSpec& sensor, const WarningSink& warn) {
  Parser parser(sensor, warn);
  CameraConfig c;
  parser.parseCamera(&c);
  if (const PluginSpec* p = parser.findPlugin(kCameraPlugins)) {
    PluginReader r = parser.pluginReader(*p);
    parser.parseCameraPlugin(r, &c);
    r.finish();
  }
  return c;
}

DepthCameraConfig parseDepthCameraConfig(const SensorSpec& sensor, const WarningSink& warn) {
  Parser parser(sensor, warn);
  DepthCameraConfig d;
  d.camera.image_topic = "ir/image_raw";  // openni_kinect's own defaults
  d.camera.camera_info_topic = "ir/camera_info";
  parser.parseCamera(&d.camera);
  if (d.camera.distortion.enabled()) {
    parser.warn("<camera><distortion> is not applied to a depth camera's images (only to "
                "camera and multicamera sensors); camera_info reports the plugin's D");
    d.camera.distortion = LensDistortion();
  }
  if (const PluginSpec* p = parser.findPlugin(kDepthPlugins)) {
    PluginReader r = parser.pluginReader(*p);
    parser.parseCameraPlugin(r, &d.camera);
    r.text("depthImageTopicName", &d.depth_image_topic);
    r.text("depthImageCameraInfoTopicName", &d.depth_camera_info_topic);
    r.text("pointCloudTopicName", &d.point_cloud_topic);
    r.number("baseline", &d.baseline);
    r.number("pointCloudCutoff", &d.point_cloud_cutoff);
    r.number("pointCloudCutoffMax", &d.point_cloud_cutoff_max);
    if (!(d.point_cloud_cutoff < d.point_cloud_cutoff_max)) {
      r.fail("<pointCloudCutoff> " + std::to_string(d.point_cloud_cutoff) +
             " must be less than <pointCloudCutoffMax> " + std::to_string(d.point_cloud_cutoff_max));
    }
    r.finish();
  }
  return d;
}

void applyModelNamespace(CameraConfig* c, const std::string& model_name) {
  if (c->namespace_from_model) c->robot_namespace = model_name;
}

CameraInfo makeCameraInfo(const CameraConfig& c) {
  CameraInfo info;
  info.frame_id = c.opticalFrame();
  info.width = c.width;
  info.height = c.height;
  const double f = c.focal_length_override > 0.0 ? c.focal_length_override : c.focalLength();
  const double cx = c.cx_override != 0.0 ? c.cx_override : (c.width + 1.0) / 2.0;
  const double cy = c.cy_override != 0.0 ? c.cy_override : (c.height + 1.0) / 2.0;
  info.D = {c.k1, c.k2, c.t1, c.t2, c.k3};
  info.K = {f, 0, cx, 0, f, cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {f, 0, cx, -f * c.hack_baseline, 0, f, cy, 0, 0, 0, 1, 0};
  return info;
}

}  // namespace tianracer_sim
