// The sim node's status: every status period (wall time) one line on the log and a
// /diagnostics array with the real-time factor, contacts per robot and each sensor's rate in sim
// and in wall time (the /diagnostics row of docs/model_and_sensors.md's topic table). With
// ~profile, the step profile and its ~profile service (docs/performance.md).
#include <iomanip>
#include <sstream>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <std_srvs/Trigger.h>

#include "tianracer_sim/ros/sim_node.h"

namespace tianracer_sim {

void SimNode::publishStatus() {
  const ros::WallTime now = ros::WallTime::now();
  const double wall = (now - status_wall_).toSec();
  if (status_period_ <= 0.0 || wall < status_period_) return;
  const double sim = sim_->time() - status_sim_;
  const double rtf = sim / wall;
  std::ostringstream line;
  line << std::fixed << std::setprecision(2) << "sim time " << sim_->time() << " s, real-time factor "
       << rtf << (sim_->paused() ? " (paused)" : "");
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time(sim_->time());
  diagnostic_msgs::DiagnosticStatus sim_status;
  sim_status.name = "tianracer_sim: simulation";
  sim_status.hardware_id = "tianracer_sim";
  sim_status.level = diagnostic_msgs::DiagnosticStatus::OK;
  sim_status.message = sim_->paused() ? "paused" : "running";
  auto kv = [](const std::string& k, double v) {
    diagnostic_msgs::KeyValue x;
    x.key = k;
    std::ostringstream o;
    o << v;
    x.value = o.str();
    return x;
  };
  sim_status.values.push_back(kv("sim_time", sim_->time()));
  sim_status.values.push_back(kv("real_time_factor", rtf));
  sim_status.values.push_back(kv("target_real_time_factor", real_time_factor_));
  for (const auto& robot : robots_) {
    sim_status.values.push_back(
        kv("contacts " + sim_->robot(robot->id())->name, sim_->contactCount(robot->id())));
  }
  array.status.push_back(sim_status);
  // In sim time every sensor keeps its rate by construction (rendering holds the step); what
  // can fall behind is the wall-clock rate a consumer sees when the sim cannot keep real time.
  for (const auto& sensor : sim_->sensors()) {
    SensorStat& stat = sensor->stat();
    const double rate = sim > 0.0 ? stat.count / sim : 0.0;
    const double wall_rate = stat.count / wall;
    diagnostic_msgs::DiagnosticStatus st;
    st.name = "tianracer_sim: " + stat.name;
    st.hardware_id = "tianracer_sim";
    st.values.push_back(kv("rate_hz_sim_time", rate));
    st.values.push_back(kv("rate_hz_wall_time", wall_rate));
    st.values.push_back(kv("target_hz", stat.target));
    st.values.push_back(kv("published", static_cast<double>(stat.count)));
    st.values.push_back(kv("renders_total", static_cast<double>(stat.renders)));
    st.level = diagnostic_msgs::DiagnosticStatus::OK;
    line << ", " << stat.name << " ";
    if (stat.count == 0) {
      st.message = "idle (no subscriber)";
      line << "idle";
    } else if (stat.skipped > 0) {
      st.message = "subscribed part of the time";
      line << std::setprecision(1) << rate << "/" << stat.target << " Hz (part time)";
    } else if (rate < 0.9 * stat.target ||
               (real_time_factor_ > 0.0 && wall_rate < 0.9 * stat.target * real_time_factor_)) {
      st.level = diagnostic_msgs::DiagnosticStatus::WARN;
      st.message = "behind its rate";
      ROS_WARN("%s: %.1f Hz in sim time, %.1f Hz in wall time: behind its target %.1f Hz x "
               "real_time_factor %g",
               stat.name.c_str(), rate, wall_rate, stat.target, real_time_factor_);
      line << std::setprecision(1) << rate << "/" << stat.target << " Hz (BEHIND: " << wall_rate
           << " Hz wall)";
    } else {
      st.message = "ok";
      line << std::setprecision(1) << rate << "/" << stat.target << " Hz";
    }
    array.status.push_back(st);
    stat.count = 0;
    stat.skipped = 0;
  }
  ROS_INFO_STREAM(line.str());
  if (diagnostics_pub_) diagnostics_pub_.publish(array);
  status_wall_ = now;
  status_sim_ = sim_->time();
}

void SimNode::setUpProfile() {
  if (!profile_) return;
  rows_ = nodeProfileRows(*profile_);  // registered first by makeNodeProfile()
  profile_service_ = pnh_.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
      "profile", [this](std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
        sim_->waitFrames();  // the frame worker's rows are complete
        res.success = true;
        res.message = profile_->table();
        return true;
      });
  ROS_INFO("~profile: each part of the step is timed; rosservice call %s gives the table",
           profile_service_.getService().c_str());
}

void SimNode::startupMark(const std::string& what) {
  if (startup_logged_) return;
  const auto now = std::chrono::steady_clock::now();
  startup_.emplace_back(what, std::chrono::duration<double, std::milli>(now - startup_last_).count());
  startup_last_ = now;
}

void SimNode::logStartup() {
  std::ostringstream line;
  line << std::fixed << std::setprecision(1) << "start-up: ";
  double all = 0.0;
  for (std::size_t i = 0; i < startup_.size(); ++i) {
    line << (i ? ", " : "") << startup_[i].first << " " << startup_[i].second << " ms";
    all += startup_[i].second;
  }
  line << "; " << all << " ms in all (the node's constructor; xacro, the master and "
       << "robot_state_publisher are other processes)";
  ROS_INFO_STREAM(line.str());
  startup_.clear();
  startup_logged_ = true;
}

}  // namespace tianracer_sim
