// Where each link and joint of a model stands in its file, so that the stages after parsing
// (the physics build) can place their messages as the parsers do ("<file>:<line>: ").
#ifndef TIANRACER_SIM_COMMON_ELEMENT_LINES_H
#define TIANRACER_SIM_COMMON_ELEMENT_LINES_H

#include <map>
#include <string>

#include "tianracer_sim/common/diagnostic.h"

namespace tianracer_sim {

struct ElementLines {
  std::string source;               // the model file (or parameter) as messages name it
  std::map<std::string, int> links;   // link name -> line of its <link>
  std::map<std::string, int> joints;  // joint name -> line of its <joint>

  /// "<source>:<line>: " of the link (or joint); "<source>: " when its line is unknown, "" when
  /// there is no source.
  std::string link(const std::string& name) const { return place(links, name); }
  std::string joint(const std::string& name) const { return place(joints, name); }

 private:
  std::string place(const std::map<std::string, int>& lines, const std::string& name) const {
    if (source.empty()) return "";
    const auto it = lines.find(name);
    return formatLocation(source, it == lines.end() ? 0 : it->second);
  }
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_ELEMENT_LINES_H
