// The one path resolver (tianracer_assets/paths.h) seen from a world and a robot: a model's
// mesh and the texture beside it are found under each kind of model path (~/.gazebo/models,
// GAZEBO_MODEL_PATH, a ROS package's gazebo_model_path export, the load's model_paths, the
// world file's models/ folder), through an inline visual, an <include> and a URDF alike; and
// the search order is Gazebo's.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <tianracer_assets/paths.h>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/world/world.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

namespace fs = std::filesystem;

const char* kStl =
    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
    "endloop\nendfacet\nendsolid t\n";

const char* kScript =
    "material Board/Checker\n{\n  technique\n  {\n    pass\n    {\n      diffuse 0.6 0.5 0.4 1\n"
    "      texture_unit\n      {\n        texture checker.png\n      }\n    }\n  }\n}\n";

// Sets an environment variable for the scope, and puts the old value back.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) setenv(name_, old_->c_str(), 1);
    else unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// Writes the model 'boardmesh' (a mesh, a material script and its texture) into `models`;
// returns the mesh's and the texture's paths.
std::pair<std::string, std::string> writeBoard(const test::TempDir& dir, const std::string& models) {
  const std::string root = models.empty() ? "" : models + "/";
  const std::string mesh = dir.write(root + "boardmesh/meshes/board.stl", kStl);
  dir.write(root + "boardmesh/materials/scripts/board.material", kScript);
  const std::string png = dir.write(root + "boardmesh/materials/textures/checker.png", "png bytes");
  dir.write(root + "boardmesh/model.sdf",
            "<sdf version='1.6'><model name='boardmesh'><static>true</static><link name='link'>"
            "<visual name='v'><geometry><mesh><uri>model://boardmesh/meshes/board.stl</uri></mesh>"
            "</geometry><material><script><uri>model://boardmesh/materials/scripts</uri>"
            "<name>Board/Checker</name></script></material></visual></link></model></sdf>");
  return {mesh, png};
}

const std::string kInlineWorld =
    "<sdf version='1.6'><world name='w'><model name='board'><static>true</static>"
    "<link name='link'><visual name='v'><geometry><mesh><uri>model://boardmesh/meshes/board.stl"
    "</uri></mesh></geometry><material><script><uri>model://boardmesh/materials/scripts</uri>"
    "<name>Board/Checker</name></script></material></visual></link></model></world></sdf>";

const std::string kIncludeWorld =
    "<sdf version='1.6'><world name='w'><include><uri>model://boardmesh</uri></include>"
    "</world></sdf>";

struct Loaded {
  std::string mesh, texture;
  std::vector<std::string> warnings;
};

Loaded loadBoard(const std::string& world_text, const std::string& world_dir,
                 const std::vector<std::string>& model_paths = {}) {
  Loaded out;
  WorldLoadOptions options;
  options.model_paths = model_paths;
  options.warn = [&out](const std::string& w) { out.warnings.push_back(w); };
  const WorldDescription w = loadWorldString(world_text, "test.world", world_dir, options);
  const VisualDescription& v = w.models.at(0).links.at(0).visuals.at(0);
  out.mesh = v.shape.mesh_path;
  out.texture = v.material.texture;
  return out;
}

std::string urdfMesh(const std::string& model_dir) {
  const std::string urdf =
      "<robot name='r'><link name='base'><visual><geometry><mesh "
      "filename='model://boardmesh/meshes/board.stl'/></geometry></visual>"
      "<inertial><mass value='1'/><inertia ixx='1' iyy='1' izz='1' ixy='0' ixz='0' iyz='0'/>"
      "</inertial></link></robot>";
  LoadOptions options;
  options.resolver.base_dir = model_dir;
  const RobotModel model = loadRobotModel(urdf, "test.urdf", options);
  return model.mesh_paths.at("model://boardmesh/meshes/board.stl");
}

// One kind of model path: where the board goes, and what points the loaders at it.
struct PathKind {
  const char* name;
  std::function<void(test::TempDir& dir, std::vector<std::unique_ptr<ScopedEnv>>* env,
                     std::vector<std::string>* model_paths, std::string* models)>
      set_up;
};

std::vector<PathKind> pathKinds() {
  return {
      {"~/.gazebo/models",
       [](test::TempDir& dir, auto* env, auto*, std::string* models) {
         env->push_back(std::make_unique<ScopedEnv>("HOME", dir.file("home")));
         *models = "home/.gazebo/models";
       }},
      {"GAZEBO_MODEL_PATH",
       [](test::TempDir& dir, auto* env, auto*, std::string* models) {
         env->push_back(std::make_unique<ScopedEnv>(
             "GAZEBO_MODEL_PATH", "/nonexistent:" + dir.file("gazebo_models")));
         *models = "gazebo_models";
       }},
      {"a ROS package's gazebo_model_path",
       [](test::TempDir& dir, auto* env, auto*, std::string* models) {
         dir.write("ros/board_pkg/package.xml",
                   "<package format='3'><name>board_pkg</name><export><gazebo_ros "
                   "gazebo_model_path='${prefix}/models'/></export></package>");
         env->push_back(std::make_unique<ScopedEnv>("ROS_PACKAGE_PATH", dir.file("ros")));
         *models = "ros/board_pkg/models";
       }},
      {"the load's model_paths",
       [](test::TempDir& dir, auto*, auto* model_paths, std::string* models) {
         model_paths->push_back(dir.file("extra"));
         *models = "extra";
       }},
      {"the world's models/ folder",
       [](test::TempDir&, auto*, auto*, std::string* models) { *models = "world/models"; }},
  };
}

