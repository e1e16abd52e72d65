// gazebo_ros's world interface (gazebo_ros_api_plugin) with gazebo_msgs types, over the
// Simulator: /gazebo/model_states and /gazebo/link_states, the set_model_state and
// set_link_state topics, and the services get/set_model_state, get/set_link_state,
// get_model_properties, get_world_properties, apply_body_wrench and clear_body_wrenches,
// pause_physics, unpause_physics, reset_simulation and reset_world (std_srvs/Empty),
// spawn_urdf_model, spawn_sdf_model and delete_model (checked here, carried out by the owner's
// ModelSpawner).
// Entities are gazebo_ros's: a model by name (a robot, or a model of the world file, the
// ground plane included), a link as "model::link". What differs from gazebo_ros is listed in
// docs/gazebo_interface.md.
//
// The owner (the sim node) calls beforeStep() before and afterStep() after each physics step;
// callbacks run on the owner's callback queue, between steps.
#ifndef TIANRACER_SIM_ROS_GAZEBO_INTERFACE_H
#define TIANRACER_SIM_ROS_GAZEBO_INTERFACE_H

#include <string>
#include <vector>

#include <dynamic_reconfigure/Reconfigure.h>
#include <gazebo_msgs/ApplyBodyWrench.h>
#include <gazebo_msgs/ApplyJointEffort.h>
#include <gazebo_msgs/DeleteLight.h>
#include <gazebo_msgs/GetJointProperties.h>
#include <gazebo_msgs/GetLightProperties.h>
#include <gazebo_msgs/GetLinkProperties.h>
#include <gazebo_msgs/GetPhysicsProperties.h>
#include <gazebo_msgs/JointRequest.h>
#include <gazebo_msgs/SetJointProperties.h>
#include <gazebo_msgs/SetLightProperties.h>
#include <gazebo_msgs/SetLinkProperties.h>
#include <gazebo_msgs/SetModelConfiguration.h>
#include <gazebo_msgs/SetPhysicsProperties.h>
#include <gazebo_msgs/BodyRequest.h>
#include <gazebo_msgs/DeleteModel.h>
#include <gazebo_msgs/GetLinkState.h>
#include <gazebo_msgs/GetModelProperties.h>
#include <gazebo_msgs/GetModelState.h>
#include <gazebo_msgs/GetWorldProperties.h>
#include <gazebo_msgs/LinkStates.h>
#include <gazebo_msgs/ModelStates.h>
#include <gazebo_msgs/SetLinkState.h>
#include <gazebo_msgs/SetModelState.h>
#include <gazebo_msgs/SpawnModel.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include "tianracer_sim/ros/service_advertiser.h"
#include "tianracer_sim/simulator/entity_state.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// What adds and removes models at run time: the sim node, which builds them as at start-up.
/// Called between steps with a name that is new (spawn) or known (delete) and a finite pose
/// within checkModelState's bounds. Each throws std::exception saying what is wrong; nothing
/// of the model stays then.
class ModelSpawner {
 public:
  virtual ~ModelSpawner() = default;
  /// A robot from URDF (xacro already expanded) with its plugins, sensors and controllers.
  virtual void spawnRobot(const std::string& name, const std::string& urdf,
                          const Eigen::Isometry3d& X_WB) = 0;
  /// A world model from SDF (<sdf><model> or <model>), static or a free body; X_WM is where
  /// its frame goes (the model's own <pose> is composed after it).
  virtual void spawnWorldModel(const std::string& name, const std::string& sdf,
                               const Eigen::Isometry3d& X_WM) = 0;
  virtual void deleteModel(const std::string& name) = 0;
};

/// The URDF with <robotNamespace>robot_namespace</robotNamespace> added to every <plugin>
/// that has none, as gazebo_ros's spawn_urdf_model does (unchanged when robot_namespace is
/// empty). Throws std::runtime_error for malformed XML, naming the line.
std::string withRobotNamespace(const std::string& urdf, const std::string& robot_namespace);

