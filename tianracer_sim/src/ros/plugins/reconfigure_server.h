// A dynamic_reconfigure server over a handful of double and bool parameters, without
// dynamic_reconfigure's generated Config classes (Debian ships its messages, not its C++
// server): <ns>/set_parameters (dynamic_reconfigure/Reconfigure), <ns>/parameter_descriptions
// and <ns>/parameter_updates (latched), and the values on the parameter server under <ns>, as
// dynamic_reconfigure::Server keeps them (server.h, setConfigCallback): a request is merged
// into the current values, clamped to each parameter's range, and handed to `set` with level 1
// when a value changed; with level 0 (nothing changed) the values are read back with `get`.
// At start, as Server::setCallback calls its callback with level ~0, the values are `get`'s.
// `rosrun dynamic_reconfigure dynparam set <ns> <name> <value>` and rqt_reconfigure use it.
#ifndef TIANRACER_SIM_SRC_ROS_SENSORS_RECONFIGURE_SERVER_H
#define TIANRACER_SIM_SRC_ROS_SENSORS_RECONFIGURE_SERVER_H

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

namespace tianracer_sim {

class ReconfigureServer {
 public:
  struct Param {
    std::string name;
    bool is_bool = false;  // else double
    std::string description;
    double min = 0.0, max = 1.0, dflt = 0.0;
  };
  using Values = std::map<std::string, double>;  // bools as 0 / 1
  using Get = std::function<Values()>;
  using Set = std::function<void(const Values&)>;

  ReconfigureServer(ros::NodeHandle root, const std::string& ns, std::vector<Param> params,
                    Get get, Set set)
      : root_(root), ns_(ns), params_(std::move(params)), get_(std::move(get)),
        set_(std::move(set)) {
    values_ = get_();
    service_ = root_.advertiseService(ns_ + "/set_parameters", &ReconfigureServer::onSet, this);
    descriptions_ = root_.advertise<dynamic_reconfigure::ConfigDescription>(
        ns_ + "/parameter_descriptions", 1, true);
    updates_ = root_.advertise<dynamic_reconfigure::Config>(ns_ + "/parameter_updates", 1, true);
    dynamic_reconfigure::ConfigDescription d;
    dynamic_reconfigure::Group group;
    group.name = "Default";
    group.type = "";
    group.id = 0;
    group.parent = 0;
    Values lo, hi, dflt;
    for (const Param& p : params_) {
      dynamic_reconfigure::ParamDescription pd;
      pd.name = p.name;
      pd.type = p.is_bool ? "bool" : "double";
      pd.level = 1;
      pd.description = p.description;
      pd.edit_method = "";
      group.parameters.push_back(pd);
      lo[p.name] = p.min;
      hi[p.name] = p.max;
      dflt[p.name] = p.dflt;
    }
    d.groups.push_back(group);
    d.min = message(lo);
    d.max = message(hi);
    d.dflt = message(dflt);
    descriptions_.publish(d);
    publish();
  }

  const std::string& ns() const { return ns_; }

 private:
  dynamic_reconfigure::Config message(const Values& v) const {
    dynamic_reconfigure::Config c;
    for (const Param& p : params_) {
      const double x = v.count(p.name) ? v.at(p.name) : p.dflt;
      if (p.is_bool) {
        dynamic_reconfigure::BoolParameter b;
        b.name = p.name;
        b.value = x != 0.0;
        c.bools.push_back(b);
      } else {
        dynamic_reconfigure::DoubleParameter d;
        d.name = p.name;
        d.value = x;
        c.doubles.push_back(d);
      }
    }
    dynamic_reconfigure::GroupState g;
    g.name = "Default";
    g.state = true;
    g.id = 0;
    g.parent = 0;
    c.groups.push_back(g);
    return c;
  }

  void publish() {
    updates_.publish(message(values_));
    for (const Param& p : params_) {
      if (p.is_bool) {
        root_.setParam(ns_ + "/" + p.name, values_[p.name] != 0.0);
      } else {
        root_.setParam(ns_ + "/" + p.name, values_[p.name]);
      }
    }
  }

  const Param* find(const std::string& name, bool is_bool) const {
    for (const Param& p : params_) {
      if (p.name == name && p.is_bool == is_bool) return &p;
    }
    return nullptr;  // not ours: ignored, as Config::__fromMessage__ ignores it
  }

  bool onSet(dynamic_reconfigure::Reconfigure::Request& req,
             dynamic_reconfigure::Reconfigure::Response& res) {
    Values next = values_;
    for (const auto& d : req.config.doubles) {
      if (const Param* p = find(d.name, false)) {
        // NaN is not within the range: clamped to the minimum (as __clamp__'s comparisons do
        // not, we refuse to hand a NaN to the model).
        const double v = std::isnan(d.value) ? p->min : d.value;
        next[p->name] = std::min(std::max(v, p->min), p->max);
      }
    }
    for (const auto& b : req.config.bools) {
      if (const Param* p = find(b.name, true)) next[p->name] = b.value ? 1.0 : 0.0;
    }
    if (next != values_) {
      set_(next);  // level 1
    } else {
      next = get_();  // level 0: the callback reads the model's values
    }
    values_ = next;
    publish();
    res.config = message(values_);
    return true;
  }

  ros::NodeHandle root_;
  std::string ns_;
  std::vector<Param> params_;
  Get get_;
  Set set_;
  Values values_;
  ros::ServiceServer service_;
  ros::Publisher descriptions_, updates_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_ROS_SENSORS_RECONFIGURE_SERVER_H
