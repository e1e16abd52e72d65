// World loader: the SDF subset, the shipped worlds, and every bad input in docs/bad_input.md.
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/world/world.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

const std::string kData = std::string(TEST_DATA_DIR) + "/worlds/";
const std::string kWorlds = std::string(TEST_DATA_DIR) + "/../../worlds/";

struct Collected {
  std::vector<std::string> warnings;
  WorldLoadOptions options() {
    WorldLoadOptions o;
    o.warn = [this](const std::string& w) { warnings.push_back(w); };
    return o;
  }
  int count(const std::string& needle) const {
    int n = 0;
    for (const auto& w : warnings) n += w.find(needle) != std::string::npos;
    return n;
  }
};

// The error that stops a strict load (~strict_world); errors that leave out a model or a mesh
// in a normal load are in test_world_meshes.cpp.
WorldLoadOptions strict() {
  WorldLoadOptions o;
  o.strict = true;
  return o;
}

std::string errorOf(const std::string& file) {
  return test::errorText<WorldError>([&] { loadWorldFile(file, strict()); }, "(no error)");
}

std::string errorOfString(const std::string& xml) {
  return test::errorText<WorldError>(
      [&] { loadWorldString(xml, "inline.world", kData, strict()); }, "(no error)");
}

TEST(WorldLoader, FeaturesWorld) {
  Collected c;
  const WorldDescription w = loadWorldFile(kData + "features.world", c.options());
  EXPECT_EQ(w.name, "features");
  EXPECT_DOUBLE_EQ(w.physics.max_step_size, 0.002);
  EXPECT_DOUBLE_EQ(w.physics.real_time_factor, 0.0);
  EXPECT_DOUBLE_EQ(w.physics.real_time_update_rate, 500.0);
  EXPECT_DOUBLE_EQ(w.physics.gravity.z(), -9.81);
  ASSERT_TRUE(w.ambient.has_value());
  EXPECT_FLOAT_EQ((*w.ambient)[2], 0.4f);
  ASSERT_TRUE(w.background.has_value());
  EXPECT_FLOAT_EQ((*w.background)[3], 1.0f);
  EXPECT_TRUE(w.ground_plane);
  EXPECT_DOUBLE_EQ(w.X_WG.translation().z(), -0.5);
  ASSERT_TRUE(w.sun.has_value());
  EXPECT_NEAR(w.sun->direction.x(), -0.5, 1e-12);
  ASSERT_EQ(w.lights.size(), 2u);  // the directional lamp, the point bulb (approximated)
  EXPECT_NEAR(w.lights[0].direction.z(), -1.0, 1e-12);
  EXPECT_NEAR(w.lights[1].direction.z(), -1.0, 1e-12);

  ASSERT_EQ(w.models.size(), 3u);
  // <include> of a model folder holding only model.sdf (found in the world's models/), with
  // <name>, <pose> and <static> applied.
  const ModelDescription& included = w.models[0];
  EXPECT_EQ(included.name, "included_cube");
  EXPECT_TRUE(included.is_static);
  EXPECT_TRUE(included.X_WM.translation().isApprox(Eigen::Vector3d(4, 4, 0)));
  ASSERT_EQ(included.links.size(), 1u);
  EXPECT_EQ(included.links[0].visuals[0].shape.mesh_path, kData + "models/unit_cube/meshes/unit_cube.stl");
  const ModelDescription& shapes = w.models[1];
  EXPECT_EQ(shapes.name, "shapes");
  EXPECT_TRUE(shapes.is_static);
  ASSERT_EQ(shapes.links.size(), 1u);
  const LinkDescription& base = shapes.links[0];
  // Model yaw 90 deg, link 0.5 along the model's x -> world (1, 2.5).
  const Eigen::Vector3d p = (shapes.X_WM * base.X_ML).translation();
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 2.5, 1e-12);
  ASSERT_EQ(base.collisions.size(), 5u);
  EXPECT_EQ(base.collisions[0].shape.type, ShapeType::kBox);
  EXPECT_EQ(base.collisions[0].shape.size, Eigen::Vector3d(1, 2, 3));
  EXPECT_DOUBLE_EQ(base.collisions[0].friction.mu, 0.3);
  EXPECT_DOUBLE_EQ(base.collisions[0].friction.mu2, 0.4);
  EXPECT_EQ(base.collisions[1].shape.type, ShapeType::kCylinder);
  EXPECT_DOUBLE_EQ(base.collisions[1].shape.radius, 0.2);
  EXPECT_DOUBLE_EQ(base.collisions[1].shape.length, 0.6);
  EXPECT_DOUBLE_EQ(base.collisions[1].X_LS.translation().z(), 1.0);
  EXPECT_DOUBLE_EQ(base.collisions[1].friction.mu, 1.0);  // SDF default
  EXPECT_EQ(base.collisions[2].shape.type, ShapeType::kSphere);
  EXPECT_EQ(base.collisions[3].shape.type, ShapeType::kPlane);
  EXPECT_NEAR(base.collisions[3].shape.normal.y(), std::sqrt(0.5), 1e-12);
  EXPECT_EQ(base.collisions[4].shape.type, ShapeType::kMesh);
  EXPECT_EQ(base.collisions[4].shape.mesh_path,
            kData + "models/unit_cube/meshes/unit_cube.stl");
  ASSERT_EQ(base.visuals.size(), 2u);
  EXPECT_EQ(base.visuals[0].material.name, "Gazebo/Orange");
  EXPECT_FLOAT_EQ(base.visuals[0].material.diffuse[1], 0.5088f);
  EXPECT_FLOAT_EQ(base.visuals[0].material.specular[0], 0.9f);  // explicit overrides script
  EXPECT_EQ(base.visuals[1].shape.mesh_path, kData + "meshes/unit_cube.stl");
  EXPECT_EQ(base.visuals[1].shape.scale, Eigen::Vector3d::Constant(0.5));
  EXPECT_FLOAT_EQ(base.visuals[1].material.ambient[1], 0.2f);

  const ModelDescription& crate = w.models[2];
  EXPECT_FALSE(crate.is_static);
  EXPECT_DOUBLE_EQ(crate.links[0].inertial.mass, 2.5);
  EXPECT_DOUBLE_EQ(crate.links[0].inertial.inertia(2, 2), 0.3);
  EXPECT_DOUBLE_EQ(crate.links[0].inertial.X_LI.translation().z(), 0.1);

  // Unsupported elements: each warned exactly once, with the file and line.
  EXPECT_EQ(c.count("<gui> in <world> is not supported"), 1) << ::testing::PrintToString(c.warnings);
  EXPECT_EQ(c.count("features.world:17: <gui>"), 1);
  EXPECT_EQ(c.count("<iters> in <solver> is not supported"), 1);  // <ode><solver><iters>
  EXPECT_EQ(c.count("<shadows> in <scene>"), 1);
  EXPECT_EQ(c.count("<cast_shadows> in <light>"), 1);
  EXPECT_EQ(c.count("<light name='bulb'> (point) is approximated by a directional light"), 1);
  EXPECT_EQ(c.count("<plugin> in <world>"), 1);
  // A model's <plugin> is the model's (the Simulator sets up those it simulates, reports the
  // rest: test_simulator_world_model_sensors.cpp).
  EXPECT_EQ(c.count("<plugin> in <model>"), 0);
  ASSERT_EQ(crate.plugins.size(), 1u);
  EXPECT_EQ(crate.plugins[0].filename, "libmodel_plugin.so");
  EXPECT_EQ(crate.plugins[0].line, 88);
  EXPECT_EQ(c.count("<fdir1> in <ode>"), 1);
  EXPECT_EQ(c.count("<cast_shadows> in <visual>"), 1);
  EXPECT_EQ(c.warnings.size(), 8u) << ::testing::PrintToString(c.warnings);
}

