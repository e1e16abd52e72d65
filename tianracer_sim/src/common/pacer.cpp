#include "tianracer_sim/common/pacer.h"

namespace tianracer_sim {

void Pacer::beginStep(double t) {
  if (!restart_) return;
  wall0_ = hooks_.now();
  sim0_ = t;
  restart_ = false;
}

void Pacer::endStep(double t, double factor) {
  if (factor != factor_) {
    if (factor_ >= 0.0) {  // set_physics_properties changed the pace: measure from here
      wall0_ = hooks_.now();
      sim0_ = t;
    }
    factor_ = factor;
  }
  if (factor_ <= 0.0) return;
  const auto target = wall0_ + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>((t - sim0_) / factor_));
  const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
  const Clock::time_point now = hooks_.now();
  if (now < target) {
    hooks_.serve(seconds(target - now));
    const Clock::time_point after = hooks_.now();
    if (after < target) hooks_.sleep(seconds(target - after));
  } else if (seconds(now - target) > 0.5) {
    restart_ = true;
  }
}

}  // namespace tianracer_sim
