#include "tianracer_control/frames.h"

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

}  // namespace tianracer_control
