#include "tianracer_control/pid_params.h"

#include <cmath>
#include <sstream>

namespace tianracer_control {

namespace {

// toPidGains's checks; `pre` starts each message ("c.yaml:7: controller 'x': " when the YAML
// place is known), `ns` is where the gains are ("pid").
PidGains checkedPidGains(const std::string& pre, const std::string& ns, const PidParams& params,
                         const WarningSink& warn) {
  if (!params.p) throw ControllerError(pre + ns + "/p is missing (pid gains are required)");
  auto finite = [&](const std::optional<double>& v, const char* key) {
    if (v && !std::isfinite(*v)) {
      std::ostringstream os;
      os << pre << ns << "/" << key << " must be finite, got " << *v;
      throw ControllerError(os.str());
    }
  };
  finite(params.p, "p");
  finite(params.i, "i");
  finite(params.d, "d");
  finite(params.i_clamp, "i_clamp");
  finite(params.i_clamp_min, "i_clamp_min");
  finite(params.i_clamp_max, "i_clamp_max");

  const double i_clamp = std::abs(params.i_clamp.value_or(0.0));
  PidGains g = PidGains::fromIClamp(*params.p, params.i.value_or(0.0), params.d.value_or(0.0),
                                    i_clamp, params.antiwindup.value_or(false));
  if (params.i_clamp_min) g.i_clamp_min = *params.i_clamp_min;
  if (params.i_clamp_max) g.i_clamp_max = *params.i_clamp_max;
  if (g.i_clamp_min > g.i_clamp_max) {
    std::ostringstream os;
    os << pre << ns << "/i_clamp_min (" << g.i_clamp_min << ") is greater than " << ns << "/i_clamp_max ("
       << g.i_clamp_max << ")";
    throw ControllerError(os.str());
  }
  if (warn && g.i != 0.0 && g.i_clamp_min == 0.0 && g.i_clamp_max == 0.0) {
    warn(pre + ns + "/i is " + std::to_string(g.i) +
         " but the integral clamp is 0, so the integral term is always 0 (set " + ns + "/i_clamp)");
  }
  return g;
}

}  // namespace

PidGains toPidGains(const std::string& controller, const PidParams& params,
                    const WarningSink& warn) {
  return checkedPidGains(controllerPrefix(controller), "pid", params, warn);
}

PidGains readPidGains(ControllerParams& params, const WarningSink& warn, const std::string& ns) {
  const PidParams pid = readPidParams(params, ns + "/");
  if (!pid.p) {
    throw ControllerError(params.prefix() + ns + "/p is missing (" + params.type() +
                          " needs pid gains)");
  }
  // The YAML's file and line first, as every other message of the controller's keys.
  return checkedPidGains(params.prefix(), ns, pid, warn);
}

}  // namespace tianracer_control
