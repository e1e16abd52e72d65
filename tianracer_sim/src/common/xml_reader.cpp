#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/common/sdf_pose.h"
#include "tianracer_sim/common/input_limits.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace tianracer_sim {

using tinyxml2::XMLElement;

namespace {

// "<what>: <tag>", or "<tag>" when the place already says what it is.
std::string lead(const std::string& what, const XMLElement* e) {
  return (what.empty() ? "" : what + ": ") + "<" + e->Name() + ">";
}

}  // namespace

tinyxml2::XMLError parseXmlDocument(const std::string& text, tinyxml2::XMLDocument* doc) {
  // Skip blanks and comments; a declaration found there, not first, is blanked.
  std::size_t p = 0;
  bool after_comment = false;
  for (;;) {
    p = text.find_first_not_of(" \t\r\n", p);
    if (p == std::string::npos || text.compare(p, 4, "<!--") != 0) break;
    const std::size_t end = text.find("-->", p + 4);
    if (end == std::string::npos) break;
    p = end + 3;
    after_comment = true;
  }
  if (after_comment && p != std::string::npos && text.compare(p, 5, "<?xml") == 0) {
    const std::size_t end = text.find("?>", p);
    if (end != std::string::npos) {
      std::string copy = text;
      for (std::size_t i = p; i < end + 2; ++i) {
        if (copy[i] != '\n') copy[i] = ' ';
      }
      return doc->Parse(copy.data(), copy.size());
    }
  }
  return doc->Parse(text.data(), text.size());
}

std::optional<double> parseNumber(const std::string& text) {
  std::string t = trimText(text);
  if (!t.empty() && t[0] == '+') t.erase(0, 1);
  if (t.empty()) return std::nullopt;
  double v = 0.0;
  const char* end = t.data() + t.size();
  const auto r = std::from_chars(t.data(), end, v);
  if (r.ptr != end) return std::nullopt;
  // from_chars leaves v unset out of range; strtod gives the saturated value (+-HUGE_VAL or 0).
  if (r.ec == std::errc::result_out_of_range) return std::strtod(t.c_str(), nullptr);
  if (r.ec != std::errc()) return std::nullopt;
  return v;
}

std::optional<std::vector<double>> parseNumbers(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  for (std::string tok; in >> tok;) {
    const auto v = parseNumber(tok);
    if (!v) return std::nullopt;
    out.push_back(*v);
  }
  return out;
}

std::optional<bool> parseBool(const std::string& text) {
  const std::string t = trimText(text);
  if (t == "true" || t == "1") return true;
  if (t == "false" || t == "0") return false;
  return std::nullopt;
}

std::string elementText(const XMLElement* e) {
  const char* t = e ? e->GetText() : nullptr;
  return t ? trimText(t) : std::string();
}

std::string attributeText(const XMLElement* e, const char* name) {
  const char* v = e ? e->Attribute(name) : nullptr;
  return v ? trimText(v) : std::string();
}

XmlReader::XmlReader(std::string source, WarningSink warn, std::string context)
    : source_(std::move(source)), context_(std::move(context)), warn_(std::move(warn)) {}

XmlReader XmlReader::copyOf(std::string source, int line, std::string context, WarningSink warn,
                            std::vector<int> element_lines) {
  XmlReader r(std::move(source), std::move(warn), std::move(context));
  r.copy_line_ = std::max(line, 0);
  r.copy_element_lines_ = std::move(element_lines);
  return r;
}

namespace {

/// `e` and its descendants in document order (pre-order), as printing and parsing keep them.
template <class Element, class Visit>
void eachElement(Element* e, Visit&& visit) {
  visit(e);
  for (Element* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) eachElement(c, visit);
}

}  // namespace

XMLElement* XmlReader::parseCopy(const std::string& xml, tinyxml2::XMLDocument* doc) {
  if (trimText(xml).empty()) fail(nullptr, "no XML to read");
  if (doc->Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS || !doc->RootElement()) {
    fail(nullptr, "its XML does not parse (line " + std::to_string(doc->ErrorLineNum()) +
                      " of the copy): " + (doc->ErrorStr() ? doc->ErrorStr() : "no element"));
  }
  std::vector<const XMLElement*> elements;
  eachElement(static_cast<const XMLElement*>(doc->RootElement()),
              [&](const XMLElement* e) { elements.push_back(e); });
  copy_lines_.clear();
  // Lines that do not match the copy (edited since it was printed) are not used.
  if (elements.size() == copy_element_lines_.size()) {
    for (std::size_t i = 0; i < elements.size(); ++i) copy_lines_[elements[i]] = copy_element_lines_[i];
  }
  return doc->RootElement();
}

