// Geometry derived from URDFs and resolved against parameters.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <tianracer_assets/paths.h>

#include "tianracer_control/urdf_geometry.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

std::string readFile(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string urdf(const std::string& name) {
  return readFile(std::string(TEST_DATA_DIR) + "/urdf/" + name + ".urdf");
}

// The nodes' resolver (tianracer_assets) with tianracer_description as the one known package.
MeshPathResolver descriptionResolver() {
  tianracer_assets::UriResolver r;
  r.find_package = [](const std::string& pkg) {
    return pkg == "tianracer_description" ? std::string(TIANRACER_DESCRIPTION_DIR) : std::string();
  };
  return [r](const std::string& uri) { return r.resolve(uri); };
}

bool anyContains(const std::vector<std::string>& lines, const std::string& what) {
  for (const std::string& l : lines) {
    if (l.find(what) != std::string::npos) return true;
  }
  return false;
}

const GeometryValue& valueOf(const ResolvedGeometry& r, const std::string& key) {
  for (const auto& kv : r.values) {
    if (kv.first == key) return kv.second;
  }
  throw std::runtime_error("no " + key);
}

}  // namespace

TEST(UrdfGeometry, FromJointOriginsThroughAFixedJoint) {
  const UrdfGeometry g = geometryFromUrdf(urdf("ackermann_cylinders"), AckermannJointNames());
  // left hinge at base_link_joint (0.01) + 0.1137 = 0.1237; right hinge 0.12626: mean 0.12498
  // rear wheels -0.12626, -0.1237: rear_axle_x = -0.12498; wheelbase 0.24996
  EXPECT_NEAR(g.values.at("rear_axle_x").value, -0.12498, 1e-12);
  EXPECT_NEAR(g.values.at("wheelbase").value, 0.24996, 1e-12);
  EXPECT_NEAR(g.values.at("hinge_separation").value, 0.070647 + 0.065953, 1e-12);
  EXPECT_NEAR(g.values.at("rear_track").value, 0.081602 + 0.086296, 1e-12);
  EXPECT_NEAR(g.values.at("wheel_radius").value, 0.032, 1e-12);
  EXPECT_NEAR(g.values.at("max_steering_angle").value, 0.55, 1e-12);  // the tighter limit
  // Asymmetry: rear axle midpoint y (0.081602 - 0.086296) / 2 = -0.002347; hinges skewed by
  // (0.12626 - 0.1237) / 2 = 0.00128 in x, their midpoint y (0.070647 - 0.065953) / 2 =
  // 0.002347 is 0.004694 left of the rear axle midpoint.
  EXPECT_NEAR(g.values.at("rear_axle_y").value, -0.002347, 1e-12);
  EXPECT_NEAR(g.values.at("hinge_skew_x").value, 0.00128, 1e-12);
  EXPECT_NEAR(g.values.at("hinge_offset_y").value, 0.004694, 1e-12);
  EXPECT_TRUE(g.warnings.empty());
  EXPECT_NE(g.values.at("wheelbase").source.find("robot_description"), std::string::npos);
}

TEST(UrdfGeometry, MeshWheelsAreMeasuredAboutTheirAxle) {
  // The generated wheel meshes reach exactly 0.032 m from the y axis (tianracer_description's
  // test checks the meshes themselves).
  const UrdfGeometry g = geometryFromUrdf(urdf("ackermann_meshes"), AckermannJointNames(),
                                          "base_link", descriptionResolver());
  EXPECT_NEAR(g.values.at("wheel_radius").value, 0.032, 1e-6);
  EXPECT_NE(g.values.at("wheel_radius").source.find("mesh vertices farthest from the axle"),
            std::string::npos);
  EXPECT_TRUE(g.warnings.empty()) << g.warnings.front();
}

