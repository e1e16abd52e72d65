#include "tianracer_sim/render/camera_sensor.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <tinyxml2.h>

namespace tianracer_sim {


std::string opticalFrameId(const std::string& frame_name) { return frame_name + "_optical_frame"; }

double CameraConfig::focalLength() const { return width / (2.0 * std::tan(horizontal_fov / 2.0)); }

CameraIntrinsics CameraConfig::intrinsics() const {
  return CameraIntrinsics::fromHorizontalFov(width, height, horizontal_fov, near_clip, far_clip);
}

Eigen::Isometry3d CameraConfig::X_LO() const { return X_LS * opticalFromLinkRotation(); }

// -----------------------------------------------------------------------------------------------
// Parsing
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string trim(const std::string& s) {
  const char* ws = " \t\n\r\f\v";
  const auto b = s.find_first_not_of(ws);
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(ws) - b + 1);
}

using tinyxml2::XMLElement;

// Text directly inside an element, trimmed ("" when none).
std::string textOf(const XMLElement* e) { return trim(e->GetText() ? e->GetText() : ""); }

uint32_t fnv1a(const std::string& s) {
  uint32_t h = 2166136261u;
  for (unsigned char c : s) {
    h ^= c;
    h *= 16777619u;
  }
  return h == 0 ? 1u : h;
}

class Parser {
 public:
  Parser(const SensorSpec& sensor, const WarningSink& warn) : sensor_(sensor), warn_(warn) {
    std::ostringstream os;
    os << sensor.type << " sensor '" << sensor.name << "'";
    if (!sensor.link.empty()) os << " on link '" << sensor.link << "'";
    if (sensor.line > 0) os << " (line " << sensor.line << ")";
    where_ = os.str();
  }

  [[noreturn]] void fail(const std::string& what) const { throw CameraError(where_ + ": " + what); }
  void warn(const std::string& what) const {
    if (warn_) warn_(where_ + ": " + what);
  }

