// Text helpers shared by the sensor parsers (until one XML reader serves every parser).
#ifndef TIANRACER_SIM_COMMON_TEXT_H
#define TIANRACER_SIM_COMMON_TEXT_H

#include <sstream>
#include <string>

namespace tianracer_sim {

/// `s` without leading and trailing blanks (space, tab, CR, LF).
inline std::string trimText(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

/// A number as messages quote it: up to 10 significant digits.
inline std::string formatNumber(double v) {
  std::ostringstream ss;
  ss.precision(10);
  ss << v;
  return ss.str();
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_TEXT_H
