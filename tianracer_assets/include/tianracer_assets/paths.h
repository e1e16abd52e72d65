// Where a model's files are found: the model path (GAZEBO_MODEL_PATH, ~/.gazebo/models, ROS
// packages exporting gazebo_model_path) and the URIs of meshes and textures (package://,
// model://, file://, absolute and relative paths), the way Gazebo (gazebo/common/SystemPaths.cc)
// and resource_retriever resolve them. ROS-free: the package lookup is injected (rospack in the
// nodes, a lambda in tests).
#ifndef TIANRACER_ASSETS_PATHS_H
#define TIANRACER_ASSETS_PATHS_H

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tianracer_assets/diagnostic.h"

namespace tianracer_assets {

/// A URI that cannot be resolved. The message names the URI (and, for model://, every folder
/// searched).
using ResourceError = InputError;  // diagnostic.h: the one error type of an input

/// $GAZEBO_MODEL_PATH: its ':'-separated folders in order, empty entries dropped (none when
/// unset). The one place the variable is read.
std::vector<std::string> gazeboModelPath();

/// ~/.gazebo/models, where Gazebo keeps the models it downloads ("" when $HOME is unset).
std::string userModelDir();

/// The gazebo_model_path exports of the ROS packages under $ROS_PACKAGE_PATH
/// (<export><gazebo_ros gazebo_model_path="${prefix}/models"/></export>), crawled as rospack
/// does (a folder with package.xml is a package; CATKIN_IGNORE and hidden folders are skipped).
/// Computed once per $ROS_PACKAGE_PATH value.
std::vector<std::string> rosExportedModelPaths();

/// Resolves the URI of a model's file (a mesh, a texture) to a path:
///   package://<pkg>/<path>  find_package(pkg) + "/<path>"
///   model://<model>/<path>  the first folder of `model_paths` holding <model>/<path>
///   file://<path>, <path>   as given when absolute, else against base_dir
struct UriResolver {
  std::function<std::string(const std::string& package)> find_package;  // "" when unknown
  std::string base_dir;  // the model file's folder, for relative paths
  /// Folders searched for model://<name>/<path>, in order; empty: gazeboModelPath(), then
  /// userModelDir().
  std::vector<std::string> model_paths;

  /// Returns the path. Only model:// looks at the disk (to pick the folder); whether the file
  /// exists is the caller's business. Throws ResourceError naming the URI.
  std::string resolve(const std::string& uri) const;
};

}  // namespace tianracer_assets

#endif  // TIANRACER_ASSETS_PATHS_H