  double number(const std::string& element, const std::string& text) const {
    const std::string t = trim(text);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v)) {
      fail(element + " '" + text + "' is not a number");
    }
    return v;
  }

  int integer(const std::string& element, const std::string& text) const {
    const double v = number(element, text);
    if (v != std::floor(v) || std::fabs(v) > 1e9) fail(element + " '" + text + "' is not an integer");
    return static_cast<int>(v);
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
    if (trim(sensor_.xml).empty()) fail("no <sensor> XML to read the <camera> element from");
    tinyxml2::XMLDocument doc;
    if (doc.Parse(sensor_.xml.c_str()) != tinyxml2::XML_SUCCESS || !doc.RootElement()) {
      fail(std::string("its XML does not parse (line ") + std::to_string(doc.ErrorLineNum()) +
           "): " + (doc.ErrorStr() ? doc.ErrorStr() : "no element"));
    }
    const XMLElement* root = doc.RootElement();
    const XMLElement* cam =
        std::string(root->Name()) == "camera" ? root : root->FirstChildElement("camera");
    if (cam == nullptr) fail("has no <camera> element");
    for (const XMLElement* child = cam->FirstChildElement(); child;
         child = child->NextSiblingElement()) {
      const std::string n = child->Name();
      const std::string child_text = textOf(child);
      if (n == "horizontal_fov") {
        c->horizontal_fov = number("<camera><horizontal_fov>", child_text);
      } else if (n == "image") {
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          if (g_name == "width") c->width = integer("<image><width>", g_text);
          else if (g_name == "height") c->height = integer("<image><height>", g_text);
          else if (g_name == "format") c->format_name = trim(g_text);
          else warn("unknown element <camera><image><" + g_name + "> ignored");
        }
      } else if (n == "clip") {
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          if (g_name == "near") c->near_clip = number("<clip><near>", g_text);
          else if (g_name == "far") c->far_clip = number("<clip><far>", g_text);
          else warn("unknown element <camera><clip><" + g_name + "> ignored");
        }
      } else if (n == "noise") {
        std::string type = "gaussian";
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          if (g_name == "type") type = trim(g_text);
          else if (g_name == "mean") c->noise_mean = number("<noise><mean>", g_text);
          else if (g_name == "stddev") c->noise_stddev = number("<noise><stddev>", g_text);
          else warn("unknown element <camera><noise><" + g_name + "> ignored");
        }
        if (type == "none") {
          c->noise = false;
        } else if (type == "gaussian") {
          c->noise = c->noise_stddev > 0.0 || c->noise_mean != 0.0;
        } else {
          fail("<noise><type> '" + type + "' is not supported (gaussian, none)");
        }
        if (c->noise_stddev < 0.0) fail("<noise><stddev> " + child_text + " must be >= 0");
      } else if (n == "distortion") {
        bool any = false;
        for (const XMLElement* g = child->FirstChildElement(); g; g = g->NextSiblingElement()) {
          const std::string g_name = g->Name(), g_text = textOf(g);
          if (g_name == "center") continue;
          if (number("<distortion><" + g_name + ">", g_text) != 0.0) any = true;
        }
        if (any) warn("<camera><distortion> is not applied to the images (like gazebo_ros's camera_info, "
                      "images are undistorted)");
      } else if (n == "save" || n == "depth_camera" || n == "lens" || n == "pose" ||
                 n == "visualize" || n == "triggered" || n == "trigger_topic") {
        warn("<camera><" + n + "> is not supported; ignored");
      } else {
        warn("unknown element <camera><" + n + "> ignored");
      }
    }
    // Validation, each value named.
    auto str = [](double v) {
      std::ostringstream os;
      os << v;
      return os.str();
    };
    if (c->width <= 0 || c->width > 8192) fail("<image><width> " + std::to_string(c->width) + " out of range 1..8192");
    if (c->height <= 0 || c->height > 8192) fail("<image><height> " + std::to_string(c->height) + " out of range 1..8192");
    if (!(c->horizontal_fov > 0.0 && c->horizontal_fov < M_PI)) {
      fail("<horizontal_fov> " + str(c->horizontal_fov) + " rad outside (0, pi)");
    }
    if (!(c->near_clip > 0.0)) fail("<clip><near> " + str(c->near_clip) + " must be > 0");
    if (!(c->near_clip < c->far_clip)) {
      fail("<clip><near> " + str(c->near_clip) + " must be less than <clip><far> " + str(c->far_clip));
    }
    if (c->format_name == "R8G8B8") c->format = ImageFormat::kR8G8B8;
    else if (c->format_name == "L8") c->format = ImageFormat::kL8;
    else fail("<image><format> '" + c->format_name + "' is not supported (R8G8B8, L8)");
    c->noise_seed = fnv1a(sensor_.name);
    c->frame_name = sensor_.link;
  }

  // Reads the plugin's parameters. `extra` are the keys only this plugin type knows; returns
  // the plugin (or nullptr).
  const PluginSpec* findPlugin(const std::vector<std::string>& filenames) const {
    for (const PluginSpec& p : sensor_.plugins) {
      for (const auto& f : filenames) {
        if (endsWith(p.filename, f)) return &p;
      }
    }
    return nullptr;
  }

  void parseCameraPlugin(const PluginSpec& p, CameraConfig* c, std::set<std::string>* used) {
    c->has_plugin = true;
    c->plugin_filename = p.filename;
    auto get = [&](const std::string& key, std::string* out) {
      const auto it = p.params.find(key);
      if (it == p.params.end()) return false;
      used->insert(key);
      *out = trim(it->second);
      return true;
    };
    auto num = [&](const std::string& key, double* out) {
      std::string text;
      if (get(key, &text)) *out = number("plugin <" + key + ">", text);
    };
    get("robotNamespace", &c->robot_namespace);
    get("cameraName", &c->camera_name);
    get("imageTopicName", &c->image_topic);
    get("cameraInfoTopicName", &c->camera_info_topic);
    std::string frame;
    if (get("frameName", &frame) && !frame.empty()) c->frame_name = frame;
    num("updateRate", &c->plugin_update_rate);
    num("hackBaseline", &c->hack_baseline);
    // gazebo_ros reads the camel-case names; openni examples write distortion_k1: take both.
    for (const auto& k : {std::make_pair("distortionK1", &c->k1), std::make_pair("distortion_k1", &c->k1),
                          std::make_pair("distortionK2", &c->k2), std::make_pair("distortion_k2", &c->k2),
                          std::make_pair("distortionK3", &c->k3), std::make_pair("distortion_k3", &c->k3),
                          std::make_pair("distortionT1", &c->t1), std::make_pair("distortion_t1", &c->t1),
                          std::make_pair("distortionT2", &c->t2), std::make_pair("distortion_t2", &c->t2)}) {
      num(k.first, k.second);
    }
    num("Cx", &c->cx_override);
    num("Cy", &c->cy_override);
    num("focalLength", &c->focal_length_override);
    double unused = 0.0;
    num("CxPrime", &unused);
    std::string ignored;
    get("alwaysOn", &ignored);
    if (c->plugin_update_rate < 0.0) fail("plugin <updateRate> must be >= 0");
    if (c->k1 != 0 || c->k2 != 0 || c->k3 != 0 || c->t1 != 0 || c->t2 != 0) {
      warn("non-zero distortion is reported in camera_info only; images are not distorted "
           "(as gazebo_ros)");
    }
    if (c->focal_length_override > 0.0 &&
        std::fabs(c->focal_length_override - c->focalLength()) > 1e-6 * c->focalLength()) {
      warn("plugin <focalLength> " + std::to_string(c->focal_length_override) +
           " disagrees with width and hfov (f = " + std::to_string(c->focalLength()) +
           "); camera_info reports it, images use the hfov");
    }
  }

  void warnUnused(const PluginSpec& p, const std::set<std::string>& used) const {
    for (const auto& kv : p.params) {
      if (!used.count(kv.first)) {
        warn("plugin " + p.filename + ": unknown parameter <" + kv.first + "> ignored");
      }
    }
  }

  const SensorSpec& sensor() const { return sensor_; }

 private:
  const SensorSpec& sensor_;
  const WarningSink& warn_;
  std::string where_;
};

