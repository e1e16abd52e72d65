#include "tianracer_sim/world/map_world.h"

#include <cmath>
#include <sstream>

#include <yaml-cpp/yaml.h>

// stb_image from Debian's libstb-dev, compiled here with internal linkage (other libraries of
// the process may carry their own copy).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include "tianracer_sim/scene/materials.h"
#include "world_parser.h"  // world_internal::isFile

namespace tianracer_sim {

namespace {

std::string dirOf(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

}  // namespace

std::vector<CellRect> mergeOccupiedCells(const OccupancyImage& image) {
  std::vector<CellRect> rects;
  std::vector<bool> covered(image.occupied.size(), false);
  auto free = [&](int c, int r) {
    const std::size_t i = static_cast<std::size_t>(r) * image.width + c;
    return image.occupied[i] && !covered[i];
  };
  for (int r = 0; r < image.height; ++r) {
    for (int c = 0; c < image.width; ++c) {
      if (!free(c, r)) continue;
      CellRect rect{c, r, 1, 1};
      while (rect.col + rect.cols < image.width && free(rect.col + rect.cols, r)) ++rect.cols;
      for (bool grow = true; grow && rect.row + rect.rows < image.height;) {
        for (int k = 0; k < rect.cols && grow; ++k) grow = free(rect.col + k, rect.row + rect.rows);
        if (grow) ++rect.rows;
      }
      for (int rr = rect.row; rr < rect.row + rect.rows; ++rr) {
        for (int cc = rect.col; cc < rect.col + rect.cols; ++cc) {
          covered[static_cast<std::size_t>(rr) * image.width + cc] = true;
        }
      }
      rects.push_back(rect);
    }
  }
  return rects;
}

MapDescription loadMapYaml(const std::string& yaml_path, double default_wall_height) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path);
  } catch (const YAML::BadFile&) {
    throw WorldError(yaml_path + ": cannot read the map YAML");
  } catch (const YAML::Exception& e) {
    throw WorldError(yaml_path + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) throw WorldError(yaml_path + ":1: a map YAML is a mapping (image, resolution, origin...)");
  auto at = [&](const YAML::Node& n) { return yaml_path + ":" + std::to_string(n.Mark().line + 1) + ": "; };
  auto need = [&](const char* key) {
    const YAML::Node n = root[key];
    if (!n) throw WorldError(yaml_path + ": map YAML has no '" + std::string(key) + "'");
    return n;
  };
  auto number = [&](const YAML::Node& n, const char* key) {
    try {
      const double v = n.as<double>();
      if (!std::isfinite(v)) throw YAML::Exception(n.Mark(), "not finite");
      return v;
    } catch (const YAML::Exception&) {
      throw WorldError(at(n) + "'" + key + "' is not a number: " + YAML::Dump(n));
    }
  };
  MapDescription map;
  map.wall_height = default_wall_height;
  const YAML::Node image = need("image");
  map.image = image.as<std::string>("");
  if (map.image.empty()) throw WorldError(at(image) + "'image' is empty");
  if (map.image[0] != '/') map.image = dirOf(yaml_path) + "/" + map.image;
  const YAML::Node res = need("resolution");
  map.resolution = number(res, "resolution");
  if (!(map.resolution > 0.0))
    throw WorldError(at(res) + "'resolution' must be > 0 m/cell (got " + YAML::Dump(res) + ")");
  const YAML::Node origin = need("origin");
  if (!origin.IsSequence() || origin.size() != 3)
    throw WorldError(at(origin) + "'origin' must be [x, y, yaw] (got " + YAML::Dump(origin) + ")");
  for (int i = 0; i < 3; ++i) map.origin[i] = number(origin[i], "origin");
  if (const YAML::Node n = root["negate"]) map.negate = number(n, "negate") != 0.0;
  if (const YAML::Node n = root["occupied_thresh"]) map.occupied_thresh = number(n, "occupied_thresh");
  if (const YAML::Node n = root["free_thresh"]) map.free_thresh = number(n, "free_thresh");
  if (!(map.occupied_thresh > 0.0 && map.occupied_thresh < 1.0))
    throw WorldError(yaml_path + ": 'occupied_thresh' must be in (0, 1) (got " +
                     std::to_string(map.occupied_thresh) + ")");
  if (const YAML::Node n = root["mode"]) {
    map.mode = n.as<std::string>("");
    if (map.mode != "trinary" && map.mode != "scale" && map.mode != "raw")
      throw WorldError(at(n) + "'mode' must be trinary, scale or raw (got " + map.mode + ")");
  }
  if (const YAML::Node n = root["wall_height"]) {
    map.wall_height = number(n, "wall_height");
    if (!(map.wall_height > 0.0))
      throw WorldError(at(n) + "'wall_height' must be > 0 m (got " + YAML::Dump(n) + ")");
  }
  return map;
}

