#include "tianracer_sim/sim/world_physics.h"

namespace tianracer_sim {

PhysicsOptions physicsOptionsFor(const WorldDescription& world, PhysicsOptions base) {
  base.dt = world.physics.max_step_size;
  base.gravity = world.physics.gravity;
  base.ground_plane = world.ground_plane;
  base.ground_mu = world.ground_friction.mu;
  base.ground_mu2 = world.ground_friction.mu2;
  return base;
}

int addWorldToPhysics(const WorldDescription& world, PhysicsWorld* physics,
                      const WarningSink& warn) {
  int added = 0;
  for (const ModelDescription& model : world.models) {
    if (!model.is_static && warn) {
      warn(world.source + ": model '" + model.name +
           "' is dynamic; it is simulated as static (free rigid bodies are not supported yet)");
    }
    for (const LinkDescription& link : model.links) {
      for (const CollisionDescription& c : link.collisions) {
        StaticShape s;
        s.name = model.name + "::" + link.name + "::" + c.name;
        s.X_WS = model.X_WM * link.X_ML * c.X_LS;
        s.surface.mu1 = c.friction.mu;
        s.surface.mu2 = c.friction.mu2;
        switch (c.shape.type) {
          case ShapeType::kBox:
            s.type = StaticShape::Type::kBox;
            s.size = c.shape.size;
            break;
          case ShapeType::kCylinder:
            s.type = StaticShape::Type::kCylinder;
            s.size = Eigen::Vector3d(c.shape.radius, c.shape.radius, c.shape.length);
            break;
          case ShapeType::kSphere:
            s.type = StaticShape::Type::kSphere;
            s.size = Eigen::Vector3d::Constant(c.shape.radius);
            break;
          case ShapeType::kPlane:
            s.type = StaticShape::Type::kPlane;
            s.size = c.shape.normal;
            break;
          case ShapeType::kMesh:
            s.type = StaticShape::Type::kMesh;
            s.mesh_path = c.shape.mesh_path;
            s.mesh_scale = c.shape.scale;
            break;
        }
        physics->addStaticShape(s);
        ++added;
      }
    }
  }
  return added;
}

}  // namespace tianracer_sim
