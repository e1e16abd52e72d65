#include "tianracer_control/controllers/joint_state_controller.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tianracer_control {

std::unique_ptr<Controller> JointStateController::create(ControllerContext& context) {
  ControllerParams& params = context.params;
  const std::optional<double> rate = params.number("publish_rate");
  if (!rate) {
    throw ControllerError(params.prefix() + "publish_rate is missing (" + params.type() + ")");
  }
  if (!(*rate > 0.0) || !std::isfinite(*rate)) {
    std::ostringstream os;
    os << params.prefix() << "publish_rate must be a positive number, got " << *rate;
    throw ControllerError(os.str());
  }
  return std::make_unique<JointStateController>(params.name(), *rate);
}

JointStateController::JointStateController(std::string name, double publish_rate)
    : Controller(std::move(name), kType), rate_(publish_rate), period_(1.0 / publish_rate) {}

void JointStateController::starting(double time) {
  next_ = time;
  started_ = true;
}

bool JointStateController::due(double t) {
  // Tolerance for accumulated floating point error of a fixed-step clock.
  const double eps = 1e-9 * std::max(1.0, std::abs(t));
  if (!started_ || t < next_ - period_ - eps) {  // first call, or time went backwards
    next_ = t;
    started_ = true;
  }
  if (t + eps < next_) return false;
  next_ += period_;
  if (next_ + eps <= t) next_ = t + period_;  // after a long gap: no burst
  return true;
}

}  // namespace tianracer_control
