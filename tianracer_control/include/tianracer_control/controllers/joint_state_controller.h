// joint_state_controller/JointStateController: publishes nothing itself; tells the host when to
// publish all joint states, at publish_rate in sim time.
#ifndef TIANRACER_CONTROL_CONTROLLERS_JOINT_STATE_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_JOINT_STATE_CONTROLLER_H

#include <memory>
#include <string>

#include "tianracer_control/controller.h"

namespace tianracer_control {

class JointStateController : public Controller {
 public:
  static constexpr const char* kType = "joint_state_controller/JointStateController";
  /// Reads publish_rate (Hz, required, > 0).
  static std::unique_ptr<Controller> create(ControllerContext& context);

  JointStateController(std::string name, double publish_rate);
  void starting(double time) override;
  void update(double) override {}
  /// True when a message is due at sim time t (at most once per call). The first call after
  /// starting() is due; then every 1/publish_rate. A jump back in time (sim reset) restarts the
  /// schedule; a long gap does not cause a burst.
  bool due(double t);
  double publishRate() const { return rate_; }

 private:
  double rate_;
  double period_;
  double next_ = 0.0;
  bool started_ = false;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_JOINT_STATE_CONTROLLER_H
