// loadRobotModel / loadRobotModelFile on test/data/urdf/{minimal,full,invalid_*}: the values that
// come out, the warnings, and the text of every error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <urdf_model/model.h>

#include "tianracer_sim/model/robot_model.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

const std::string kData = std::string(TEST_DATA_DIR) + "/urdf/";

struct Loader {
  std::vector<std::string> warnings;
  LoadOptions options;
  Loader() {
    options.warn = [this](const std::string& w) { warnings.push_back(w); };
    options.resolver.find_package = [](const std::string& p) -> std::string {
      return p == "test_meshes" ? kData : "";
    };
  }
  RobotModel load(const std::string& file) { return loadRobotModelFile(kData + file, options); }
  /// The ModelError text of loading `file` ("" if it loads).
  std::string error(const std::string& file) {
    return test::errorText<ModelError>([&] { load(file); });
  }
  std::string errorOf(const std::string& xml, const std::string& source = "robot_description") {
    return test::errorText<ModelError>([&] { loadRobotModel(xml, source, options); });
  }
  size_t countWarnings(const std::string& needle) const {
    return std::count_if(warnings.begin(), warnings.end(), [&](const std::string& w) {
      return w.find(needle) != std::string::npos;
    });
  }
};

TEST(ModelLoader, MinimalHasOneLinkAndNoExtensions) {
  Loader l;
  const RobotModel m = l.load("minimal.urdf");
  ASSERT_TRUE(m.urdf);
  EXPECT_EQ(m.urdf->getName(), "minimal");
  EXPECT_EQ(m.urdf->links_.size(), 1u);
  EXPECT_EQ(m.urdf->joints_.size(), 0u);
  EXPECT_EQ(m.urdf->getRoot()->name, "base_link");
  EXPECT_DOUBLE_EQ(m.urdf->getLink("base_link")->inertial->mass, 1.0);
  EXPECT_EQ(m.source, kData + "minimal.urdf");
  EXPECT_TRUE(m.ext.links.empty());
  EXPECT_TRUE(m.ext.transmissions.empty());
  EXPECT_TRUE(m.ext.model_plugins.empty());
  EXPECT_FALSE(m.ext.ros_control);
  EXPECT_FALSE(m.ext.joint_state_publisher);
  EXPECT_TRUE(m.mesh_paths.empty());
  EXPECT_TRUE(l.warnings.empty()) << l.warnings.front();
}

TEST(ModelLoader, FullLinksJointsAndMeshes) {
  Loader l;
  const RobotModel m = l.load("full.urdf");
  EXPECT_EQ(m.urdf->links_.size(), 7u);
  EXPECT_EQ(m.urdf->joints_.size(), 6u);
  EXPECT_FALSE(m.urdf->getLink("base_link")->inertial);  // massless is fine
  EXPECT_EQ(m.urdf->getJoint("left_hinge_joint")->type, urdf::Joint::REVOLUTE);
  // package://, relative (against the file's folder) for visual and collision alike.
  EXPECT_EQ(m.mesh_paths.size(), 2u);
  EXPECT_EQ(m.mesh_paths.at("package://test_meshes/meshes/cube.stl"), kData + "meshes/cube.stl");
  EXPECT_EQ(m.mesh_paths.at("meshes/cube.stl"), kData + "meshes/cube.stl");
}

