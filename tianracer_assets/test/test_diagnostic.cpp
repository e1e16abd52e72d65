// The diagnostic policy the three ROS-free libraries share (diagnostic.h): the location format, the error
// type and warn-once.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tianracer_assets/diagnostic.h"

namespace tianracer_assets {
namespace {

TEST(Diagnostic, OneLocationFormatAsCompilersWriteIt) {
  EXPECT_EQ(formatLocation("a.urdf", 12), "a.urdf:12: ");
  EXPECT_EQ(formatLocation("a.urdf", 0), "a.urdf: ");
  EXPECT_EQ(formatLocation("", 7), "line 7: ");
  EXPECT_EQ(formatLocation("", 0), "");
  EXPECT_EQ(formatLocation(SourceLocation{"w.world", 3, "box"}), "w.world:3: ");
}

TEST(Diagnostic, InputErrorPutsTheLocationInFrontAndKeepsItsParts) {
  const InputError e({"w.world", 3, "size"}, "<size> '1 x 1' is not a list of numbers");
  EXPECT_STREQ(e.what(), "w.world:3: <size> '1 x 1' is not a list of numbers");
  EXPECT_EQ(e.where().file, "w.world");
  EXPECT_EQ(e.where().line, 3);
  EXPECT_EQ(e.where().element, "size");
  EXPECT_EQ(e.message(), "<size> '1 x 1' is not a list of numbers");
  // Context added by a caller goes after the location.
  const InputError outer(e.where(), "robot 'r': " + e.message());
  EXPECT_STREQ(outer.what(), "w.world:3: robot 'r': <size> '1 x 1' is not a list of numbers");

  const InputError plain("controller 'x': no type given");
  EXPECT_STREQ(plain.what(), "controller 'x': no type given");
  EXPECT_EQ(plain.message(), plain.what());
  EXPECT_TRUE(plain.where().file.empty());
  EXPECT_EQ(plain.where().line, 0);
  EXPECT_THROW(throw plain, std::runtime_error);
}

TEST(Diagnostic, WarnOnceForwardsEachMessageOnceAndEachKeyOnce) {
  std::vector<std::string> got;
  WarnOnce warn([&](const std::string& w) { got.push_back(w); });
  EXPECT_TRUE(warn("a"));
  EXPECT_FALSE(warn("a"));
  EXPECT_TRUE(warn("key", "first"));
  EXPECT_FALSE(warn("key", "second"));  // same key
  EXPECT_FALSE(warn("other key", "a"));  // same message
  EXPECT_EQ(got, (std::vector<std::string>{"a", "first"}));

  WarnOnce quiet;  // no sink: nothing to call, nothing breaks
  EXPECT_TRUE(quiet("dropped"));
  EXPECT_FALSE(quiet("dropped"));
}

}  // namespace
}  // namespace tianracer_assets