XmlReader::Copy XmlReader::printCopy(const XMLElement* e) const {
  Copy copy;
  tinyxml2::XMLPrinter printer;
  e->Accept(&printer);
  copy.xml = printer.CStr();
  eachElement(e, [&](const XMLElement* x) { copy.lines.push_back(where(x).line); });
  return copy;
}

SourceLocation XmlReader::where(const XMLElement* e) const {
  int line = lineOf(e);
  if (copy_line_ >= 0) {
    const auto it = e ? copy_lines_.find(e) : copy_lines_.end();
    line = it != copy_lines_.end() ? it->second : copy_line_;
  }
  return {source_, line, e ? e->Name() : ""};
}

std::string XmlReader::at(const XMLElement* e) const {
  return formatLocation(where(e)) + context_;
}

void XmlReader::fail(const XMLElement* e, const std::string& message) const {
  throw InputError(where(e), context_ + message);
}

void XmlReader::warn(const XMLElement* e, const std::string& message) {
  const std::string full = at(e) + message;
  warnOnce(full, full);
}

void XmlReader::warnOnce(const std::string& key, const std::string& message) {
  warn_(key, message);
}

void XmlReader::unsupported(const XMLElement* e, const std::string& why) {
  const XMLElement* parent = e->Parent() ? e->Parent()->ToElement() : nullptr;
  const std::string key = std::string(parent ? parent->Name() : "") + "/" + e->Name();
  std::string msg = at(e) + "<" + e->Name() + ">";
  if (parent) msg += " in <" + std::string(parent->Name()) + ">";
  msg += " is not supported, ignored";
  if (!why.empty()) msg += " (" + why + ")";
  warnOnce("unsupported " + key, msg);
}

int XmlReader::checkChildren(const XMLElement* e, const std::set<std::string>& known) {
  int unknown = 0;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (known.count(c->Name())) continue;
    unsupported(c);
    ++unknown;
  }
  return unknown;
}

const XMLElement* XmlReader::required(const XMLElement* e, const char* name,
                                      const std::string& what) const {
  const XMLElement* c = e->FirstChildElement(name);
  if (!c) fail(e, lead(what, e) + " has no <" + name + ">");
  return c;
}

std::vector<double> XmlReader::numbers(const XMLElement* e, const std::string& what) const {
  const std::string t = text(e);
  std::vector<double> out;
  std::istringstream in(t);
  for (std::string tok; in >> tok;) {
    const auto v = parseNumber(tok);
    if (!v) fail(e, lead(what, e) + " '" + t + "' is not a list of numbers");
    if (!std::isfinite(*v)) fail(e, lead(what, e) + " '" + t + "' is not finite");
    out.push_back(*v);
  }
  return out;
}

double XmlReader::number(const XMLElement* e, const std::string& what) const {
  const auto v = numbers(e, what);
  if (v.size() != 1) fail(e, lead(what, e) + " '" + text(e) + "' is not a number");
  return v[0];
}

double XmlReader::anyNumber(const XMLElement* e, const std::string& what) const {
  const std::string t = text(e);
  std::istringstream in(t);
  std::string tok, extra;
  in >> tok >> extra;
  const auto v = parseNumber(tok);
  if (!v || !extra.empty()) fail(e, lead(what, e) + " '" + t + "' is not a number");
  return *v;
}

double XmlReader::bounded(const XMLElement* e, const std::string& what, double bound,
                          const std::string& unit) const {
  const double v = number(e, what);
  if (std::abs(v) > bound)
    fail(e, lead(what, e) + " " + text(e) + " is out of range (<= " + limits::formatNumber(bound) +
                (unit.empty() ? "" : " " + unit) + ")");
  return v;
}

double XmlReader::positive(const XMLElement* e, const std::string& what) const {
  const double v = number(e, what);
  if (!(v > 0.0)) fail(e, lead(what, e) + " must be > 0 (got " + text(e) + ")");
  return v;
}

double XmlReader::nonNegative(const XMLElement* e, const std::string& what) const {
  const double v = number(e, what);
  if (!(v >= 0.0)) fail(e, lead(what, e) + " must be >= 0 (got " + text(e) + ")");
  return v;
}

std::optional<int> parseInteger(const std::string& text) {
  const std::string t = trimText(text);
  const char* begin = t.data() + (t.size() > 1 && t[0] == '+' && t[1] != '-' ? 1 : 0);  // as strtol
  const char* end = t.data() + t.size();
  int v = 0;
  const auto r = std::from_chars(begin, end, v);
  if (t.empty() || r.ec != std::errc() || r.ptr != end) return std::nullopt;
  return v;
}

int XmlReader::integer(const XMLElement* e, const std::string& what) const {
  const auto v = parseInteger(text(e));
  if (!v) fail(e, lead(what, e) + " '" + text(e) + "' is not an integer");
  return *v;
}

