// ros_controllers-style joint controllers run inside the simulator's step loop. ROS-free: the ROS
// adapter (tianracer_control/ros/) turns the parameter server into ControllerSpecs and command
// topics into setCommand(); all validation lives here so that it is unit tested.
// One header for the simulator: the base (controller.h), the registry by type name, the set of a
// robot's controllers, and the joint state controller (the host publishes when it is due). The
// other classes, one per file under controllers/, are reached through the registry.
#ifndef TIANRACER_CONTROL_JOINT_CONTROLLERS_H
#define TIANRACER_CONTROL_JOINT_CONTROLLERS_H

#include "tianracer_control/controller.h"
#include "tianracer_control/controller_params.h"
#include "tianracer_control/controller_registry.h"
#include "tianracer_control/controller_set.h"
#include "tianracer_control/controllers/joint_state_controller.h"
#include "tianracer_control/pid_params.h"

#endif  // TIANRACER_CONTROL_JOINT_CONTROLLERS_H