TEST(ModelLoader, FullSurfacesInBothForms) {
  Loader l;
  const RobotModel m = l.load("full.urdf");
  const LinkExtension& chassis = m.ext.links.at("chassis");  // <mu1 value="..."/>
  EXPECT_EQ(*chassis.mu1, 0.0);
  EXPECT_EQ(*chassis.mu2, 0.0);
  EXPECT_EQ(*chassis.kp, 1e7);
  EXPECT_EQ(*chassis.kd, 1.0);
  EXPECT_EQ(chassis.material, "Gazebo/Red");
  EXPECT_FALSE(chassis.fdir1);
  EXPECT_FALSE(chassis.self_collide);

  const LinkExtension& lw = m.ext.links.at("left_wheel");  // <mu1>...</mu1>, two blocks merged
  EXPECT_EQ(*lw.mu1, 2.0);
  EXPECT_EQ(*lw.mu2, 1.5);
  EXPECT_EQ(*lw.kp, 1e7);
  EXPECT_EQ(*lw.kd, 1.0);
  EXPECT_EQ(*lw.fdir1, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(*lw.max_vel, 0.5);
  EXPECT_EQ(*lw.min_depth, 0.001);
  EXPECT_TRUE(*lw.self_collide);
  EXPECT_EQ(lw.material, "Gazebo/Black");

  const LinkExtension& rw = m.ext.links.at("right_wheel");
  EXPECT_EQ(*rw.fdir1, Eigen::Vector3d(0, 0, 1));
  EXPECT_FALSE(*rw.self_collide);
  EXPECT_FALSE(rw.mu2);
  EXPECT_EQ(m.ext.links.count("no_such_link"), 0u);
}

TEST(ModelLoader, FullSensors) {
  Loader l;
  const RobotModel m = l.load("full.urdf");
  const auto& lidar = m.ext.links.at("lidar").sensors;
  ASSERT_EQ(lidar.size(), 1u);
  const SensorSpec& s = lidar[0];
  EXPECT_EQ(s.name, "laser");
  EXPECT_EQ(s.type, "ray");
  EXPECT_EQ(s.link, "lidar");
  EXPECT_EQ(s.update_rate, 40.0);
  EXPECT_FALSE(s.always_on);
  EXPECT_TRUE(s.X_LS.translation().isApprox(Eigen::Vector3d(0, 0, 0.0124)));
  // yaw 90 deg: the sensor's x axis is the link's y axis.
  EXPECT_TRUE((s.X_LS.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_THAT(s.xml, AllOf(HasSubstr("<sensor type=\"ray\" name=\"laser\">"),
                           HasSubstr("<samples>5</samples>"), HasSubstr("</sensor>")));
  ASSERT_EQ(s.plugins.size(), 1u);
  EXPECT_EQ(s.plugins[0].filename, "libgazebo_ros_laser.so");
  EXPECT_EQ(s.plugins[0].name, "laser_controller");
  EXPECT_EQ(s.plugins[0].params.at("topicName"), "/scan");  // trimmed
  EXPECT_GT(s.line, 0);

  const auto& cam = m.ext.links.at("camera").sensors;
  ASSERT_EQ(cam.size(), 1u);
  EXPECT_EQ(cam[0].type, "camera");
  EXPECT_EQ(cam[0].update_rate, 30.0);
  EXPECT_TRUE(cam[0].always_on);  // default
  EXPECT_TRUE(cam[0].X_LS.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(cam[0].plugins.at(0).params.at("cameraName"), "full/camera");
}

TEST(ModelLoader, FullPlugins) {
  Loader l;
  const RobotModel m = l.load("full.urdf");
  ASSERT_TRUE(m.ext.ros_control);
  EXPECT_EQ(m.ext.ros_control->robot_namespace, "/full");
  EXPECT_EQ(m.ext.ros_control->robot_param, "robot_description");
  EXPECT_DOUBLE_EQ(m.ext.ros_control->control_period, 0.001);
  ASSERT_TRUE(m.ext.joint_state_publisher);
  EXPECT_THAT(m.ext.joint_state_publisher->joint_names,
              ElementsAre("left_wheel_joint", "right_wheel_joint", "left_hinge_joint"));
  EXPECT_EQ(m.ext.joint_state_publisher->update_rate, 50.0);
  EXPECT_EQ(m.ext.joint_state_publisher->robot_namespace, "/full");
  // Every model plugin is kept, the unknown ones too.
  ASSERT_EQ(m.ext.model_plugins.size(), 4u);
  EXPECT_EQ(m.ext.model_plugins[2].filename, "libgazebo_ros_p3d.so");
  EXPECT_EQ(m.ext.model_plugins[2].params.at("bodyName"), "base_link");
}

TEST(ModelLoader, FullTransmissionsInBothInterfaceForms) {
  Loader l;
  const RobotModel m = l.load("full.urdf");
  const auto& t = m.ext.transmissions;
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].name, "left_hinge_trans");
  EXPECT_EQ(t[0].type, "transmission_interface/SimpleTransmission");
  EXPECT_EQ(t[0].joint, "left_hinge_joint");
  EXPECT_THAT(t[0].joint_interfaces, ElementsAre(JointInterface::kEffort));
  EXPECT_EQ(t[0].actuator, "left_hinge_motor");
  EXPECT_THAT(t[0].actuator_interfaces, ElementsAre(JointInterface::kEffort));
  EXPECT_EQ(t[0].mechanical_reduction, 1.0);

  EXPECT_THAT(t[1].joint_interfaces, ElementsAre(JointInterface::kVelocity));  // bare form
  EXPECT_TRUE(t[1].actuator_interfaces.empty());
  EXPECT_EQ(t[1].mechanical_reduction, 2.5);

  EXPECT_THAT(t[2].joint_interfaces,
              ElementsAre(JointInterface::kPosition, JointInterface::kVelocity));
  EXPECT_EQ(t[2].mechanical_reduction, 1.0);  // default
}

TEST(ModelLoader, FullWarnsOnceAboutEachUnknownThing) {
  Loader l;
  l.load("full.urdf");
  EXPECT_EQ(l.countWarnings("<turnGravityOff>"), 0u);  // twice in the file: read (the link's gravity)
  EXPECT_EQ(l.countWarnings("<dampingFactor>"), 1u);
  EXPECT_EQ(l.countWarnings("<motorTorqueConstant>"), 1u);  // twice in the file
  // p3d (twice in the file) is simulated: the sensor registry, not the parser, judges plugins.
  EXPECT_EQ(l.countWarnings("libgazebo_ros_p3d.so"), 0u);
  EXPECT_EQ(l.countWarnings("no link named 'no_such_link'"), 1u);
  EXPECT_THAT(l.warnings, Contains(AllOf(HasSubstr("full.urdf:"),
                                         HasSubstr("unknown element <dampingFactor> ignored"))));
  EXPECT_EQ(l.warnings.size(), 3u) << ::testing::PrintToString(l.warnings);
}

TEST(ModelLoader, MissingMeshesToleratedWhenNotRequired) {
  Loader l;
  l.options.require_meshes = false;
  const RobotModel m = l.load("invalid_missing_mesh.urdf");
  EXPECT_EQ(m.mesh_paths.at("meshes/no_such_wheel.stl"), kData + "meshes/no_such_wheel.stl");
}

TEST(ModelLoader, XacroFileExpands) {
  Loader l;
  const RobotModel m = l.load("minimal.xacro");
  EXPECT_EQ(m.urdf->getName(), "minimal_xacro");
  EXPECT_DOUBLE_EQ(m.urdf->getLink("base_link")->inertial->ixx, 0.01);
  EXPECT_EQ(m.mesh_paths.at("meshes/cube.stl"), kData + "meshes/cube.stl");
  EXPECT_EQ(m.source, kData + "minimal.xacro");
}

TEST(ModelLoader, XacroArgsArePassed) {
  const std::string urdf = expandXacro(kData + "minimal.xacro", {"mass:=3.5"});
  EXPECT_THAT(urdf, HasSubstr("<mass value=\"3.5\"/>"));
}

// ---- Bad input: each error names the file, the element and the value. ----

// A camera's links as robots' URDFs write them (TurtleBot3's camera_rgb_frame and
// camera_rgb_optical_frame): fixed joints up to base_link, a revolute arm beside them.
const char* kCameraLinks = R"(<robot name="r">
  <link name="base_link"/>
  <link name="camera_frame"/>
  <link name="camera_optical_frame"/>
  <link name="arm"/>
  <joint name="camera_joint" type="fixed"><parent link="base_link"/><child link="camera_frame"/>
    <origin xyz="0.1 0 0.2" rpy="0 0 0.5"/></joint>
  <joint name="optical_joint" type="fixed"><parent link="camera_frame"/>
    <child link="camera_optical_frame"/><origin xyz="0 0 0" rpy="-1.57 0 -1.57"/></joint>
  <joint name="arm_joint" type="revolute"><parent link="base_link"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>)";

TEST(ModelLoader, FixedPoseFollowsFixedJointsOnly) {
  const RobotModel m = loadRobotModel(kCameraLinks, "camera_links", {});
  const std::optional<Eigen::Isometry3d> X_CO = fixedPose(*m.urdf, "camera_frame", "camera_optical_frame");
  ASSERT_TRUE(X_CO);
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(-1.57, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(-1.57, Eigen::Vector3d::UnitX())).toRotationMatrix();
  EXPECT_TRUE(X_CO->linear().isApprox(R, 1e-12));
  EXPECT_TRUE(X_CO->translation().isZero(1e-12));
  // Up the tree and down again: base_link -> camera_frame -> camera_optical_frame.
  const std::optional<Eigen::Isometry3d> X_BO = fixedPose(*m.urdf, "base_link", "camera_optical_frame");
  ASSERT_TRUE(X_BO);
  EXPECT_TRUE(X_BO->translation().isApprox(Eigen::Vector3d(0.1, 0.0, 0.2), 1e-12));
  const std::optional<Eigen::Isometry3d> X_OB = fixedPose(*m.urdf, "camera_optical_frame", "base_link");
  ASSERT_TRUE(X_OB);
  EXPECT_TRUE((*X_OB * *X_BO).isApprox(Eigen::Isometry3d::Identity(), 1e-12));
  EXPECT_TRUE(fixedPose(*m.urdf, "arm", "arm")->isApprox(Eigen::Isometry3d::Identity()));
  // A joint that moves, or a name that is no link: none.
  EXPECT_FALSE(fixedPose(*m.urdf, "camera_frame", "arm"));
  EXPECT_FALSE(fixedPose(*m.urdf, "camera_frame", "nowhere"));
}

TEST(ModelLoaderBadInput, EmptyInput) {
  Loader l;
  EXPECT_EQ(l.errorOf(""), "robot_description: robot_description is empty");
  EXPECT_THAT(l.errorOf(" \n\t "), HasSubstr("robot_description is empty"));
  EXPECT_THAT(l.error("invalid_empty.urdf"),
              AllOf(HasSubstr("invalid_empty.urdf"), HasSubstr("robot_description is empty")));
}

TEST(ModelLoaderBadInput, SyntaxErrorNamesTheLine) {
  Loader l;
  EXPECT_THAT(l.error("invalid_syntax.urdf"),
              AllOf(HasSubstr("invalid_syntax.urdf:4: XML error: "),  // the unclosed one
                    HasSubstr("XML_ERROR_MISMATCHED_ELEMENT"), HasSubstr("inertial")));
  EXPECT_THAT(l.errorOf("<robot name='x'>\n<link name='a'/>\n<link", "param"),
              HasSubstr("param:3: XML error: "));
}

TEST(ModelLoaderBadInput, RootIsNotRobot) {
  Loader l;
  EXPECT_THAT(l.errorOf("<sdf version='1.6'/>"), HasSubstr("root element is <sdf>"));
}

TEST(ModelLoaderBadInput, NonPositiveMass) {
  Loader l;
  EXPECT_THAT(l.error("invalid_mass.urdf"),
              AllOf(HasSubstr("invalid_mass.urdf:6: link 'body': mass '-2.5'"),
                    HasSubstr("positive")));
  const std::string tmpl =
      "<robot name='r'><link name='b'><inertial><mass value='M'/>"
      "<inertia ixx='1' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/></inertial></link></robot>";
  for (const std::string bad : {"0", "nan", "inf", "-inf", "heavy", ""}) {
    std::string xml = tmpl;
    xml.replace(xml.find('M'), 1, bad);
    EXPECT_THAT(l.errorOf(xml), HasSubstr("link 'b': mass '" + bad + "'")) << bad;
  }
}

TEST(ModelLoaderBadInput, InertiaNotPositiveDefinite) {
  Loader l;
  EXPECT_THAT(l.error("invalid_inertia.urdf"),
              AllOf(HasSubstr("invalid_inertia.urdf:8: link 'body': inertia is not positive "
                              "definite"),
                    HasSubstr("ixy=2"), HasSubstr("smallest eigenvalue -1")));
  // Positive diagonal is not enough; zero is not enough; non-finite is rejected by name.
  EXPECT_THAT(l.errorOf("<robot name='r'><link name='b'><inertial><mass value='1'/>"
                        "<inertia ixx='0' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/>"
                        "</inertial></link></robot>"),
              HasSubstr("link 'b': inertia is not positive definite"));
  EXPECT_THAT(l.errorOf("<robot name='r'><link name='b'><inertial><mass value='1'/>"
                        "<inertia ixx='1' ixy='0' ixz='nan' iyy='1' iyz='0' izz='1'/>"
                        "</inertial></link></robot>"),
              HasSubstr("link 'b': inertia ixz='nan' is not a finite number"));
  // The triangle inequality is not required (Gazebo does not either): ixx > iyy + izz loads.
  EXPECT_EQ(l.errorOf("<robot name='r'><link name='b'><inertial><mass value='1'/>"
                      "<inertia ixx='5' ixy='0' ixz='0' iyy='1' iyz='0' izz='1'/>"
                      "</inertial></link></robot>"),
            "");
}

// The inertial checks' errors are placed by the XmlReader: the exception carries the file, line
// and element, and the message reads as before.
TEST(ModelLoaderBadInput, InertialErrorsCarryTheirElementsPlace) {
  Loader l;
  try {
    loadRobotModel("<robot name='r'><link name='b'><inertial><mass value='1'/>\n"
                   "<inertia ixx='1' ixy='0' ixz='nan' iyy='1' iyz='0' izz='1'/>"
                   "</inertial></link></robot>",
                   "car.urdf", l.options);
    FAIL() << "loaded";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.where().file, "car.urdf");
    EXPECT_EQ(e.where().line, 2);
    EXPECT_EQ(e.where().element, "inertia");
    EXPECT_EQ(e.message(), "link 'b': inertia ixz='nan' is not a finite number");
    EXPECT_STREQ(e.what(), "car.urdf:2: link 'b': inertia ixz='nan' is not a finite number");
  }
}