TEST(WorldLoader, AddToScene) {
  const WorldDescription w = loadWorldFile(kData + "features.world");
  Scene scene;
  const auto bodies = addToScene(w, scene);
  EXPECT_TRUE(scene.ground_plane);
  ASSERT_EQ(bodies.count("ground_plane::link"), 1u);
  ASSERT_EQ(bodies.count("shapes::base"), 1u);
  ASSERT_EQ(bodies.count("crate::body"), 1u);
  EXPECT_TRUE(scene.bodies[bodies.at("shapes::base")].is_static);
  EXPECT_FALSE(scene.bodies[bodies.at("crate::body")].is_static);
  EXPECT_EQ(scene.bodies[bodies.at("crate::body")].model, "crate");
  EXPECT_EQ(scene.lights.size(), 3u);
  EXPECT_FLOAT_EQ(scene.ambient[0], 0.2f);
  EXPECT_FLOAT_EQ(scene.sky[2], 0.7f);
  int collisions = 0, visuals = 0, planes = 0;
  for (const SceneItem& it : scene.items) {
    collisions += it.collision;
    visuals += it.visual;
    EXPECT_NE(it.collision, it.visual);
    if (it.shape.type == ShapeType::kPlane && it.body == bodies.at("ground_plane::link")) ++planes;
  }
  EXPECT_EQ(planes, 1);
  EXPECT_EQ(collisions, 1 + 5 + 1);
  EXPECT_EQ(visuals, 2 + 1 + 1);  // + the included cube
  EXPECT_NEAR(scene.bodies[bodies.at("ground_plane::link")].X_WB.translation().z(), -0.5, 1e-12);
}

TEST(WorldLoader, InvalidSyntaxNamesFileAndLine) {
  const std::string e = errorOf(kData + "invalid_syntax.world");
  EXPECT_NE(e.find("invalid_syntax.world:6: malformed XML: XML_ERROR_MISMATCHED_ELEMENT (XMLElement name=link)"), std::string::npos) << e;
}

