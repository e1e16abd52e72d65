// The one XML reader of the parsers (URDF <gazebo> tags, SDF worlds, <sensor> blocks, materials):
// text, numbers, vectors, poses, warn-once and the unknown-element report, every message prefixed
// with the place it came from ("<file>:<line>: ", common/diagnostic.h). Failures raise InputError.
#ifndef TIANRACER_SIM_COMMON_XML_READER_H
#define TIANRACER_SIM_COMMON_XML_READER_H

#include <cstdint>
#include <optional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <tinyxml2.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/common/diagnostic.h"

namespace tianracer_sim {

/// A whole string (blanks around it ignored, one leading '+' allowed) as a double, independent of
/// the C locale; nullopt on anything else. "nan" and "inf" parse (callers decide whether they may);
/// a value beyond double's range reads as +-inf, one below it as 0 or a denormal.
std::optional<double> parseNumber(const std::string& text);

/// Blank-separated numbers ("1 2.5 -3"); nullopt when any token is not a number. "" -> {}.
std::optional<std::vector<double>> parseNumbers(const std::string& text);

/// "true"/"1" and "false"/"0" (blanks around ignored), as SDF and gazebo_ros read them.
std::optional<bool> parseBool(const std::string& text);

/// A whole string (blanks around it ignored, one leading '+' allowed) as an int; nullopt on
/// anything else, a fraction or a value out of int's range.
std::optional<int> parseInteger(const std::string& text);

/// The text directly inside `e`, trimmed; "" when there is none.
std::string elementText(const tinyxml2::XMLElement* e);

/// An attribute's value, trimmed; "" when absent.
std::string attributeText(const tinyxml2::XMLElement* e, const char* name);

/// `e`'s line in its document (0 when unknown).
inline int lineOf(const tinyxml2::XMLElement* e) { return e ? e->GetLineNum() : 0; }

/// tinyxml2's XMLDocument::Parse, also taking an XML declaration that follows comments, as
/// TinyXML (sdformat 9, Gazebo 11's parser) does: Gazebo's own worlds/cafe.world starts with
/// a comment. tinyxml2 refuses a declaration anywhere but first; it is blanked, lines kept.
tinyxml2::XMLError parseXmlDocument(const std::string& text, tinyxml2::XMLDocument* doc);

/// Reads values out of the elements of one document named `source`: a bad value raises
/// InputError "<source>:<line>: <what>: <tag> '<text>' is not ...".
class XmlReader {
 public:
  /// A reader of a document of its own (a URDF, a world, a model file): each element is placed
  /// at its own line, and every message goes on with `context` (e.g. "model 'm' visual 'v': ").
  XmlReader(std::string source, WarningSink warn, std::string context = "");
  /// A reader of a printed copy of one element of `source` that stands at `line` there (the
  /// <sensor> blocks a SensorSpec keeps), every message going on with `context` ("sensor
  /// 'lidar': "). The copy's line numbers are not the file's: with `element_lines` (printCopy's,
  /// one per element of the copy in document order) each element is placed at its own line in
  /// `source`; without them, or when they do not match the copy, every place is `line`.
  static XmlReader copyOf(std::string source, int line, std::string context, WarningSink warn,
                          std::vector<int> element_lines = {});
  /// Parses such a printed copy (`xml`, e.g. SensorSpec::xml) into `doc` and returns its root
  /// element; fails "no XML to read" when it is blank, "its XML does not parse (line <n> of the
  /// copy): <tinyxml2's error>" when it does not parse. The one place a kept copy is parsed.
  tinyxml2::XMLElement* parseCopy(const std::string& xml, tinyxml2::XMLDocument* doc);

  /// An element printed back for a later copyOf() reader: the text, and the line of each of its
  /// elements (document order) as this reader places them.
  struct Copy {
    std::string xml;
    std::vector<int> lines;
  };
  Copy printCopy(const tinyxml2::XMLElement* e) const;

  const std::string& source() const { return source_; }
  /// The file, line and name of `e` (line 0 and no name for nullptr).
  SourceLocation where(const tinyxml2::XMLElement* e) const;
  /// The place of `e` as every message starts: "<source>:<line>: " and the context.
  std::string at(const tinyxml2::XMLElement* e) const;

  /// Throws InputError(where(e), context + message).
  [[noreturn]] void fail(const tinyxml2::XMLElement* e, const std::string& message) const;
  /// Forwards at(e) + message, once per distinct message.
  void warn(const tinyxml2::XMLElement* e, const std::string& message);
  /// Forwards `message` (already placed) once.
  void warn(const std::string& message) { warnOnce(message, message); }
  /// Forwards `message` once per `key` (and once per distinct message).
  void warnOnce(const std::string& key, const std::string& message);
  /// "<tag> in <parent> is not supported, ignored[ (why)]", once per (parent, tag) pair.
  void unsupported(const tinyxml2::XMLElement* e, const std::string& why = "");
  /// Reports each child of `e` whose name is not in `known` (unsupported()); returns how many.
  int checkChildren(const tinyxml2::XMLElement* e, const std::set<std::string>& known);

