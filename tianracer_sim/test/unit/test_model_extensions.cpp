// parseExtensions alone (the fuzzer's entry point), parseJointInterface, and a deterministic
// mutation run showing that any input gives a result or a ModelError, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "tianracer_sim/model/robot_model.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

/// A two-wheel robot with `body` spliced in after the links and joints.
std::string robot(const std::string& body) {
  return "<robot name='r'>\n"
         "<link name='base_link'/>\n"
         "<link name='wheel'/>\n"
         "<joint name='wheel_joint' type='continuous'><parent link='base_link'/>"
         "<child link='wheel'/><axis xyz='0 1 0'/></joint>\n" +
         body + "\n</robot>\n";
}

struct Parser {
  std::vector<std::string> warnings;
  RobotExtensions parse(const std::string& xml) {
    return parseExtensions(xml, "test.urdf",
                           [this](const std::string& w) { warnings.push_back(w); });
  }
  std::string error(const std::string& xml) {
    return test::errorText<ModelError>([&] { parse(xml); });
  }
};

TEST(JointInterface, BothSpellings) {
  EXPECT_EQ(parseJointInterface("hardware_interface/EffortJointInterface"),
            JointInterface::kEffort);
  EXPECT_EQ(parseJointInterface("EffortJointInterface"), JointInterface::kEffort);
  EXPECT_EQ(parseJointInterface(" VelocityJointInterface\n"), JointInterface::kVelocity);
  EXPECT_EQ(parseJointInterface("hardware_interface/PositionJointInterface"),
            JointInterface::kPosition);
  EXPECT_FALSE(parseJointInterface("hardware_interface/"));
  EXPECT_FALSE(parseJointInterface("effortjointinterface"));
  EXPECT_FALSE(parseJointInterface("other_interface/EffortJointInterface"));
  EXPECT_FALSE(parseJointInterface(""));
  for (auto i : {JointInterface::kEffort, JointInterface::kVelocity, JointInterface::kPosition})
    EXPECT_EQ(parseJointInterface(toString(i)), i);
}

