#include "tianracer_sim/physics/rigid_tree.h"

#include <cmath>
#include <sstream>

#include "tianracer_sim/common/input_limits.h"

namespace tianracer_sim {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  if (q.norm() > 0.0) X.linear() = q.normalized().toRotationMatrix();
  return X;
}

MassProperties linkMassProperties(const urdf::Link& link) {
  MassProperties m;
  if (!link.inertial) return m;
  const urdf::Inertial& in = *link.inertial;
  MassProperties m_I;  // in the inertial frame
  m_I.mass = in.mass;
  m_I.inertia << in.ixx, in.ixy, in.ixz,  //
      in.ixy, in.iyy, in.iyz,             //
      in.ixz, in.iyz, in.izz;
  // The COM is the inertial frame's origin: transform (mass at origin) into the link frame.
  return transformMassProperties(m_I, toIsometry(in.origin));
}

bool shapeFromUrdf(const urdf::Geometry& geometry,
                   const std::function<std::string(const std::string&)>& resolve_mesh,
                   Shape* shape) {
  switch (geometry.type) {
    case urdf::Geometry::BOX: {
      const auto& b = static_cast<const urdf::Box&>(geometry);
      shape->type = ShapeType::kBox;
      shape->size = Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z);
      return true;
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(geometry);
      shape->type = ShapeType::kCylinder;
      shape->radius = c.radius;
      shape->length = c.length;
      return true;
    }
    case urdf::Geometry::SPHERE: {
      shape->type = ShapeType::kSphere;
      shape->radius = static_cast<const urdf::Sphere&>(geometry).radius;
      return true;
    }
    case urdf::Geometry::MESH: {
      const auto& m = static_cast<const urdf::Mesh&>(geometry);
      const std::string path = resolve_mesh(m.filename);
      if (path.empty()) return false;
      shape->type = ShapeType::kMesh;
      shape->mesh_path = path;
      shape->scale = Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z);
      return true;
    }
  }
  return false;
}

namespace {

std::string resolveMesh(const std::string& uri, const std::map<std::string, std::string>& paths,
                        const std::string& link) {
  auto it = paths.find(uri);
  if (it != paths.end()) return it->second;
  if (uri.rfind("file://", 0) == 0) return uri.substr(7);
  if (!uri.empty() && uri[0] == '/') return uri;
  throw PhysicsError("link '" + link + "': mesh '" + uri + "' was not resolved to a file");
}

void addCollisions(const urdf::Link& link, const Eigen::Isometry3d& X_BL,
                   const std::map<std::string, std::string>& mesh_paths,
                   const ElementLines& lines, TreeBody* body) {
  for (const auto& col : link.collision_array) {
    if (!col || !col->geometry) continue;
    CollisionGeometry g;
    g.link = link.name;
    g.X_BG = X_BL * toIsometry(col->origin);
    const auto resolve = [&](const std::string& uri) {
      g.mesh_uri = uri;
      try {
        return resolveMesh(uri, mesh_paths, link.name);
      } catch (const PhysicsError& e) {
        throw PhysicsError(lines.link(link.name) + e.what());
      }
    };
    if (!shapeFromUrdf(*col->geometry, resolve, &g.shape))
      throw PhysicsError(lines.link(link.name) + "link '" + link.name +
                         "': unsupported collision geometry type");
    body->collisions.push_back(g);
  }
}

class TreeBuilder {
 public:
  TreeBuilder(const std::map<std::string, std::string>& mesh_paths, const ElementLines& lines,
              RigidTree* tree)
      : mesh_paths_(mesh_paths), lines_(lines), tree_(tree) {}