TEST(ModelLoaderBadInput, DuplicateLink) {
  Loader l;
  EXPECT_THAT(l.error("invalid_duplicate_link.urdf"),
              HasSubstr("invalid_duplicate_link.urdf: duplicate link name 'wheel' (lines 4 and 10)"));
}

TEST(ModelLoaderBadInput, DuplicateJoint) {
  Loader l;
  EXPECT_THAT(
      l.error("invalid_duplicate_joint.urdf"),
      HasSubstr("invalid_duplicate_joint.urdf: duplicate joint name 'wheel_joint' (lines 6 and 11)"));
}

TEST(ModelLoaderBadInput, JointLoop) {
  Loader l;
  EXPECT_THAT(l.error("invalid_loop.urdf"),
              AllOf(HasSubstr("invalid_loop.urdf:8: joint loop: "), HasSubstr("'arm_a'"),
                    HasSubstr("'arm_b'"), HasSubstr("a URDF must be a tree")));
  EXPECT_THAT(l.error("invalid_two_parents.urdf"),
              HasSubstr("link 'wheel' has two parent joints, 'wheel_joint' and 'wheel_shortcut'"));
  EXPECT_THAT(l.errorOf("<robot name='r'><link name='a'/><joint name='j' type='fixed'>"
                        "<parent link='a'/><child link='a'/></joint></robot>"),
              HasSubstr("joint loop: 'a' -> 'a' (joint 'j'"));
}

