// URDF string -> RobotModel: structural checks with line numbers (tinyxml2), urdfdom for the
// model itself, then the extensions and mesh files. ROS-free.
#include "tianracer_sim/model/robot_model.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include "model_internal.h"
#include "tianracer_assets/file_kind.h"
#include "tianracer_sim/common/input_limits.h"

namespace tianracer_sim {

namespace mi = model_internal;
using model_internal::attr;
using tinyxml2::XMLElement;

namespace {

std::string lines(const XMLElement* a, const XMLElement* b) {
  return "lines " + std::to_string(a->GetLineNum()) + " and " + std::to_string(b->GetLineNum());
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

/// mass > 0 and finite; inertia finite and positive definite (all eigenvalues of the symmetric
/// 3x3 tensor > 0). The triangle inequalities are not required, as in Gazebo. Values are read
/// with the XmlReader's readers (mi::attribute, parseNumber), errors placed by it.
void checkInertial(const XMLElement* link, const std::string& name, const std::string& source) {
  const XMLElement* inertial = link->FirstChildElement("inertial");
  if (!inertial) return;  // massless link (e.g. base_link): merged into its parent or ignored
  const XmlReader reader = mi::modelReader(source, {});
  const std::string what = "link '" + name + "': ";
  const XMLElement* mass = inertial->FirstChildElement("mass");
  const std::optional<std::string> mv = mi::attribute(mass, "value");
  if (!mv) reader.fail(mass ? mass : inertial, what + "<inertial> has no <mass value=...>");
  const auto m = parseNumber(*mv);
  if (!m || !std::isfinite(*m) || *m <= 0.0)
    reader.fail(mass, what + "mass '" + *mv + "' must be a positive finite number");
  if (*m > limits::kMass)
    reader.fail(mass, what + "mass " + *mv + " is out of range (<= " +
                          limits::formatNumber(limits::kMass) + " kg)");
  const XMLElement* inertia = inertial->FirstChildElement("inertia");
  if (!inertia) reader.fail(inertial, what + "<inertial> has no <inertia>");
  static const char* kKeys[6] = {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"};
  double v[6];
  for (int i = 0; i < 6; ++i) {
    const std::optional<std::string> a = mi::attribute(inertia, kKeys[i]);
    if (!a) reader.fail(inertia, what + "<inertia> has no " + kKeys[i]);
    const auto d = parseNumber(*a);
    if (!d || !std::isfinite(*d))
      reader.fail(inertia, what + "inertia " + kKeys[i] + "='" + *a + "' is not a finite number");
    if (std::abs(*d) > limits::kInertia)
      reader.fail(inertia, what + "inertia " + kKeys[i] + "=" + *a + " is out of range (|" +
                               kKeys[i] + "| <= " + limits::formatNumber(limits::kInertia) +
                               " kg m^2)");
    v[i] = *d;
  }
  Eigen::Matrix3d I;
  I << v[0], v[1], v[2], v[1], v[3], v[4], v[2], v[4], v[5];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(I, Eigen::EigenvaluesOnly);
  const double min_eig = es.eigenvalues().minCoeff();
  if (!(min_eig > 0.0)) {
    std::string values;
    for (int i = 0; i < 6; ++i) values += std::string(i ? " " : "") + kKeys[i] + "=" + fmt(v[i]);
    reader.fail(inertia, what + "inertia is not positive definite (" + values +
                             "; smallest eigenvalue " + fmt(min_eig) + ")");
  }
}

/// The numbers of attribute `name` of `e` when it has `count` of them; nullopt when absent or
/// unreadable (urdfdom reports those with its own message).
std::optional<std::vector<double>> numbersOf(const XMLElement* e, const char* name,
                                             std::size_t count) {
  const std::optional<std::string> a = mi::attribute(e, name);
  if (!a) return std::nullopt;
  auto v = parseNumbers(*a);
  if (!v || v->size() != count) return std::nullopt;
  return v;
}

/// Magnitudes urdfdom takes as they come (it checks only that numbers parse): origins within
/// limits::kPosition, rpy finite, shape sizes > 0 and within limits::kSize, a joint axis that is
/// finite and not zero, damping and friction within limits::kJointCoefficient.
void checkOrigin(const XMLElement* parent, const std::string& what, const std::string& source) {
  const XMLElement* o = parent->FirstChildElement("origin");
  if (!o) return;
  if (const auto xyz = numbersOf(o, "xyz", 3)) {
    const std::string bad =
        limits::checkVector({(*xyz)[0], (*xyz)[1], (*xyz)[2]}, limits::kPosition, "m");
    if (!bad.empty())
      throw ModelError(mi::at(source, o) + what + "<origin xyz='" + attr(o, "xyz") + "'>: " + bad);
  }
  if (const auto rpy = numbersOf(o, "rpy", 3)) {
    for (double r : *rpy)
      if (!std::isfinite(r))
        throw ModelError(mi::at(source, o) + what + "<origin rpy='" + attr(o, "rpy") +
                         "'> is not finite");
  }
}

void checkGeometry(const XMLElement* holder, const std::string& what, const std::string& source) {
  checkOrigin(holder, what, source);
  const XMLElement* g = holder->FirstChildElement("geometry");
  if (!g) return;
  auto check = [&](const XMLElement* e, const char* name, std::size_t count) {
    const auto v = numbersOf(e, name, count);
    if (!v) return;
    for (std::size_t i = 0; i < v->size(); ++i) {
      const double x = (*v)[i];
      std::string bad;
      if (!std::isfinite(x)) bad = "is not finite";
      else if (!(x > 0.0)) bad = "must be > 0";
      else if (x > limits::kSize) bad = "is out of range (<= " + limits::formatNumber(limits::kSize) + " m)";
      if (!bad.empty())
        throw ModelError(mi::at(source, e) + what + "<" + e->Name() + " " + name + "='" +
                         attr(e, name) + "'> " + bad);
    }
  };
  check(g->FirstChildElement("box"), "size", 3);
  check(g->FirstChildElement("cylinder"), "radius", 1);
  check(g->FirstChildElement("cylinder"), "length", 1);
  check(g->FirstChildElement("sphere"), "radius", 1);
  check(g->FirstChildElement("mesh"), "scale", 3);
}

void checkMagnitudes(const XMLElement* link_or_joint, const std::string& source) {
  const XMLElement* e = link_or_joint;
  const bool is_link = std::string(e->Name()) == "link";
  const std::string what = (is_link ? "link '" : "joint '") + attr(e, "name") + "': ";
  if (is_link) {
    if (const XMLElement* in = e->FirstChildElement("inertial"))
      checkOrigin(in, what + "<inertial> ", source);
    for (const char* tag : {"visual", "collision"}) {
      for (const XMLElement* c = e->FirstChildElement(tag); c; c = c->NextSiblingElement(tag))
        checkGeometry(c, what + "<" + tag + "> ", source);
    }
    return;
  }
  checkOrigin(e, what, source);
  // A fixed or floating joint's axis is not used (urdfdom ignores it; the tianracer's fixed
  // joints say "0 0 0"). A movable one's is checked before it is normalised, in a way that
  // cannot overflow (limits::unitAxis).
  const std::string type = attr(e, "type");
  const bool movable = type == "revolute" || type == "continuous" || type == "prismatic";
  if (const auto xyz = movable ? numbersOf(e->FirstChildElement("axis"), "xyz", 3) : std::nullopt) {
    if (!limits::unitAxis({(*xyz)[0], (*xyz)[1], (*xyz)[2]}))
      throw ModelError(mi::at(source, e->FirstChildElement("axis")) + what + "<axis xyz='" +
                       attr(e->FirstChildElement("axis"), "xyz") +
                       "'> must be finite and not zero");
  }
  if (const XMLElement* d = e->FirstChildElement("dynamics")) {
    for (const char* name : {"damping", "friction"}) {
      const auto v = numbersOf(d, name, 1);
      if (!v) continue;
      const double x = (*v)[0];
      if (!std::isfinite(x) || x < 0.0 || x > limits::kJointCoefficient)
        throw ModelError(mi::at(source, d) + what + "<dynamics " + name + "='" + attr(d, name) +
                         "'> must be finite, >= 0 and <= " + limits::formatNumber(limits::kJointCoefficient));
    }
  }
}

/// What urdfdom reports vaguely or not at all: names, duplicates, dangling links, loops,
/// several roots, masses and inertias; each with its line.
void checkStructure(const XMLElement* robot, const std::string& source) {
  std::map<std::string, const XMLElement*> links, joints;
  for (const XMLElement* e = robot->FirstChildElement("link"); e;
       e = e->NextSiblingElement("link")) {
    const std::string name = attr(e, "name");
    if (name.empty()) throw ModelError(mi::at(source, e) + "<link> without a name");
    const auto ins = links.emplace(name, e);
    if (!ins.second)
      throw ModelError(source + ": duplicate link name '" + name + "' (" +
                       lines(ins.first->second, e) + ")");
    if (links.size() > limits::kLinksPerModel)
      throw ModelError(mi::at(source, e) + "the model has more than " +
                       std::to_string(limits::kLinksPerModel) + " links (limit of one model)");
    checkInertial(e, name, source);
    checkMagnitudes(e, source);
  }
  if (links.empty()) throw ModelError(mi::at(source, robot) + "<robot> has no <link>");

  struct Parent {
    std::string link, joint;
    const XMLElement* element;
  };
  std::map<std::string, Parent> parent_of;  // child link -> its parent
  for (const XMLElement* e = robot->FirstChildElement("joint"); e;
       e = e->NextSiblingElement("joint")) {
    const std::string name = attr(e, "name");
    if (name.empty()) throw ModelError(mi::at(source, e) + "<joint> without a name");
    const auto ins = joints.emplace(name, e);
    if (!ins.second)
      throw ModelError(source + ": duplicate joint name '" + name + "' (" +
                       lines(ins.first->second, e) + ")");
    checkMagnitudes(e, source);
    const std::string what = "joint '" + name + "': ";
    const std::string parent = attr(e->FirstChildElement("parent"), "link");
    const std::string child = attr(e->FirstChildElement("child"), "link");
    if (parent.empty()) throw ModelError(mi::at(source, e) + what + "no <parent link=...>");
    if (child.empty()) throw ModelError(mi::at(source, e) + what + "no <child link=...>");
    if (!links.count(parent))
      throw ModelError(mi::at(source, e) + what + "parent link '" + parent + "' does not exist");
    if (!links.count(child))
      throw ModelError(mi::at(source, e) + what + "child link '" + child + "' does not exist");
    const auto pin = parent_of.emplace(child, Parent{parent, name, e});
    if (!pin.second)
      throw ModelError(source + ": link '" + child + "' has two parent joints, '" +
                       pin.first->second.joint + "' and '" + name + "' (" +
                       lines(pin.first->second.element, e) +
                       "): joint loops are not supported, a URDF must be a tree");
  }

  // Each link has at most one parent now; a loop is a parent chain that comes back.
  for (const auto& kv : links) {
    std::vector<std::string> chain{kv.first};
    std::string cur = kv.first;
    for (size_t steps = 0; steps <= links.size(); ++steps) {
      const auto it = parent_of.find(cur);
      if (it == parent_of.end()) break;
      cur = it->second.link;
      chain.push_back(cur);
      if (cur == kv.first) {
        std::string path;
        for (size_t i = 0; i < chain.size(); ++i) path += (i ? " -> '" : "'") + chain[i] + "'";
        throw ModelError(formatLocation(source, it->second.element->GetLineNum()) +
                         "joint loop: " + path + " (joint '" + it->second.joint +
                         "'): a URDF must be a tree");
      }
    }
  }

  std::vector<std::string> roots;
  for (const auto& kv : links)
    if (!parent_of.count(kv.first)) roots.push_back(kv.first);
  if (roots.size() > 1)
    throw ModelError(source + ": links '" + roots[0] + "' and '" + roots[1] +
                     "' both have no parent joint: a URDF must be one connected tree");
}

/// Collects urdfdom's console_bridge messages while it parses (its only error channel).
class CaptureHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) ++errors;
  }
  std::vector<std::string> messages;
  int errors = 0;
};

urdf::ModelInterfaceSharedPtr parseWithUrdfdom(const std::string& xml, const std::string& source,
                                               XmlReader& warner) {
  static std::mutex mutex;
  static CaptureHandler handler;  // static: console_bridge keeps a pointer as "previous"
  std::lock_guard<std::mutex> lock(mutex);
  handler.messages.clear();
  handler.errors = 0;
  // console_bridge drops messages below its global level before any handler sees them.
  const console_bridge::LogLevel previous_level = console_bridge::getLogLevel();
  console_bridge::setLogLevel(console_bridge::CONSOLE_BRIDGE_LOG_WARN);
  console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    handler.messages.push_back(e.what());
  }
  console_bridge::useOutputHandler(previous);
  console_bridge::setLogLevel(previous_level);
  // urdfdom 3.0 logs an error and still returns a model when a link's <inertial> does not parse
  // (e.g. a bad <origin xyz>): that link then has mass 0. An error is an error (found by
  // fuzz_extensions).
  if (!model || handler.errors > 0) {
    std::string msg = source + ": urdfdom could not parse the URDF";
    for (const auto& m : handler.messages) msg += ": " + m;
    throw ModelError(msg);
  }
  for (const auto& m : handler.messages) warner.warn(source + ": urdfdom: " + m);
  return model;
}

