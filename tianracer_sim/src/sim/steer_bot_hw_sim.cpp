#include "tianracer_sim/sim/steer_bot_hw_sim.h"

#include <cmath>
#include <set>

#include <urdf_model/model.h>

#include <tianracer_control/pid_params.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/physics/world.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

namespace {

/// Reads <ns>/<group>/<key> as SBH's nh.getParam calls do, and refuses what SBH would turn
/// into garbage: "steer_bot_hardware_gazebo/SteerBotHardwareGazebo: parameter <name> ...".
class Params {
 public:
  Params(const tc::ParamValue& group, std::string name) : group_(group), name_(std::move(name)) {
    if (!group_.isNone() && group_.kind() != tc::ParamValue::Kind::kDict)
      fail("", std::string("is ") + group_.typeName() + ", not a dictionary");
  }
  const tc::ParamValue* find(const std::string& key) const {
    return group_.kind() == tc::ParamValue::Kind::kDict ? group_.find(key) : nullptr;
  }
  std::string text(const std::string& key) const {
    const tc::ParamValue* v = find(key);
    if (!v) fail(key, "is not set");
    if (v->kind() != tc::ParamValue::Kind::kString || v->asString().empty())
      fail(key, v->kind() == tc::ParamValue::Kind::kString
                    ? "is empty: it must name a joint"
                    : std::string("is ") + v->typeName() + ", not a joint name");
    return v->asString();
  }
  /// SBH indexes [INDEX_RIGHT] and [INDEX_LEFT]: exactly two names, right then left.
  std::array<std::string, 2> pair(const std::string& key) const {
    const tc::ParamValue* v = find(key);
    if (!v) fail(key, "is not set");
    if (v->kind() != tc::ParamValue::Kind::kList)
      fail(key, std::string("is ") + v->typeName() + ", not a list of two joint names");
    std::string shown;
    bool names = true;
    for (const tc::ParamValue& item : v->items()) {
      names = names && item.kind() == tc::ParamValue::Kind::kString && !item.asString().empty();
      shown += (shown.empty() ? "'" : ", '") +
               (item.kind() == tc::ParamValue::Kind::kString ? item.asString() : item.typeName()) + "'";
    }
    if (!names || v->items().size() != 2)
      fail(key, "[" + shown + "] must be two joint names (right, left)");
    return {v->items()[0].asString(), v->items()[1].asString()};
  }
  std::optional<double> number(const std::string& key) const {
    const tc::ParamValue* v = find(key);
    if (!v) return std::nullopt;
    if (const std::string why = tc::finiteNumberProblem(*v); !why.empty()) fail(key, why);
    return v->asNumber();
  }
  std::optional<bool> boolean(const std::string& key) const {
    const tc::ParamValue* v = find(key);
    if (!v) return std::nullopt;
    if (v->kind() != tc::ParamValue::Kind::kBool)
      fail(key, std::string("is ") + v->typeName() + ", not true or false");
    return v->asBool();
  }
  std::string name(const std::string& key) const { return name_ + (key.empty() ? "" : "/" + key); }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ModelError(std::string(kSteerBotHardwareGazebo) + ": parameter " + name(key) + " " + what);
  }

 private:
  const tc::ParamValue& group_;
  std::string name_;
};

double shortestAngularDistance(double from, double to) {
  double d = std::fmod(to - from + M_PI, 2.0 * M_PI);
  if (d < 0.0) d += 2.0 * M_PI;
  return d - M_PI;
}

}  // namespace