  std::string text(const tinyxml2::XMLElement* e) const { return elementText(e); }
  /// The child named `name`, or a failure naming `what` and the parent's place.
  const tinyxml2::XMLElement* required(const tinyxml2::XMLElement* e, const char* name,
                                       const std::string& what) const;

  /// Finite numbers separated by blanks.
  std::vector<double> numbers(const tinyxml2::XMLElement* e, const std::string& what) const;
  double number(const tinyxml2::XMLElement* e, const std::string& what) const;
  /// One number, nan and inf included, for values checked where they are used (sdformat reads
  /// "nan" as a double; Gazebo's saved worlds write it in static links' inertia).
  double anyNumber(const tinyxml2::XMLElement* e, const std::string& what) const;
  /// A finite number with |v| <= bound, else "<tag> <text> is out of range (<= <bound> <unit>)"
  /// (common/input_limits.h).
  double bounded(const tinyxml2::XMLElement* e, const std::string& what, double bound,
                 const std::string& unit) const;
  double positive(const tinyxml2::XMLElement* e, const std::string& what) const;
  double nonNegative(const tinyxml2::XMLElement* e, const std::string& what) const;
  int integer(const tinyxml2::XMLElement* e, const std::string& what) const;
  /// SDF's "unsigned int" as sdformat reads it (Param.cc, ValueFromString: std::stoul, base 16
  /// after a "0x" prefix, else 10): a bitmask such as <collide_bitmask>0x01</collide_bitmask>.
  /// Fails for a sign, other text or a value above 0xffffffff.
  std::uint32_t unsignedInteger(const tinyxml2::XMLElement* e, const std::string& what) const;
  bool boolean(const tinyxml2::XMLElement* e, const std::string& what) const;
  Eigen::Vector3d vector3(const tinyxml2::XMLElement* e, const std::string& what) const;
  /// "r g b [a]" (alpha 1 when left out).
  Eigen::Vector4f color(const tinyxml2::XMLElement* e, const std::string& what) const;
  /// SDF "x y z roll pitch yaw": translation, then R = Rz(yaw) Ry(pitch) Rx(roll); each
  /// coordinate within limits::kPosition ("position x 1e+30 is out of range (|x| <= 1e+06 m)"). A frame or
  /// relative_to attribute is warned about and the pose taken relative to the parent.
  Eigen::Isometry3d pose(const tinyxml2::XMLElement* e, const std::string& what);

  /// sdformat's rule for an SDF value element (sdformat 9 src/parser.cc, readXml: the value is
  /// set from the element's text only when GetText() is not null): an element with no text
  /// (<size/>, <pose></pose>, blanks only) keeps `fallback`, the SDF default; any text is read as
  /// by the reader without one. URDF attributes do not follow it (urdfdom fails an empty one).
  static bool keepsDefault(const tinyxml2::XMLElement* e) { return elementText(e).empty(); }
  double number(const tinyxml2::XMLElement* e, const std::string& what, double fallback) const;
  double positive(const tinyxml2::XMLElement* e, const std::string& what, double fallback) const;
  double nonNegative(const tinyxml2::XMLElement* e, const std::string& what, double fallback) const;
  bool boolean(const tinyxml2::XMLElement* e, const std::string& what, bool fallback) const;
  Eigen::Vector3d vector3(const tinyxml2::XMLElement* e, const std::string& what,
                          const Eigen::Vector3d& fallback) const;
  Eigen::Vector4f color(const tinyxml2::XMLElement* e, const std::string& what,
                        const Eigen::Vector4f& fallback) const;
  Eigen::Isometry3d pose(const tinyxml2::XMLElement* e, const std::string& what,
                         const Eigen::Isometry3d& fallback);

  /// Attribute `name` of `e` as a finite number / an int (as integer()): fails
  /// "<what>: <tag> <name> '<text>' is not a finite number / an integer" (absent reads as "").
  double numberAttribute(const tinyxml2::XMLElement* e, const char* name,
                         const std::string& what) const;
  int integerAttribute(const tinyxml2::XMLElement* e, const char* name,
                       const std::string& what) const;

 private:
  std::string source_;
  int copy_line_ = -1;  // >= 0: a printed copy standing at this line of source_
  std::vector<int> copy_element_lines_;  // copyOf's element_lines
  std::map<const tinyxml2::XMLElement*, int> copy_lines_;  // parseCopy: element -> line in source_
  std::string context_;
  WarnOnce warn_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_XML_READER_H