void collectMeshes(RobotModel& model, const LoadOptions& options, XmlReader& warner) {
  for (const auto& kv : model.urdf->links_) {
    const urdf::LinkSharedPtr& link = kv.second;
    if (!link) continue;
    std::vector<urdf::GeometrySharedPtr> geometries;
    for (const auto& v : link->visual_array)
      if (v) geometries.push_back(v->geometry);
    for (const auto& c : link->collision_array)
      if (c) geometries.push_back(c->geometry);
    for (const auto& g : geometries) {
      if (!g || g->type != urdf::Geometry::MESH) continue;
      const auto mesh = std::dynamic_pointer_cast<urdf::Mesh>(g);
      if (!mesh) continue;
      const std::string& uri = mesh->filename;
      std::string path;
      try {
        path = options.resolver.resolve(uri);
      } catch (const ModelError& e) {
        const std::string msg = model.source + ": link '" + link->name + "': " + e.what();
        if (options.require_meshes) throw ModelError(msg);
        warner.warn(msg);
        continue;
      }
      model.mesh_paths[uri] = path;
      if (!options.require_meshes) continue;
      // A directory or a device is said to be one; only a missing file is "not found".
      const std::string problem = tianracer_assets::fileProblem(path);
      if (problem == "file not found")
        throw ModelError(model.source + ": link '" + link->name + "': mesh '" + uri +
                         "' not found (resolved to " + path + ")");
      if (!problem.empty())
        throw ModelError(model.source + ": link '" + link->name + "': mesh '" + uri + "' (resolved to " +
                         path + ") " + problem);
    }
  }
}