TEST(ModelLoaderBadInput, DanglingLinksAndSeveralRoots) {
  Loader l;
  EXPECT_THAT(l.errorOf("<robot name='r'><link name='a'/><joint name='j' type='fixed'>"
                        "<parent link='a'/><child link='ghost'/></joint></robot>"),
              HasSubstr("joint 'j': child link 'ghost' does not exist"));
  EXPECT_THAT(l.errorOf("<robot name='r'><link name='a'/><link name='b'/></robot>"),
              HasSubstr("links 'a' and 'b' both have no parent joint"));
  EXPECT_THAT(l.errorOf("<robot name='r'></robot>"), HasSubstr("<robot> has no <link>"));
}

TEST(ModelLoaderBadInput, UrdfdomErrorsNameTheSource) {
  Loader l;
  EXPECT_THAT(l.errorOf("<robot name='r'><link name='a'/><link name='b'/>"
                        "<joint name='j' type='sliding'><parent link='a'/><child link='b'/>"
                        "</joint></robot>",
                        "my_param"),
              AllOf(HasSubstr("my_param: urdfdom could not parse the URDF"), HasSubstr("sliding")));
}

// urdfdom logs an error for a link whose <inertial> does not parse and returns the model anyway,
// with mass 0 on that link; the loader must refuse it (a crash fuzz_extensions found).
TEST(ModelLoaderBadInput, UrdfdomErrorWithAModelIsStillAnError) {
  Loader l;
  EXPECT_THAT(l.error("invalid_inertial_origin.urdf"),
              AllOf(HasSubstr("invalid_inertial_origin.urdf: urdfdom could not parse the URDF"),
                    HasSubstr("Unable to parse component [0.1x]"),
                    HasSubstr("Could not parse inertial element for Link [body]")));
}

