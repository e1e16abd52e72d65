#include "tianracer_control/urdf_geometry.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include <Eigen/Geometry>
#include <tianracer_assets/mesh.h>
#include <tianracer_assets/wheel_fit.h>
#include <urdf_parser/urdf_parser.h>

namespace tianracer_control {

namespace {

Eigen::Isometry3d toEigen(const urdf::Pose& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  X.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return X;
}

// Pose of `link` in `base`, walking up the tree; false if base is not an ancestor.
bool poseInBase(const urdf::ModelInterface& model, const std::string& base, const std::string& link,
                Eigen::Isometry3d* X_BL) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  urdf::LinkConstSharedPtr l = model.getLink(link);
  while (l && l->name != base) {
    const urdf::JointSharedPtr& j = l->parent_joint;
    if (!j) return false;
    X = toEigen(j->parent_to_joint_origin_transform) * X;
    l = model.getLink(j->parent_link_name);
  }
  if (!l) return false;
  *X_BL = X;
  return true;
}

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

const std::vector<std::string>& geometryKeys() {
  static const std::vector<std::string> keys = {
      "wheelbase",   "hinge_separation", "wheel_radius", "rear_track",    "max_steering_angle",
      "rear_axle_x", "rear_axle_y",      "hinge_skew_x", "hinge_offset_y"};
  return keys;
}

namespace {

// Names of `names` equal to `wanted`, else those ending in "/wanted" or "_wanted".
std::vector<std::string> matchName(const std::vector<std::string>& names, const std::string& wanted) {
  for (const std::string& n : names) {
    if (n == wanted) return {n};
  }
  std::vector<std::string> out;
  for (const std::string& n : names) {
    if (n.size() <= wanted.size() || n.compare(n.size() - wanted.size(), wanted.size(), wanted))
      continue;
    const char sep = n[n.size() - wanted.size() - 1];
    if (sep == '/' || sep == '_') out.push_back(n);
  }
  return out;
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
  return s;
}

}  // namespace

ModelNames findModelNames(const std::string& urdf_xml, const AckermannJointNames& wanted,
                          const std::string& base_link) {
  if (urdf_xml.empty()) throw AckermannError("robot_description is empty");
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw AckermannError("robot_description does not parse as URDF");
  std::vector<std::string> joints, links;
  for (const auto& kv : model->joints_) joints.push_back(kv.first);
  for (const auto& kv : model->links_) links.push_back(kv.first);

  ModelNames out;
  out.joints = wanted;
  out.base_link = base_link;
  const AckermannJointNames defaults;
  std::vector<std::string> prefixes;
  const auto find = [&](const std::string& param, std::string* name, const std::vector<std::string>& pool,
                        const char* what) {
    const std::vector<std::string> m = matchName(pool, *name);
    const std::string looked = "'" + *name + "' or a name ending in '/" + *name + "' or '_" +
                               *name + "'";
    if (m.size() == 1) {
      if (m[0] != *name) {
        out.found.push_back(std::string(what) + " '" + m[0] + "' for ~" + param + " '" + *name + "'");
        prefixes.push_back(m[0].substr(0, m[0].size() - name->size()));
        *name = m[0];
      } else {
        prefixes.push_back("");
      }
      return true;
    }
    out.warnings.push_back(
        m.empty() ? std::string("no ") + what + " " + looked + " in the URDF: set ~" + param +
                        " to the model's name"
                  : std::string("several ") + what + "s match " + looked + " (" + joinNames(m) +
                        "): set ~" + param + " to the one to use");
    return false;
  };
  find(defaults.left_hinge, &out.joints.left_hinge, joints, "joint");
  find(defaults.right_hinge, &out.joints.right_hinge, joints, "joint");
  find(defaults.left_rear_wheel, &out.joints.left_rear_wheel, joints, "joint");
  find(defaults.right_rear_wheel, &out.joints.right_rear_wheel, joints, "joint");
  const bool one_prefix =
      !prefixes.empty() &&
      std::all_of(prefixes.begin(), prefixes.end(), [&](const std::string& p) { return p == prefixes[0]; });
  if (one_prefix) out.prefix = prefixes[0];

  if (!base_link.empty()) {
    const std::vector<std::string> m = matchName(links, base_link);
    if (m.size() == 1) {
      out.base_link = m[0];
    } else if (!out.prefix.empty() && model->getLink(out.prefix + base_link)) {
      out.base_link = out.prefix + base_link;  // several candidates: the joints' prefix decides
    }
    if (out.base_link != base_link) {
      out.found.push_back("link '" + out.base_link + "' for ~base_frame '" + base_link + "'");
    }
  }
  return out;
}

UrdfGeometry geometryFromUrdf(const std::string& urdf_xml, const AckermannJointNames& names,
                              const std::string& base_link, const MeshPathResolver& mesh_path) {
  if (urdf_xml.empty()) throw AckermannError("robot_description is empty");
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) throw AckermannError("robot_description does not parse as URDF");

