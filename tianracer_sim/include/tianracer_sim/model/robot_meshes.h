// A robot's mesh files read as the simulator reads them, so that a tool (model_info) reports
// what the simulator would at start-up. ROS-free.
#ifndef TIANRACER_SIM_MODEL_ROBOT_MESHES_H
#define TIANRACER_SIM_MODEL_ROBOT_MESHES_H

#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {

/// Reads every mesh of `model` (resolved in model.mesh_paths; unresolved ones are skipped)
/// through the process-wide mesh cache: each <collision> mesh as the physics loads it (its
/// file and <mesh scale>), each <visual> mesh as the renderer draws it (with its materials).
/// A collision mesh that cannot be used stops the simulator: here it throws ModelError
/// "<source>: link '<link>' collision mesh '<uri>': <the loader's message>". A visual mesh the
/// renderer would skip is a warning, the same text ending "; the renderer leaves it out".
/// Returns the number of mesh files read.
int readRobotMeshes(const RobotModel& model, const WarningSink& warn);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_MODEL_ROBOT_MESHES_H