OccupancyImage loadOccupancy(const MapDescription& map, const std::string& yaml_path) {
  if (!world_internal::isFile(map.image))
    throw WorldError(yaml_path + ": map image '" + map.image + "' does not exist");
  int w = 0, h = 0, n = 0;
  unsigned char* data = stbi_load(map.image.c_str(), &w, &h, &n, 0);
  if (!data) {
    throw WorldError(yaml_path + ": map image '" + map.image + "' cannot be decoded (" +
                     stbi_failure_reason() + ")");
  }
  OccupancyImage img;
  img.width = w;
  img.height = h;
  img.occupied.resize(static_cast<std::size_t>(w) * h);
  const int colours = n >= 3 ? 3 : 1;  // alpha (n = 2 or 4) is not a colour
  for (std::size_t i = 0; i < img.occupied.size(); ++i) {
    double v = 0.0;
    for (int k = 0; k < colours; ++k) v += data[i * n + k];
    v /= colours;
    if (map.mode == "raw") {
      img.occupied[i] = v > map.occupied_thresh * 100.0;
    } else {
      const double p = map.negate ? v / 255.0 : (255.0 - v) / 255.0;
      img.occupied[i] = p > map.occupied_thresh;
    }
  }
  stbi_image_free(data);
  return img;
}

WorldDescription loadMapWorld(const std::string& yaml_path, const WorldLoadOptions& options) {
  const MapDescription map = loadMapYaml(yaml_path, options.map_wall_height);
  const OccupancyImage img = loadOccupancy(map, yaml_path);
  const std::vector<CellRect> rects = mergeOccupiedCells(img);

  WorldDescription world;
  world.source = yaml_path;
  world.name = "map";
  world.ground_plane = true;
  world.sun = DirectionalLight();
  world.sun->name = "sun";
  world.sun->attenuation = {0.9, 0.01, 0.001};  // Gazebo's sun/model.sdf
  ModelDescription model;
  model.name = "map";
  model.is_static = true;
  // The origin is the pose of the image's lower-left corner in the world.
  model.X_WM = sdfPose(map.origin.x(), map.origin.y(), 0.0, 0.0, 0.0, map.origin.z());
  LinkDescription link;
  link.name = "walls";
  Material grey = findGazeboMaterial("Gazebo/Grey")->material;
  const double r = map.resolution;
  for (std::size_t k = 0; k < rects.size(); ++k) {
    const CellRect& c = rects[k];
    Shape box;
    box.type = ShapeType::kBox;
    box.size = Eigen::Vector3d(c.cols * r, c.rows * r, map.wall_height);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d((c.col + 0.5 * c.cols) * r,
                                      (img.height - c.row - 0.5 * c.rows) * r,
                                      0.5 * map.wall_height);
    const std::string name = "wall_" + std::to_string(k);
    link.collisions.push_back({name, box, X, Friction{}, 0, ContactDescription{}});
    link.visuals.push_back({name, box, X, grey, 0});
  }
  if (options.warn && rects.empty()) options.warn(yaml_path + ": the map has no occupied cells: no walls");
  model.links.push_back(std::move(link));
  world.models.push_back(std::move(model));
  return world;
}

}  // namespace tianracer_sim