TEST(ModelLoaderBadInput, TransmissionOnUnknownJoint) {
  Loader l;
  EXPECT_THAT(l.error("invalid_transmission_joint.urdf"),
              HasSubstr("invalid_transmission_joint.urdf:12: transmission 'wheel_trans': "
                        "unknown joint 'whel_joint'"));
}

TEST(ModelLoaderBadInput, TransmissionUnknownInterface) {
  Loader l;
  EXPECT_THAT(l.error("invalid_transmission_interface.urdf"),
              AllOf(HasSubstr(":13: transmission 'wheel_trans': joint 'wheel_joint'"),
                    HasSubstr("unknown hardwareInterface "
                              "'hardware_interface/TorqueJointInterface'")));
}

TEST(ModelLoaderBadInput, TransmissionTypeAndReduction) {
  Loader l;
  EXPECT_THAT(l.error("invalid_transmission_type.urdf"),
              HasSubstr("transmission 'wheel_trans': unsupported type "
                        "'transmission_interface/DifferentialTransmission'"));
  EXPECT_THAT(l.error("invalid_transmission_reduction.urdf"),
              HasSubstr("transmission 'wheel_trans': actuator 'wheel_motor': mechanicalReduction "
                        "'0' must be a finite non-zero number"));
}

TEST(ModelLoaderBadInput, MissingMesh) {
  Loader l;
  const std::string path = kData + "meshes/no_such_wheel.stl";
  EXPECT_THAT(l.error("invalid_missing_mesh.urdf"),
              HasSubstr("invalid_missing_mesh.urdf: link 'wheel': mesh 'meshes/no_such_wheel.stl' "
                        "not found (resolved to " + path + ")"));
}

