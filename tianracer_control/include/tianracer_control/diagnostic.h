// tianracer_control's names for the one diagnostic policy (tianracer_assets/diagnostic.h): an
// input that cannot be used raises InputError ("<file>:<line>: " in front), a warning goes
// through a WarningSink, once (WarnOnce).
#ifndef TIANRACER_CONTROL_DIAGNOSTIC_H
#define TIANRACER_CONTROL_DIAGNOSTIC_H

#include <tianracer_assets/diagnostic.h>

namespace tianracer_control {

using tianracer_assets::formatLocation;
using tianracer_assets::InputError;
using tianracer_assets::SourceLocation;
using tianracer_assets::WarningSink;
using tianracer_assets::WarnOnce;

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_DIAGNOSTIC_H