class GazeboInterface {
 public:
  struct Options {
    /// model_states / link_states per sim second; 0 = every step. gazebo_ros publishes at
    /// every step (1 kHz), more than a rospy subscriber reads; 50 Hz is the ground truth's and
    /// joint_states' rate, on the same steps, so a relay's odometry lines up with them.
    double states_rate = 50.0;
    /// gazebo_ros's ~enable_ros_network: false = none of the /gazebo topics and services
    /// (/clock stays, it is the owner's).
    bool enable_ros_network = true;
  };

  /// Advertises on `gazebo_nh` (the /gazebo namespace, with the owner's callback queue). The
  /// spawn and delete services only with a spawner. `after_reset` is called once
  /// reset_simulation has brought the Simulator back to time 0 (the owner restarts its own
  /// schedules and /clock).
  GazeboInterface(ros::NodeHandle gazebo_nh, Simulator& sim, const Options& options,
                  ModelSpawner* spawner = nullptr, std::function<void()> after_reset = {});

  /// Applies the external wrenches due in the coming step.
  void beforeStep();
  /// Publishes model_states and link_states when due (and subscribed).
  void afterStep();
  /// Models were added or removed: the state messages are rebuilt before the next publish.
  void onModelsChanged() { msgs_valid_ = false; }

  // The handlers, public so that tests and the topics share them. Each answers success false
  // with a message naming the entity and the value on bad input, and changes nothing then.
  bool getModelState(gazebo_msgs::GetModelState::Request& req,
                     gazebo_msgs::GetModelState::Response& res);
  bool setModelState(gazebo_msgs::SetModelState::Request& req,
                     gazebo_msgs::SetModelState::Response& res);
  bool getLinkState(gazebo_msgs::GetLinkState::Request& req,
                    gazebo_msgs::GetLinkState::Response& res);
  bool setLinkState(gazebo_msgs::SetLinkState::Request& req,
                    gazebo_msgs::SetLinkState::Response& res);
  bool getModelProperties(gazebo_msgs::GetModelProperties::Request& req,
                          gazebo_msgs::GetModelProperties::Response& res);
  bool getWorldProperties(gazebo_msgs::GetWorldProperties::Request& req,
                          gazebo_msgs::GetWorldProperties::Response& res);
  bool applyBodyWrench(gazebo_msgs::ApplyBodyWrench::Request& req,
                       gazebo_msgs::ApplyBodyWrench::Response& res);
  bool clearBodyWrenches(gazebo_msgs::BodyRequest::Request& req,
                         gazebo_msgs::BodyRequest::Response& res);
  bool spawnUrdfModel(gazebo_msgs::SpawnModel::Request& req,
                      gazebo_msgs::SpawnModel::Response& res);
  bool spawnSdfModel(gazebo_msgs::SpawnModel::Request& req,
                     gazebo_msgs::SpawnModel::Response& res);
  bool deleteModel(gazebo_msgs::DeleteModel::Request& req,
                   gazebo_msgs::DeleteModel::Response& res);
  bool pausePhysics(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool unpausePhysics(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  /// Time to 0, models to their spawn poses, controllers and sensors restarted, wrenches gone.
  bool resetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  /// Poses only; time keeps running.
  bool resetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  // Properties (gazebo_properties.cpp): the Simulator's state changes behind gazebo_ros's
  // services of the same names.
  bool getJointProperties(gazebo_msgs::GetJointProperties::Request& req,
                          gazebo_msgs::GetJointProperties::Response& res);
  bool setJointProperties(gazebo_msgs::SetJointProperties::Request& req,
                          gazebo_msgs::SetJointProperties::Response& res);
  bool getPhysicsProperties(gazebo_msgs::GetPhysicsProperties::Request& req,
                            gazebo_msgs::GetPhysicsProperties::Response& res);
  bool setPhysicsProperties(gazebo_msgs::SetPhysicsProperties::Request& req,
                            gazebo_msgs::SetPhysicsProperties::Response& res);
  bool getLightProperties(gazebo_msgs::GetLightProperties::Request& req,
                          gazebo_msgs::GetLightProperties::Response& res);
  bool setLightProperties(gazebo_msgs::SetLightProperties::Request& req,
                          gazebo_msgs::SetLightProperties::Response& res);
  bool deleteLight(gazebo_msgs::DeleteLight::Request& req, gazebo_msgs::DeleteLight::Response& res);
  bool getLinkProperties(gazebo_msgs::GetLinkProperties::Request& req,
                         gazebo_msgs::GetLinkProperties::Response& res);
  bool setLinkProperties(gazebo_msgs::SetLinkProperties::Request& req,
                         gazebo_msgs::SetLinkProperties::Response& res);
  bool setModelConfiguration(gazebo_msgs::SetModelConfiguration::Request& req,
                             gazebo_msgs::SetModelConfiguration::Response& res);
  bool applyJointEffort(gazebo_msgs::ApplyJointEffort::Request& req,
                        gazebo_msgs::ApplyJointEffort::Response& res);
  bool clearJointForces(gazebo_msgs::JointRequest::Request& req,
                        gazebo_msgs::JointRequest::Response& res);
  /// dynamic_reconfigure's set_parameters over the physics properties (gazebo_ros's
  /// physics reconfigure: its parameter names).
  bool setParameters(dynamic_reconfigure::Reconfigure::Request& req,
                     dynamic_reconfigure::Reconfigure::Response& res);

 private:
  /// Applies the joint efforts due in the coming step (and clears those that ended).
  void applyJointEfforts();
  /// The entity and the reference frame a request names (Entities::find(), then frame());
  /// when either fails, !ok and `error` says what is wrong.
  struct Target {
    Entity entity;
    EntityState frame;
    std::string error;
    bool ok = false;
  };
  Target target(const std::string& name, bool allow_model,
                const std::string& reference_frame) const;
  void rebuildStateMessages();
  void onModelStateTopic(const gazebo_msgs::ModelState::ConstPtr& msg);
  void onLinkStateTopic(const gazebo_msgs::LinkState::ConstPtr& msg);
  /// Both spawn services: checks the request, then hands it to the spawner by the XML's root
  /// element (<robot>: a robot, <sdf>/<model>: a world model).
  bool spawn(const std::string& service, gazebo_msgs::SpawnModel::Request& req,
             gazebo_msgs::SpawnModel::Response& res);
  /// Time went back or the world was reset: wrenches are cleared and the publishing schedule
  /// restarts.
  void onReset();
  /// The properties services (gazebo_properties.cpp) and the physics reconfigure topics.
  void advertiseProperties(ServiceAdvertiser<GazeboInterface>& serve, ros::NodeHandle& nh);
  /// The physics properties as dynamic_reconfigure's Config, published on parameter_updates.
  void publishPhysicsConfig();

  /// apply_joint_effort's jobs (gazebo_ros's ForceJointJob): effort from start to end.
  struct JointEffortJob {
    std::string joint;
    double effort = 0.0, start = 0.0, end = 0.0;  // end < 0: until cleared
  };
  std::vector<JointEffortJob> joint_efforts_;
  std::vector<std::string> joints_pushed_;  // joints with an effort applied in the last step
  ros::Publisher reconfigure_descriptions_pub_, reconfigure_updates_pub_;

  Simulator& simulator_;
  Entities entities_;  // the one name resolver (simulator/entities.h)
  const WorldDescription& world_;
  Options options_;
  ModelSpawner* spawner_ = nullptr;
  std::function<void()> after_reset_;
  WrenchSchedule wrenches_;

  ros::Publisher model_states_pub_, link_states_pub_;
  ros::Subscriber set_model_state_sub_, set_link_state_sub_;
  std::vector<ros::ServiceServer> services_;
  double period_ = 0.0, next_ = 0.0;  // publishing schedule (sim time)
  // The state messages' slots were built for this Simulator::modelsVersion() (a model added or
  // removed, even one for another of the same count, rebuilds them).
  std::uint64_t msgs_models_version_ = 0;
  bool msgs_valid_ = false;
  gazebo_msgs::ModelStates model_states_;
  gazebo_msgs::LinkStates link_states_;
  /// What each entry of the messages is (Entities::models(), links()): read each time when it
  /// moves, filled in once for a static model.
  std::vector<Entity> model_slots_, link_slots_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_GAZEBO_INTERFACE_H
