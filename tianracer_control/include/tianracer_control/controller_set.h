// The running controllers of one robot (controller_manager without ROS). ROS-free.
#ifndef TIANRACER_CONTROL_CONTROLLER_SET_H
#define TIANRACER_CONTROL_CONTROLLER_SET_H

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controller.h"

namespace tianracer_control {

class ControllerSet {
 public:
  /// Adds and starts a controller at `time`. Throws ControllerError for a duplicate name or a
  /// joint already written by another controller (ros_control's resource conflict).
  Controller& add(std::unique_ptr<Controller> controller, double time = 0.0);
  /// builtinControllers().create() + add().
  Controller& load(const ControllerSpec& spec, std::map<std::string, JointHandle*>& joints,
                   double time = 0.0, const WarningSink& warn = WarningSink());

  /// Updates every controller in the order they were added (call between read and write).
  void update(double dt);
  /// Sim reset: clears every PID and restarts every controller at `time`.
  void reset(double time = 0.0);

  Controller* find(const std::string& name);
  const Controller* find(const std::string& name) const;
  const std::vector<std::unique_ptr<Controller>>& controllers() const { return controllers_; }
  std::size_t size() const { return controllers_.size(); }
  bool empty() const { return controllers_.empty(); }

 private:
  std::vector<std::unique_ptr<Controller>> controllers_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLER_SET_H
