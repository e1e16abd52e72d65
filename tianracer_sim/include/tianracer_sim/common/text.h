// Text helpers shared by the parsers (common/xml_reader.h), the sensor registry and the
// start-up table.
#ifndef TIANRACER_SIM_COMMON_TEXT_H
#define TIANRACER_SIM_COMMON_TEXT_H

#include <cctype>
#include <cstdint>
#include <cstdio>
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

/// `s` in lower case (ASCII letters).
inline std::string lowerCase(std::string s) {
  for (char& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

/// A number as messages quote it: up to 10 significant digits.
inline std::string formatNumber(double v) {
  std::ostringstream ss;
  ss.precision(10);
  ss << v;
  return ss.str();
}

/// A number as tables print it: printf's %g (6 significant digits).
inline std::string formatShort(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

/// Whether `s` ends with `suffix`.
inline bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The last component of a path ("lib/libfoo.so" -> "libfoo.so").
inline std::string baseName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

/// "/a/b/" -> "a/b" (a ROS name without its leading and trailing slashes).
inline std::string trimSlashes(std::string s) {
  while (!s.empty() && s.front() == '/') s.erase(s.begin());
  while (!s.empty() && s.back() == '/') s.pop_back();
  return s;
}

/// A stable hash of a name (32-bit FNV-1a), never 0: the default noise seed of a sensor, so
/// that two sensors of one model draw different noise and every run draws the same.
inline std::uint32_t nameHash(const std::string& s) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : s) {
    h ^= c;
    h *= 16777619u;
  }
  return h == 0 ? 1u : h;
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_TEXT_H