std::uint32_t XmlReader::unsignedInteger(const XMLElement* e, const std::string& what) const {
  const std::string t = text(e);
  const bool hex = t.size() > 2 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X');
  const char* begin = t.data() + (hex ? 2 : 0);
  const char* end = t.data() + t.size();
  std::uint64_t v = 0;
  const auto r = std::from_chars(begin, end, v, hex ? 16 : 10);
  if (t.empty() || r.ec != std::errc() || r.ptr != end || v > 0xffffffffull)
    fail(e, lead(what, e) + " '" + t + "' is not an unsigned integer (decimal, or hex after 0x) of 32 bits");
  return static_cast<std::uint32_t>(v);
}

bool XmlReader::boolean(const XMLElement* e, const std::string& what) const {
  const auto b = parseBool(text(e));
  if (!b) fail(e, lead(what, e) + " '" + text(e) + "' is not a boolean (true/false/1/0)");
  return *b;
}

Eigen::Vector3d XmlReader::vector3(const XMLElement* e, const std::string& what) const {
  const auto v = numbers(e, what);
  if (v.size() != 3)
    fail(e, lead(what, e) + " '" + text(e) + "' is not 3 numbers \"x y z\"");
  return {v[0], v[1], v[2]};
}

Eigen::Vector4f XmlReader::color(const XMLElement* e, const std::string& what) const {
  const auto v = numbers(e, what);
  if (v.size() != 3 && v.size() != 4)
    fail(e, lead(what, e) + " '" + text(e) + "' is not a colour \"r g b [a]\"");
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]),
          v.size() == 4 ? static_cast<float>(v[3]) : 1.0f};
}

namespace {

// SDF 1.5's frame and 1.7's relative_to attributes, warned about where a <pose> is read.
void warnPoseFrame(XmlReader* r, const XMLElement* e, const std::string& what) {
  for (const char* a : {"frame", "relative_to"}) {
    const char* v = e->Attribute(a);
    if (v && *v)
      r->warn(e, what + ": <pose " + a + "='" + v + "'> is not supported; taken relative to the parent");
  }
}

}  // namespace

Eigen::Isometry3d XmlReader::pose(const XMLElement* e, const std::string& what) {
  warnPoseFrame(this, e, what);
  const auto v = numbers(e, what);
  if (v.size() != 6)
    fail(e, lead(what, e) + " '" + text(e) + "' is not 6 numbers \"x y z roll pitch yaw\"");
  const std::string bad = limits::checkVector({v[0], v[1], v[2]}, limits::kPosition, "m");
  if (!bad.empty()) fail(e, lead(what, e) + " position " + bad);
  return sdfPose(v[0], v[1], v[2], v[3], v[4], v[5]);
}

double XmlReader::number(const XMLElement* e, const std::string& what, double fallback) const {
  return keepsDefault(e) ? fallback : number(e, what);
}

double XmlReader::positive(const XMLElement* e, const std::string& what, double fallback) const {
  return keepsDefault(e) ? fallback : positive(e, what);
}

double XmlReader::nonNegative(const XMLElement* e, const std::string& what, double fallback) const {
  return keepsDefault(e) ? fallback : nonNegative(e, what);
}

bool XmlReader::boolean(const XMLElement* e, const std::string& what, bool fallback) const {
  return keepsDefault(e) ? fallback : boolean(e, what);
}

Eigen::Vector3d XmlReader::vector3(const XMLElement* e, const std::string& what,
                                   const Eigen::Vector3d& fallback) const {
  return keepsDefault(e) ? fallback : vector3(e, what);
}

Eigen::Vector4f XmlReader::color(const XMLElement* e, const std::string& what,
                                 const Eigen::Vector4f& fallback) const {
  return keepsDefault(e) ? fallback : color(e, what);
}

Eigen::Isometry3d XmlReader::pose(const XMLElement* e, const std::string& what,
                                  const Eigen::Isometry3d& fallback) {
  if (!keepsDefault(e)) return pose(e, what);
  warnPoseFrame(this, e, what);
  return fallback;
}

double XmlReader::numberAttribute(const XMLElement* e, const char* name,
                                  const std::string& what) const {
  const std::string t = attributeText(e, name);
  const auto v = parseNumber(t);
  if (!v || !std::isfinite(*v))
    fail(e, lead(what, e) + " " + name + " '" + t + "' is not a finite number");
  return *v;
}

int XmlReader::integerAttribute(const XMLElement* e, const char* name,
                                const std::string& what) const {
  const std::string t = attributeText(e, name);
  const auto v = parseInteger(t);
  if (!v) fail(e, lead(what, e) + " " + name + " '" + t + "' is not an integer");
  return *v;
}

Eigen::Isometry3d sdfPose(double x, double y, double z, double roll, double pitch, double yaw) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  X.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return X;
}

}  // namespace tianracer_sim
