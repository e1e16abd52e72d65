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

/// The folders searched for model://<name>/<path>, each once at its first place, in Gazebo's
/// order: ~/.gazebo/models first (gazebo-classic gazebo/common/SystemPaths.cc, the
/// constructor), then $GAZEBO_MODEL_PATH's entries (SystemPaths::UpdateModelPaths appends
/// them), then the gazebo_model_path exports of the ROS packages (gazebo_ros's
/// src/gazebo_ros_paths_plugin.cpp appends them with AddModelPaths); after those, `extra`: the
/// folders only we search (a load's model_paths, the folders of the enclosing <include>s, the
/// world file's folder and its models/). The one place this order is written.
std::vector<std::string> modelSearchPath(const std::vector<std::string>& extra = {});

/// Resolves the URI of a model's file (a mesh, a texture, a material script) or folder (an
/// <include>d model); the one resolver of meshes, materials, textures, includes and the Python
/// side:
///   package://<pkg>/<path>  find_package(pkg) + "/<path>" (resource_retriever's rule)
///   model://<model>/<path>  the first folder of modelSearchPath(model_paths) holding
///                           <model>/<path> (SystemPaths::FindFileURI)
///   file://<path>, <path>   as given when absolute, else against base_dir
struct UriResolver {
  std::function<std::string(const std::string& package)> find_package;  // "" when unknown
  std::string base_dir;  // the model file's folder, for relative paths
  /// Folders searched for model:// after Gazebo's model path (modelSearchPath()'s `extra`).
  std::vector<std::string> model_paths;

  /// What a URI is to name: a file (a mesh, a texture), a folder (an <include>d model) or
  /// either (a material script's <uri>, which Gazebo takes as a file or a folder).
  enum class Want { kFile, kFolder, kAny };
  struct Found {
    std::string path;                // "" when no candidate exists as `want`
    std::vector<std::string> tried;  // every candidate looked at, in order
  };
  /// Looks at the disk for every candidate (model:// has one per folder of the search path).
  /// Throws ResourceError naming the URI when it is malformed (an empty URI, a model:// or
  /// package:// without a path, an unknown scheme, an unknown package, a relative path with no
  /// base_dir).
  Found find(const std::string& uri, Want want = Want::kFile) const;

  /// Returns the path of a file URI. Only model:// looks at the disk (to pick the folder); whether
  /// the file of another URI exists is the caller's business. Throws ResourceError naming the
  /// URI (for model:// not found, with every folder searched).
  std::string resolve(const std::string& uri) const;

 private:
  /// The path of a URI that is not model://; throws as find().
  std::string direct(const std::string& uri) const;
};

}  // namespace tianracer_assets

#endif  // TIANRACER_ASSETS_PATHS_H
