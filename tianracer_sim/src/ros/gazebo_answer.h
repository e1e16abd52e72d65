// How the Gazebo services answer (gazebo_ros_api_plugin.cpp): success with a status text, or
// success false with the reason. The call itself always succeeds (the handler returns true).
#ifndef TIANRACER_SIM_SRC_ROS_GAZEBO_ANSWER_H
#define TIANRACER_SIM_SRC_ROS_GAZEBO_ANSWER_H

#include <string>
#include <utility>

#include <ros/console.h>

#include "tianracer_sim/common/diagnostic.h"

namespace tianracer_sim {

/// success true with `status`.
template <class Response>
bool succeeded(Response& res, const std::string& status) {
  res.success = true;
  res.status_message = status;
  return true;
}

/// A failed call's status: prefix + the InputError's text + suffix, warned unless !warn.
struct OnInputError {
  OnInputError(std::string prefix = "", std::string suffix = "", bool warn = true)
      : prefix(std::move(prefix)), suffix(std::move(suffix)), warn(warn) {}
  std::string prefix;
  std::string suffix;
  bool warn;
};

/// Runs `work`, which fills the response and returns the success status; when it throws
/// InputError, success is false with the status `on_error` makes of it.
template <class Response, class Work>
bool answer(Response& res, const OnInputError& on_error, Work&& work) {
  res.success = false;
  try {
    const std::string status = work();
    return succeeded(res, status);
  } catch (const InputError& e) {
    res.status_message = on_error.prefix + e.what() + on_error.suffix;
    if (on_error.warn) ROS_WARN_STREAM(res.status_message);
  }
  return true;
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_ROS_GAZEBO_ANSWER_H
