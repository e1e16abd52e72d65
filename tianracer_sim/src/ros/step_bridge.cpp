#include "tianracer_sim/ros/step_bridge.h"

namespace tianracer_sim {

namespace {

/// A callback that does nothing: posted on the node's queue, it ends the run loop's wait.
class Wake : public ros::CallbackInterface {
 public:
  CallResult call() override { return Success; }
};

}  // namespace

StepBridge::StepBridge(const ros::NodeHandle& pnh, Simulator& sim, ros::CallbackQueue* wake,
                       Hooks hooks)
    : sim_(sim), wake_(wake), hooks_(std::move(hooks)) {
  ros::NodeHandle nh(pnh);
  nh.setCallbackQueue(&queue_);
  service_ = nh.advertiseService("step", &StepBridge::onStep, this);
  action_ = std::make_unique<actionlib::SimpleActionServer<StepAndWaitAction>>(
      nh, "step_and_wait", [this](const StepAndWaitGoalConstPtr& g) { onStepAndWait(g); }, false);
  action_->start();
  // Two threads: a ~step call waiting (calls of it are taken one at a time) does not hold up
  // the action server's goal and cancel messages; its goals run on a thread of its own.
  spinner_ = std::make_unique<ros::AsyncSpinner>(2, &queue_);
  spinner_->start();
}

StepBridge::~StepBridge() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    for (const auto& r : pending_) {
      r->finished = true;
      r->message = "the simulator is shutting down";
    }
    pending_.clear();
  }
  changed_.notify_all();
  action_->shutdown();
  spinner_->stop();
}

void StepBridge::call(const std::shared_ptr<Request>& r,
                      const std::function<bool(const Request&)>& progress) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (stopping_) {
    r->message = "the simulator is shutting down";
    return;
  }
  pending_.push_back(r);
  wake_->addCallback(boost::make_shared<Wake>());
  while (!r->finished && !stopping_) {
    changed_.wait_for(lock, std::chrono::milliseconds(100));
    if (progress && !r->finished) {
      const Request copy = *r;
      lock.unlock();
      const bool cancel = progress(copy);
      lock.lock();
      if (cancel) r->cancel = true;
    }
  }
}

bool StepBridge::serve() {
  std::shared_ptr<Request> r;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pending_.empty()) return false;
    r = pending_.front();
  }
  sim_.setPaused(true);  // as Gazebo's step: the simulation waits after the steps
  if (hooks_.begin) hooks_.begin();
  std::uint32_t done = 0;
  bool cancelled = false;
  while (done < r->steps && ros::ok()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (r->cancel) {
        cancelled = true;
        break;
      }
    }
    hooks_.step();
    ++done;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      r->done = done;
      r->time = sim_.time();
    }
    changed_.notify_all();
  }
  if (hooks_.finish) hooks_.finish();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.pop_front();
    r->finished = true;
    r->success = done == r->steps;
    r->message = r->success ? "stepped " + std::to_string(done) + " steps"
                            : std::string(cancelled ? "cancelled" : "the node is shutting down") +
                                  " after " + std::to_string(done) + " of " +
                                  std::to_string(r->steps) + " steps";
    r->sim_time = sim_.time();
    r->step_count = sim_.stepCount();
  }
  changed_.notify_all();
  return true;
}

bool StepBridge::onStep(Step::Request& req, Step::Response& res) {
  auto r = std::make_shared<Request>();
  r->steps = req.steps;
  if (r->steps == 0) {
    res.success = false;
    res.status_message = "steps must be at least 1, got 0";
    res.sim_time = ros::Time(sim_.time());
    res.step_count = sim_.stepCount();
    return true;
  }
  call(r);
  res.success = r->success;
  res.status_message = r->message;
  res.sim_time = ros::Time(r->sim_time);
  res.step_count = r->step_count;
  return true;
}

void StepBridge::onStepAndWait(const StepAndWaitGoalConstPtr& goal) {
  StepAndWaitResult result;
  auto r = std::make_shared<Request>();
  r->steps = goal->steps;
  if (r->steps == 0) {
    result.success = false;
    result.status_message = "steps must be at least 1, got 0";
    action_->setAborted(result, result.status_message);
    return;
  }
  std::uint32_t reported = 0;
  call(r, [this, &reported](const Request& now) {
    if (now.done != reported) {
      StepAndWaitFeedback feedback;
      feedback.steps_done = reported = now.done;
      feedback.sim_time = ros::Time(now.time);
      action_->publishFeedback(feedback);
    }
    return action_->isPreemptRequested() || !ros::ok();
  });
  result.success = r->success;
  result.status_message = r->message;
  result.sim_time = ros::Time(r->sim_time);
  result.step_count = r->step_count;
  result.steps_done = r->done;
  if (r->success) {
    action_->setSucceeded(result, r->message);
  } else if (r->cancel) {
    action_->setPreempted(result, r->message);
  } else {
    action_->setAborted(result, r->message);
  }
}

}  // namespace tianracer_sim
