// MeshResolver: package://, file://, absolute and relative URIs, and the errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

MeshResolver resolver() {
  MeshResolver r;
  r.find_package = [](const std::string& p) -> std::string {
    if (p == "tianracer_description") return "/ws/src/tianracer_description";
    if (p == "slash") return "/ws/src/slash/";
    return "";
  };
  r.base_dir = "/models/car";
  return r;
}

std::string error(const MeshResolver& r, const std::string& uri) {
  try {
    r.resolve(uri);
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshResolver, Package) {
  EXPECT_EQ(resolver().resolve("package://tianracer_description/meshes/base_link.STL"),
            "/ws/src/tianracer_description/meshes/base_link.STL");
  EXPECT_EQ(resolver().resolve("package://slash/a/b.stl"), "/ws/src/slash/a/b.stl");
}

TEST(MeshResolver, FileAbsoluteAndRelative) {
  EXPECT_EQ(resolver().resolve("file:///abs/mesh.dae"), "/abs/mesh.dae");
  EXPECT_EQ(resolver().resolve("/abs/mesh.stl"), "/abs/mesh.stl");
  EXPECT_EQ(resolver().resolve("meshes/wheel.stl"), "/models/car/meshes/wheel.stl");
  EXPECT_EQ(resolver().resolve("../shared/wheel.stl"), "/models/car/../shared/wheel.stl");
  EXPECT_EQ(resolver().resolve("file://meshes/wheel.stl"), "/models/car/meshes/wheel.stl");
}

TEST(MeshResolver, ResolvesWithoutTouchingTheDisk) {
  // Existence is the loader's business (require_meshes), not the resolver's.
  EXPECT_EQ(resolver().resolve("package://tianracer_description/nope.stl"),
            "/ws/src/tianracer_description/nope.stl");
}

TEST(MeshResolver, Errors) {
  const MeshResolver r = resolver();
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

  MeshResolver bare;  // no package lookup, no folder
  EXPECT_THAT(error(bare, "package://tianracer_description/m.stl"),
              HasSubstr("no package lookup configured to find 'tianracer_description'"));
  EXPECT_THAT(error(bare, "meshes/m.stl"),
              HasSubstr("is relative but the model has no folder to resolve it against"));
  EXPECT_EQ(bare.resolve("/abs/m.stl"), "/abs/m.stl");
}

TEST(MeshResolver, ModelPath) {
  MeshResolver r = resolver();
  const std::string data = TEST_DATA_DIR;
  // test/data/urdf/meshes holds the test meshes: a "model" named meshes in test/data/urdf.
  r.model_paths = {"/nonexistent/models", data + "/urdf"};
  EXPECT_EQ(r.resolve("model://meshes/cube.stl"), data + "/urdf/meshes/cube.stl");
  // A miss names the URI and every folder searched.
  EXPECT_THAT(error(r, "model://no_such_model/meshes/x.dae"),
              HasSubstr("mesh URI 'model://no_such_model/meshes/x.dae' not found in the model path"));
  EXPECT_THAT(error(r, "model://no_such_model/meshes/x.dae"),
              HasSubstr("searched /nonexistent/models, " + data + "/urdf"));
  EXPECT_THAT(error(r, "model://"), HasSubstr("is not model://<model>/<path>"));
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);  // gtest only: gmock matchers are header-only
  return RUN_ALL_TESTS();
}
