// What a controller's update() produced for its ROS side to publish (ros/*_ros.cpp takes it
// after each step), oldest first. A box nobody empties (a host without ROS) keeps the latest
// kLimit samples only.
#ifndef TIANRACER_CONTROL_CONTROLLERS_OUTBOX_H
#define TIANRACER_CONTROL_CONTROLLERS_OUTBOX_H

#include <cstddef>
#include <utility>
#include <vector>

namespace tianracer_control {

template <class T>
class Outbox {
 public:
  static constexpr std::size_t kLimit = 100;

  /// Appends `sample`, dropping the oldest when kLimit are held.
  void post(T sample) {
    if (items_.size() >= kLimit) items_.erase(items_.begin());
    items_.push_back(std::move(sample));
  }
  /// Everything posted since the last take(), oldest first; the box is empty after.
  std::vector<T> take() {
    std::vector<T> out;
    out.swap(items_);
    return out;
  }
  void clear() { items_.clear(); }
  std::size_t size() const { return items_.size(); }

 private:
  std::vector<T> items_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_OUTBOX_H