// The topmost link reached from `link` through fixed joints, and the pose of `link` in it.
std::pair<std::string, Eigen::Isometry3d> fixedRoot(const urdf::ModelInterface& model,
                                                    std::string link) {
  Eigen::Isometry3d X_RL = Eigen::Isometry3d::Identity();
  for (urdf::LinkConstSharedPtr l = model.getLink(link); l && l->parent_joint &&
                                                        l->parent_joint->type == urdf::Joint::FIXED;
       l = model.getLink(link)) {
    const urdf::Pose& p = l->parent_joint->parent_to_joint_origin_transform;
    const Eigen::Isometry3d X_PC =
        Eigen::Translation3d(p.position.x, p.position.y, p.position.z) *
        Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
    X_RL = X_PC * X_RL;
    link = l->parent_joint->parent_link_name;
  }
  return {link, X_RL};
}

}  // namespace

std::optional<Eigen::Isometry3d> fixedPose(const urdf::ModelInterface& model,
                                           const std::string& from, const std::string& to) {
  if (!model.getLink(from) || !model.getLink(to)) return std::nullopt;
  const auto [root_from, X_RF] = fixedRoot(model, from);
  const auto [root_to, X_RT] = fixedRoot(model, to);
  if (root_from != root_to) return std::nullopt;
  return X_RF.inverse() * X_RT;
}

