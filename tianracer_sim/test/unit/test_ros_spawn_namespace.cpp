// spawn_urdf_model's robot_namespace: given to every <plugin> that names none, as gazebo_ros
// does; a plugin's own <robotNamespace> wins; malformed XML is an error naming the line.
#include <gtest/gtest.h>

#include <string>

#include <tinyxml2.h>

#include "tianracer_sim/ros/gazebo_interface.h"

namespace tianracer_sim {
namespace {

const char* kUrdf = R"(<robot name='r'>
  <link name='base_link'/>
  <gazebo><plugin name='control' filename='libgazebo_ros_control.so'/></gazebo>
  <gazebo reference='base_link'><sensor name='s' type='ray'>
    <plugin name='laser' filename='libgazebo_ros_laser.so'><topicName>scan</topicName></plugin>
  </sensor></gazebo>
  <gazebo><plugin name='imu' filename='libgazebo_ros_imu.so'>
    <robotNamespace>/own</robotNamespace></plugin></gazebo>
</robot>)";

std::string namespaceOf(const tinyxml2::XMLDocument& doc, const std::string& plugin) {
  for (const tinyxml2::XMLElement* g = doc.RootElement()->FirstChildElement("gazebo"); g;
       g = g->NextSiblingElement("gazebo")) {
    const tinyxml2::XMLElement* p = g->FirstChildElement("plugin");
    if (!p && g->FirstChildElement("sensor")) p = g->FirstChildElement("sensor")->FirstChildElement("plugin");
    if (p && plugin == p->Attribute("name")) {
      const tinyxml2::XMLElement* ns = p->FirstChildElement("robotNamespace");
      return ns && ns->GetText() ? ns->GetText() : "(none)";
    }
  }
  return "(no plugin)";
}

TEST(SpawnNamespace, GivenToPluginsWithoutOne) {
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(doc.Parse(withRobotNamespace(kUrdf, "/car2").c_str()), tinyxml2::XML_SUCCESS);
  EXPECT_EQ(namespaceOf(doc, "control"), "/car2");
  EXPECT_EQ(namespaceOf(doc, "laser"), "/car2");  // sensor plugins too
  EXPECT_EQ(namespaceOf(doc, "imu"), "/own");
}

TEST(SpawnNamespace, EmptyNamespaceChangesNothing) {
  EXPECT_EQ(withRobotNamespace(kUrdf, ""), kUrdf);
}

TEST(SpawnNamespace, MalformedXmlNamesTheLine) {
  try {
    withRobotNamespace("<robot name='r'>\n<link name='a'>\n</robot>", "/x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("model_xml:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("malformed XML"), std::string::npos) << e.what();
  }
  EXPECT_THROW(withRobotNamespace("", ""), std::runtime_error);
}

}  // namespace
}  // namespace tianracer_sim