TEST(UrdfGeometry, UnlocatedMeshWheelsGiveNoRadius) {
  const UrdfGeometry g = geometryFromUrdf(urdf("ackermann_meshes"), AckermannJointNames());
  EXPECT_EQ(g.values.count("wheel_radius"), 0u);
  EXPECT_TRUE(anyContains(g.warnings,
                          "link 'left_rear_wheel' collides with mesh "
                          "package://tianracer_description/meshes/left_rear_wheel.STL, which "
                          "could not be located"));
  // The default 0.032 is used, with a warning.
  const ResolvedGeometry r = resolveGeometry({}, &g);
  EXPECT_EQ(r.geometry.wheel_radius, 0.032);
  EXPECT_EQ(valueOf(r, "wheel_radius").source, "default");
  EXPECT_TRUE(anyContains(r.warnings, "wheel_radius not given and not found in robot_description"));
}

TEST(UrdfGeometry, UnreadableMeshIsReportedWithItsPath) {
  const UrdfGeometry g = geometryFromUrdf(urdf("ackermann_meshes"), AckermannJointNames(),
                                          "base_link",
                                          [](const std::string&) { return "/nonexistent/w.stl"; });
  EXPECT_EQ(g.values.count("wheel_radius"), 0u);
  EXPECT_TRUE(anyContains(g.warnings, "link 'left_rear_wheel': mesh '/nonexistent/w.stl': "
                                      "file not found: no wheel radius from it"));
}

TEST(UrdfGeometry, UnresolvableMeshUriIsReportedWithTheResolversReason) {
  tianracer_assets::UriResolver r;  // no package lookup
  const UrdfGeometry g =
      geometryFromUrdf(urdf("ackermann_meshes"), AckermannJointNames(), "base_link",
                       [&](const std::string& uri) { return r.resolve(uri); });
  EXPECT_EQ(g.values.count("wheel_radius"), 0u);
  EXPECT_TRUE(anyContains(g.warnings, "which could not be located (mesh URI "
                                      "'package://tianracer_description/meshes/left_rear_wheel.STL': "
                                      "no package lookup configured"));
}

TEST(UrdfGeometry, ParametersWin) {
  const UrdfGeometry g = geometryFromUrdf(urdf("ackermann_cylinders"), AckermannJointNames());
  const ResolvedGeometry r = resolveGeometry({{"wheelbase", 0.3}, {"wheel_radius", 0.05}}, &g);
  EXPECT_EQ(r.geometry.wheelbase, 0.3);
  EXPECT_EQ(valueOf(r, "wheelbase").source, "parameter ~wheelbase");
  EXPECT_EQ(r.geometry.wheel_radius, 0.05);
  EXPECT_NEAR(r.geometry.hinge_separation, 0.1366, 1e-12);
  EXPECT_NEAR(r.geometry.hinge_skew_x, 0.00128, 1e-12);
  ASSERT_EQ(r.values.size(), 9u);
  EXPECT_EQ(r.values[0].first, "wheelbase");
  EXPECT_EQ(r.values[8].first, "hinge_offset_y");
}

TEST(UrdfGeometry, MissingJointsAreWarnedAndDefaulted) {
  AckermannJointNames names;
  names.left_hinge = "front_left_steer";
  const UrdfGeometry g = geometryFromUrdf(urdf("ackermann_cylinders"), names);
  EXPECT_TRUE(anyContains(g.warnings, "joint 'front_left_steer' not in the URDF"));
  EXPECT_EQ(g.values.count("wheelbase"), 0u);
  EXPECT_EQ(g.values.count("rear_track"), 1u);
}

TEST(UrdfGeometry, Errors) {
  EXPECT_THROW(geometryFromUrdf(urdf("invalid_syntax"), AckermannJointNames()), AckermannError);
  try {
    geometryFromUrdf("", AckermannJointNames());
    FAIL();
  } catch (const AckermannError& e) {
    EXPECT_STREQ(e.what(), "robot_description is empty");
  }
  try {
    resolveGeometry({{"wheel_base", 0.3}}, nullptr);
    FAIL();
  } catch (const AckermannError& e) {
    EXPECT_STREQ(e.what(), "unknown geometry parameter 'wheel_base'");
  }
  EXPECT_THROW(resolveGeometry({{"wheelbase", -1.0}}, nullptr), AckermannError);
}

