// The one warning callback type of the ROS-free libraries: parsers and the renderer report each
// warning once through it, the node logs what arrives.
#ifndef TIANRACER_SIM_COMMON_WARNING_H
#define TIANRACER_SIM_COMMON_WARNING_H

#include <functional>
#include <string>

namespace tianracer_sim {

/// Receives each warning once (unknown tag, unknown plugin, defaulted value, skipped visual...).
/// May be empty: warnings are then dropped.
using WarningSink = std::function<void(const std::string&)>;

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_WARNING_H