TEST(WorldLoader, UnknownGeometry) {
  const std::string e = errorOf(kData + "invalid_unknown_geometry.world");
  EXPECT_NE(e.find("invalid_unknown_geometry.world:9:"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown geometry <heightmap>"), std::string::npos) << e;
  EXPECT_NE(e.find("model 'terrain' link 'link' collision 'collision'"), std::string::npos) << e;
}

TEST(WorldLoader, MissingMesh) {
  const std::string e = errorOf(kData + "invalid_missing_mesh.world");
  EXPECT_NE(e.find("model 'statue' link 'base'"), std::string::npos) << e;
  EXPECT_NE(e.find("mesh 'meshes/does_not_exist.dae' not found"), std::string::npos) << e;
  EXPECT_NE(e.find(kData + "meshes/does_not_exist.dae"), std::string::npos) << e;
  // Not an error when meshes are optional (e.g. a headless check of the layout).
  WorldLoadOptions o;
  o.require_meshes = false;
  EXPECT_NO_THROW(loadWorldFile(kData + "invalid_missing_mesh.world", o));
  // Not strict (Gazebo's way): the same message as an error, and the world loads without the
  // mesh's geometry.
  std::vector<std::string> errors;
  WorldLoadOptions lenient;
  lenient.error = [&](const std::string& m) { errors.push_back(m); };
  const WorldDescription w = loadWorldFile(kData + "invalid_missing_mesh.world", lenient);
  ASSERT_FALSE(errors.empty());
  EXPECT_NE(errors[0].find(e), std::string::npos) << errors[0];
  ASSERT_EQ(w.models.size(), 1u);
  EXPECT_EQ(w.models[0].name, "statue");
}

TEST(WorldLoader, NonexistentFile) {
  const std::string e = errorOf(kData + "no_such.world");
  EXPECT_NE(e.find("world file '" + kData + "no_such.world' does not exist"), std::string::npos)
      << e;
  EXPECT_NE(errorOf(kData).find("is a directory"), std::string::npos);
}

TEST(WorldLoader, OtherBadValues) {
  // Test world files and what their error says.
  const std::pair<const char*, const char*> files[] = {
      {"invalid_pose.world", ":5: model 'm': <pose> '1 2 3 0 0' is not 6 numbers"},
      {"invalid_box_size.world", "<box> <size> must be > 0"},
      {"invalid_no_world.world", "no <world> element"},
      {"invalid_duplicate_model.world", "duplicate model name 'twin'"},
      {"invalid_number.world", "<max_step_size> 'nan' is not finite"}};
  for (const auto& [file, message] : files) {
    const std::string e = errorOf(kData + file);
    EXPECT_NE(e.find(message), std::string::npos) << e;
  }
  // Worlds given as text, and what their error says.
  const std::string kLink = "<sdf><world><model name='m'><link name='l'><collision name='c'>";
  const std::pair<std::string, const char*> texts[] = {
      {"<robot name='r'/>", "inline.world:1: root element is <robot>"},
      {"", "inline.world:"},
      {kLink + "<geometry/></collision></link></model></world></sdf>", "<geometry> is empty"},
      {kLink + "<geometry><cylinder><radius>-1</radius><length>1</length></cylinder>"
               "</geometry></collision></link></model></world></sdf>",
       "<radius> must be > 0 (got -1)"},
      {"<sdf><world><model><static>1</static></model></world></sdf>", "<model> has no name"},
      {"<sdf><world><model name='m'><static>maybe</static></model></world></sdf>",
       "'maybe' is not a boolean"},
      {kLink + "<geometry><mesh><uri>ftp://x/y.stl</uri></mesh></geometry></collision>"
               "</link></model></world></sdf>",
       "unsupported scheme"}};
  for (const auto& [xml, message] : texts) {
    const std::string e = errorOfString(xml);
    EXPECT_NE(e.find(message), std::string::npos) << e;
  }
  // A mass <= 0 is read as it is: it matters only for a link that moves, which the physics
  // reports (test_sim_world_models.cpp) while the rest of the world loads.
  EXPECT_EQ(errorOfString("<sdf><world><model name='m'><link name='l'><inertial><mass>0</mass>"
                          "</inertial></link></model></world></sdf>"),
            "(no error)");
}

// Gazebo's collision_zero.world: shapes of size 0 (ODE collides them as points). Each is left
// out with an error at its line, and the rest of the world loads; ~strict_world stops.
TEST(WorldLoader, AShapeOfNoSizeIsLeftOutAndTheRestLoads) {
  const std::string xml =
      "<sdf version='1.5'><world name='w'><model name='box'><link name='link'>\n"
      "<collision name='c'><geometry><box><size>0 0 0</size></box></geometry></collision>"
      "<visual name='v'><geometry><box><size>1 1 1</size></box></geometry></visual></link></model>\n"
      "<model name='ball'><link name='link'><collision name='c'><geometry><sphere>\n"
      "<radius>0</radius></sphere></geometry></collision></link></model>\n"
      "<model name='can'><link name='link'><collision name='c'><geometry><cylinder><radius>0.5"
      "</radius>\n<length>0</length></cylinder></geometry></collision></link></model>"
      "<model name='ok'><link name='link'><collision name='c'><geometry><sphere><radius>0.5"
      "</radius></sphere></geometry></collision></link></model></world></sdf>";
  std::vector<std::string> errors;
  WorldLoadOptions o;
  o.error = [&](const std::string& m) { errors.push_back(m); };
  const WorldDescription w = loadWorldString(xml, "zero.world", kData, o);
  ASSERT_EQ(errors.size(), 3u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0], "zero.world:2: model 'box' link 'link' collision 'c': <box> <size> must be > 0 "
                       "in x, y and z (Gazebo's ODE collides a zero-size shape as a point); the "
                       "collision is left out");
  EXPECT_EQ(errors[1], "zero.world:4: model 'ball' link 'link' collision 'c': <sphere> <radius> must "
                       "be > 0 (got 0) (Gazebo's ODE collides a zero-size shape as a point); the "
                       "collision is left out");
  EXPECT_EQ(errors[2], "zero.world:6: model 'can' link 'link' collision 'c': <cylinder> <length> must "
                       "be > 0 (got 0) (Gazebo's ODE collides a zero-size shape as a point); the "
                       "collision is left out");
  ASSERT_EQ(w.models.size(), 4u);
  EXPECT_TRUE(w.models[0].links[0].collisions.empty());
  EXPECT_EQ(w.models[0].links[0].visuals.size(), 1u);  // the visual of its own size stays
  EXPECT_EQ(w.models[3].links[0].collisions.size(), 1u);
  EXPECT_NE(errorOfString(xml).find("<box> <size> must be > 0"), std::string::npos);  // strict
}

// Gazebo's robocup14_spl_field.world includes one goal model twice without a <name>: Gazebo's
// World::LoadModel warns "Model with name [...] already exists. Not inserting model." and
// loads the rest. So do we, with an error at the <include>'s line; ~strict_world stops.
TEST(WorldLoader, ASecondModelOfANameIsLeftOutAndTheRestLoads) {
  const std::string xml =
      "<sdf version='1.5'><world name='w'>\n<include><uri>model://test_crate</uri></include>\n"
      "<include><pose>4 0 0 0 0 0</pose><uri>model://test_crate</uri></include>\n"
      "<model name='twin'><static>1</static><link name='a'/></model>\n"
      "<model name='twin'><static>1</static><link name='b'/></model>\n"
      "<model name='other'><static>1</static><link name='a'/></model></world></sdf>";
  std::vector<std::string> errors;
  WorldLoadOptions o;
  o.model_paths = {kData + "gazebo_models"};
  o.error = [&](const std::string& m) { errors.push_back(m); };
  const WorldDescription w = loadWorldString(xml, "dup.world", kData, o);
  ASSERT_EQ(errors.size(), 2u) << ::testing::PrintToString(errors);
  ASSERT_EQ(w.models.size(), 3u);
  const std::string crate = w.models[0].name;
  EXPECT_EQ(errors[0], "dup.world:3: duplicate model name '" + crate +
                           "' (Gazebo does not insert a second model of a name); the model is left out");
  EXPECT_EQ(errors[1], "dup.world:5: duplicate model name 'twin' (Gazebo does not insert a second "
                       "model of a name); the model is left out");
  EXPECT_DOUBLE_EQ(w.models[0].X_WM.translation().x(), 0.0);  // the first include stays
  EXPECT_EQ(w.models[1].name, "twin");
  EXPECT_EQ(w.models[1].links[0].name, "a");  // the first of the name stays
  EXPECT_EQ(w.models[2].name, "other");
}

// sdformat sets an element's value only from text it has: an empty <direction></direction>
// (Gazebo's deprecated_worlds/actor_circle.world) keeps the default 0 0 -1; a wrong one is
// still an error.
TEST(WorldLoader, AnEmptyLightValueKeepsItsDefault) {
  Collected c;
  const WorldDescription w = loadWorldString(
      "<sdf version='1.4'><world name='w'><light type='directional' name='sun'>"
      "<direction></direction><diffuse/><pose></pose></light></world></sdf>",
      "empty.world", kData, c.options());
  ASSERT_EQ(w.lights.size(), 1u);
  EXPECT_TRUE(w.lights[0].direction.isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_TRUE(c.warnings.empty()) << ::testing::PrintToString(c.warnings);
  EXPECT_NE(errorOfString("<sdf><world><light type='directional' name='sun'><direction>0 x 1"
                          "</direction></light></world></sdf>")
                .find("<direction>"),
            std::string::npos);
}

// The same rule for every SDF value a world reads with a default: an empty <pose> is the
// identity (or the model's own, for an <include>), an empty box <size/> is SDF's 1 1 1, an
// empty <static/> is false; a value that is there and wrong is still an error at its line.
TEST(WorldLoader, EmptySdfValuesKeepTheirDefaults) {
  Collected c;
  const WorldDescription w = loadWorldString(
      "<sdf version='1.6'><world name='w'>\n"
      "<model name='m'><pose></pose><static/>\n"
      "<link name='l'><pose/><inertial><pose/><mass/><inertia><ixx/><iyy>2</iyy></inertia>"
      "</inertial>\n"
      "<collision name='c'><pose> </pose><geometry><box><size/></box></geometry></collision>\n"
      "<visual name='v'><geometry><sphere><radius/></sphere></geometry></visual>\n"
      "</link></model></world></sdf>",
      "empty.world", kData, c.options());
  ASSERT_EQ(w.models.size(), 1u);
  const ModelDescription& m = w.models[0];
  EXPECT_TRUE(m.X_WM.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_FALSE(m.is_static);
  ASSERT_EQ(m.links.size(), 1u);
  EXPECT_TRUE(m.links[0].X_ML.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(m.links[0].inertial.mass, 1.0);  // SDF's default mass and ixx
  EXPECT_EQ(m.links[0].inertial.inertia, Eigen::Vector3d(1, 2, 1).asDiagonal().toDenseMatrix());
  ASSERT_EQ(m.links[0].collisions.size(), 1u);
  EXPECT_EQ(m.links[0].collisions[0].shape.size, Eigen::Vector3d::Ones());
  ASSERT_EQ(m.links[0].visuals.size(), 1u);
  EXPECT_EQ(m.links[0].visuals[0].shape.radius, 1.0);
  EXPECT_TRUE(c.warnings.empty()) << ::testing::PrintToString(c.warnings);
  EXPECT_EQ(errorOfString("<sdf><world name='w'>\n<model name='m'>\n<pose>1 2</pose>\n"
                          "</model></world></sdf>"),
            "inline.world:3: model 'm': <pose> '1 2' is not 6 numbers \"x y z roll pitch yaw\"");
}

// <physics><ode><solver><friction_model> is read (Gazebo 11's three values); an unknown one is
// said at its line and the default kept, as Gazebo's ODEPhysics does; ODE's other solver
// settings are reported as not supported, each at its line.
TEST(WorldLoader, OdeFrictionModelIsRead) {
  const auto load = [](const std::string& model, Collected* c) {
    return loadWorldString("<sdf version='1.6'><world name='w'>\n<physics type='ode'>\n"
                           "<ode><solver><type>quick</type>\n<friction_model>" + model +
                               "</friction_model></solver></ode></physics>\n</world></sdf>",
                           "fm.world", kData, c->options());
  };
  Collected c;
  EXPECT_EQ(load("cone_model", &c).physics.friction_model, "cone_model");
  ASSERT_EQ(c.warnings.size(), 1u) << ::testing::PrintToString(c.warnings);
  EXPECT_NE(c.warnings[0].find("fm.world:3"), std::string::npos) << c.warnings[0];  // <type>
  EXPECT_NE(c.warnings[0].find("type"), std::string::npos) << c.warnings[0];
  Collected d;
  EXPECT_EQ(load("box_model", &d).physics.friction_model, "box_model");
  Collected bad;
  EXPECT_EQ(load("round_model", &bad).physics.friction_model, "pyramid_model");
  ASSERT_EQ(bad.warnings.size(), 2u) << ::testing::PrintToString(bad.warnings);
  EXPECT_NE(bad.warnings[1].find("fm.world:4"), std::string::npos) << bad.warnings[1];
  EXPECT_NE(bad.warnings[1].find("unknown <friction_model> 'round_model'"), std::string::npos)
      << bad.warnings[1];
  Collected none;
  EXPECT_EQ(loadWorldString("<sdf version='1.6'><world name='w'></world></sdf>", "n.world", kData,
                            none.options())
                .physics.friction_model,
            "pyramid_model");
}

// An <include> without <uri> (SDF 1.3's <include filename='...'>, as in Gazebo's
// deprecated_worlds/weshare2012.world) is skipped by sdformat with an error; the rest loads.
TEST(WorldLoader, AnIncludeWithoutUriIsLeftOutAndTheRestLoads) {
  const std::string xml =
      "<sdf version='1.5'><world name='w'>\n<include filename='old.model'/>\n"
      "<model name='m'><include/><link name='a'/></model>\n"
      "<model name='other'><static>1</static><link name='a'/></model></world></sdf>";
  std::vector<std::string> errors;
  WorldLoadOptions o;
  o.error = [&](const std::string& m) { errors.push_back(m); };
  const WorldDescription w = loadWorldString(xml, "old.world", kData, o);
  ASSERT_EQ(errors.size(), 2u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0], "old.world:2: <include filename='old.model'> has no <uri> (the filename "
                       "attribute is SDF 1.3's, which sdformat no longer reads); the include is "
                       "left out");
  EXPECT_EQ(errors[1], "old.world:3: <include> has no <uri>; the include is left out");
  ASSERT_EQ(w.models.size(), 2u);
  EXPECT_EQ(w.models[0].links.size(), 1u);
  EXPECT_NE(errorOfString(xml).find("has no <uri>"), std::string::npos);  // strict
}

TEST(WorldLoader, AbsoluteAndFileUris) {
  const std::string cube = kData + "meshes/unit_cube.stl";
  for (const std::string& uri : {cube, "file://" + cube}) {
    const WorldDescription w = loadWorldString(
        "<sdf><world><model name='m'><static>true</static><link name='l'><collision name='c'>"
        "<geometry><mesh><uri>" + uri + "</uri></mesh></geometry></collision></link></model>"
        "</world></sdf>",
        "inline", "/nonexistent");
    EXPECT_EQ(w.models[0].links[0].collisions[0].shape.mesh_path, cube);
  }
}

TEST(WorldLoader, ResolveWorld) {
  EXPECT_EQ(resolveWorld("walled_room", kWorlds), kWorlds + "walled_room.world");
  EXPECT_EQ(resolveWorld(kData + "box_room.world", kWorlds), kData + "box_room.world");
  try {
    resolveWorld("moon_base", kWorlds);
    FAIL() << "no error";
  } catch (const WorldError& e) {
    EXPECT_NE(std::string(e.what()).find("world 'moon_base' is neither a shipped world (empty, "
                                         "walled_room, racetrack"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(resolveWorld("/no/such/file.world", kWorlds), WorldError);
  EXPECT_THROW(resolveWorld("", kWorlds), WorldError);
}

// Every shipped world loads without a single warning and yields a scene.
class ShippedWorld : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedWorld, Loads) {
  Collected c;
  const std::string path = resolveWorld(GetParam(), kWorlds);
  const WorldDescription w = loadWorldFile(path, c.options());
  EXPECT_TRUE(c.warnings.empty()) << ::testing::PrintToString(c.warnings);
  EXPECT_TRUE(w.ground_plane);
  EXPECT_TRUE(w.sun.has_value());
  EXPECT_DOUBLE_EQ(w.physics.max_step_size, 0.001);
  Scene scene;
  addToScene(w, scene);
  EXPECT_TRUE(scene.ground_plane);
  EXPECT_FALSE(scene.items.empty());
}

INSTANTIATE_TEST_SUITE_P(All, ShippedWorld, ::testing::ValuesIn(shippedWorldNames()));

// Distance in the xy plane from point p to the footprint of a box item (world frame).
double footprintDistance(const Scene& scene, const SceneItem& item, const Eigen::Vector2d& p) {
  const Eigen::Isometry3d X_WS = scene.bodies[item.body].X_WB * item.X_BS;
  const Eigen::Vector3d q = X_WS.inverse() * Eigen::Vector3d(p.x(), p.y(), X_WS.translation().z());
  const Eigen::Vector2d h = item.shape.size.head<2>() / 2;
  const Eigen::Vector2d d = (q.head<2>().cwiseAbs() - h).cwiseMax(0.0);
  return d.norm();
}

TEST(ShippedWorlds, WalledRoomLayout) {
  const WorldDescription w = loadWorldFile(kWorlds + "walled_room.world");
  Scene scene;
  addToScene(w, scene);
  // Inside 6 x 4: the inner wall faces are at x = +-3, y = +-2.
  int walls = 0;
  for (const SceneItem& it : scene.items) {
    if (!it.collision || scene.bodies[it.body].model != "walls") continue;
    ++walls;
    const Eigen::Vector3d c = (scene.bodies[it.body].X_WB * it.X_BS).translation();
    const Eigen::Vector3d h = it.shape.size / 2;
    const double inner = std::abs(c.x()) > 1.0 ? std::abs(c.x()) - h.x() : std::abs(c.y()) - h.y();
    EXPECT_NEAR(inner, std::abs(c.x()) > 1.0 ? 3.0 : 2.0, 1e-12);
    EXPECT_NEAR(h.z() * 2, 1.0, 1e-12);
  }
  EXPECT_EQ(walls, 4);
}

TEST(ShippedWorlds, RacetrackSpawnIsClear) {
  const WorldDescription w = loadWorldFile(kWorlds + "racetrack.world");
  Scene scene;
  addToScene(w, scene);
  // Nearest wall face on each side of the spawn: 0.5 m (track 1 m wide, spawn on the centreline).
  double nearest = 1e9;
  int boxes = 0, cones = 0;
  for (const SceneItem& it : scene.items) {
    if (!it.collision || it.shape.type == ShapeType::kPlane) continue;
    if (it.shape.type == ShapeType::kBox) {
      ++boxes;
      nearest = std::min(nearest, footprintDistance(scene, it, {0.0, 0.0}));
    } else {
      ++cones;
      const Eigen::Vector3d c = (scene.bodies[it.body].X_WB * it.X_BS).translation();
      EXPECT_GT(c.head<2>().norm(), 1.0);
    }
  }
  EXPECT_GT(boxes, 40);
  EXPECT_GE(cones, 4);
  EXPECT_NEAR(nearest, 0.5, 1e-6);
  // The whole bottom straight is clear for a car 0.2 m wide: every point of the centreline
  // from x = -2.75 to 2.75 keeps 0.45 m from the walls.
  for (double x = -2.75; x <= 2.75; x += 0.05) {
    for (const SceneItem& it : scene.items) {
      if (it.collision && it.shape.type == ShapeType::kBox) {
        EXPECT_GT(footprintDistance(scene, it, {x, 0.0}), 0.45) << x;
      }
    }
  }
}


// A world as Gazebo 9 saves it (SDF 1.6): an inline ground plane model, <state> with model and
// link poses, <include>s of a model folder (model.config with several SDF versions, a nested
// <include>), a point light, and the elements a save adds that we do not use.
TEST(WorldLoader, GazeboSavedWorldWithStateAndIncludes) {
  Collected c;
  WorldLoadOptions o = c.options();
  o.model_paths = {kData + "gazebo_models"};
  const WorldDescription w = loadWorldFile(kData + "gazebo_saved.world", o);
  auto model = [&](const std::string& name) -> const ModelDescription& {
    for (const auto& m : w.models)
      if (m.name == name) return m;
    throw std::runtime_error("no model " + name);
  };
  // <state> overrides <pose>: the box was moved and turned before the save.
  const ModelDescription& box = model("unit_box");
  EXPECT_TRUE(box.X_WM.isApprox(sdfPose(1.5, -0.5, 0.5, 0, 0, 1.2), 1e-12));
  EXPECT_TRUE(box.links[0].X_ML.isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  EXPECT_FALSE(box.is_static);
  // The included crate: renamed, its state pose, the 1.6 file of its model.config (0.4 m).
  const ModelDescription& crate = model("crate_a");
  EXPECT_TRUE(crate.X_WM.isApprox(sdfPose(3, 1, 0.2, 0, 0, 0.5), 1e-12));
  ASSERT_EQ(crate.links.size(), 1u);
  EXPECT_TRUE(crate.links[0].collisions[0].shape.size.isApprox(Eigen::Vector3d::Constant(0.4)));
  EXPECT_EQ(crate.links[0].visuals[0].shape.mesh_path, kData + "models/unit_cube/meshes/unit_cube.stl");
  // A model made of two nested includes: links "<name>::<link>" at the include poses.
  const ModelDescription& pair = model("crate_pair");
  EXPECT_TRUE(pair.is_static);
  EXPECT_TRUE(pair.X_WM.translation().isApprox(Eigen::Vector3d(-2, 0, 0)));
  ASSERT_EQ(pair.links.size(), 2u);
  EXPECT_EQ(pair.links[0].name, "left::body");
  EXPECT_TRUE(pair.links[0].X_ML.translation().isApprox(Eigen::Vector3d(0, 0.5, 0.2)));
  EXPECT_EQ(pair.links[1].name, "right::body");
  EXPECT_TRUE(pair.links[1].X_ML.translation().isApprox(Eigen::Vector3d(0, -0.5, 0.2)));
  // Scene: ambient and background, the sun and the point light (straight down, dimmed by its
  // attenuation at 2 m: 1 / (0.5 + 0.75 * 2) = 0.5).
  ASSERT_EQ(w.lights.size(), 2u);
  EXPECT_TRUE(w.lights[0].direction.isApprox(Eigen::Vector3d(-0.5, 0.1, -0.9).normalized()));
  EXPECT_FLOAT_EQ(w.lights[0].diffuse.x(), 0.8f);
  EXPECT_TRUE(w.lights[1].direction.isApprox(Eigen::Vector3d(0, 0, -1)));
  EXPECT_FLOAT_EQ(w.lights[1].diffuse.x(), 0.25f);
  Scene scene;
  addToScene(w, scene);
  EXPECT_FLOAT_EQ(scene.ambient.x(), 0.4f);
  EXPECT_FLOAT_EQ(scene.sky.x(), 0.7f);
  EXPECT_EQ(scene.lights.size(), 2u);
  // What a save adds and we do not use: each listed once, with file and line.
  for (const char* e : {"<gui> in <world>", "<audio> in <world>", "<spherical_coordinates> in <world>",
                        "<magnetic_field> in <world>", "<atmosphere> in <world>", "<wind> in <world>",
                        "<max_contacts> in <collision>"}) {
    EXPECT_EQ(c.count(e), 1) << e << ::testing::PrintToString(c.warnings);
  }
  EXPECT_EQ(c.count("gazebo_saved.world:"), static_cast<int>(c.warnings.size()) - c.count("model.sdf:"))
      << ::testing::PrintToString(c.warnings);
  EXPECT_EQ(c.count("(point) is approximated"), 1);
}

// A joint of a model that names its nested models' links by their world-scoped names, the
// model's own name first, as gazebo's pioneer2dx_camera.world does ("pioneer2dx::pioneer2dx::
// chassis" in model 'pioneer2dx'): Gazebo finds them through World::BaseByName (Joint::Load).
TEST(WorldLoader, AJointMayNameNestedLinksByTheirWorldScopedNames) {
  Collected c;
  WorldLoadOptions o = c.options();
  o.error = [&c](const std::string& e) { c.warnings.push_back(e); };
  const WorldDescription w = loadWorldString(
      "<sdf version='1.5'><world name='w'><model name='robot'>"
      "<model name='robot'><link name='chassis'><inertial><mass>1</mass></inertial></link></model>"
      "<model name='camera'><pose>0.2 0 0.3 0 0 0</pose><link name='link'><inertial><mass>0.1</mass>"
      "</inertial></link></model>\n"
      "<joint name='camera_joint' type='revolute'><parent>robot::robot::chassis</parent>"
      "<child>robot::camera::link</child><axis><xyz>0 0 1</xyz></axis></joint>\n"
      "<joint name='bad' type='fixed'><parent>robot::robot::chassis</parent>"
      "<child>other::camera::link</child></joint></model></world></sdf>",
      "scoped.world", kData, o);
  ASSERT_EQ(w.models.size(), 1u);
  const ModelDescription& m = w.models[0];
  ASSERT_EQ(m.joints.size(), 1u) << ::testing::PrintToString(c.warnings);
  EXPECT_EQ(m.joints[0].name, "camera_joint");
  EXPECT_EQ(m.joints[0].parent, "robot::chassis");
  EXPECT_EQ(m.joints[0].child, "camera::link");
  // Another model's scope is not this model's: that joint is left out, at its line.
  EXPECT_EQ(c.count("scoped.world:3: model 'robot' joint 'bad': no link 'other::camera::link'"), 1)
      << ::testing::PrintToString(c.warnings);
}

std::string errorWithModels(const std::string& xml) {
  try {
    WorldLoadOptions o = strict();
    o.model_paths = {kData + "gazebo_models"};
    loadWorldString(xml, "inline.world", kData, o);
  } catch (const WorldError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(WorldLoader, StateNamingAMissingModelOrLinkIsReportedAndIgnored) {
  // Gazebo logs "Unable to find model[ground]" and loads the rest (World::SetState); saved
  // worlds carry such states (TurtleBot3's autorace_2020 world names a model 'ground').
  std::vector<std::string> errors;
  WorldLoadOptions o;
  o.error = [&](const std::string& m) { errors.push_back(m); };
  const WorldDescription w = loadWorldString(
      "<sdf version='1.6'><world name='w'><model name='m'><static>1</static><link name='a'/>"
      "</model>\n<state world_name='w'>\n<model name='ghost'><pose>0 0 0 0 0 0</pose></model>"
      "\n<model name='m'><pose>1 2 3 0 0 0</pose>\n<link name='b'><pose>0 0 0 0 0 0</pose></link>"
      "</model>\n<deletions><name>gone</name></deletions></state></world></sdf>",
      "inline.world", kData, o);
  ASSERT_EQ(errors.size(), 3u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0], "inline.world:3: <state> names model 'ghost', which the world does not "
                       "have; its state is ignored");
  EXPECT_EQ(errors[1], "inline.world:5: <state> of model 'm' names link 'b', which the model "
                       "does not have; its state is ignored");
  EXPECT_EQ(errors[2], "inline.world:6: <state> <deletions> names model 'gone', which the world "
                       "does not have; nothing is deleted");
  ASSERT_EQ(w.models.size(), 1u);
  EXPECT_TRUE(w.models[0].X_WM.translation().isApprox(Eigen::Vector3d(1, 2, 3)));  // the rest
}

TEST(WorldLoader, StateScaleResizesShapesAsGazebo) {
  // A world saved after resizing models in Gazebo's editor: <state><model><scale> scales each
  // shape as Model::SetScale does (box size x scale; sphere radius x max; cylinder radius x
  // max(x, y), length x z; a mesh's scale replaced); placements and masses stay.
  std::vector<std::string> errors;
  WorldLoadOptions o;
  o.error = [&](const std::string& m) { errors.push_back(m); };
  o.require_meshes = false;
  const WorldDescription w = loadWorldString(
      "<sdf version='1.6'><world name='w'><model name='m'><pose>0 0 0.5 0 0 0</pose>"
      "<link name='a'><pose>0.1 0 0 0 0 0</pose>"
      "<collision name='box'><geometry><box><size>1 2 3</size></box></geometry></collision>"
      "<collision name='ball'><geometry><sphere><radius>0.5</radius></sphere></geometry></collision>"
      "<collision name='can'><geometry><cylinder><radius>0.5</radius><length>2</length></cylinder>"
      "</geometry></collision>"
      "<visual name='v'><geometry><mesh><uri>file://m.dae</uri><scale>2 2 2</scale></mesh></geometry>"
      "</visual></link></model>\n<model name='bad'><static>1</static><link name='a'>"
      "<collision name='c'><geometry><box><size>1 1 1</size></box></geometry></collision></link></model>"
      "<state world_name='w'><model name='m'><pose>0 0 0.5 0 0 0</pose><scale>2 0.5 4</scale>"
      "</model>\n<model name='bad'><scale>-1 1 1</scale></model></state></world></sdf>",
      "scaled.world", kData, o);
  ASSERT_EQ(errors.size(), 1u) << ::testing::PrintToString(errors);
  EXPECT_EQ(errors[0], "scaled.world:3: <state> of model 'bad': <scale> '-1 1 1' must be > 0 and "
                       "<= 1000 in x, y and z; the model keeps its size");
  const LinkDescription& l = w.models[0].links[0];
  EXPECT_TRUE(l.collisions[0].shape.size.isApprox(Eigen::Vector3d(2, 1, 12)));
  EXPECT_DOUBLE_EQ(l.collisions[1].shape.radius, 2.0);   // 0.5 x 4
  EXPECT_DOUBLE_EQ(l.collisions[2].shape.radius, 1.0);   // 0.5 x max(2, 0.5)
  EXPECT_DOUBLE_EQ(l.collisions[2].shape.length, 8.0);   // 2 x 4
  EXPECT_TRUE(l.visuals[0].shape.scale.isApprox(Eigen::Vector3d(2, 0.5, 4)));  // replaced
  EXPECT_TRUE(l.X_ML.translation().isApprox(Eigen::Vector3d(0.1, 0, 0)));     // not scaled
  EXPECT_DOUBLE_EQ(l.inertial.mass, 1.0);
  EXPECT_TRUE(w.models[1].links[0].collisions[0].shape.size.isApprox(Eigen::Vector3d::Ones()));
}

TEST(WorldLoader, StateNamingAMissingModelOrLinkIsAnErrorWhenStrict) {
  std::string e = errorWithModels(
      "<sdf version='1.6'><world name='w'>\n<state world_name='w'>\n<model name='ghost'>"
      "<pose>0 0 0 0 0 0</pose></model></state></world></sdf>");
  EXPECT_NE(e.find("inline.world:3: <state> names model 'ghost', which the world does not have"),
            std::string::npos) << e;
  e = errorWithModels(
      "<sdf version='1.6'><world name='w'><model name='m'><static>1</static><link name='a'/></model>"
      "\n<state world_name='w'><model name='m'>\n<link name='b'><pose>0 0 0 0 0 0</pose></link>"
      "</model></state></world></sdf>");
  EXPECT_NE(e.find("inline.world:3: <state> of model 'm' names link 'b'"), std::string::npos) << e;
}

TEST(WorldLoader, MissingIncludeNamesTheUriAndEveryFolderSearched) {
  setenv("GAZEBO_MODEL_PATH", "/nonexistent/gz_a:/nonexistent/gz_b", 1);
  const std::string e = errorWithModels(
      "<sdf version='1.6'><world name='w'>\n<include><uri>model://no_such_model</uri></include>"
      "</world></sdf>");
  unsetenv("GAZEBO_MODEL_PATH");
  EXPECT_NE(e.find("inline.world:2: <include> of 'model://no_such_model': model not found; searched:"),
            std::string::npos) << e;
  for (const std::string& d : {std::string("/nonexistent/gz_a"), std::string("/nonexistent/gz_b"),
                               kData + "gazebo_models", std::string("/.gazebo/models"), kData + "models"}) {
    EXPECT_NE(e.find(d), std::string::npos) << d << " in " << e;
  }
}

TEST(WorldLoader, IncludeLoopIsAnError) {
  const std::string e = errorWithModels(
      "<sdf version='1.6'><world name='w'><include><uri>model://loop_a</uri></include></world></sdf>");
  EXPECT_NE(e.find("<include> loop: "), std::string::npos) << e;
  EXPECT_NE(e.find("loop_a/model.sdf -> "), std::string::npos) << e;
  EXPECT_NE(e.find("loop_b/model.sdf -> "), std::string::npos) << e;
}

TEST(WorldLoader, ModelConfigWithoutSdfIsAnError) {
  const std::string e = errorWithModels(
      "<sdf version='1.6'><world name='w'><include><uri>model://no_sdf</uri></include></world></sdf>");
  EXPECT_NE(e.find("model.config names no <sdf> file"), std::string::npos) << e;
}

// model.config is read as the world is: its XML error names its line (tinyxml2 places an
// unclosed element at its start, line 4).
TEST(WorldLoader, ABrokenModelConfigIsAnErrorAtItsLine) {
  const std::string e = errorWithModels(
      "<sdf version='1.6'><world name='w'>\n<include><uri>model://bad_config</uri></include>"
      "</world></sdf>");
  EXPECT_NE(e.find("inline.world:2: <include> of 'model://bad_config': " + kData +
                   "gazebo_models/bad_config/model.config:4: is not valid XML (XML_ERROR_MISMATCHED"),
            std::string::npos)
      << e;
}

// model.config's versions compare as versions: 1.10 is above 1.7 (not 1.1 > 1.0), so 1.0 is chosen.
TEST(WorldLoader, ModelConfigVersionsCompareAsVersions) {
  WorldLoadOptions o = strict();
  o.model_paths = {kData + "gazebo_models"};
  const WorldDescription w = loadWorldString(
      "<sdf version='1.6'><world name='w'><include><uri>model://version_1_10</uri></include>"
      "</world></sdf>",
      "inline.world", kData, o);
  ASSERT_EQ(w.models.size(), 1u);  // 1.10's file does not exist: read, it would be an error
  EXPECT_EQ(w.models[0].name, "test_crate");
}

TEST(WorldLoader, IncludeFindsModelsThroughGazeboModelPathAndRosPackages) {
  // GAZEBO_MODEL_PATH alone.
  setenv("GAZEBO_MODEL_PATH", (kData + "gazebo_models").c_str(), 1);
  WorldDescription w = loadWorldString(
      "<sdf version='1.6'><world name='w'><include><uri>model://test_crate</uri></include></world></sdf>",
      "inline.world", kData);
  unsetenv("GAZEBO_MODEL_PATH");
  ASSERT_EQ(w.models.size(), 1u);
  EXPECT_EQ(w.models[0].name, "test_crate");
  // A ROS package exporting gazebo_model_path (as gazebo_ros reads package.xml exports).
  const std::string root = ::testing::TempDir() + "ros_ws_" + std::to_string(::getpid());
  const std::string pkg = root + "/src/my_worlds";
  ASSERT_EQ(std::system(("mkdir -p " + pkg + "/models && cp -r " + kData +
                         "gazebo_models/test_crate " + kData + "models/unit_cube " + pkg +
                         "/models/").c_str()), 0);
  {
    std::ofstream f(pkg + "/package.xml");
    f << "<package format='2'><name>my_worlds</name><version>0.0.0</version>"
         "<export><gazebo_ros gazebo_model_path='${prefix}/models'/></export></package>";
  }
  const char* old = std::getenv("ROS_PACKAGE_PATH");
  const std::string saved = old ? old : "";
  setenv("ROS_PACKAGE_PATH", root.c_str(), 1);
  w = loadWorldString(
      "<sdf version='1.6'><world name='w'><include><uri>model://test_crate</uri><name>c</name>"
      "</include></world></sdf>",
      "inline.world", "/nonexistent");
  if (old) setenv("ROS_PACKAGE_PATH", saved.c_str(), 1); else unsetenv("ROS_PACKAGE_PATH");
  ASSERT_EQ(w.models.size(), 1u);
  EXPECT_EQ(w.models[0].name, "c");
  EXPECT_NE(w.models[0].links[0].visuals[0].shape.mesh_path.find("unit_cube.stl"), std::string::npos);
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