TEST(UrdfGeometry, UnknownBaseLinkFallsBackToTheRoot) {
  const UrdfGeometry g =
      geometryFromUrdf(urdf("ackermann_cylinders"), AckermannJointNames(), "base_footprint");
  EXPECT_TRUE(anyContains(g.warnings, "link 'base_footprint' not in the URDF; using the root link "
                                      "'base_link'"));
  EXPECT_NEAR(g.values.at("wheelbase").value, 0.24996, 1e-12);
}

// The shipped model, expanded by xacro (skipped where xacro or rospack cannot run).
TEST(UrdfGeometry, SeedTianracer) {
  const std::string cmd = std::string("xacro '") + TIANRACER_DESCRIPTION_DIR +
                          "/urdf/tianracer_description.xacro' 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) GTEST_SKIP() << "cannot run xacro";
  std::string xml;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) xml.append(buf, n);
  if (pclose(pipe) != 0 || xml.empty()) GTEST_SKIP() << "xacro failed (not installed?)";
  const UrdfGeometry g =
      geometryFromUrdf(xml, AckermannJointNames(), "base_link", descriptionResolver());
  EXPECT_NEAR(g.values.at("wheel_radius").value, 0.032, 1e-6);
  EXPECT_NEAR(g.values.at("wheelbase").value, 0.24996, 1e-9);
  EXPECT_NEAR(g.values.at("hinge_separation").value, 0.1366, 1e-9);
  EXPECT_NEAR(g.values.at("rear_track").value, 0.167898, 1e-9);
  EXPECT_NEAR(g.values.at("rear_axle_x").value, -0.12498, 1e-9);
  EXPECT_NEAR(g.values.at("max_steering_angle").value, 0.6, 1e-9);
  EXPECT_NEAR(g.values.at("rear_axle_y").value, -0.002347, 1e-9);
  EXPECT_NEAR(g.values.at("hinge_skew_x").value, 0.00128, 1e-9);
  EXPECT_NEAR(g.values.at("hinge_offset_y").value, 0.004694, 1e-9);
  const ResolvedGeometry r = resolveGeometry({}, &g);
  // Measured from the mesh (float32 STL vertices): the rolling radius the odometry uses.
  EXPECT_NEAR(r.geometry.wheel_radius, 0.032, 1e-6);
  EXPECT_EQ(valueOf(r, "wheel_radius").source,
            "robot_description: collision of the rear wheel links (mesh vertices farthest from "
            "the axle)");
}

namespace {

// ackermann_cylinders with every link and joint name written as a prefix:=car1 xacro writes it.
std::string prefixed(const std::string& prefix) {
  std::string xml = urdf("ackermann_cylinders");
  for (const std::string attr : {"name=\"", "link=\""}) {
    for (size_t at = xml.find(attr); at != std::string::npos; at = xml.find(attr, at + 1)) {
      if (xml.compare(at - 7, 7, "<robot ") == 0) continue;
      xml.insert(at + attr.size(), prefix);
    }
  }
  return xml;
}

}  // namespace

TEST(ModelNames, SeedNamesAreFoundAsTheyAre) {
  const ModelNames n = findModelNames(urdf("ackermann_cylinders"), AckermannJointNames());
  EXPECT_EQ(n.joints.left_hinge, "left_steering_hinge_joint");
  EXPECT_EQ(n.base_link, "base_link");
  EXPECT_EQ(n.prefix, "");
  EXPECT_TRUE(n.found.empty());
  EXPECT_TRUE(n.warnings.empty());
}