  UrdfGeometry out;
  std::string base = base_link;
  if (base.empty() || !model->getLink(base)) {
    const std::string root = model->getRoot() ? model->getRoot()->name : "";
    if (!base.empty()) {
      out.warnings.push_back("link '" + base + "' not in the URDF; using the root link '" + root +
                             "' as the base frame");
    }
    base = root;
  }

  // Joint origin of `name` in the base frame.
  struct Found {
    urdf::JointConstSharedPtr joint;
    Eigen::Vector3d p_B = Eigen::Vector3d::Zero();
    bool ok = false;
  };
  auto find = [&](const std::string& name) {
    Found f;
    f.joint = model->getJoint(name);
    if (!f.joint) {
      out.warnings.push_back("joint '" + name + "' not in the URDF");
      return f;
    }
    Eigen::Isometry3d X_BP;
    if (!poseInBase(*model, base, f.joint->parent_link_name, &X_BP)) {
      out.warnings.push_back("joint '" + name + "' is not below link '" + base + "'");
      return f;
    }
    f.p_B = (X_BP * toEigen(f.joint->parent_to_joint_origin_transform)).translation();
    f.ok = true;
    return f;
  };
  const Found lh = find(names.left_hinge), rh = find(names.right_hinge);
  const Found lr = find(names.left_rear_wheel), rr = find(names.right_rear_wheel);
  const std::string hinges = names.left_hinge + " / " + names.right_hinge;
  const std::string rears = names.left_rear_wheel + " / " + names.right_rear_wheel;

  if (lr.ok && rr.ok) {
    const double rear_x = 0.5 * (lr.p_B.x() + rr.p_B.x());
    const double rear_y = 0.5 * (lr.p_B.y() + rr.p_B.y());
    out.values["rear_axle_x"] = {rear_x, "robot_description: origins of " + rears};
    out.values["rear_axle_y"] = {rear_y, "robot_description: origins of " + rears};
    out.values["rear_track"] = {std::abs(lr.p_B.y() - rr.p_B.y()),
                                "robot_description: origins of " + rears};
    if (lh.ok && rh.ok) {
      const std::string both = "robot_description: origins of " + hinges + " and " + rears;
      out.values["wheelbase"] = {0.5 * (lh.p_B.x() + rh.p_B.x()) - rear_x, both};
      out.values["hinge_offset_y"] = {0.5 * (lh.p_B.y() + rh.p_B.y()) - rear_y, both};
    }
  }
  if (lh.ok && rh.ok) {
    out.values["hinge_separation"] = {std::abs(lh.p_B.y() - rh.p_B.y()),
                                      "robot_description: origins of " + hinges};
    out.values["hinge_skew_x"] = {0.5 * (rh.p_B.x() - lh.p_B.x()),
                                  "robot_description: origins of " + hinges};
    double m = INFINITY;
    bool limited = true;
    for (const Found* h : {&lh, &rh}) {
      if (h->joint->type != urdf::Joint::REVOLUTE || !h->joint->limits) {
        limited = false;
        out.warnings.push_back("joint '" + h->joint->name +
                               "' is not a revolute joint with limits: no steering limit from it");
        continue;
      }
      m = std::min({m, std::abs(h->joint->limits->lower), std::abs(h->joint->limits->upper)});
    }
    if (limited) {
      out.values["max_steering_angle"] = {m, "robot_description: limits of " + hinges};
    }
  }

