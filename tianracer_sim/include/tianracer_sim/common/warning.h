// WarningSink and WarnOnce, now part of the one diagnostic policy (common/diagnostic.h). Kept so
// that existing includes build; new code includes common/diagnostic.h.
#ifndef TIANRACER_SIM_COMMON_WARNING_H
#define TIANRACER_SIM_COMMON_WARNING_H

#include "tianracer_sim/common/diagnostic.h"

#endif  // TIANRACER_SIM_COMMON_WARNING_H