void SteerBotHwSim::init(const RobotModel& model, const PhysicsRobot& robot,
                         const RobotHwSimParams& params, const WarningSink& warn,
                         std::vector<tc::JointHandle>* handles, std::vector<int>* handle_joint) {
  // GetJointNames (SBH 301-342), under ns_ "steer_bot_hardware_gazebo/" of the robot's namespace.
  const Params p(params.steer_bot_hardware_gazebo, params.ns + "/steer_bot_hardware_gazebo");
  const std::string rear_wheel = p.text("rear_wheel");
  const std::array<std::string, 2> rear = p.pair("virtual_rear_wheels");
  const std::array<std::string, 2> front = p.pair("virtual_front_wheels");
  const std::string front_steer = p.text("front_steer");
  const std::array<std::string, 2> steers = p.pair("virtual_front_steers");

  // SBH 42-48: no default in the code (the members are left uninitialised); the README gives
  // true for enable_ackermann_link. The separations are needed by the link only.
  if (const auto link = p.boolean("enable_ackermann_link")) {
    ackermann_link_ = *link;
  } else {
    ackermann_link_ = true;
    if (warn) {
      warn(std::string(kSteerBotHardwareGazebo) + ": parameter " + p.name("enable_ackermann_link") +
           " is not set; true (steer_bot_hardware_gazebo's README; its code leaves it undefined)");
    }
  }
  const auto w = p.number("wheel_separation_w");
  const auto h = p.number("wheel_separation_h");
  if (ackermann_link_) {
    if (!w) p.fail("wheel_separation_w", "is not set (the Ackermann link needs it)");
    if (!h) p.fail("wheel_separation_h", "is not set (the Ackermann link needs it)");
    if (!(*w > 0.0)) p.fail("wheel_separation_w", formatShort(*w) + " must be > 0");
    if (!(*h > 0.0)) p.fail("wheel_separation_h", formatShort(*h) + " must be > 0");
  }
  w_ = w.value_or(0.0);
  h_ = h.value_or(0.0);

  // RegisterSteerInterface, RegisterWheelInterface (SBH 344-413): one handle per name.
  struct Entry {
    std::string name;
    std::string param;
    tc::JointHandle::Interface iface;
    bool driven;
  };
  using I = tc::JointHandle::Interface;
  const std::array<Entry, kHandleCount> entries = {{
      {front_steer, "front_steer", I::kPosition, false},
      {steers[0], "virtual_front_steers", I::kPosition, true},
      {steers[1], "virtual_front_steers", I::kPosition, true},
      {rear_wheel, "rear_wheel", I::kVelocity, false},
      {rear[0], "virtual_rear_wheels", I::kVelocity, true},
      {rear[1], "virtual_rear_wheels", I::kVelocity, true},
      {front[0], "virtual_front_wheels", I::kVelocity, true},
      {front[1], "virtual_front_wheels", I::kVelocity, true},
  }};
  std::set<std::string> seen;
  std::vector<tc::JointHandle> hs;
  for (size_t k = 0; k < kHandleCount; ++k) {
    const Entry& e = entries[k];
    if (!seen.insert(e.name).second)
      p.fail(e.param, "names joint '" + e.name + "' that another of its parameters names too");
    const int j = robot.jointIndex(e.name);
    // SBH drives only the joints Gazebo has (readSim/writeSim match them by name): a driven
    // joint the robot lacks would never move.
    if (e.driven && j < 0)
      p.fail(e.param, "names joint '" + e.name + "', which is not a movable joint of robot '" +
                          robot.name() + "'");
    hs.push_back(makeJointHandle(e.name, e.iface, j >= 0 ? &robot.joints()[j] : nullptr));
    joint_[k] = e.driven ? j : -1;
  }

  // SBH 50-77: the steers' own command handles get soft limits from the URDF (<limit> and
  // <safety_controller>); writeSim never reads those commands, so only the warning matters.
  for (const std::string& steer : steers) {
    urdf::JointConstSharedPtr uj = model.urdf ? model.urdf->getJoint(steer) : nullptr;
    if ((!uj || !uj->limits || !uj->safety) && warn)
      warn(std::string(kSteerBotHardwareGazebo) + ": Joint limits won't be enforced for joint '" +
           steer + "'.");
  }

  // SBH 79-95: a PID per rear wheel from <ns>/gains/<joint>; Pid::init fails without p, and so
  // does initSim (gazebo_ros_control: "Could not initialize robot simulation interface").
  const Params gains(params.gains, params.ns + "/gains");
  for (size_t i = 0; i < 2; ++i) {
    const tc::ParamValue* g = gains.find(rear[i]);
    const tc::ParamValue none;
    const Params one(g ? *g : none, gains.name(rear[i]));
    const tc::PidParams pp = tc::readPidParams(one);
    if (!pp.p) {
      throw ModelError(std::string(kSteerBotHardwareGazebo) + ": No p gain specified for pid.  "
                       "Namespace: " + gains.name(rear[i]) + " (control_toolbox), so initSim "
                       "fails: Could not initialize robot simulation interface");
    }
    try {
      pids_[i] = tc::Pid(tc::toPidGains(gains.name(rear[i]), pp, WarningSink()));
    } catch (const tc::ControllerError& e) {
      throw ModelError(std::string(kSteerBotHardwareGazebo) + ": " + e.what());
    }
  }

  *handles = std::move(hs);
  handle_joint->assign(joint_.begin(), joint_.end());
  position_.assign(kHandleCount, 0.0);  // CleanUp (SBH 263-299): every state starts at 0
  drives_.clear();
  drives_.reserve(kHandleCount);
}

