// The one diagnostic policy of the parsers and the other ROS-free libraries, shared with
// tianracer_control (tianracer_assets/diagnostic.h): an input that cannot be used raises
// InputError (file, line and element where known; messages start with "<file>:<line>: "), a
// warning goes through a WarningSink, once (WarnOnce). The node catches at one boundary and logs.
#ifndef TIANRACER_SIM_COMMON_DIAGNOSTIC_H
#define TIANRACER_SIM_COMMON_DIAGNOSTIC_H

#include <tianracer_assets/diagnostic.h>

namespace tianracer_sim {

using tianracer_assets::formatLocation;
using tianracer_assets::InputError;
using tianracer_assets::SourceLocation;
/// Receives each warning once (unknown tag, unknown plugin, defaulted value, skipped visual...).
/// May be empty: warnings are then dropped.
using tianracer_assets::WarningSink;
using tianracer_assets::say;
using tianracer_assets::WarnOnce;

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_DIAGNOSTIC_H