RobotModel loadRobotModel(const std::string& urdf_xml, const std::string& source,
                          const LoadOptions& options) {
  XmlReader warner = mi::modelReader(source, options.warn);
  tinyxml2::XMLDocument doc;
  const XMLElement* robot = mi::parseRobotXml(doc, urdf_xml, source);
  checkStructure(robot, source);
  RobotModel model;
  model.source = source;
  model.lines.source = source;
  for (const XMLElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "link") model.lines.links.emplace(attr(e, "name"), e->GetLineNum());
    if (tag == "joint") model.lines.joints.emplace(attr(e, "name"), e->GetLineNum());
  }
  model.urdf = parseWithUrdfdom(urdf_xml, source, warner);
  model.ext = mi::parseExtensionsXml(robot, source, warner);
  collectMeshes(model, options, warner);
  return model;
}

RobotModel loadRobotModelFile(const std::string& path, LoadOptions options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) throw ModelError("model file path is empty");
  if (!fs::is_regular_file(path, ec)) throw ModelError(path + ": model file not found");
  if (options.resolver.base_dir.empty())
    options.resolver.base_dir = fs::absolute(fs::path(path), ec).parent_path().string();

  const std::string ext = fs::path(path).extension().string();
  std::string xml, source = path;
  if (ext == ".xacro") {
    xml = expandXacro(path, {}, options.warn);
    source = path + " (expanded by xacro)";
  } else if (ext == ".urdf" || ext == ".xml") {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in) throw ModelError(path + ": cannot read the model file");
    xml = s.str();
  } else {
    throw ModelError(path + ": unknown model file type '" + ext +
                     "' (expected .urdf, .xml or .xacro)");
  }
  RobotModel model = loadRobotModel(xml, source, options);
  model.source = path;
  return model;
}

}  // namespace tianracer_sim
