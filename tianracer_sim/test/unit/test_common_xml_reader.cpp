// The XML reader every parser uses: text, numbers, vectors, poses, warn-once, unknown elements,
// and the place (file:line) at the start of every message.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/common/sdf_pose.h"
#include "tianracer_sim/common/xml_reader.h"

namespace tianracer_sim {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using tinyxml2::XMLElement;

// One document; `el(name)` finds the first element of that name anywhere in it.
class XmlReaderTest : public ::testing::Test {
 protected:
  void load(const std::string& xml) {
    ASSERT_EQ(doc_.Parse(xml.c_str()), tinyxml2::XML_SUCCESS) << xml;
  }
  const XMLElement* el(const char* name) const { return find(doc_.RootElement(), name); }
  static const XMLElement* find(const XMLElement* e, const char* name) {
    if (!e) return nullptr;
    if (std::string(e->Name()) == name) return e;
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
      if (const XMLElement* f = find(c, name)) return f;
    return nullptr;
  }
  // The message of the InputError `f` throws ("" when it throws none).
  template <class F>
  static std::string error(F f) {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  std::vector<std::string> warnings_;
  tinyxml2::XMLDocument doc_;
  XmlReader reader_{"room.world", [this](const std::string& w) { warnings_.push_back(w); }};
};

TEST(XmlText, ParseNumberTakesTheWholeStringOnly) {
  EXPECT_EQ(parseNumber("1.5"), 1.5);
  EXPECT_EQ(parseNumber("  -2e3\n"), -2000.0);
  EXPECT_EQ(parseNumber("+4"), 4.0);
  EXPECT_FALSE(parseNumber(""));
  EXPECT_FALSE(parseNumber("   "));
  EXPECT_FALSE(parseNumber("1.5m"));
  EXPECT_FALSE(parseNumber("1 2"));
  EXPECT_FALSE(parseNumber("abc"));
  EXPECT_FALSE(parseNumber("1,5"));  // never the locale's decimal comma
  EXPECT_FALSE(parseNumber("++1"));
}

TEST(XmlText, ParseNumberLeavesNanAndInfToTheCaller) {
  ASSERT_TRUE(parseNumber("nan"));
  EXPECT_TRUE(std::isnan(*parseNumber("nan")));
  ASSERT_TRUE(parseNumber("-inf"));
  EXPECT_EQ(*parseNumber("-inf"), -INFINITY);
  // Beyond double's range: saturates (so a finiteness check names it) instead of failing.
  ASSERT_TRUE(parseNumber("1e999"));
  EXPECT_EQ(*parseNumber("1e999"), INFINITY);
}

TEST(XmlText, ParseNumbersAndBools) {
  EXPECT_EQ(parseNumbers(" 1 2.5\t-3\n"), std::vector<double>({1.0, 2.5, -3.0}));
  EXPECT_EQ(parseNumbers(""), std::vector<double>());
  EXPECT_FALSE(parseNumbers("1 two 3"));
  EXPECT_EQ(parseBool(" true "), true);
  EXPECT_EQ(parseBool("1"), true);
  EXPECT_EQ(parseBool("false"), false);
  EXPECT_EQ(parseBool("0"), false);
  EXPECT_FALSE(parseBool("yes"));
  EXPECT_FALSE(parseBool(""));
}

TEST_F(XmlReaderTest, TextAndAttributesAreTrimmed) {
  load("<a name='  box '>\n  hello \n<b/></a>");
  EXPECT_EQ(elementText(el("a")), "hello");
  EXPECT_EQ(elementText(el("b")), "");
  EXPECT_EQ(elementText(nullptr), "");
  EXPECT_EQ(attributeText(el("a"), "name"), "box");
  EXPECT_EQ(attributeText(el("a"), "missing"), "");
  EXPECT_EQ(lineOf(el("b")), 3);
  EXPECT_EQ(lineOf(nullptr), 0);
}

TEST(ParseXmlDocument, TakesADeclarationAfterCommentsAsGazeboDoes) {
  // Gazebo's own worlds/cafe.world: a comment, then the declaration (TinyXML takes it,
  // tinyxml2 does not). Line numbers stay those of the file.
  tinyxml2::XMLDocument doc;
  ASSERT_EQ(parseXmlDocument("<!-- Usage notes -->\n<?xml version=\"1.0\" ?>\n<sdf version=\"1.5\">"
                             "<world name='w'/></sdf>\n",
                             &doc),
            tinyxml2::XML_SUCCESS);
  ASSERT_NE(doc.RootElement(), nullptr);
  EXPECT_STREQ(doc.RootElement()->Name(), "sdf");
  EXPECT_EQ(doc.RootElement()->GetLineNum(), 3);
  tinyxml2::XMLDocument first;
  EXPECT_EQ(parseXmlDocument("<?xml version=\"1.0\"?><sdf/>", &first), tinyxml2::XML_SUCCESS);
  // Anything else malformed stays malformed: a declaration after an element, a broken tag.
  tinyxml2::XMLDocument late, broken;
  EXPECT_NE(parseXmlDocument("<sdf/><?xml version=\"1.0\"?>", &late), tinyxml2::XML_SUCCESS);
  EXPECT_NE(parseXmlDocument("<!-- c -->\n<?xml version=\"1.0\"?>\n<sdf>", &broken),
            tinyxml2::XML_SUCCESS);
  EXPECT_EQ(broken.ErrorLineNum(), 3);
}

TEST_F(XmlReaderTest, NumbersNameFileLineElementAndValue) {
  load("<physics>\n<step>0.001</step>\n<bad>fast</bad>\n<nan>nan</nan>\n<big>1e999</big>\n"
       "<neg>-1</neg>\n<zero>0</zero>\n<two>1 2</two>\n<int>7</int>\n<frac>7.5</frac>\n"
       "<plus>+7</plus><minus>-7</minus><huge>99999999999</huge></physics>");
  EXPECT_EQ(reader_.number(el("step"), "<physics>"), 0.001);
  EXPECT_EQ(error([&] { reader_.number(el("bad"), "<physics>"); }),
            "room.world:3: <physics>: <bad> 'fast' is not a list of numbers");
  EXPECT_EQ(error([&] { reader_.number(el("nan"), "<physics>"); }),
            "room.world:4: <physics>: <nan> 'nan' is not finite");
  EXPECT_EQ(error([&] { reader_.number(el("big"), "<physics>"); }),
            "room.world:5: <physics>: <big> '1e999' is not finite");
  EXPECT_EQ(error([&] { reader_.number(el("two"), "<physics>"); }),
            "room.world:8: <physics>: <two> '1 2' is not a number");
  // anyNumber: nan and inf are numbers (checked where they are used), words and lists are not.
  EXPECT_TRUE(std::isnan(reader_.anyNumber(el("nan"), "<physics>")));
  EXPECT_TRUE(std::isinf(reader_.anyNumber(el("big"), "<physics>")));
  EXPECT_EQ(reader_.anyNumber(el("step"), "<physics>"), 0.001);
  EXPECT_EQ(error([&] { reader_.anyNumber(el("bad"), "<physics>"); }),
            "room.world:3: <physics>: <bad> 'fast' is not a number");
  EXPECT_EQ(error([&] { reader_.anyNumber(el("two"), "<physics>"); }),
            "room.world:8: <physics>: <two> '1 2' is not a number");
  EXPECT_EQ(reader_.nonNegative(el("zero"), "w"), 0.0);
  EXPECT_EQ(error([&] { reader_.nonNegative(el("neg"), "w"); }),
            "room.world:6: w: <neg> must be >= 0 (got -1)");
  EXPECT_EQ(error([&] { reader_.positive(el("zero"), "w"); }),
            "room.world:7: w: <zero> must be > 0 (got 0)");
  EXPECT_EQ(reader_.integer(el("int"), "w"), 7);
  EXPECT_EQ(reader_.integer(el("plus"), "w"), 7);
  EXPECT_EQ(reader_.integer(el("minus"), "w"), -7);
  EXPECT_THAT(error([&] { reader_.integer(el("huge"), "w"); }), HasSubstr("is not an integer"));
  EXPECT_EQ(error([&] { reader_.integer(el("frac"), "w"); }),
            "room.world:10: w: <frac> '7.5' is not an integer");
  // Without a `what` the message starts at the element.
  EXPECT_EQ(error([&] { reader_.integer(el("bad"), ""); }),
            "room.world:3: <bad> 'fast' is not an integer");
}

TEST_F(XmlReaderTest, VectorsColoursBooleans) {
  load("<m><v>1 2 3</v><v2>1 2</v2><c>0.1 0.2 0.3</c><c4>0.1 0.2 0.3 0.5</c4>"
       "<b>true</b><nb>maybe</nb></m>");
  EXPECT_EQ(reader_.vector3(el("v"), "m"), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(error([&] { reader_.vector3(el("v2"), "m"); }),
            "room.world:1: m: <v2> '1 2' is not 3 numbers \"x y z\"");
  EXPECT_EQ(reader_.color(el("c"), "m"), Eigen::Vector4f(0.1f, 0.2f, 0.3f, 1.0f));
  EXPECT_EQ(reader_.color(el("c4"), "m"), Eigen::Vector4f(0.1f, 0.2f, 0.3f, 0.5f));
  EXPECT_THAT(error([&] { reader_.color(el("v2"), "m"); }), HasSubstr("is not a colour"));
  EXPECT_TRUE(reader_.boolean(el("b"), "m"));
  EXPECT_EQ(error([&] { reader_.boolean(el("nb"), "m"); }),
            "room.world:1: m: <nb> 'maybe' is not a boolean (true/false/1/0)");
}

TEST_F(XmlReaderTest, PosesAreSdfPoses) {
  load("<m>\n<pose>1 2 3 0.1 0.2 0.3</pose>\n<p5>1 2 3 4 5</p5>\n"
       "<pr relative_to='other'>0 0 1 0 0 0</pr></m>");
  EXPECT_TRUE(reader_.pose(el("pose"), "model 'm'").isApprox(sdfPose(1, 2, 3, 0.1, 0.2, 0.3)));
  const Eigen::Isometry3d X = sdfPose(0, 0, 0, 0, 0, M_PI / 2);  // yaw turns x onto y
  EXPECT_TRUE((X.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_EQ(error([&] { reader_.pose(el("p5"), "model 'm'"); }),
            "room.world:3: model 'm': <p5> '1 2 3 4 5' is not 6 numbers \"x y z roll pitch yaw\"");
  EXPECT_TRUE(warnings_.empty());
  reader_.pose(el("pr"), "model 'm'");
  EXPECT_THAT(warnings_, ElementsAre("room.world:4: model 'm': <pose relative_to='other'> is not "
                                     "supported; taken relative to the parent"));
}

// sdformat 9 src/parser.cc, readXml: a value is set only from text the element has; an empty
// one keeps its default. Text that is there is read as always (a bad one still fails).
TEST_F(XmlReaderTest, AnSdfElementWithNoTextKeepsTheDefaultItIsGiven) {
  load("<m>\n<pose></pose>\n<size/>\n<update_rate>  </update_rate>\n<static/>\n<c/>\n"
       "<bad>1 x 3</bad>\n<rate>5</rate>\n<neg>-1</neg>\n</m>");
  const Eigen::Isometry3d X0 = sdfPose(1, 2, 3, 0, 0, 0.5);
  EXPECT_TRUE(reader_.pose(el("pose"), "model 'm'", X0).isApprox(X0));
  EXPECT_EQ(reader_.vector3(el("size"), "box", Eigen::Vector3d::Ones()), Eigen::Vector3d::Ones());
  EXPECT_EQ(reader_.nonNegative(el("update_rate"), "sensor", 0.0), 0.0);
  EXPECT_EQ(reader_.number(el("update_rate"), "sensor", 7.0), 7.0);
  EXPECT_EQ(reader_.positive(el("update_rate"), "sensor", 2.0), 2.0);
  EXPECT_TRUE(reader_.boolean(el("static"), "model 'm'", true));
  EXPECT_FALSE(reader_.boolean(el("static"), "model 'm'", false));
  EXPECT_EQ(reader_.color(el("c"), "scene", Eigen::Vector4f(0.4f, 0.4f, 0.4f, 1.0f)),
            Eigen::Vector4f(0.4f, 0.4f, 0.4f, 1.0f));
  EXPECT_TRUE(XmlReader::keepsDefault(el("size")));
  EXPECT_FALSE(XmlReader::keepsDefault(el("rate")));
  // Text there is read, defaults or not.
  EXPECT_EQ(reader_.number(el("rate"), "sensor", 7.0), 5.0);
  EXPECT_EQ(error([&] { reader_.vector3(el("bad"), "box", Eigen::Vector3d::Ones()); }),
            "room.world:7: box: <bad> '1 x 3' is not a list of numbers");
  EXPECT_EQ(error([&] { reader_.nonNegative(el("neg"), "sensor", 0.0); }),
            "room.world:9: sensor: <neg> must be >= 0 (got -1)");
  // An empty <pose relative_to=...> is warned about as a full one is.
  load("<m>\n<pose relative_to='other'/>\n</m>");
  EXPECT_TRUE(reader_.pose(el("pose"), "model 'm'", X0).isApprox(X0));
  EXPECT_THAT(warnings_, ElementsAre("room.world:2: model 'm': <pose relative_to='other'> is not "
                                     "supported; taken relative to the parent"));
  warnings_.clear();
  load("<m>\n<pose></pose>\n</m>");
  // Without a default an empty element is still an error.
  EXPECT_EQ(error([&] { reader_.pose(el("pose"), "model 'm'"); }),
            "room.world:2: model 'm': <pose> '' is not 6 numbers \"x y z roll pitch yaw\"");
  EXPECT_TRUE(warnings_.empty());
}

TEST_F(XmlReaderTest, AttributeNumbersAndIntegers) {
  load("<m>\n<t id=' 3 ' tension='0.5' big='3000000000' frac='1.5' nan='nan' empty=''/>\n</m>");
  EXPECT_EQ(reader_.integerAttribute(el("t"), "id", "actor 'a'"), 3);
  EXPECT_EQ(reader_.numberAttribute(el("t"), "tension", "actor 'a'"), 0.5);
  EXPECT_EQ(error([&] { reader_.integerAttribute(el("t"), "big", "actor 'a'"); }),
            "room.world:2: actor 'a': <t> big '3000000000' is not an integer");
  EXPECT_EQ(error([&] { reader_.integerAttribute(el("t"), "frac", "actor 'a'"); }),
            "room.world:2: actor 'a': <t> frac '1.5' is not an integer");
  EXPECT_EQ(error([&] { reader_.integerAttribute(el("t"), "absent", "actor 'a'"); }),
            "room.world:2: actor 'a': <t> absent '' is not an integer");
  EXPECT_EQ(error([&] { reader_.numberAttribute(el("t"), "nan", "actor 'a'"); }),
            "room.world:2: actor 'a': <t> nan 'nan' is not a finite number");
  EXPECT_EQ(error([&] { reader_.numberAttribute(el("t"), "empty", "actor 'a'"); }),
            "room.world:2: actor 'a': <t> empty '' is not a finite number");
  EXPECT_EQ(parseInteger(" +7 "), 7);
  EXPECT_EQ(parseInteger("-2147483648"), -2147483648LL);
  EXPECT_FALSE(parseInteger("+-1"));
  EXPECT_FALSE(parseInteger("1e3"));
  EXPECT_FALSE(parseInteger(""));
}

TEST_F(XmlReaderTest, MissingElements) {
  load("<link>\n<visual/>\n</link>");
  EXPECT_EQ(reader_.required(el("link"), "visual", "link 'a'"), el("visual"));
  EXPECT_EQ(error([&] { reader_.required(el("link"), "collision", "link 'a'"); }),
            "room.world:1: link 'a': <link> has no <collision>");
}

TEST_F(XmlReaderTest, UnknownElementsAreReportedOncePerParentAndTag) {
  load("<world>\n<physics/>\n<wind/>\n<wind/>\n<model><wind/></model>\n<magnet/>\n</world>");
  EXPECT_EQ(reader_.checkChildren(el("world"), {"physics", "model"}), 3);
  reader_.checkChildren(el("model"), {});
  EXPECT_THAT(warnings_,
              ElementsAre("room.world:3: <wind> in <world> is not supported, ignored",
                          "room.world:6: <magnet> in <world> is not supported, ignored",
                          "room.world:5: <wind> in <model> is not supported, ignored"));
  warnings_.clear();
  reader_.unsupported(el("physics"), "not simulated");
  EXPECT_THAT(warnings_, ElementsAre("room.world:2: <physics> in <world> is not supported, "
                                     "ignored (not simulated)"));
}

TEST_F(XmlReaderTest, WarningsAreForwardedOnce) {
  load("<a/>");
  reader_.warn(el("a"), "odd");
  reader_.warn(el("a"), "odd");
  reader_.warn("placed elsewhere");
  reader_.warn("placed elsewhere");
  reader_.warnOnce("key", "first text");
  reader_.warnOnce("key", "second text");
  EXPECT_THAT(warnings_, ElementsAre("room.world:1: odd", "placed elsewhere", "first text"));
}

TEST_F(XmlReaderTest, AnEmptySinkDropsWarningsAndACopyIsPlacedWhereItsElementStands) {
  // A <sensor> printed back out of a model file: its own line numbers are not the file's.
  load("<sensor>\n<samples>many</samples></sensor>");
  XmlReader quiet = XmlReader::copyOf("car.urdf", 40, "sensor 'lidar': ", {});
  quiet.unsupported(el("samples"));  // no sink: nothing to call, nothing breaks
  EXPECT_EQ(quiet.at(el("samples")), "car.urdf:40: sensor 'lidar': ");
  EXPECT_EQ(error([&] { quiet.integer(el("samples"), ""); }),
            "car.urdf:40: sensor 'lidar': <samples> 'many' is not an integer");
  // Unknown file and line: the context alone.
  EXPECT_EQ(XmlReader::copyOf("", 0, "sensor 'lidar': ", {}).at(el("samples")), "sensor 'lidar': ");
}

TEST_F(XmlReaderTest, AKeptCopyIsParsedInOnePlaceWithItsErrorsAtTheElementsLine) {
  XmlReader r = XmlReader::copyOf("car.urdf", 40, "sensor 'lidar': ", {});
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* root = r.parseCopy("<sensor name='lidar'><ray/></sensor>", &doc);
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(root->Name(), "sensor");
  EXPECT_NE(root->FirstChildElement("ray"), nullptr);
  tinyxml2::XMLDocument blank;
  EXPECT_EQ(error([&] { r.parseCopy(" \n", &blank); }), "car.urdf:40: sensor 'lidar': no XML to read");
  tinyxml2::XMLDocument broken;
  EXPECT_THAT(error([&] { r.parseCopy("<sensor>\n<ray></sensor>", &broken); }),
              HasSubstr("car.urdf:40: sensor 'lidar': its XML does not parse (line 2 of the copy): "));
}

TEST_F(XmlReaderTest, APrintedCopyKeepsEachElementsLine) {
  tinyxml2::XMLDocument file;
  ASSERT_EQ(file.Parse("<robot>\n<sensor name='lidar'>\n<ray>\n<samples>many</samples>\n</ray>\n"
                       "</sensor>\n</robot>"),
            tinyxml2::XML_SUCCESS);
  const XmlReader in_file("car.urdf", {});
  const XmlReader::Copy copy = in_file.printCopy(file.RootElement()->FirstChildElement("sensor"));
  EXPECT_EQ(copy.lines, (std::vector<int>{2, 3, 4}));
  XmlReader r = XmlReader::copyOf("car.urdf", 2, "sensor 'lidar': ", {}, copy.lines);
  tinyxml2::XMLDocument doc;
  const tinyxml2::XMLElement* samples =
      r.parseCopy(copy.xml, &doc)->FirstChildElement("ray")->FirstChildElement("samples");
  EXPECT_EQ(error([&] { r.integer(samples, ""); }),
            "car.urdf:4: sensor 'lidar': <samples> 'many' is not an integer");
  // A copy of the copy (a multicamera's cameras) keeps the file's lines.
  const XmlReader::Copy again = r.printCopy(doc.RootElement()->FirstChildElement("ray"));
  EXPECT_EQ(again.lines, (std::vector<int>{3, 4}));
}

TEST_F(XmlReaderTest, FailuresRaiseTheOneErrorTypeWithFileLineAndElement) {
  load("<a>\n<b>x</b></a>");
  try {
    reader_.number(el("b"), "thing");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "room.world");
    EXPECT_EQ(e.where().line, 2);
    EXPECT_EQ(e.where().element, "b");
    EXPECT_EQ(e.message(), "thing: <b> 'x' is not a list of numbers");
    EXPECT_STREQ(e.what(), "room.world:2: thing: <b> 'x' is not a list of numbers");
  }
}

}  // namespace
}  // namespace tianracer_sim
