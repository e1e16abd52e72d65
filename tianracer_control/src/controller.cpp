#include "tianracer_control/controller.h"

#include <algorithm>
#include <cmath>

namespace tianracer_control {

namespace {

// "the effort interface (EffortJointInterface)"
std::string describe(JointHandle::Interface iface) {
  const char* word = iface == JointHandle::Interface::kEffort     ? "effort"
                     : iface == JointHandle::Interface::kVelocity ? "velocity"
                                                                  : "position";
  return std::string("the ") + word + " interface (" + toString(iface) + ")";
}

}  // namespace

JointHandle* findJoint(ControllerContext& context, const std::string& joint,
                       JointHandle::Interface needs) {
  ControllerParams& params = context.params;
  const std::string pre = params.prefix();
  const auto it = context.joints.find(joint);
  if (it == context.joints.end() || it->second == nullptr) {
    std::string names;
    for (const auto& kv : context.joints) names += (names.empty() ? "" : ", ") + kv.first;
    throw ControllerError(pre + "joint '" + joint + "' not found among the joints with a " +
                          "transmission (" + (names.empty() ? "none" : names) + ")");
  }
  if (it->second->interface != needs) {
    throw ControllerError(pre + params.type() + " needs " + describe(needs) +
                          " but the transmission of joint '" + joint + "' gives " +
                          describe(it->second->interface));
  }
  return it->second;
}

JointHandle* SingleJointController::claimJoint(ControllerContext& context,
                                               JointHandle::Interface needs) {
  ControllerParams& params = context.params;
  const std::string joint = params.text("joint").value_or("");
  if (joint.empty()) {
    throw ControllerError(params.prefix() + "no joint given (parameter 'joint' of " +
                          params.type() + ")");
  }
  return findJoint(context, joint, needs);
}

double shortestAngularDistance(double from, double to) {
  const double two_pi = 2.0 * M_PI;
  double d = std::fmod(to - from + M_PI, two_pi);
  if (d < 0.0) d += two_pi;
  return d - M_PI;
}

double clampToPositionLimits(const JointHandle& j, double x) {
  return j.has_position_limits ? std::min(std::max(x, j.lower), j.upper) : x;
}

const char* toString(JointHandle::Interface iface) {
  switch (iface) {
    case JointHandle::Interface::kEffort:
      return "EffortJointInterface";
    case JointHandle::Interface::kVelocity:
      return "VelocityJointInterface";
    case JointHandle::Interface::kPosition:
      return "PositionJointInterface";
  }
  return "?";
}

}  // namespace tianracer_control
