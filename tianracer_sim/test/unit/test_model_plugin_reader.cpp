// The one reader of a <plugin>'s parameters: values by name, errors placed at the <plugin>,
// one warning for each parameter nothing read.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {
namespace {

using ::testing::ElementsAre;

PluginSpec plugin(std::map<std::string, std::string> params) {
  PluginSpec p;
  p.name = "drive";
  p.filename = "libgazebo_ros_diff_drive.so";
  p.params = std::move(params);
  p.source = "car.urdf";
  p.line = 12;
  return p;
}

TEST(PluginReader, ReadsValuesByName) {
  const PluginSpec p = plugin({{"topicName", "  odom "},
                               {"frameName", "//base"},
                               {"rate", "2.5"},
                               {"offset", "1 2 3"},
                               {"publishTf", "True"}});
  PluginReader r(p, "x", {});
  EXPECT_EQ(r.fileName(), "libgazebo_ros_diff_drive.so");
  EXPECT_EQ(r.text("topicName"), std::optional<std::string>("odom"));
  EXPECT_EQ(r.text("missing"), std::nullopt);
  std::string kept = "default";
  EXPECT_FALSE(r.text("missing", &kept));
  EXPECT_EQ(kept, "default");
  EXPECT_EQ(r.frame("frameName", "link"), "base");
  EXPECT_EQ(r.frame("noFrame", "link"), "link");
  double rate = 0.0;
  EXPECT_TRUE(r.number("rate", &rate, true));
  EXPECT_DOUBLE_EQ(rate, 2.5);
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  EXPECT_TRUE(r.vector3("offset", &offset));
  EXPECT_EQ(offset, Eigen::Vector3d(1, 2, 3));
  bool tf = false;
  EXPECT_TRUE(r.boolean("publishTf", &tf));
  EXPECT_TRUE(tf);
}

TEST(PluginReader, BadValuesArePlacedAtThePluginAndNameTheValue) {
  double number = 0.0;
  Eigen::Vector3d vector;
  bool flag = false;
  const struct {
    std::string key, value;
    std::function<void(PluginReader&)> read;
    std::string message;
  } cases[] = {
      {"rate", "fast", [&](PluginReader& r) { r.number("rate", &number); }, "<rate> 'fast' is not a number"},
      {"rate", "inf", [&](PluginReader& r) { r.number("rate", &number); }, "<rate> inf is not finite"},
      {"rate", "-1", [&](PluginReader& r) { r.number("rate", &number, true); }, "<rate> -1 must be >= 0"},
      {"offset", "1 2", [&](PluginReader& r) { r.vector3("offset", &vector); },
       "<offset> '1 2' is not 3 numbers"},
      {"publishTf", "yes", [&](PluginReader& r) { r.boolean("publishTf", &flag); },
       "<publishTf> 'yes' is not a boolean (true, false, 1 or 0)"},
      {"leftJoint", "", [&](PluginReader& r) { r.fail("<leftJoint> is empty"); }, "<leftJoint> is empty"},
  };
  for (const auto& c : cases) {
    const PluginSpec p = plugin({{c.key, c.value}});
    PluginReader r(p, "plugin 'drive' of model 'car'", {});
    try {
      c.read(r);
      ADD_FAILURE() << c.key << " '" << c.value << "': no error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, "car.urdf");
      EXPECT_EQ(e.where().line, 12);
      EXPECT_EQ(std::string(e.what()), "car.urdf:12: plugin 'drive' of model 'car': " + c.message);
    }
  }
}

TEST(PluginReader, WarnsOnceAboutEachParameterNothingRead) {
  std::vector<std::string> warnings;
  const PluginSpec p = plugin({{"topicName", "odom"}, {"alwaysOn", "true"}, {"colour", "red"}});
  PluginReader r(p, "plugin 'drive'", [&](const std::string& w) { warnings.push_back(w); });
  r.text("topicName");
  r.ignore({"alwaysOn"});
  r.finish();
  r.finish();
  r.warn("<odometrySource> 'gps' read as world");
  EXPECT_THAT(warnings,
              ElementsAre("car.urdf:12: plugin 'drive': <colour> is not a parameter of "
                          "libgazebo_ros_diff_drive.so, ignored",
                          "car.urdf:12: plugin 'drive': <odometrySource> 'gps' read as world"));
}

// <robotNamespace> is read here for every plugin, each by its plugin's rule.
TEST(PluginReader, RobotNamespaceByTheRuleOfThePlugin) {
  const auto read = [](std::map<std::string, std::string> params, NamespaceRule rule,
                       NamespaceFrom* from) {
    const PluginSpec p = plugin(std::move(params));
    std::vector<std::string> warnings;
    PluginReader r(p, "plugin 'drive'", [&](const std::string& w) { warnings.push_back(w); });
    std::string ns = "default";
    *from = r.robotNamespace(rule, &ns);
    r.finish();  // read: not reported
    EXPECT_THAT(warnings, ::testing::IsEmpty());
    return ns;
  };
  NamespaceFrom from;
  EXPECT_EQ(read({}, NamespaceRule::kAsGiven, &from), "default");
  EXPECT_EQ(from, NamespaceFrom::kMissing);
  EXPECT_EQ(read({}, NamespaceRule::kEmptyIsModel, &from), "default");
  EXPECT_EQ(from, NamespaceFrom::kMissing);
  EXPECT_EQ(read({{"robotNamespace", " /car "}}, NamespaceRule::kAsGiven, &from), "/car");
  EXPECT_EQ(from, NamespaceFrom::kGiven);
  EXPECT_EQ(read({{"robotNamespace", " /car "}}, NamespaceRule::kEmptyIsModel, &from), "/car");
  EXPECT_EQ(from, NamespaceFrom::kGiven);
  EXPECT_EQ(read({{"robotNamespace", " "}}, NamespaceRule::kAsGiven, &from), "");
  EXPECT_EQ(from, NamespaceFrom::kGiven);
  EXPECT_EQ(read({{"robotNamespace", " "}}, NamespaceRule::kEmptyIsModel, &from), "default");
  EXPECT_EQ(from, NamespaceFrom::kModel);
}

}  // namespace
}  // namespace tianracer_sim
