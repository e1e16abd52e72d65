#include "tianracer_control/naming.h"

namespace tianracer_control {

namespace {
std::string stripSlashes(std::string s) {
  while (!s.empty() && s.front() == '/') s.erase(s.begin());
  while (!s.empty() && s.back() == '/') s.pop_back();
  return s;
}
}  // namespace

std::string resolveFrame(const std::string& prefix, const std::string& frame) {
  if (!frame.empty() && frame.front() == '/') return stripSlashes(frame);
  const std::string p = stripSlashes(prefix);
  if (p.empty()) return frame;
  return p + "/" + frame;
}

std::string resolveTopic(const std::string& ns, const std::string& name) {
  std::string joined = (!name.empty() && name[0] == '/') ? name : "/" + ns + "/" + name;
  std::string out;
  for (char c : joined) {
    if (c == '/' && !out.empty() && out.back() == '/') continue;
    out.push_back(c);
  }
  if (out.size() > 1 && out.back() == '/') out.pop_back();
  return out;
}

}  // namespace tianracer_control