TEST(ModelPaths, MeshAndTextureBesideItFoundUnderEveryKindOfModelPath) {
  for (const PathKind& kind : pathKinds()) {
    SCOPED_TRACE(kind.name);
    test::TempDir dir("model_paths");
    // Nothing of the machine's own model path may answer for the test's model.
    std::vector<std::unique_ptr<ScopedEnv>> env;
    env.push_back(std::make_unique<ScopedEnv>("HOME", dir.file("empty_home")));
    env.push_back(std::make_unique<ScopedEnv>("GAZEBO_MODEL_PATH", ""));
    env.push_back(std::make_unique<ScopedEnv>("ROS_PACKAGE_PATH", dir.file("no_ros")));
    std::vector<std::string> model_paths;
    std::string models;
    kind.set_up(dir, &env, &model_paths, &models);
    const auto [mesh, png] = writeBoard(dir, models);
    const std::string world_dir = dir.file("world");
    fs::create_directories(world_dir);

    const Loaded inline_world = loadBoard(kInlineWorld, world_dir, model_paths);
    EXPECT_TRUE(inline_world.warnings.empty()) << inline_world.warnings.front();
    EXPECT_EQ(fs::path(inline_world.mesh), fs::path(mesh));
    EXPECT_EQ(fs::path(inline_world.texture), fs::path(png));

    const Loaded included = loadBoard(kIncludeWorld, world_dir, model_paths);
    EXPECT_TRUE(included.warnings.empty()) << included.warnings.front();
    EXPECT_EQ(fs::path(included.mesh), fs::path(mesh));
    EXPECT_EQ(fs::path(included.texture), fs::path(png));

    // A robot's model:// mesh: the same search (the world's folder is no robot's folder).
    if (std::string(kind.name) != "the world's models/ folder" &&
        std::string(kind.name) != "the load's model_paths") {
      EXPECT_EQ(fs::path(urdfMesh(world_dir)), fs::path(mesh));
    }
  }
}

TEST(ModelPaths, SearchOrderIsGazebos) {
  test::TempDir dir("model_paths");
  ScopedEnv home("HOME", dir.file("home"));
  ScopedEnv gazebo("GAZEBO_MODEL_PATH", dir.file("a") + ":" + dir.file("b") + ":" + dir.file("a"));
  dir.write("ros/pkg/package.xml",
            "<package format='3'><name>pkg</name><export><gazebo_ros "
            "gazebo_model_path='${prefix}/models'/></export></package>");
  ScopedEnv ros("ROS_PACKAGE_PATH", dir.file("ros"));
  // gazebo/common/SystemPaths.cc: ~/.gazebo/models, then GAZEBO_MODEL_PATH (each once); then
  // gazebo_ros_paths_plugin.cpp's exports; then ours.
  EXPECT_EQ(tianracer_assets::modelSearchPath({dir.file("extra"), dir.file("b")}),
            (std::vector<std::string>{dir.file("home/.gazebo/models"), dir.file("a"), dir.file("b"),
                                      dir.file("ros/pkg/models"), dir.file("extra")}));

  // The first folder holding the model wins, for a world's mesh as for its include.
  const auto [home_mesh, home_png] = writeBoard(dir, "home/.gazebo/models");
  writeBoard(dir, "a");
  const Loaded w = loadBoard(kIncludeWorld, dir.file("a"));
  EXPECT_EQ(fs::path(w.mesh), fs::path(home_mesh));
  EXPECT_EQ(fs::path(w.texture), fs::path(home_png));
}

TEST(ModelPaths, UriResolverFindsFilesFoldersAndSaysWhatItTried) {
  test::TempDir dir("model_paths");
  ScopedEnv home("HOME", dir.file("home"));
  ScopedEnv gazebo("GAZEBO_MODEL_PATH", dir.file("models"));
  ScopedEnv ros("ROS_PACKAGE_PATH", dir.file("no_ros"));
  const std::string mesh = dir.write("models/m/meshes/x.stl", kStl);
  tianracer_assets::UriResolver r;
  r.base_dir = dir.file("models/m");
  using Want = tianracer_assets::UriResolver::Want;
  EXPECT_EQ(r.find("model://m/meshes/x.stl").path, mesh);
  EXPECT_EQ(r.find("model://m", Want::kFolder).path, dir.file("models/m"));
  EXPECT_THROW(r.find("model://m", Want::kFile), tianracer_assets::ResourceError);  // no file
  dir.write("models/f/file_not_folder", "x");
  EXPECT_EQ(r.find("model://f/file_not_folder", Want::kFolder).path, "");  // a file is no folder
  EXPECT_EQ(r.find("meshes/x.stl").path, mesh);           // relative to base_dir
  const auto missing = r.find("model://m/meshes/gone.stl");
  EXPECT_EQ(missing.path, "");
  EXPECT_EQ(missing.tried, (std::vector<std::string>{dir.file("home/.gazebo/models/m/meshes/gone.stl"),
                                                      dir.file("models/m/meshes/gone.stl")}));
  EXPECT_THROW(r.find("model://"), tianracer_assets::ResourceError);
  EXPECT_THROW(r.find("ftp://host/x.stl"), tianracer_assets::ResourceError);
}

}  // namespace
}  // namespace tianracer_sim
