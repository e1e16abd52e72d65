// What the control tests share: the cars they compute by hand, the seed's actuated joints, and
// controller specs as the parameter server gives them.
#ifndef TIANRACER_CONTROL_TEST_CONTROL_TEST_SUPPORT_H
#define TIANRACER_CONTROL_TEST_CONTROL_TEST_SUPPORT_H

#include <map>
#include <string>
#include <vector>

#include "tianracer_control/ackermann.h"
#include "tianracer_control/joint_controllers.h"

namespace tianracer_control {
namespace test {

// AckermannGeometry's members in their order: L, T, r, Tr, m, then the rear axle midpoint P
// (x, y) and the hinges' skew s and offset c (ackermann.h); those not given keep their defaults.

/// The round-number car the control unit tests compute by hand: L = 0.25, T = 0.14
/// (T/2 = 0.07), r = 0.05, Tr = 0.16, max steering 0.6 rad; symmetric.
inline AckermannGeometry geometry() { return {0.25, 0.14, 0.05, 0.16, 0.6}; }

/// The seed tianracer as the nodes derive it from its URDF (and from
/// test/data/urdf/ackermann_cylinders.urdf, whose hinges stop at 0.55 rad). Joint origins in
/// base_link (m): hinges left (0.1237, 0.070647), right (0.12626, -0.065953); rear wheels left
/// (-0.12626, 0.081602), right (-0.1237, -0.086296). Rear axle midpoint P = (-0.12498,
/// -0.002347); L = 0.24996, T = 0.1366; s = (0.12626 - 0.1237) / 2 = 0.00128;
/// c = (0.070647 - 0.065953) / 2 + 0.002347 = 0.004694.
inline AckermannGeometry seedGeometry(double max_steering_angle = 0.6) {
  return {0.24996,  0.1366,    0.032,   0.167898, max_steering_angle,
          -0.12498, -0.002347, 0.00128, 0.004694};
}

/// angular.z as the bicycle steering angle, rear wheels differential.
inline AckermannOptions steeringAngleDifferential() {
  AckermannOptions o;
  o.angular_z_is_steering_angle = true;
  o.differential = true;
  return o;
}

/// The seed's actuated joints as their transmissions give them: steering hinges (effort,
/// +-0.6 rad, effort 10), rear wheels (continuous, velocity), and the map controllers take.
struct SeedJoints {
  JointHandle left_hinge, right_hinge, left_rear, right_rear;
  std::map<std::string, JointHandle*> joints;

  SeedJoints() {
    left_hinge.name = "left_steering_hinge_joint";
    right_hinge.name = "right_steering_hinge_joint";
    left_rear.name = "left_rear_wheel_joint";
    right_rear.name = "right_rear_wheel_joint";
    for (JointHandle* h : {&left_hinge, &right_hinge}) {
      h->interface = JointHandle::Interface::kEffort;
      h->has_position_limits = true;
      h->lower = -0.6;
      h->upper = 0.6;
      h->effort_limit = 10.0;
      h->velocity_limit = 1000.0;
    }
    for (JointHandle* h : {&left_rear, &right_rear}) {
      h->interface = JointHandle::Interface::kVelocity;
      h->continuous = true;
    }
    for (JointHandle* h : {&left_hinge, &right_hinge, &left_rear, &right_rear}) joints[h->name] = h;
  }
};

/// A YAML entry as the parameter server gives it: type, joint (when not empty).
inline ControllerSpec spec(const std::string& name, const std::string& type,
                           const std::string& joint) {
  ControllerSpec s;
  s.name = name;
  s.type = type;
  if (!type.empty()) s.params["type"] = type;
  if (!joint.empty()) s.params["joint"] = joint;
  return s;
}

/// What building `s` over `joints` with the built-in types warns, in order.
inline std::vector<std::string> creationWarnings(const ControllerSpec& s,
                                                 std::map<std::string, JointHandle*>& joints) {
  std::vector<std::string> warnings;
  builtinControllers().create(s, joints, [&](const std::string& w) { warnings.push_back(w); });
  return warnings;
}

/// The warnings, in order, for `keys` that the class of a controller of `type` does not read,
/// each after `where` (location and controller): "<where>key '<key>' is not used by <type>,
/// ignored".
inline std::vector<std::string> unusedKeyWarnings(const std::string& where,
                                                  const std::string& type,
                                                  const std::vector<std::string>& keys) {
  std::vector<std::string> warnings;
  for (const std::string& key : keys) {
    warnings.push_back(where + "key '" + key + "' is not used by " + type + ", ignored");
  }
  return warnings;
}

}  // namespace test
}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_TEST_CONTROL_TEST_SUPPORT_H