  // Adds `link` (placed at X_BL in body `b`) and, recursively, everything below it.
  void visit(const urdf::Link& link, int b, const Eigen::Isometry3d& X_BL) {
    TreeBody& body = tree_->bodies[b];
    body.merged_links.push_back(link.name);
    body.X_BL[link.name] = X_BL;
    tree_->links[link.name] = {b, X_BL};
    body.mass = combineMassProperties(body.mass,
                                      transformMassProperties(linkMassProperties(link), X_BL));
    addCollisions(link, X_BL, mesh_paths_, lines_, &body);

    for (const auto& joint : link.child_joints) {
      const urdf::LinkConstSharedPtr child = findChild(link, joint->child_link_name);
      const Eigen::Isometry3d X_BC = X_BL * toIsometry(joint->parent_to_joint_origin_transform);
      if (joint->type == urdf::Joint::FIXED) {
        visit(*child, b, X_BC);
        continue;
      }
      TreeBody nb;
      nb.link = child->name;
      nb.parent = b;
      nb.joint = joint->name;
      nb.X_PB = X_BC;
      switch (joint->type) {
        case urdf::Joint::REVOLUTE: nb.joint_type = TreeJointType::kRevolute; break;
        case urdf::Joint::CONTINUOUS: nb.joint_type = TreeJointType::kContinuous; break;
        case urdf::Joint::PRISMATIC: nb.joint_type = TreeJointType::kPrismatic; break;
        default:
          throw PhysicsError(lines_.joint(joint->name) + "joint '" + joint->name +
                             "': only fixed, revolute, continuous and prismatic joints are "
                             "supported inside a robot");
      }
      // Normalised without overflow (an axis of 1e308 once normalised to zero).
      const std::optional<Eigen::Vector3d> axis =
          limits::unitAxis(Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z));
      if (!axis) {
        throw PhysicsError(lines_.joint(joint->name) + "joint '" + joint->name +
                           "': zero or invalid axis");
      }
      nb.axis_B = *axis;
      if (joint->limits) {
        nb.effort_limit = std::max(0.0, joint->limits->effort);
        nb.velocity_limit = std::max(0.0, joint->limits->velocity);
        if (nb.joint_type != TreeJointType::kContinuous &&
            joint->limits->lower < joint->limits->upper) {
          nb.has_position_limits = true;
          nb.lower = joint->limits->lower;
          nb.upper = joint->limits->upper;
        }
      }
      if (joint->dynamics) {
        nb.damping = std::max(0.0, joint->dynamics->damping);
        nb.friction = std::max(0.0, joint->dynamics->friction);
      }
      tree_->bodies.push_back(nb);
      visit(*child, static_cast<int>(tree_->bodies.size()) - 1, Eigen::Isometry3d::Identity());
    }
  }

 private:
  static urdf::LinkConstSharedPtr findChild(const urdf::Link& link, const std::string& name) {
    for (const auto& c : link.child_links) {
      if (c->name == name) return c;
    }
    throw PhysicsError("link '" + link.name + "': child link '" + name + "' not found");
  }

  const std::map<std::string, std::string>& mesh_paths_;
  const ElementLines& lines_;
  RigidTree* tree_;
};

}  // namespace

void setLinkGravityFree(const urdf::ModelInterface& urdf, const std::string& link, RigidTree* tree) {
  const auto it = tree->links.find(link);
  const urdf::LinkConstSharedPtr l = urdf.getLink(link);
  if (it == tree->links.end() || !l) return;
  TreeBody& body = tree->bodies[it->second.first];
  body.gravity_free =
      combineMassProperties(body.gravity_free, transformMassProperties(linkMassProperties(*l), it->second.second));
}

RigidTree buildRigidTree(const urdf::ModelInterface& urdf,
                         const std::map<std::string, std::string>& mesh_paths,
                         const ElementLines& lines, const WarningSink& warn) {
  const urdf::LinkConstSharedPtr root = urdf.getRoot();
  if (!root) throw PhysicsError("robot '" + urdf.getName() + "': no root link");
  RigidTree tree;
  tree.fixed_base = root->name == "world";
  TreeBody base;
  base.link = root->name;
  tree.bodies.push_back(base);
  TreeBuilder(mesh_paths, lines, &tree).visit(*root, 0, Eigen::Isometry3d::Identity());

  for (std::size_t i = 0; i < tree.bodies.size(); ++i) {
    const TreeBody& b = tree.bodies[i];
    if (i == 0 && tree.fixed_base) continue;
    if (!(b.mass.mass > 0.0)) {
      std::ostringstream os;
      os << lines.link(b.link) << "link '" << b.link << "'"
         << (i == 0 ? " (root, with its fixed children)" : " (child of joint '" + b.joint + "')")
         << ": a moving body needs a positive mass, got " << b.mass.mass;
      throw PhysicsError(os.str());
    }
    if (!isPositiveDefiniteInertia(b.mass.inertia)) {
      std::ostringstream os;
      os << lines.link(b.link) << "link '" << b.link
         << "': the inertia of the links moving with it is not positive definite:\n"
         << b.mass.inertia;
      throw PhysicsError(os.str());
    }
    if (!isPhysicalInertia(b.mass.inertia) && warn) {
      // The one rule for robots and world models (sim/world_physics.cpp): no rigid body has
      // such moments, but ODE checks only that the inertia is positive definite (dMassCheck),
      // so Gazebo simulates it as given. So do we, with a warning.
      const Eigen::Vector3d I = principalInertia(b.mass.inertia).moments;
      std::ostringstream os;
      os << lines.link(b.link) << "link '" << b.link
         << "': the principal moments of inertia of the links moving with it, (" << I.x() << " "
         << I.y() << " " << I.z() << "), violate the triangle inequality (each at most the sum "
         << "of the other two); simulated as given, as Gazebo does";
      warn(os.str());
    }
  }
  return tree;
}

}  // namespace tianracer_sim