TEST(ModelLoaderBadInput, AMeshUriNamingADirectoryOrADeviceSaysSo) {
  // Issue 43: these were "not found"; reading /dev/zero would never end.
  Loader l;
  const auto urdf = [](const std::string& uri) {
    return "<robot name='r'><link name='wheel'><visual><geometry><mesh filename='" + uri +
           "'/></geometry></visual></link></robot>";
  };
  EXPECT_THAT(l.errorOf(urdf("file:///dev/zero")),
              HasSubstr("robot_description: link 'wheel': mesh 'file:///dev/zero' (resolved to /dev/zero) "
                        "is not a regular file (a character device)"));
  EXPECT_THAT(l.errorOf(urdf("package://test_meshes/meshes")),
              HasSubstr("link 'wheel': mesh 'package://test_meshes/meshes' (resolved to " + kData +
                        "meshes) is a directory, not a mesh file"));
}

TEST(ModelLoaderBadInput, UnresolvablePackage) {
  Loader l;
  l.options.resolver.find_package = [](const std::string&) { return std::string(); };
  EXPECT_THAT(l.error("full.urdf"),
              HasSubstr("link 'chassis': mesh URI 'package://test_meshes/meshes/cube.stl': "
                        "package 'test_meshes' not found"));
  // Not required: a warning, and the rest still loads.
  l.options.require_meshes = false;
  EXPECT_NO_THROW(l.load("full.urdf"));
  EXPECT_EQ(l.countWarnings("package 'test_meshes' not found"), 1u);
}

TEST(ModelLoaderBadInput, JointStatePublisherUnknownJoint) {
  Loader l;
  EXPECT_THAT(l.error("invalid_jsp_joint.urdf"),
              HasSubstr("invalid_jsp_joint.urdf:11: plugin 'joint_state_publisher' "
                        "(libgazebo_ros_joint_state_publisher.so): unknown joint 'steering_joint'"));
}

TEST(ModelLoaderBadInput, MissingFileAndUnknownType) {
  Loader l;
  EXPECT_THAT(l.error("no_such_model.urdf"),
              HasSubstr(kData + "no_such_model.urdf: model file not found"));
  EXPECT_THAT(l.error("meshes/cube.stl"),
              HasSubstr("unknown model file type '.stl' (expected .urdf, .xml or .xacro)"));
}

TEST(ModelLoaderBadInput, XacroFailureCarriesItsMessage) {
  Loader l;
  EXPECT_THAT(l.error("invalid_xacro.xacro"),
              AllOf(HasSubstr("xacro failed on " + kData + "invalid_xacro.xacro: "),
                    HasSubstr("undefined_mass")));
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);  // gtest only: gmock matchers are header-only
  return RUN_ALL_TESTS();
}