const std::vector<std::string> kCameraPlugins = {"libgazebo_ros_camera.so"};
const std::vector<std::string> kDepthPlugins = {"libgazebo_ros_openni_kinect.so",
                                                "libgazebo_ros_depth_camera.so"};

}  // namespace

CameraConfig parseCameraConfig(const SensorSpec& sensor, const WarningSink& warn) {
  Parser parser(sensor, warn);
  CameraConfig c;
  parser.parseCamera(&c);
  if (const PluginSpec* p = parser.findPlugin(kCameraPlugins)) {
    std::set<std::string> used;
    parser.parseCameraPlugin(*p, &c, &used);
    parser.warnUnused(*p, used);
  }
  return c;
}

DepthCameraConfig parseDepthCameraConfig(const SensorSpec& sensor, const WarningSink& warn) {
  Parser parser(sensor, warn);
  DepthCameraConfig d;
  d.camera.image_topic = "ir/image_raw";  // openni_kinect's own defaults
  d.camera.camera_info_topic = "ir/camera_info";
  parser.parseCamera(&d.camera);
  if (const PluginSpec* p = parser.findPlugin(kDepthPlugins)) {
    std::set<std::string> used;
    parser.parseCameraPlugin(*p, &d.camera, &used);
    auto get = [&](const std::string& key, std::string* out) {
      const auto it = p->params.find(key);
      if (it == p->params.end()) return false;
      used.insert(key);
      *out = trim(it->second);
      return true;
    };
    auto num = [&](const std::string& key, double* out) {
      std::string text;
      if (get(key, &text)) *out = parser.number("plugin <" + key + ">", text);
    };
    get("depthImageTopicName", &d.depth_image_topic);
    get("depthImageCameraInfoTopicName", &d.depth_camera_info_topic);
    get("pointCloudTopicName", &d.point_cloud_topic);
    num("baseline", &d.baseline);
    num("pointCloudCutoff", &d.point_cloud_cutoff);
    num("pointCloudCutoffMax", &d.point_cloud_cutoff_max);
    if (!(d.point_cloud_cutoff < d.point_cloud_cutoff_max)) {
      parser.fail("plugin <pointCloudCutoff> " + std::to_string(d.point_cloud_cutoff) +
                  " must be less than <pointCloudCutoffMax> " +
                  std::to_string(d.point_cloud_cutoff_max));
    }
    parser.warnUnused(*p, used);
  }
  return d;
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

// -----------------------------------------------------------------------------------------------
// Noise
namespace {

// Inverse of the standard normal CDF (P. J. Acklam's rational approximation, relative error
// 1.15e-9), enough for a table of 65536 quantiles.
double inverseNormalCdf(double p) {
  static const double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                             1.383577518672690e+02, -3.066479806614716e+01, 2.506628277459239e+00};
  static const double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                             6.680131188771972e+01, -1.328068155288572e+01};
  static const double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                             -2.549732539343734e+00, 4.374664141464968e+00, 2.938163982698783e+00};
  static const double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                             3.754408661907416e+00};
  const double plow = 0.02425, phigh = 1 - plow;
  if (p < plow) {
    const double q = std::sqrt(-2 * std::log(p));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (p > phigh) {
    const double q = std::sqrt(-2 * std::log(1 - p));
    return -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  const double q = p - 0.5, r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

uint8_t clampByte(int v) { return static_cast<uint8_t>(v < 0 ? 0 : (v > 255 ? 255 : v)); }

}  // namespace

ImageNoise::ImageNoise(double mean, double stddev, uint32_t seed) : rng_(seed) {
  enabled_ = stddev > 0.0 || mean != 0.0;
  if (!enabled_) return;
  constexpr int kSize = 1 << 16;
  table_.resize(kSize);
  saturating_.resize(kSize);
  for (int i = 0; i < kSize; ++i) {
    const double z = inverseNormalCdf((i + 0.5) / kSize);
    const double v = std::round((mean + stddev * z) * 255.0);
    table_[i] = static_cast<int16_t>(std::max(-512.0, std::min(512.0, v)));
    // clamp(p + n, 0, 255) = saturate_u8(saturate_u8(p + max(n, 0)) - max(-n, 0)) with each
    // part clamped to 255: the same bytes, as two saturating byte operations.
    const int pos = std::min(255, std::max(0, static_cast<int>(table_[i])));
    const int neg = std::min(255, std::max(0, -static_cast<int>(table_[i])));
    saturating_[i] = static_cast<uint16_t>(pos | (neg << 8));
  }
}

namespace {

// SplitMix64's finaliser: a counter-based generator, four 16-bit table indices per call.
inline uint64_t splitmix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

void ImageNoise::apply(uint8_t* data, std::size_t pixels, int channels) {
  if (!enabled_) return;
  // One draw from the seeded mt19937 per frame; the pixels' samples are hashes of (that
  // seed, pixel block): deterministic, independent, and 2-3x faster than an mt19937 draw
  // per pixel pair.
  const uint64_t frame_seed = (static_cast<uint64_t>(rng_()) << 32) | rng_();
  const int16_t* t = table_.data();
  auto add = [&](uint8_t* px, int n) {
    for (int c = 0; c < channels; ++c) px[c] = clampByte(px[c] + n);
  };
  const std::size_t blocks = pixels / 4;
  std::size_t k = 0;
#if defined(__SSE2__)
  if (channels == 3) {
    // 16 pixels (48 bytes, four hashes) at a time: each pixel's (positive, negative) part is
    // replicated into its 3 bytes of two 48-byte rows, then added to and subtracted from the
    // pixels with saturation, 16 bytes per instruction. Same samples, same bytes as below.
    const uint16_t* sat = saturating_.data();
    alignas(16) uint8_t add_row[48 + 4], sub_row[48 + 4];
    for (; k + 4 <= blocks; k += 4) {
      for (int b = 0; b < 4; ++b) {
        const uint64_t r = splitmix64(frame_seed + 0x9e3779b97f4a7c15ULL * (k + b + 1));
        for (int j = 0; j < 4; ++j) {
          const uint32_t v = sat[(r >> (16 * j)) & 0xffff];
          const uint32_t up = (v & 0xff) * 0x010101u, down = (v >> 8) * 0x010101u;
          std::memcpy(add_row + 12 * b + 3 * j, &up, 4);  // the 4th byte is the next pixel's
          std::memcpy(sub_row + 12 * b + 3 * j, &down, 4);
        }
      }
      uint8_t* p = data + 4 * k * 3;
      for (int q = 0; q < 3; ++q) {
        __m128i px = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16 * q));
        px = _mm_adds_epu8(px, _mm_load_si128(reinterpret_cast<const __m128i*>(add_row + 16 * q)));
        px = _mm_subs_epu8(px, _mm_load_si128(reinterpret_cast<const __m128i*>(sub_row + 16 * q)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(p + 16 * q), px);
      }
    }
  }
#endif
  for (; k < blocks; ++k) {
    const uint64_t r = splitmix64(frame_seed + 0x9e3779b97f4a7c15ULL * (k + 1));
    uint8_t* p = data + 4 * k * channels;
    if (channels == 3) {
      for (int j = 0; j < 4; ++j) {
        const int n = t[(r >> (16 * j)) & 0xffff];
        p[3 * j] = clampByte(p[3 * j] + n);
        p[3 * j + 1] = clampByte(p[3 * j + 1] + n);
        p[3 * j + 2] = clampByte(p[3 * j + 2] + n);
      }
    } else {
      for (int j = 0; j < 4; ++j) add(p + j * channels, t[(r >> (16 * j)) & 0xffff]);
    }
  }
  const uint64_t r = splitmix64(frame_seed + 0x9e3779b97f4a7c15ULL * (blocks + 1));
  for (std::size_t i = 4 * blocks, j = 0; i < pixels; ++i, ++j) {
    add(data + i * channels, t[(r >> (16 * j)) & 0xffff]);
  }
}

// -----------------------------------------------------------------------------------------------
// Sensors
namespace {

void toMono(const std::vector<uint8_t>& rgb, std::vector<uint8_t>* mono) {
  // ITU-R BT.601 luma, in integers.
  const std::size_t n = mono->size();
  for (std::size_t i = 0; i < n; ++i) {
    const uint8_t* p = &rgb[3 * i];
    (*mono)[i] = static_cast<uint8_t>((299 * p[0] + 587 * p[1] + 114 * p[2] + 500) / 1000);
  }
}

}  // namespace

CameraSensor::CameraSensor(CameraConfig config, Renderer& renderer)
    : config_(std::move(config)),
      renderer_(&renderer),
      info_(makeCameraInfo(config_)),
      intrinsics_(config_.intrinsics()),
      noise_(config_.noise ? ImageNoise(config_.noise_mean, config_.noise_stddev, config_.noise_seed)
                           : ImageNoise()) {
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  image_.resize(pixels * channels());
  if (config_.format == ImageFormat::kL8) rgb_scratch_.resize(pixels * 3);
}

void CameraSensor::render(const Scene& scene, const Eigen::Isometry3d& X_WL) {
  const Eigen::Isometry3d X_WC = X_WL * config_.X_LS;
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  if (config_.format == ImageFormat::kL8) {
    renderer_->renderView(scene, X_WC, intrinsics_, rgb_scratch_.data(), nullptr);
    toMono(rgb_scratch_, &image_);
  } else {
    renderer_->renderView(scene, X_WC, intrinsics_, image_.data(), nullptr);
  }
  noise_.apply(image_.data(), pixels, channels());
  ++renders_;
}

DepthCameraSensor::DepthCameraSensor(DepthCameraConfig config, Renderer& renderer)
    : config_(std::move(config)),
      renderer_(&renderer),
      info_(makeCameraInfo(config_.camera)),
      intrinsics_(config_.camera.intrinsics()),
      noise_(config_.camera.noise ? ImageNoise(config_.camera.noise_mean, config_.camera.noise_stddev,
                                               config_.camera.noise_seed)
                                  : ImageNoise()) {
  const CameraConfig& c = config_.camera;
  const std::size_t pixels = static_cast<std::size_t>(c.width) * c.height;
  image_.resize(pixels * channels());
  if (c.format == ImageFormat::kL8) rgb_scratch_.resize(pixels * 3);
  depth_.resize(pixels);
  cloud_.assign(pixels * CloudLayout::kPointStep, 0);
  const double f = c.focalLength();
  ray_x_.resize(c.width);
  ray_y_.resize(c.height);
  for (int u = 0; u < c.width; ++u) ray_x_[u] = static_cast<float>((u - 0.5 * (c.width - 1)) / f);
  for (int v = 0; v < c.height; ++v) ray_y_[v] = static_cast<float>((v - 0.5 * (c.height - 1)) / f);
}

void DepthCameraSensor::render(const Scene& scene, const Eigen::Isometry3d& X_WL,
                               DepthOutputs outputs) {
  const CameraConfig& c = config_.camera;
  const Eigen::Isometry3d X_WC = X_WL * c.X_LS;
  const std::size_t pixels = static_cast<std::size_t>(c.width) * c.height;
  const bool want_rgb = outputs.image || outputs.cloud;
  const bool want_depth = outputs.depth || outputs.cloud;
  if (!want_rgb && !want_depth) return;
  const bool mono = c.format == ImageFormat::kL8;
  uint8_t* rgb = want_rgb ? (mono ? rgb_scratch_.data() : image_.data()) : nullptr;
  renderer_->renderView(scene, X_WC, intrinsics_, rgb, want_depth ? depth_.data() : nullptr);
  ++renders_;
  if (want_rgb) {
    if (mono) toMono(rgb_scratch_, &image_);
    noise_.apply(image_.data(), pixels, channels());
  }
  if (!want_depth) return;

  const float lo = static_cast<float>(config_.point_cloud_cutoff);
  const float hi = static_cast<float>(config_.point_cloud_cutoff_max);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  bool dense = true;
  for (std::size_t i = 0; i < pixels; ++i) {
    const float d = depth_[i];
    if (!(d > lo && d < hi)) {
      depth_[i] = nan;
      dense = false;
    }
  }
  cloud_dense_ = dense;
  if (!outputs.cloud) return;
  writeCloud(cloud_.data());
}

void DepthCameraSensor::writeCloud(uint8_t* out) const {
  const CameraConfig& c = config_.camera;
  const int ch = channels();
  for (int v = 0; v < c.height; ++v) {
    const float ry = ray_y_[v];
    for (int u = 0; u < c.width; ++u, out += CloudLayout::kPointStep) {
      const std::size_t i = static_cast<std::size_t>(v) * c.width + u;
      const float d = depth_[i];
      const uint8_t* px = &image_[i * ch];
      const uint32_t r = px[0], g = px[ch > 1 ? 1 : 0], b = px[ch > 1 ? 2 : 0];
      // x, y, z, 0 | rgb (PCL: 0x00RRGGBB in a float's bits), 0, 0, 0; NaN depth stays NaN.
      float xyz0[4] = {d * ray_x_[u], d * ry, d, 0.0f};
      const uint32_t rgb0[4] = {(r << 16) | (g << 8) | b, 0, 0, 0};
      std::memcpy(out + CloudLayout::kOffsetX, xyz0, sizeof(xyz0));
      std::memcpy(out + CloudLayout::kOffsetRgb, rgb0, sizeof(rgb0));
    }
  }
}

}  // namespace tianracer_sim
