#include "tianracer_sim/common/schedule.h"

namespace tianracer_sim {

bool Schedule::due(double t) {
  if (t + 1e-9 < next) return false;
  if (period <= 0.0) {
    next = t;
    return true;
  }
  // Keep the nominal grid (a 30 Hz camera on 1 ms steps fires at 34, 67, 100 ms: 30 Hz on
  // average); only when more than a period behind (a pause, a reset) restart from now, so
  // that nothing bursts to catch up.
  next += period;
  if (next <= t) next = t + period;
  return true;
}

}  // namespace tianracer_sim