TEST(Extensions, SurfaceValuesInBothForms) {
  Parser p;
  const auto ext = p.parse(robot(
      "<gazebo reference='wheel'><mu1 value=' 0.8 '/><mu2>0.7</mu2><kp value='1e7'/>"
      "<kd>+1</kd><fdir1> 0 1 0 </fdir1><material value='Gazebo/Blue'/>"
      "<selfCollide>1</selfCollide><maxVel value='0.01'/><minDepth>0</minDepth></gazebo>"));
  const LinkExtension& w = ext.links.at("wheel");
  EXPECT_EQ(*w.mu1, 0.8);
  EXPECT_EQ(*w.mu2, 0.7);
  EXPECT_EQ(*w.kp, 1e7);
  EXPECT_EQ(*w.kd, 1.0);
  EXPECT_EQ(*w.fdir1, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(w.material, "Gazebo/Blue");
  EXPECT_TRUE(*w.self_collide);
  EXPECT_EQ(*w.max_vel, 0.01);
  EXPECT_EQ(*w.min_depth, 0.0);
  EXPECT_FALSE(w.gravity.has_value());  // not given: Gazebo's default (true)
  EXPECT_TRUE(p.warnings.empty());
  // A negative mu is Gazebo's "no limit" (contact_law.cpp toSurface), not an error.
  EXPECT_EQ(*p.parse(robot("<gazebo reference='wheel'><mu1>-1</mu1></gazebo>")).links.at("wheel").mu1,
            -1.0);
}

TEST(Extensions, BadSurfaceValuesNameElementAndValue) {
  Parser p;
  EXPECT_THAT(p.error(robot("<gazebo reference='wheel'><mu1>slippery</mu1></gazebo>")),
              HasSubstr("test.urdf:5: <gazebo reference='wheel'>: <mu1> value 'slippery' "
                        "is not a number"));
  // <gazebo reference='wheel'> bodies and what their error says.
  const std::pair<const char*, const char*> cases[] = {
      {"<kp value='-1'/>", "<kp> value '-1' must be finite and >= 0"},
      {"<kd value='inf'/>", "<kd> value 'inf' must be finite and >= 0"},
      {"<mu2/>", "<mu2> value '' is not a number"},
      {"<mu1>-inf</mu1>", "<mu1> value '-inf' must be finite"},
      {"<fdir1>1 0</fdir1>", "<fdir1> value '1 0' is not 3 finite numbers"},
      {"<fdir1>1 nan 0</fdir1>", "<fdir1> value '1 nan 0'"},
      {"<selfCollide>yes</selfCollide>", "<selfCollide> value 'yes' is not a boolean"}};
  for (const auto& [body, message] : cases) {
    EXPECT_THAT(p.error(robot(std::string("<gazebo reference='wheel'>") + body + "</gazebo>")),
                HasSubstr(message));
  }
}

// sdformat's parser_urdf.cc: <turnGravityOff> (inverted) and <gravity> both become the link's
// <gravity>.
TEST(Extensions, GravityAndTurnGravityOff) {
  Parser p;
  EXPECT_FALSE(*p.parse(robot("<gazebo reference='wheel'><gravity>0</gravity></gazebo>")).links.at("wheel").gravity);
  EXPECT_TRUE(*p.parse(robot("<gazebo reference='wheel'><gravity>true</gravity></gazebo>")).links.at("wheel").gravity);
  EXPECT_FALSE(
      *p.parse(robot("<gazebo reference='wheel'><turnGravityOff>true</turnGravityOff></gazebo>")).links.at("wheel").gravity);
  EXPECT_TRUE(
      *p.parse(robot("<gazebo reference='wheel'><turnGravityOff>false</turnGravityOff></gazebo>")).links.at("wheel").gravity);
  EXPECT_THAT(p.error(robot("<gazebo reference='wheel'><turnGravityOff>off</turnGravityOff></gazebo>")),
              HasSubstr("<turnGravityOff> value 'off' is not a boolean"));
}

TEST(Extensions, ReferencesToJointsAndMissingLinksAreWarnings) {
  Parser p;
  const auto ext = p.parse(robot("<gazebo reference='wheel_joint'><provideFeedback>true"
                                 "</provideFeedback></gazebo>"
                                 "<gazebo reference='ghost'><mu1>1</mu1></gazebo>"
                                 "<gazebo reference='ghost'><mu1>1</mu1></gazebo>"));
  EXPECT_TRUE(ext.links.empty());
  EXPECT_THAT(p.warnings,
              ElementsAre(HasSubstr("<gazebo reference='wheel_joint'> names a joint"),
                          HasSubstr("<gazebo reference='ghost'>: no link named 'ghost' (Gazebo "
                                    "ignores it)")));
}

TEST(Extensions, UnknownTopLevelAndModelElementsAreWarnedOnce) {
  Parser p;
  p.parse(robot("<sensor name='s'/><sensor name='t'/><gazebo><static>true</static></gazebo>"));
  EXPECT_THAT(p.warnings, ElementsAre(HasSubstr("unknown element <sensor> ignored"),
                                      HasSubstr("<gazebo>: unknown element <static> ignored")));
}

TEST(Extensions, SensorFields) {
  Parser p;
  const auto ext = p.parse(robot(
      "<gazebo reference='wheel'><sensor name='s' type='depth'><always_on>1</always_on>"
      "<update_rate>20.0</update_rate><pose>1 2 3 0 0 0</pose>"
      "<plugin name='k' filename='libgazebo_ros_openni_kinect.so'><cameraName>rs</cameraName>"
      "<updateRate>10</updateRate><empty/></plugin></sensor></gazebo>"));
  const SensorSpec& s = ext.links.at("wheel").sensors.at(0);
  EXPECT_EQ(s.type, "depth");
  EXPECT_EQ(s.update_rate, 20.0);
  EXPECT_TRUE(s.always_on);
  EXPECT_TRUE(s.X_LS.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_EQ(s.plugins.at(0).params.at("updateRate"), "10");
  EXPECT_EQ(s.plugins.at(0).params.at("empty"), "");
  EXPECT_EQ(s.line, 5);
  // The printed element parses back to the same sensor.
  const auto again = p.parse(robot("<gazebo reference='wheel'>" + s.xml + "</gazebo>"));
  EXPECT_EQ(again.links.at("wheel").sensors.at(0).update_rate, 20.0);

  EXPECT_THAT(p.error(robot("<gazebo reference='wheel'><sensor type='ray'/></gazebo>")),
              HasSubstr("sensor on link 'wheel' has no name"));
  EXPECT_THAT(p.error(robot("<gazebo reference='wheel'><sensor name='x'/></gazebo>")),
              HasSubstr("sensor 'x' on link 'wheel' has no type"));
  // A sensor's own bad values leave the sensor out (its error set), not the robot.
  const auto sensorError = [&](const std::string& body) {
    const auto e = p.parse(robot("<gazebo reference='wheel'><sensor name='x' type='ray'>" + body +
                                 "</sensor></gazebo>"));
    return e.links.at("wheel").sensors.at(0).error;
  };
  EXPECT_THAT(sensorError("<pose>0 0 0</pose>"),
              HasSubstr("sensor 'x' on link 'wheel': <pose> '0 0 0' is not 6 numbers"));
  EXPECT_THAT(sensorError("<update_rate>-5</update_rate>"),
              HasSubstr("<update_rate> value '-5' must be finite and >= 0"));
  EXPECT_THAT(sensorError("<update_rate>nan</update_rate>"), HasSubstr("<update_rate> value 'nan'"));
  EXPECT_EQ(sensorError("<update_rate>5</update_rate>"), "");
  EXPECT_THAT(p.error(robot("<gazebo reference='wheel'><sensor name='x' type='ray'>"
                            "<plugin name='p'/></sensor></gazebo>")),
              HasSubstr("plugin 'p' has no filename"));
}

TEST(Extensions, RosControlPlugin) {
  Parser p;
  auto ext = p.parse(robot("<gazebo><plugin name='rc' filename='libgazebo_ros_control.so'>"
                           "<robotNamespace>/car</robotNamespace></plugin></gazebo>"));
  ASSERT_TRUE(ext.ros_control);
  EXPECT_EQ(ext.ros_control->robot_namespace, "/car");
  EXPECT_EQ(ext.ros_control->robot_param, "robot_description");  // default
  EXPECT_EQ(ext.ros_control->control_period, 0.0);                // every step
  EXPECT_TRUE(p.warnings.empty());

  ext = p.parse(robot("<gazebo><plugin name='rc' filename='libgazebo_ros_control.so'>"
                      "<controlPeriod>0.01</controlPeriod><robotParam>desc</robotParam>"
                      "<robotSimType>my/Sim</robotSimType><colour>red</colour></plugin>"
                      "</gazebo>"));
  EXPECT_EQ(ext.ros_control->control_period, 0.01);
  EXPECT_EQ(ext.ros_control->robot_param, "desc");
  EXPECT_THAT(p.warnings,
              ElementsAre(HasSubstr("robotSimType 'my/Sim' is not supported"),
                          HasSubstr("<colour> is not a parameter of libgazebo_ros_control.so")));
  EXPECT_EQ(ext.ros_control->robot_sim_type, "gazebo_ros_control/DefaultRobotHWSim");  // fallback

  // The robotSimTypes the simulator runs: chosen, no warning (sim/steer_bot_hw_sim.h).
  Parser steer;
  ext = steer.parse(robot("<gazebo><plugin name='rc' filename='libgazebo_ros_control.so'>"
                          "<robotSimType>steer_bot_hardware_gazebo/SteerBotHardwareGazebo"
                          "</robotSimType></plugin></gazebo>"));
  EXPECT_EQ(ext.ros_control->robot_sim_type, "steer_bot_hardware_gazebo/SteerBotHardwareGazebo");
  EXPECT_TRUE(steer.warnings.empty());

  // eStopTopic (gazebo_ros_control_plugin.cpp's emergency stop): the topic, no warning; none
  // without the element.
  EXPECT_EQ(ext.ros_control->e_stop_topic, "");
  Parser stop;
  ext = stop.parse(robot("<gazebo><plugin name='rc' filename='libgazebo_ros_control.so'>"
                         "<eStopTopic>/e_stop</eStopTopic></plugin></gazebo>"));
  ASSERT_TRUE(ext.ros_control);
  EXPECT_EQ(ext.ros_control->e_stop_topic, "/e_stop");
  EXPECT_TRUE(stop.warnings.empty());

  EXPECT_THAT(p.error(robot("<gazebo><plugin name='rc' filename='libgazebo_ros_control.so'>"
                            "<controlPeriod>fast</controlPeriod></plugin></gazebo>")),
              HasSubstr("plugin 'rc' (libgazebo_ros_control.so): <controlPeriod> 'fast' is not a "
                        "number"));
  EXPECT_THAT(p.error(robot("<gazebo><plugin name='a' filename='libgazebo_ros_control.so'/>"
                            "<plugin name='b' filename='libgazebo_ros_control.so'/></gazebo>")),
              HasSubstr("second libgazebo_ros_control.so plugin"));
}

TEST(Extensions, JointStatePublisherStripsWhitespaceInsideNames) {
  Parser p;
  const auto ext = p.parse(robot(
      "<gazebo><plugin name='jsp' filename='libgazebo_ros_joint_state_publisher.so'>"
      "<jointName> wheel_ joint,\n\twhe el_joint , </jointName><updateRate>50.0</updateRate>"
      "<robotNamespace>/car</robotNamespace></plugin></gazebo>"));
  ASSERT_TRUE(ext.joint_state_publisher);
  EXPECT_THAT(ext.joint_state_publisher->joint_names, ElementsAre("wheel_joint", "wheel_joint"));
  EXPECT_EQ(ext.joint_state_publisher->update_rate, 50.0);
  EXPECT_EQ(ext.joint_state_publisher->robot_namespace, "/car");
  EXPECT_EQ(ext.model_plugins.size(), 1u);

  EXPECT_THAT(p.error(robot("<gazebo><plugin name='jsp' "
                            "filename='libgazebo_ros_joint_state_publisher.so'>"
                            "<jointName>wheel_joint,axle</jointName></plugin></gazebo>")),
              HasSubstr("plugin 'jsp' (libgazebo_ros_joint_state_publisher.so): unknown joint "
                        "'axle'"));
  EXPECT_THAT(p.error(robot("<gazebo><plugin name='jsp' "
                            "filename='libgazebo_ros_joint_state_publisher.so'/></gazebo>")),
              HasSubstr("no <jointName>"));
  EXPECT_THAT(p.error(robot("<gazebo><plugin name='jsp' "
                            "filename='libgazebo_ros_joint_state_publisher.so'>"
                            "<jointName>wheel_joint</jointName><updateRate>nan</updateRate>"
                            "</plugin></gazebo>")),
              HasSubstr("<updateRate> nan is not finite"));
}

// Other model plugins are kept for the sensor registry and the start-up table to judge
// (test_plugins_model_report.cpp): the parser neither drops them nor calls a simulated one
// (libgazebo_ros_p3d.so) unknown.
TEST(Extensions, OtherPluginsKeptWithoutWarning) {
  Parser p;
  const auto ext =
      p.parse(robot("<gazebo><plugin name='a' filename='libfoo.so'/></gazebo>"
                    "<gazebo><plugin name='b' filename='libgazebo_ros_p3d.so'>"
                    "<bodyName>base_link</bodyName></plugin>"
                    "<plugin name='c' filename='libbar.so'/></gazebo>"));
  ASSERT_EQ(ext.model_plugins.size(), 3u);
  EXPECT_EQ(ext.model_plugins[0].filename, "libfoo.so");
  EXPECT_EQ(ext.model_plugins[1].filename, "libgazebo_ros_p3d.so");
  EXPECT_EQ(ext.model_plugins[2].filename, "libbar.so");
  EXPECT_THAT(p.warnings, IsEmpty());
}

TEST(Extensions, TransmissionFormsAndErrors) {
  const std::string head =
      "<transmission name='t'><type>transmission_interface/SimpleTransmission</type>";
  Parser p;
  // Old format: type attribute, interface only on the actuator (used, with a warning).
  auto ext = p.parse(robot(
      "<transmission name='t' type='transmission_interface/SimpleTransmission'>"
      "<joint name='wheel_joint'/><actuator name='m'><hardwareInterface>EffortJointInterface"
      "</hardwareInterface><mechanicalReduction>-3</mechanicalReduction></actuator>"
      "</transmission>"));
  ASSERT_EQ(ext.transmissions.size(), 1u);
  EXPECT_THAT(ext.transmissions[0].joint_interfaces, ElementsAre(JointInterface::kEffort));
  EXPECT_EQ(ext.transmissions[0].mechanical_reduction, -3.0);  // a reversed gear is allowed
  EXPECT_THAT(p.warnings, ElementsAre(HasSubstr("using the actuator's (deprecated format)")));

  EXPECT_THAT(p.error(robot(head + "<joint name='wheel_joint'/><actuator name='m'/>"
                                   "</transmission>")),
              HasSubstr("transmission 't': joint 'wheel_joint' has no <hardwareInterface>"));
  EXPECT_THAT(p.error(robot(head + "<joint name='wheel_joint'><hardwareInterface>"
                                   "VelocityJointInterface</hardwareInterface></joint>"
                                   "</transmission>")),
              HasSubstr("transmission 't': no <actuator>"));
  EXPECT_THAT(p.error(robot(head + "</transmission>")), HasSubstr("transmission 't': no <joint>"));
  EXPECT_THAT(p.error(robot("<transmission name='t'><joint name='wheel_joint'/></transmission>")),
              HasSubstr("transmission 't': no <type>"));
  EXPECT_THAT(p.error(robot("<transmission><type>x</type></transmission>")),
              HasSubstr("transmission without a name"));
  EXPECT_THAT(p.error(robot(head + "<joint name='wheel_joint'><hardwareInterface>"
                                   "VelocityJointInterface</hardwareInterface></joint>"
                                   "<actuator name='m'><mechanicalReduction>nan"
                                   "</mechanicalReduction></actuator></transmission>")),
              HasSubstr("mechanicalReduction 'nan' must be a finite non-zero number"));
  EXPECT_THAT(p.error(robot(head + "<joint name='wheel_joint'><hardwareInterface>"
                                   "VelocityJointInterface</hardwareInterface></joint>"
                                   "<actuator name='m'><hardwareInterface>Bogus"
                                   "</hardwareInterface></actuator></transmission>")),
              HasSubstr("transmission 't': actuator 'm': unknown hardwareInterface 'Bogus'"));
  const std::string good = "<joint name='wheel_joint'><hardwareInterface>VelocityJointInterface"
                           "</hardwareInterface></joint><actuator name='m'/></transmission>";
  EXPECT_THAT(p.error(robot(head + good + "<transmission name='u'>"
                                          "<type>transmission_interface/SimpleTransmission</type>" +
                            good)),
              HasSubstr("transmission 'u': joint 'wheel_joint' already has transmission 't'"));
}

// ros_controllers' test robots (diffbot.xacro's wheel.xacro): the type without the
// transmission_interface/ namespace, as an attribute or a <type> element; gazebo_ros_control
// takes any <type> text for a one-joint transmission and hardware interfaces with or without
// hardware_interface/. Other transmission types stay refused, in either spelling.
TEST(Extensions, TransmissionTypeWithoutNamespace) {
  Parser p;
  for (const std::string& open : {std::string("<transmission name='t'><type>SimpleTransmission</type>"),
                                  std::string("<transmission name='t' type='SimpleTransmission'>")}) {
    for (const std::string& iface : {std::string("VelocityJointInterface"),
                                     std::string("hardware_interface/VelocityJointInterface")}) {
      auto ext = p.parse(robot(open + "<joint name='wheel_joint'><hardwareInterface>" + iface +
                               "</hardwareInterface></joint><actuator name='m'>"
                               "<mechanicalReduction>1</mechanicalReduction></actuator>"
                               "</transmission>"));
      ASSERT_EQ(ext.transmissions.size(), 1u) << open << iface;
      EXPECT_EQ(ext.transmissions[0].type, "transmission_interface/SimpleTransmission");
      EXPECT_THAT(ext.transmissions[0].joint_interfaces, ElementsAre(JointInterface::kVelocity));
    }
  }
  EXPECT_THAT(p.error(robot("<transmission name='t'><type>DifferentialTransmission</type>"
                            "<joint name='wheel_joint'><hardwareInterface>VelocityJointInterface"
                            "</hardwareInterface></joint><actuator name='m'/></transmission>")),
              HasSubstr("transmission 't': unsupported type 'DifferentialTransmission' (only "
                        "transmission_interface/SimpleTransmission, or SimpleTransmission)"));
  EXPECT_THAT(p.error(robot("<transmission name='t'><type>simpletransmission</type>"
                            "<joint name='wheel_joint'/><actuator name='m'/></transmission>")),
              HasSubstr("unsupported type 'simpletransmission'"));
}

TEST(Extensions, SyntaxAndEmptyInput) {
  Parser p;
  EXPECT_EQ(p.error(""), "test.urdf: robot_description is empty");
  EXPECT_THAT(p.error("<robot>\n<gazebo>\n</robot>"),
              AllOf(HasSubstr("test.urdf:2: XML error: "), HasSubstr("MISMATCHED")));
  EXPECT_THAT(p.error("not xml at all"), HasSubstr("test.urdf:1: XML error: "));
}

// A small deterministic stand-in for the libFuzzer run (fuzz.sh): byte flips, insertions and
// truncations of full.urdf. Anything but a result or a ModelError fails the test (a crash
// fails it too).
TEST(Extensions, MutatedInputsOnlyEverThrowModelError) {
  const std::string seed = test::readFile(std::string(TEST_DATA_DIR) + "/urdf/full.urdf");
  ASSERT_FALSE(seed.empty());
  const std::string alphabet = "<>/='\" \n0123456789.-+eEnaif,abcdefghijklmnopqrstuvwxyz_&;!?";
  std::mt19937 rng(12345);
  int parsed = 0, rejected = 0;
  for (int i = 0; i < 3000; ++i) {
    std::string s = seed;
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int k = 0; k < edits && !s.empty(); ++k) {
      const size_t pos = rng() % s.size();
      switch (rng() % 4) {
        case 0:
          s[pos] = alphabet[rng() % alphabet.size()];
          break;
        case 1:
          s.insert(pos, 1, alphabet[rng() % alphabet.size()]);
          break;
        case 2:
          s.erase(pos, 1 + rng() % 16);
          break;
        default:
          s.resize(pos);
          break;
      }
    }
    try {
      parseExtensions(s, "fuzz", [](const std::string&) {});
      ++parsed;
    } catch (const ModelError&) {
      ++rejected;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "non-ModelError exception: " << e.what() << "\ninput:\n" << s;
    }
  }
  EXPECT_GT(parsed, 0);
  EXPECT_GT(rejected, 0);
}

TEST(Extensions, DeepNestingIsRejectedNotRecursed) {
  std::string deep = "<robot name='r'><gazebo reference='x'>";
  for (int i = 0; i < 100000; ++i) deep += "<a>";
  EXPECT_THROW(parseExtensions(deep, "deep", nullptr), ModelError);
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);  // gtest only: gmock matchers are header-only
  return RUN_ALL_TESTS();
}
