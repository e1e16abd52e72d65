// A small XML reader for one <sensor> element (SensorSpec::xml, printed back by tinyxml2):
// elements, attributes, text, comments, CDATA and the five predefined entities. The render
// library does not link tinyxml2, and this input is always well formed; malformed text still
// gets a clear error, never a crash.
#ifndef TIANRACER_SIM_SRC_RENDER_MINI_XML_H
#define TIANRACER_SIM_SRC_RENDER_MINI_XML_H

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace tianracer_sim {
namespace render_internal {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // concatenated character data directly inside this element, trimmed
  std::vector<std::unique_ptr<XmlElement>> children;
  int line = 1;

  /// First child with this name, or nullptr.
  const XmlElement* child(const std::string& child_name) const;
};

class XmlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses the first element of `text` (a prolog and comments before it are skipped).
std::unique_ptr<XmlElement> parseXml(const std::string& text);

}  // namespace render_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_RENDER_MINI_XML_H