TEST(ModelNames, PrefixedNamesAreFoundAndGiveTheSameGeometry) {
  for (const std::string prefix : {"car1/", "car1_"}) {
    const std::string xml = prefixed(prefix);
    ASSERT_NE(xml.find("\"" + prefix + "right_rear_wheel_joint\""), std::string::npos);
    const ModelNames n = findModelNames(xml, AckermannJointNames());
    EXPECT_EQ(n.prefix, prefix);
    EXPECT_EQ(n.joints.left_hinge, prefix + "left_steering_hinge_joint");
    EXPECT_EQ(n.joints.right_hinge, prefix + "right_steering_hinge_joint");
    EXPECT_EQ(n.joints.left_rear_wheel, prefix + "left_rear_wheel_joint");
    EXPECT_EQ(n.joints.right_rear_wheel, prefix + "right_rear_wheel_joint");
    EXPECT_EQ(n.base_link, prefix + "base_link");
    EXPECT_TRUE(n.warnings.empty()) << n.warnings.front();
    EXPECT_TRUE(anyContains(n.found, "link '" + prefix + "base_link' for ~base_frame 'base_link'"));
    EXPECT_TRUE(anyContains(n.found, "joint '" + prefix +
                                         "left_rear_wheel_joint' for ~left_rear_wheel_joint"));

    const UrdfGeometry g = geometryFromUrdf(xml, n.joints, n.base_link);
    EXPECT_TRUE(g.warnings.empty());
    EXPECT_NEAR(g.values.at("wheelbase").value, 0.24996, 1e-12);
    EXPECT_NEAR(g.values.at("rear_track").value, 0.081602 + 0.086296, 1e-12);
    EXPECT_NEAR(g.values.at("wheel_radius").value, 0.032, 1e-12);
    EXPECT_NEAR(g.values.at("max_steering_angle").value, 0.55, 1e-12);
  }
}

TEST(ModelNames, TheJointsPrefixPicksTheBaseLinkAmongSeveral) {
  // car1/base_link under a root whose own name also ends in base_link.
  std::string xml = prefixed("car1/");
  xml.replace(xml.find("<link name=\"car1/base_link\"/>"), 0,
              "<link name=\"world_base_link\"/><joint name=\"mount\" type=\"fixed\">"
              "<parent link=\"world_base_link\"/><child link=\"car1/base_link\"/></joint>");
  const ModelNames n = findModelNames(xml, AckermannJointNames());
  EXPECT_EQ(n.base_link, "car1/base_link");
}

TEST(ModelNames, MissingAndAmbiguousNamesNameTheParameterAndWhatWasLookedFor) {
  std::string xml = urdf("ackermann_cylinders");
  // Two candidates for the right rear wheel, none for the left hinge.
  xml.replace(xml.find("\"right_rear_wheel_joint\""), 24, "\"a_right_rear_wheel_joint\"");
  xml.replace(xml.find("</robot>"), 0,
              "<link name=\"x\"/><joint name=\"b/right_rear_wheel_joint\" type=\"continuous\">"
              "<parent link=\"base_link\"/><child link=\"x\"/></joint>");
  xml.replace(xml.find("\"left_steering_hinge_joint\""), 27, "\"front_left_steer\"");
  const ModelNames n = findModelNames(xml, AckermannJointNames());
  ASSERT_EQ(n.warnings.size(), 2u);
  EXPECT_EQ(n.warnings[0],
            "no joint 'left_steering_hinge_joint' or a name ending in '/left_steering_hinge_joint' "
            "or '_left_steering_hinge_joint' in the URDF: set ~left_steering_hinge_joint to the "
            "model's name");
  EXPECT_EQ(n.warnings[1],
            "several joints match 'right_rear_wheel_joint' or a name ending in "
            "'/right_rear_wheel_joint' or '_right_rear_wheel_joint' ('a_right_rear_wheel_joint', "
            "'b/right_rear_wheel_joint'): set ~right_rear_wheel_joint to the one to use");
  EXPECT_EQ(n.joints.left_hinge, "left_steering_hinge_joint");  // kept as asked
  // A name given as a parameter is looked for as given.
  AckermannJointNames given;
  given.left_hinge = "front_left_steer";
  given.right_rear_wheel = "b/right_rear_wheel_joint";
  const ModelNames m = findModelNames(xml, given);
  EXPECT_TRUE(m.warnings.empty());
  EXPECT_THROW(findModelNames("<robot", AckermannJointNames()), AckermannError);
}
