#include "tianracer_sim/model/sensor_topics.h"

namespace tianracer_sim {

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

}  // namespace tianracer_sim
