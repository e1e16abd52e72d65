// A world from a ROS map (map_server's YAML + image): occupied cells extruded into walls, merged
// into few boxes. ROS-free.
#ifndef TIANRACER_SIM_WORLD_MAP_WORLD_H
#define TIANRACER_SIM_WORLD_MAP_WORLD_H

#include <string>
#include <vector>

#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// Occupancy of each cell, row 0 at the top of the image (as map_server reads it).
struct OccupancyImage {
  int width = 0, height = 0;
  std::vector<bool> occupied;  // width * height, row-major
  bool at(int col, int row) const { return occupied[static_cast<std::size_t>(row) * width + col]; }
};

/// A rectangle of cells: columns [col, col + cols), rows [row, row + rows).
struct CellRect {
  int col = 0, row = 0, cols = 0, rows = 0;
};

/// Covers exactly the occupied cells with disjoint rectangles, greedily: the first uncovered
/// occupied cell in row-major order grows right as far as it can, then down while the whole
/// span stays occupied and uncovered. A wall of any straight run is one rectangle.
std::vector<CellRect> mergeOccupiedCells(const OccupancyImage& image);

/// map_server's YAML: image (relative to the YAML's folder), resolution (m/cell), origin
/// [x, y, yaw] of the lower-left pixel, negate, occupied_thresh, free_thresh, mode
/// (trinary, scale or raw). A cell is occupied when p > occupied_thresh, with
/// p = (255 - v) / 255 for negate 0 and v / 255 for negate 1 (v the pixel's mean of its colour
/// channels; raw mode: v > occupied_thresh * 100). Images are read by stb_image (PGM from
/// map_saver, PNG, BMP, JPEG...). Throws WorldError naming the YAML file (and line), the key
/// and the value.
struct MapDescription {
  std::string image;  // resolved path
  double resolution = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // x, y, yaw
  bool negate = false;
  double occupied_thresh = 0.65, free_thresh = 0.196;
  std::string mode = "trinary";
  double wall_height = 0.5;  // m; the YAML's optional wall_height key, else the load option
};
MapDescription loadMapYaml(const std::string& yaml_path, double default_wall_height);
OccupancyImage loadOccupancy(const MapDescription& map, const std::string& yaml_path);

/// The world of a map: the ground plane, the sun, and one static model "map" whose link holds
/// one box (collision and visual) per merged rectangle, wall_height tall, standing on z = 0.
WorldDescription loadMapWorld(const std::string& yaml_path, const WorldLoadOptions& options);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_WORLD_MAP_WORLD_H