void SteerBotHwSim::read(std::vector<tc::JointHandle>& handles) {
  // GetCurrentState (SBH 469-481): position += shortest_angular_distance(position, physics');
  // velocity and effort as the physics has them (the host put them into the handle).
  for (size_t k = 0; k < kHandleCount; ++k) {
    if (joint_[k] < 0) continue;
    position_[k] += shortestAngularDistance(position_[k], handles[k].position);
    handles[k].position = position_[k];
  }
  // SBH 137-139: front_steer is the steers' mean.
  tc::JointHandle& steer = handles[kFrontSteer];
  steer.position = (handles[kRightSteer].position + handles[kLeftSteer].position) / 2.0;
  steer.velocity = (handles[kRightSteer].velocity + handles[kLeftSteer].velocity) / 2.0;
  steer.effort = (handles[kRightSteer].effort + handles[kLeftSteer].effort) / 2.0;
}

const std::vector<std::pair<int, JointDrive>>& SteerBotHwSim::write(std::vector<tc::JointHandle>& handles) {
  drives_.clear();
  // SBH 154-194: the four wheels SetVelocity(0, rear_wheel's command).
  const double v = handles[kRearWheel].command;
  if (std::isfinite(v)) {
    for (size_t k : {kRightRearWheel, kLeftRearWheel, kRightFrontWheel, kLeftFrontWheel}) {
      JointDrive d;
      d.mode = JointDrive::Mode::kSetVelocity;
      d.value = v;
      drives_.emplace_back(joint_[k], d);
    }
  }
  // SBH 201-240: the steers SetPosition(0, angle, true).
  const double delta = handles[kFrontSteer].command;
  if (std::isfinite(delta)) {
    double right = delta, left = 2.0 * delta;  // SBH 213, 233: without the link, as upstream
    if (ackermann_link_) {
      right = std::atan2(2.0 * h_ * std::tan(delta), 2.0 * h_ + w_ / 2.0 * std::tan(delta));
      left = std::atan2(2.0 * h_ * std::tan(delta), 2.0 * h_ - w_ / 2.0 * std::tan(delta));
    }
    for (const auto& [k, q] : {std::pair{kRightSteer, right}, std::pair{kLeftSteer, left}}) {
      JointDrive d;
      d.mode = JointDrive::Mode::kPosition;
      d.value = q;
      drives_.emplace_back(joint_[k], d);
    }
    // SBH 248: front_steer's position is its command from now until the next read.
    handles[kFrontSteer].position = delta;
  }
  // SBH 254-255: rear_wheel's state, the rear wheels' mean as read.
  handles[kRearWheel].position = 0.5 * (position_[kRightRearWheel] + position_[kLeftRearWheel]);
  handles[kRearWheel].velocity =
      0.5 * (handles[kRightRearWheel].velocity + handles[kLeftRearWheel].velocity);
  return drives_;
}

}  // namespace tianracer_sim