  // Wheel radius from the rear wheels' collision shapes.
  std::vector<double> radii;
  std::string mesh_source;
  for (const Found* w : {&lr, &rr}) {
    if (!w->joint) continue;
    const urdf::LinkConstSharedPtr link = model->getLink(w->joint->child_link_name);
    const urdf::CollisionSharedPtr c = link ? link->collision : nullptr;
    const std::string what = "link '" + w->joint->child_link_name + "'";
    if (!c || !c->geometry) {
      out.warnings.push_back(what + " has no collision geometry: no wheel radius from it");
      continue;
    }
    if (c->geometry->type == urdf::Geometry::CYLINDER) {
      radii.push_back(static_cast<const urdf::Cylinder&>(*c->geometry).radius);
    } else if (c->geometry->type == urdf::Geometry::SPHERE) {
      radii.push_back(static_cast<const urdf::Sphere&>(*c->geometry).radius);
    } else if (c->geometry->type == urdf::Geometry::MESH) {
      const auto& mesh = static_cast<const urdf::Mesh&>(*c->geometry);
      std::string path, why;
      try {
        path = mesh_path ? mesh_path(mesh.filename) : "";
      } catch (const std::exception& e) {
        why = std::string(" (") + e.what() + ")";
      }
      if (path.empty()) {
        out.warnings.push_back(what + " collides with mesh " + mesh.filename +
                               ", which could not be located" + why +
                               ": its radius is not measured");
        continue;
      }
      // The axle: the wheel joint's axis through the link origin (the joint frame).
      Eigen::Vector3d axis(w->joint->axis.x, w->joint->axis.y, w->joint->axis.z);
      if (axis.norm() < 1e-9) {
        out.warnings.push_back("joint '" + w->joint->name + "' has no axis: no wheel radius");
        continue;
      }
      try {
        // The shared mesh loader and wheel fit: the radius the simulator's physics gives the
        // same wheel (the largest distance of a vertex, scaled and posed, from the axle).
        const auto triangles = tianracer_assets::MeshCache::global().get(
            path, Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z));
        const Eigen::Isometry3d X_JC = toEigen(c->origin);
        std::vector<Eigen::Vector3d> vertices_J;
        vertices_J.reserve(triangles->vertices.size());
        for (const Eigen::Vector3f& v : triangles->vertices) vertices_J.push_back(X_JC * v.cast<double>());
        const tianracer_assets::WheelFit fit = tianracer_assets::fitWheel(vertices_J, axis.normalized());
        if (!(fit.radius > 0.0)) {
          out.warnings.push_back(what + ": mesh " + path + " has too few vertices off the axle: " +
                                 "no wheel radius from it");
          continue;
        }
        radii.push_back(fit.radius);
        mesh_source = " (mesh vertices farthest from the axle)";
      } catch (const tianracer_assets::MeshError& e) {
        out.warnings.push_back(what + ": " + e.what() + ": no wheel radius from it");
      }
    } else {
      out.warnings.push_back(what + " collides with a box: its radius is not measured");
    }
  }
  if (!radii.empty()) {
    const double r = radii.size() == 2 ? 0.5 * (radii[0] + radii[1]) : radii[0];
    if (radii.size() == 2 && std::abs(radii[0] - radii[1]) > 0.01 * r) {
      out.warnings.push_back("rear wheel radii differ (" + fmt(radii[0]) + ", " + fmt(radii[1]) +
                             "): using their mean");
    }
    out.values["wheel_radius"] = {
        r, "robot_description: collision of the rear wheel links" + mesh_source};
  }
  return out;
}

ResolvedGeometry resolveGeometry(const std::map<std::string, double>& parameters,
                                 const UrdfGeometry* urdf) {
  ResolvedGeometry out;
  const AckermannGeometry defaults;
  const std::map<std::string, double> default_values = {
      {"wheelbase", defaults.wheelbase},
      {"hinge_separation", defaults.hinge_separation},
      {"wheel_radius", defaults.wheel_radius},
      {"rear_track", defaults.rear_track},
      {"max_steering_angle", defaults.max_steering_angle},
      {"rear_axle_x", defaults.rear_axle_x},
      {"rear_axle_y", defaults.rear_axle_y},
      {"hinge_skew_x", defaults.hinge_skew_x},
      {"hinge_offset_y", defaults.hinge_offset_y}};
  if (urdf) out.warnings = urdf->warnings;
  for (const auto& kv : parameters) {
    if (default_values.count(kv.first) == 0) {
      throw AckermannError("unknown geometry parameter '" + kv.first + "'");
    }
  }
  for (const std::string& key : geometryKeys()) {
    GeometryValue v;
    const auto p = parameters.find(key);
    if (p != parameters.end()) {
      v = {p->second, "parameter ~" + key};
    } else if (urdf && urdf->values.count(key)) {
      v = urdf->values.at(key);
    } else {
      v = {default_values.at(key), "default"};
      out.warnings.push_back(key + " not given and not found in robot_description: using the " +
                             "default " + fmt(v.value));
    }
    out.values.emplace_back(key, v);
  }
  auto get = [&](const char* key) {
    for (const auto& kv : out.values) {
      if (kv.first == key) return kv.second.value;
    }
    return 0.0;
  };
  out.geometry.wheelbase = get("wheelbase");
  out.geometry.hinge_separation = get("hinge_separation");
  out.geometry.wheel_radius = get("wheel_radius");
  out.geometry.rear_track = get("rear_track");
  out.geometry.max_steering_angle = get("max_steering_angle");
  out.geometry.rear_axle_x = get("rear_axle_x");
  out.geometry.rear_axle_y = get("rear_axle_y");
  out.geometry.hinge_skew_x = get("hinge_skew_x");
  out.geometry.hinge_offset_y = get("hinge_offset_y");
  out.geometry.validate();
  return out;
}

}  // namespace tianracer_control
