// UriResolver: package://, model://, file://, absolute and relative URIs, and the errors; the
// model path from the environment.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tianracer_assets/paths.h"

namespace tianracer_assets {
namespace {

using ::testing::HasSubstr;

UriResolver resolver() {
  UriResolver r;
  r.find_package = [](const std::string& p) -> std::string {
    if (p == "tianracer_description") return "/ws/src/tianracer_description";
    if (p == "slash") return "/ws/src/slash/";
    return "";
  };
  r.base_dir = "/models/car";
  return r;
}

std::string error(const UriResolver& r, const std::string& uri) {
  try {
    r.resolve(uri);
  } catch (const ResourceError& e) {
    return e.what();
  }
  return "";
}

TEST(UriResolver, Package) {
  EXPECT_EQ(resolver().resolve("package://tianracer_description/meshes/base_link.STL"),
            "/ws/src/tianracer_description/meshes/base_link.STL");
  EXPECT_EQ(resolver().resolve("package://slash/a/b.stl"), "/ws/src/slash/a/b.stl");
}

TEST(UriResolver, FileAbsoluteAndRelative) {
  EXPECT_EQ(resolver().resolve("file:///abs/mesh.dae"), "/abs/mesh.dae");
  EXPECT_EQ(resolver().resolve("/abs/mesh.stl"), "/abs/mesh.stl");
  EXPECT_EQ(resolver().resolve("meshes/wheel.stl"), "/models/car/meshes/wheel.stl");
  EXPECT_EQ(resolver().resolve("../shared/wheel.stl"), "/models/car/../shared/wheel.stl");
  EXPECT_EQ(resolver().resolve("file://meshes/wheel.stl"), "/models/car/meshes/wheel.stl");
}

TEST(UriResolver, ResolvesWithoutTouchingTheDisk) {
  // Existence is the loader's business (require_meshes), not the resolver's.
  EXPECT_EQ(resolver().resolve("package://tianracer_description/nope.stl"),
            "/ws/src/tianracer_description/nope.stl");
}

TEST(UriResolver, Errors) {
  const UriResolver r = resolver();
  EXPECT_THAT(error(r, "package://unknown_pkg/m.stl"),
              HasSubstr("mesh URI 'package://unknown_pkg/m.stl': package 'unknown_pkg' not found"));
  EXPECT_THAT(error(r, "package://tianracer_description"),
              HasSubstr("is not package://<package>/<path>"));
  EXPECT_THAT(error(r, "package:///meshes/a.stl"), HasSubstr("is not package://<package>/<path>"));
  EXPECT_THAT(error(r, "package://tianracer_description/"),
              HasSubstr("is not package://<package>/<path>"));
  EXPECT_THAT(error(r, "http://host/x.dae"), HasSubstr("unsupported scheme"));  // model:// is resolved (ModelPath)
  EXPECT_THAT(error(r, ""), HasSubstr("empty mesh URI"));
  EXPECT_THAT(error(r, "file://"), HasSubstr("has no path"));

  UriResolver bare;  // no package lookup, no folder
  EXPECT_THAT(error(bare, "package://tianracer_description/m.stl"),
              HasSubstr("no package lookup configured to find 'tianracer_description'"));
  EXPECT_THAT(error(bare, "meshes/m.stl"),
              HasSubstr("is relative but the model has no folder to resolve it against"));
  EXPECT_EQ(bare.resolve("/abs/m.stl"), "/abs/m.stl");
}

// A model folder <root>/<model>/meshes/<file> in the test's temporary directory.
std::string modelRoot() {
  const std::string root = ::testing::TempDir() + "/paths_models";
  std::filesystem::create_directories(root + "/meshes_model/meshes");
  std::ofstream(root + "/meshes_model/meshes/cube.stl") << "solid cube\nendsolid cube\n";
  return root;
}

TEST(UriResolver, ModelPath) {
  UriResolver r = resolver();
  const std::string data = modelRoot();
  r.model_paths = {"/nonexistent/models", data};
  EXPECT_EQ(r.resolve("model://meshes_model/meshes/cube.stl"), data + "/meshes_model/meshes/cube.stl");
  // A miss names the URI and every folder searched.
  EXPECT_THAT(error(r, "model://no_such_model/meshes/x.dae"),
              HasSubstr("mesh URI 'model://no_such_model/meshes/x.dae' not found in the model path"));
  // The given folders come after Gazebo's own model path (modelSearchPath).
  EXPECT_THAT(error(r, "model://no_such_model/meshes/x.dae"),
              HasSubstr("/nonexistent/models, " + data));
  EXPECT_THAT(error(r, "model://"), HasSubstr("is not model://<model>/<path>"));
  EXPECT_THAT(error(r, "model:///"), HasSubstr("is not model://<model>/<path>"));
  // Gazebo's FindFileURI appends "/meshes_model/..." to each folder: a third slash is found.
  EXPECT_EQ(r.resolve("model:///meshes_model/meshes/cube.stl"), data + "/meshes_model/meshes/cube.stl");
}

TEST(UriResolver, ModelPathFromTheEnvironmentInGazebosOrder) {
  const std::string data = modelRoot();
  setenv("GAZEBO_MODEL_PATH", ("/nonexistent/a::" + data).c_str(), 1);
  setenv("HOME", "/nonexistent/home", 1);
  UriResolver r;
  EXPECT_EQ(r.resolve("model://meshes_model/meshes/cube.stl"), data + "/meshes_model/meshes/cube.stl");
  // gazebo/common/SystemPaths.cc: ~/.gazebo/models first, then GAZEBO_MODEL_PATH.
  EXPECT_THAT(error(r, "model://nope/x.stl"),
              HasSubstr("searched /nonexistent/home/.gazebo/models, /nonexistent/a, " + data));
  unsetenv("GAZEBO_MODEL_PATH");
}

TEST(ModelPath, GazeboModelPathDropsEmptyEntries) {
  setenv("GAZEBO_MODEL_PATH", ":/a::/b/:", 1);
  EXPECT_EQ(gazeboModelPath(), (std::vector<std::string>{"/a", "/b/"}));
  unsetenv("GAZEBO_MODEL_PATH");
  EXPECT_TRUE(gazeboModelPath().empty());
  setenv("HOME", "/home/u", 1);
  EXPECT_EQ(userModelDir(), "/home/u/.gazebo/models");
  unsetenv("HOME");
  EXPECT_EQ(userModelDir(), "");
}

}  // namespace
}  // namespace tianracer_assets

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);  // gtest only: gmock matchers are header-only
  return RUN_ALL_TESTS();
}
