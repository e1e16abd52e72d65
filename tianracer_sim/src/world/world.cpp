// SDF world subset -> WorldDescription (tinyxml2). Must never crash on any input: every value is
// checked, every failure is a WorldError naming file and line, every element we do not use is
// reported once through the WarningSink.
#include "tianracer_sim/world/world.h"
#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/common/input_limits.h"
#include "world_parser.h"
#include "tianracer_sim/world/sdf_material.h"
#include "tianracer_sim/world/map_world.h"

#include "tianracer_sim/mesh/mesh_loader.h"
#include "tianracer_assets/file_kind.h"
#include "tianracer_sim/scene/materials.h"

#include <sys/stat.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <tinyxml2.h>

namespace tianracer_sim {

namespace {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

}  // namespace

namespace world_internal {

WorldDescription Parser::parse(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  if (parseXmlDocument(xml, &doc) != tinyxml2::XML_SUCCESS) {
    // tinyxml2's ErrorStr() is "Error=<name> ErrorID=<n> (0x..) Line number=<l>[: <detail>]".
    std::string detail = doc.ErrorStr() ? doc.ErrorStr() : "";
    const auto colon = detail.find(": ", detail.find("Line number="));
    detail = colon == std::string::npos ? "" : " (" + detail.substr(colon + 2) + ")";
    throw WorldError(source_ + ":" + std::to_string(doc.ErrorLineNum()) +
                     ": malformed XML: " + doc.ErrorName() + detail);
  }
  const XMLElement* root = doc.RootElement();
  if (!root) throw WorldError(source_ + ":1: malformed XML: no root element");
  if (std::string(root->Name()) != "sdf")
    fail(root, "root element is <" + std::string(root->Name()) + ">, expected <sdf>");
  const XMLElement* w = nullptr;
  for (const XMLElement* c = root->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "world" && !w) {
      w = c;
    } else if (tag == "world") {
      warn(c, "a second <world> is ignored (one world per file)");
    } else {
      unsupported(c, "a world file holds one <world>");
    }
  }
  if (!w) fail(root, "no <world> element in <sdf>");

  WorldDescription world;
  world.source = source_;
  world.name = w->Attribute("name") ? w->Attribute("name") : "default";
  std::set<std::string> model_names;
  std::vector<const XMLElement*> states;  // applied once every model is known
  bool have_physics = false;
  for (const XMLElement* c = w->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "physics") {
      if (have_physics) {
        warn(c, "only the first <physics> is used");
        continue;
      }
      have_physics = true;
      parsePhysics(c, world.physics);
    } else if (tag == "gravity") {  // SDF >= 1.5 puts gravity in <world>
      if (!keepsDefault(c)) world.physics.gravity = gravity(c, "world");
    } else if (tag == "scene") {
      parseScene(c, world);
    } else if (tag == "include") {
      const std::size_t before = world.models.size();
      parseInclude(c, world);
      checkModelCount(c, world);
      for (std::size_t i = before; i < world.models.size();) {
        if (model_names.insert(world.models[i].name).second) {
          ++i;
        } else {
          duplicate(c, world.models[i].name);
          world.models.erase(world.models.begin() + static_cast<std::ptrdiff_t>(i));
        }
      }
    } else if (tag == "state") {
      states.push_back(c);
    } else if (tag == "light") {
      parseLight(c, world);
    } else if (tag == "model") {
      ModelDescription m = parseModel(c);
      if (!model_names.insert(m.name).second) {
        duplicate(c, m.name);
        continue;
      }
      world.models.push_back(std::move(m));
      checkModelCount(c, world);
    } else if (tag == "actor") {
      // A broken actor is left out with its error and the rest of the world loads.
      try {
        ActorDescription a = parseActor(c);
        if (!model_names.insert(a.model.name).second) {
          duplicate(c, a.model.name, "actor");
          continue;
        }
        world.actors.push_back(std::move(a));
      } catch (const InputError& err) {
        leftOutError(err, "the actor is left out");
      }
    } else {
      unsupported(c);
    }
  }
  // Gazebo applies a saved <state> on load: its poses override the models' <pose>.
  for (const XMLElement* st : states) applyState(st, world, model_names);
  return world;
}

void Parser::parsePhysics(const XMLElement* e, PhysicsSettings& physics) {
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "max_step_size") {
      // As PhysicsWorld::setTimeStep takes it (0, kMaxTimeStep], checked here with the line.
      physics.max_step_size = positive(c, "<physics>", physics.max_step_size);
      if (physics.max_step_size > limits::kTimeStep)
        fail(c, "<physics>: <max_step_size> " + text(c) + " is out of range (0 < step <= " +
                    limits::formatNumber(limits::kTimeStep) + " s)");
    } else if (tag == "real_time_factor") {
      physics.real_time_factor = nonNegative(c, "<physics>", physics.real_time_factor);
    } else if (tag == "real_time_update_rate") {
      physics.real_time_update_rate =
          nonNegative(c, "<physics>", physics.real_time_update_rate);
    } else if (tag == "gravity") {
      if (!keepsDefault(c)) physics.gravity = gravity(c, "<physics>");
    } else if (tag == "ode") {
      parsePhysicsOde(c, physics);
    } else {
      unsupported(c);
    }
  }
}

// <physics><ode>: only <solver><friction_model> is read; ODE's other solver and constraint
// settings have no counterpart in Bullet's solver and are reported as not supported.
void Parser::parsePhysicsOde(const XMLElement* e, PhysicsSettings& physics) {
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (std::string(c->Name()) != "solver") {
      unsupported(c);
      continue;
    }
    for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement()) {
      if (std::string(k->Name()) != "friction_model") {
        unsupported(k);
        continue;
      }
      const std::string model = text(k);
      if (model == "pyramid_model" || model == "cone_model" || model == "box_model") {
        physics.friction_model = model;
      } else {  // as Gazebo's ODEPhysics::SetFrictionModel: said, and the default kept
        warn(k, "<physics><ode><solver>: unknown <friction_model> '" + model +
                    "' (pyramid_model, cone_model, box_model); pyramid_model is used");
      }
    }
  }
}

void Parser::checkModelCount(const XMLElement* e, const WorldDescription& world) {
  // Each dynamic model is a multibody stepped every step: 20,000 hung the first step.
  if (world.models.size() > limits::kModelsPerWorld)
    fail(e, "the world has more than " + std::to_string(limits::kModelsPerWorld) +
                " models (limit of one world)");
}

Eigen::Vector3d Parser::gravity(const XMLElement* e, const std::string& what) {
  const Eigen::Vector3d g = vector3(e, what);
  const std::string bad = limits::checkVector(g, limits::kGravity, "m/s^2");
  if (!bad.empty()) fail(e, what + ": <gravity> " + bad);
  return g;
}

void Parser::checkSize(const XMLElement* e, const Eigen::Vector3d& size, const std::string& what) {
  const std::string bad = limits::checkVector(size, limits::kSize, "m");
  if (!bad.empty()) fail(e, what + " " + bad);
}

double Parser::coefficient(const XMLElement* e, const std::string& what) {
  nonNegative(e, what);
  return bounded(e, what, limits::kJointCoefficient, "");
}

void Parser::parseScene(const XMLElement* e, WorldDescription& world) {
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "ambient") {
      if (!keepsDefault(c)) world.ambient = color(c, "<scene>");
    } else if (tag == "background") {
      if (!keepsDefault(c)) world.background = color(c, "<scene>");
    } else {
      unsupported(c);
    }
  }
}

void Parser::parseLight(const XMLElement* e, WorldDescription& world) {
  const std::string type = e->Attribute("type") ? e->Attribute("type") : "point";
  const std::string name = e->Attribute("name") ? e->Attribute("name") : "";
  const std::string what = "<light name='" + name + "'>";
  if (type != "directional" && type != "point" && type != "spot")
    fail(e, what + ": unknown light type '" + type + "' (directional, point, spot)");
  DirectionalLight light;
  light.name = name;
  light.direction = Eigen::Vector3d(0, 0, -1);  // SDF default
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  double constant = 1.0, linear = 0.0, quadratic = 0.0;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "direction") {
      light.direction = vector3(c, what, light.direction);
    } else if (tag == "diffuse") {
      light.given_diffuse = color(c, what, light.given_diffuse);
    } else if (tag == "specular") {
      light.given_specular = color(c, what, light.given_specular);
    } else if (tag == "pose") {
      X = pose(c, what, X);
    } else if (tag == "attenuation") {  // kept for get_light_properties; drawn: below
      for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement()) {
        const std::string ktag = k->Name();
        if (ktag == "constant") constant = nonNegative(k, what, constant);
        else if (ktag == "linear") linear = nonNegative(k, what, linear);
        else if (ktag == "quadratic") quadratic = nonNegative(k, what, quadratic);
        else if (ktag != "range") unsupported(k);
      }
    } else {
      unsupported(c);
    }
  }
  if (type == "point") light.direction = Eigen::Vector3d(0, 0, -1);
  const std::optional<Eigen::Vector3d> direction = limits::unitAxis(light.direction);
  if (!direction) fail(e, what + ": <direction> must not be zero");
  light.direction = X.linear() * *direction;
  light.attenuation = {constant, linear, quadratic};
  if (type != "directional") light.attenuation_height = std::max(0.0, X.translation().z());
  litColours(&light);
  if (type != "directional") {
    // The renderer has directional lights only. A point light becomes one shining straight
    // down, a spot light one along its direction; both dimmed by their attenuation at the
    // light's height above the ground, 1 / (constant + linear h + quadratic h^2) (at most 1).
    const double h = light.attenuation_height;
    const double k = attenuationFactor(light);
    std::ostringstream os;
    os << what << " (" << type << ") is approximated by a directional light along ("
       << light.direction.transpose() << "), its colour scaled by its attenuation at height " << h
       << " m (x" << k << ")";
    warn(e, os.str());
  }
  world.lights.push_back(light);
}

ModelDescription Parser::parseModel(const XMLElement* e) {
  ModelDescription m;
  m.name = attributeText(e, "name");
  m.line = e->GetLineNum();
  if (m.name.empty()) fail(e, "<model> has no name");
  const std::string what = "model '" + m.name + "'";
  std::set<std::string> link_names;
  std::vector<std::size_t> axes_in_model_frame;  // joints whose <axis> is in the model frame
  int left_out_includes = 0;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "static") {
      m.is_static = boolean(c, what, m.is_static);
    } else if (tag == "pose") {
      m.X_WM = pose(c, what, m.X_WM);
    } else if (tag == "link") {
      LinkDescription l = parseLink(c, m.name);
      if (!link_names.insert(l.name).second) fail(c, what + ": duplicate link name '" + l.name + "'");
      m.links.push_back(std::move(l));
    } else if (tag == "plugin") {
      try {
        m.plugins.push_back(parsePluginElement(c, source_));
      } catch (const ModelError& err) {
        leftOutError(err, "the plugin is left out");
      }
    } else if (tag == "allow_auto_disable") {
      m.allow_auto_disable = boolean(c, what, m.allow_auto_disable);
    } else if (tag == "joint") {
      bool in_model_frame = false;
      m.joints.push_back(parseJoint(c, m.name, &in_model_frame));
      if (in_model_frame) axes_in_model_frame.push_back(m.joints.size() - 1);
    } else if (tag == "include" || tag == "model") {
      // A nested model: its links (and joints) join this model as "<sub>::<link>".
      ModelDescription sub;
      Eigen::Isometry3d X_MS;
      if (tag == "include") {
        const std::optional<IncludeSpec> spec = parseIncludeSpec(c);
        std::optional<ModelDescription> included;
        if (spec) included = includeModel(c, *spec);
        if (!included) {  // left out, reported
          ++left_out_includes;
          continue;
        }
        sub = std::move(*included);
        X_MS = sub.X_WM;
      } else {
        sub = parseModel(c);
        X_MS = sub.X_WM;
      }
      mergeSubModel(&m, sub, X_MS);
      for (const LinkDescription& l : sub.links) {
        if (!link_names.insert(sub.name + "::" + l.name).second)
          fail(c, what + ": duplicate link name '" + sub.name + "::" + l.name + "'");
      }
    } else {
      unsupported(c);
    }
  }
  if (m.links.empty()) warn(e, what + " has no <link>: nothing to simulate or see");
  if (m.links.size() > limits::kLinksPerModel)
    fail(e, what + " has " + std::to_string(m.links.size()) + " links, more than " +
                std::to_string(limits::kLinksPerModel) + " (limit of one model)");
  // A joint may name a link by its world-scoped name, the model's own name first
  // ("pioneer2dx::pioneer2dx::chassis" in model 'pioneer2dx', as pioneer2dx_camera.world does):
  // Gazebo's Joint::Load (gazebo/physics/Joint.cc) looks the name up in the model, then in the
  // world (World::BaseByName, scoped names), then scoped by each enclosing model.
  const std::string own_scope = m.name + "::";
  for (JointDescription& j : m.joints) {
    for (std::string* end : {&j.parent, &j.child}) {
      if (*end == "world" || link_names.count(*end) || end->rfind(own_scope, 0) != 0) continue;
      const std::string local = end->substr(own_scope.size());
      if (link_names.count(local)) *end = local;
    }
  }
  auto linkOf = [&](const std::string& name) -> const LinkDescription* {
    for (const LinkDescription& l : m.links)
      if (l.name == name) return &l;
    return nullptr;
  };
  // An axis in the model frame, turned into the joint frame: R_MJ^T axis_M, R_MJ = R_MC R_CJ.
  for (const std::size_t k : axes_in_model_frame) {
    JointDescription& j = m.joints[k];
    if (const LinkDescription* child = linkOf(j.child)) {
      j.axis = (child->X_ML.linear() * j.X_CJ.linear()).transpose() * j.axis;
    }
  }
  // A joint naming no link of the model is left out with an error, and the rest of the model
  // loads (its links then move as the remaining joints say); ~strict_world stops. Gazebo throws
  // "Couldn't Find Child Link[...]" from Joint::Load (gazebo/physics/Joint.cc), which gzserver
  // logs as an [Err] for that joint. When an <include> of the model was left out, the link was
  // most likely in it, and the message says so.
  std::vector<JointDescription> joints;
  for (JointDescription& j : m.joints) {
    std::string missing;
    for (const std::string* end : {&j.parent, &j.child}) {
      if (missing.empty() && *end != "world" && !link_names.count(*end)) missing = *end;
    }
    if (missing.empty()) {
      joints.push_back(std::move(j));
      continue;
    }
    std::string why;
    if (left_out_includes > 0) {
      why = " (an <include> of it was left out)";
    } else {
      for (const LinkDescription& l : m.links) why += (why.empty() ? "" : ", ") + l.name;
      why = " (links: " + why + ")";
    }
    const XMLElement* joint_e = e->FirstChildElement("joint");
    while (joint_e && joint_e->GetLineNum() != j.line) joint_e = joint_e->NextSiblingElement("joint");
    leftOut(joint_e ? joint_e : e,
            what + " joint '" + j.name + "': no link '" + missing + "' in the model" + why,
            "the joint is left out");
  }
  m.joints = std::move(joints);
  return m;
}

LinkDescription Parser::parseLink(const XMLElement* e, const std::string& model) {
  LinkDescription l;
  l.name = attributeText(e, "name");
  l.line = e->GetLineNum();
  if (l.name.empty()) fail(e, "model '" + model + "': <link> has no name");
  const std::string what = "model '" + model + "' link '" + l.name + "'";
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "pose") {
      l.X_ML = pose(c, what, l.X_ML);
    } else if (tag == "inertial") {
      l.inertial = parseInertial(c, what);
    } else if (tag == "self_collide") {
      l.self_collide = boolean(c, what, l.self_collide);
    } else if (tag == "gravity") {
      l.gravity = boolean(c, what, l.gravity);
    } else if (tag == "collision" || tag == "visual") {
      const std::string name = c->Attribute("name") ? c->Attribute("name") : "";
      const std::string cwhat = what + " " + tag + " '" + name + "'";
      const XMLElement* geometry = nullptr;
      Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();
      Friction friction;
      ContactDescription contact;
      Material material;
      for (const XMLElement* g = c->FirstChildElement(); g; g = g->NextSiblingElement()) {
        const std::string gtag = g->Name();
        if (gtag == "geometry") {
          if (geometry) fail(g, cwhat + ": more than one <geometry>");
          geometry = g;
        } else if (gtag == "pose") {
          X_LS = pose(g, cwhat, X_LS);
        } else if (gtag == "surface" && tag == "collision") {
          friction = parseSurface(g, cwhat, &contact);
        } else if (gtag == "material" && tag == "visual") {
          material = parseSdfMaterial(g, {source_, uriResolver(), cwhat, options_.warn});
        } else {
          unsupported(g);
        }
      }
      if (!geometry) fail(c, cwhat + " has no <geometry>");
      const std::optional<Shape> shape = parseGeometry(geometry, cwhat, tag);
      if (!shape) continue;  // left out, reported
      if (tag == "collision") {
        l.collisions.push_back({name, *shape, X_LS, friction, c->GetLineNum(), contact});
      } else {
        l.visuals.push_back({name, *shape, X_LS, material, c->GetLineNum()});
      }
    } else if (tag == "sensor") {
      // The robot loader's <sensor> parser: the sensor kinds read the rest from its XML.
      try {
        l.sensors.push_back(parseSensorElement(c, l.name, source_));
      } catch (const ModelError& err) {
        leftOutError(err, "the sensor is left out");
      }
    } else {
      unsupported(c);
    }
  }
  return l;
}

InertialDescription Parser::parseInertial(const XMLElement* e, const std::string& what) {
  InertialDescription in;
  in.line = e->GetLineNum();
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "mass") {
      // Mass and inertia are checked where they matter, for a link that moves
      // (sim/world_physics.h): a static model's may be anything, nan included.
      if (!keepsDefault(c)) in.mass = anyNumber(c, what + " <inertial>");
    } else if (tag == "pose") {
      in.X_LI = pose(c, what + " <inertial>", in.X_LI);
    } else if (tag == "inertia") {
      Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
      const std::string iwhat = what + " <inertia>";
      for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement()) {
        const std::string key = k->Name();
        static const std::set<std::string> kInertia = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
        if (keepsDefault(k) && kInertia.count(key)) continue;  // keeps its default (sdformat)
        if (key == "ixx") I(0, 0) = anyNumber(k, iwhat);
        else if (key == "iyy") I(1, 1) = anyNumber(k, iwhat);
        else if (key == "izz") I(2, 2) = anyNumber(k, iwhat);
        else if (key == "ixy") I(0, 1) = I(1, 0) = anyNumber(k, iwhat);
        else if (key == "ixz") I(0, 2) = I(2, 0) = anyNumber(k, iwhat);
        else if (key == "iyz") I(1, 2) = I(2, 1) = anyNumber(k, iwhat);
        else unsupported(k);
      }
      in.inertia = I;
    } else {
      unsupported(c);
    }
  }
  return in;
}

std::optional<Shape> Parser::parseGeometry(const XMLElement* e, const std::string& what,
                                           const std::string& kind) {
  const XMLElement* g = e->FirstChildElement();
  if (!g) fail(e, what + ": <geometry> is empty");
  if (g->NextSiblingElement())
    fail(g->NextSiblingElement(), what + ": <geometry> holds more than one shape");
  const std::string type = g->Name();
  Shape s;
  // A shape of no size is left out with an error, and the rest of the world loads. Gazebo
  // passes it to ODE as it is (ODEBoxShape::SetSize: dCreateBox(0, x, y, z)), where a zero
  // box, sphere or cylinder collides as a point (worlds/collision_zero.world).
  static const std::string kZeroShape = " (Gazebo's ODE collides a zero-size shape as a point)";
  const std::string consequence = "the " + kind + " is left out";
  // Each shape reads only its own children; anything else is reported.
  auto children = [&](std::initializer_list<const char*> known,
                      const std::function<void(const XMLElement*, const std::string&)>& use) {
    for (const XMLElement* c = g->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      bool ok = false;
      for (const char* k : known) ok = ok || tag == k;
      if (ok) use(c, tag);
      else unsupported(c);
    }
  };
  if (type == "box") {
    s.type = ShapeType::kBox;
    bool have = false;
    children({"size"}, [&](const XMLElement* c, const std::string&) {
      s.size = vector3(c, what + " box", Eigen::Vector3d::Ones());  // SDF box size 1 1 1
      checkSize(c, s.size, what + ": <box> <size>");
      have = true;
    });
    if (!have) fail(g, what + ": <box> has no <size>");
    if (!(s.size.minCoeff() > 0.0)) {
      leftOut(g, what + ": <box> <size> must be > 0 in x, y and z" + kZeroShape, consequence);
      return std::nullopt;
    }
  } else if (type == "cylinder") {
    s.type = ShapeType::kCylinder;
    bool r = false, l = false;
    const XMLElement* not_positive = nullptr;
    children({"radius", "length"}, [&](const XMLElement* c, const std::string& tag) {
      const double v = number(c, what + " cylinder", 1.0);  // SDF radius, length 1
      if (!(v > 0.0) && !not_positive) not_positive = c;
      if (tag == "radius") s.radius = v, r = true;
      else s.length = v, l = true;
      checkSize(c, Eigen::Vector3d::Constant(v), what + ": <cylinder> <" + tag + ">");
    });
    if (!r || !l) fail(g, what + ": <cylinder> needs <radius> and <length>");
    if (not_positive) {
      leftOut(not_positive, what + ": <cylinder> <" + not_positive->Name() + "> must be > 0 (got " +
                                text(not_positive) + ")" + kZeroShape,
              consequence);
      return std::nullopt;
    }
  } else if (type == "sphere") {
    s.type = ShapeType::kSphere;
    bool r = false;
    const XMLElement* not_positive = nullptr;
    children({"radius"}, [&](const XMLElement* c, const std::string&) {
      s.radius = number(c, what + " sphere", 1.0);  // SDF radius 1
      if (!(s.radius > 0.0)) not_positive = c;
      checkSize(c, Eigen::Vector3d::Constant(s.radius), what + ": <sphere> <radius>");
      r = true;
    });
    if (!r) fail(g, what + ": <sphere> has no <radius>");
    if (not_positive) {
      leftOut(not_positive, what + ": <sphere> <radius> must be > 0 (got " + text(not_positive) + ")" +
                                kZeroShape,
              consequence);
      return std::nullopt;
    }
  } else if (type == "plane") {
    s.type = ShapeType::kPlane;
    s.size = Eigen::Vector3d::Zero();
    children({"normal", "size"}, [&](const XMLElement* c, const std::string& tag) {
      if (tag == "normal") {
        const std::optional<Eigen::Vector3d> n = limits::unitAxis(vector3(c, what + " plane"));
        if (!n) fail(c, what + ": <plane> <normal> must not be zero");
        s.normal = *n;
      } else {
        const auto v = numbers(c, what + " plane");
        if (v.size() != 2 || v[0] < 0.0 || v[1] < 0.0)
          fail(c, what + ": <plane> <size> '" + text(c) + "' is not 2 numbers >= 0");
        s.size = Eigen::Vector3d(v[0], v[1], 0.0);
        checkSize(c, s.size, what + ": <plane> <size>");
      }
    });
  } else if (type == "mesh") {
    s.type = ShapeType::kMesh;
    std::string uri;
    const XMLElement* uri_e = g;
    const XMLElement* bad_scale = nullptr;
    children({"uri", "scale", "submesh"}, [&](const XMLElement* c, const std::string& tag) {
      if (tag == "uri") {
        uri = text(c);
        uri_e = c;
      } else if (tag == "scale") {
        s.scale = vector3(c, what + " mesh", s.scale);
        if (!(s.scale.minCoeff() > 0.0)) bad_scale = c;
        else checkSize(c, s.scale, what + ": <mesh> <scale>");
      } else {
        // <submesh>: the file's parts of one name (mesh/mesh_loader.h), centred or not.
        for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement()) {
          const std::string ktag = k->Name();
          if (ktag == "name") s.submesh = text(k);
          else if (ktag == "center") s.center_submesh = boolean(k, what + " <submesh>");
          else unsupported(k);
        }
      }
    });
    if (uri.empty()) fail(g, what + ": <mesh> has no <uri>");
    if (bad_scale) {
      leftOut(bad_scale, what + ": <mesh> <scale> '" + text(bad_scale) +
                             "' must be > 0 in x, y and z (mesh '" + uri + "')",
              consequence);
      return std::nullopt;
    }
    const std::optional<std::string> path = resolveMesh(uri_e, uri, what, kind);
    if (!path) return std::nullopt;
    s.mesh_path = *path;
    if (options_.require_meshes) {
      // Read now (cached for the physics and sensors): a file that is no mesh, or has no
      // triangles or no such <submesh>, leaves out this geometry only, not the world.
      try {
        meshOf(s);
      } catch (const MeshError& err) {
        leftOut(uri_e, what + ": " + err.what(), consequence);
        return std::nullopt;
      }
    }
  } else {
    fail(g, what + ": unknown geometry <" + type +
                "> (supported: box, cylinder, sphere, plane, mesh)");
  }
  return s;
}

void Parser::leftOut(const XMLElement* e, const std::string& problem,
                     const std::string& consequence) {
  const std::string message = at(e) + problem;
  if (options_.strict) throw WorldError(message);
  const WarningSink& sink = options_.error ? options_.error : options_.warn;
  if (sink) sink(message + "; " + consequence);
}

void Parser::duplicate(const XMLElement* e, const std::string& name, const std::string& kind) {
  leftOut(e, "duplicate model name '" + name + "' (Gazebo does not insert a second model of a name)",
          "the " + kind + " is left out");
}

void Parser::leftOutError(const InputError& error, const std::string& consequence) {
  // The message starts with the place already.
  const std::string message = error.what();
  if (options_.strict) throw WorldError(message);
  const WarningSink& sink = options_.error ? options_.error : options_.warn;
  if (sink) sink(message + "; " + consequence);
}

std::optional<std::string> Parser::resolveMesh(const XMLElement* e, const std::string& uri,
                                               const std::string& what, const std::string& kind) {
  tianracer_assets::UriResolver::Found found;
  try {
    found = uriResolver().find(uri);
  } catch (const InputError& err) {
    leftOut(e, what + ": " + err.what(), "the " + kind + " is left out");
    return std::nullopt;
  }
  const std::vector<std::string>& tried = found.tried;
  std::string path = found.path;
  if (path.empty()) {
    // None is a file: report the first that exists (a directory, a device), else the first.
    path = tried.front();
    for (const std::string& t : tried) {
      if (tianracer_assets::fileProblem(t) != "file not found") {
        path = t;
        break;
      }
    }
  }
  if (options_.require_meshes && !isFile(path)) {
    // A directory or a device is said to be one (reading /dev/zero would never end); only a
    // missing file is "not found".
    const std::string problem = tianracer_assets::fileProblem(path);
    if (problem != "file not found") {
      leftOut(e, what + ": mesh '" + uri + "' (" + path + ") " + problem, "the " + kind + " is left out");
      return std::nullopt;
    }
    std::string msg = what + ": mesh '" + uri + "' not found (";
    for (std::size_t i = 0; i < tried.size(); ++i) msg += (i ? ", " : "tried ") + tried[i];
    leftOut(e, msg + ")", "the " + kind + " is left out");
    return std::nullopt;
  }
  return path;
}

Friction Parser::parseSurface(const XMLElement* e, const std::string& what,
                              ContactDescription* contact) {
  Friction f;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string ctag = c->Name();
    if (ctag != "friction" && ctag != "contact") {
      unsupported(c);
      continue;
    }
    for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement()) {
      if (ctag == "contact" && std::string(k->Name()) == "collide_without_contact") {
        contact->collide_without_contact = boolean(k, what + " contact");
        continue;
      }
      if (ctag == "contact" && std::string(k->Name()) == "collide_without_contact_bitmask") {
        contact->collide_without_contact_bitmask = unsignedInteger(k, what + " contact");
        continue;
      }
      if (ctag == "contact" && std::string(k->Name()) == "collide_bitmask") {
        contact->collide_bitmask = unsignedInteger(k, what + " contact");
        continue;
      }
      if (std::string(k->Name()) != "ode") {
        unsupported(k);
        continue;
      }
      for (const XMLElement* p = k->FirstChildElement(); p; p = p->NextSiblingElement()) {
        const std::string tag = p->Name();
        // An empty value keeps its default (sdformat); an unknown element is still reported.
        if (keepsDefault(p) && (tag == "mu" || tag == "mu2" || tag == "kp" || tag == "kd" ||
                                tag == "max_vel" || tag == "min_depth"))
          continue;
        // A negative mu is no limit (toSurface), as Gazebo reads it.
        if (ctag == "friction" && tag == "mu") f.mu = number(p, what + " friction");
        else if (ctag == "friction" && tag == "mu2") f.mu2 = number(p, what + " friction");
        else if (ctag == "contact" && tag == "kp") contact->kp = positive(p, what + " contact");
        else if (ctag == "contact" && tag == "kd") contact->kd = nonNegative(p, what + " contact");
        else if (ctag == "contact" && tag == "max_vel") contact->max_vel = number(p, what + " contact");
        else if (ctag == "contact" && tag == "min_depth")
          contact->min_depth = nonNegative(p, what + " contact");
        else unsupported(p);
      }
    }
  }
  return f;
}

JointDescription Parser::parseJoint(const XMLElement* e, const std::string& model,
                                    bool* axis_in_model_frame) {
  JointDescription j;
  j.name = attributeText(e, "name");
  j.type = attributeText(e, "type");
  j.line = e->GetLineNum();
  *axis_in_model_frame = false;
  const std::string what = "model '" + model + "' joint '" + j.name + "'";
  if (j.type.empty()) fail(e, what + " has no type");
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "parent") {
      j.parent = text(c);
    } else if (tag == "child") {
      j.child = text(c);
    } else if (tag == "pose") {
      j.X_CJ = pose(c, what, j.X_CJ);
    } else if (tag == "axis") {
      // SDF 1.5-1.7 <axis> (sdformat's joint.sdf): xyz in the joint frame unless
      // use_parent_model_frame (1.5, 1.6) or expressed_in="__model__" (1.7) says the model's.
      const std::string awhat = what + " <axis>";
      for (const XMLElement* a = c->FirstChildElement(); a; a = a->NextSiblingElement()) {
        const std::string atag = a->Name();
        if (atag == "xyz") {
          // Normalised without overflow: "1e308 1e308 0" is the unit vector it points along.
          const std::optional<Eigen::Vector3d> axis = limits::unitAxis(vector3(a, awhat));
          if (!axis) fail(a, awhat + ": <xyz> must not be zero");
          j.axis = *axis;
          if (const char* in = a->Attribute("expressed_in")) {
            const std::string frame = trimText(in);
            if (frame == "__model__") *axis_in_model_frame = true;
            else if (!frame.empty() && frame != j.name)
              warn(a, awhat + ": <xyz expressed_in='" + frame +
                          "'> is not supported; taken in the joint frame");
          }
        } else if (atag == "use_parent_model_frame") {
          *axis_in_model_frame = boolean(a, awhat);
        } else if (atag == "limit") {
          for (const XMLElement* l = a->FirstChildElement(); l; l = l->NextSiblingElement()) {
            const std::string ltag = l->Name();
            if (keepsDefault(l) && (ltag == "lower" || ltag == "upper" || ltag == "effort" ||
                                    ltag == "velocity"))
              continue;  // an empty value keeps its default (sdformat)
            if (ltag == "lower") j.lower = number(l, awhat + " <limit>");
            else if (ltag == "upper") j.upper = number(l, awhat + " <limit>");
            else if (ltag == "effort") j.effort = number(l, awhat + " <limit>");
            else if (ltag == "velocity") j.velocity = number(l, awhat + " <limit>");
            else unsupported(l);
          }
        } else if (atag == "dynamics") {
          for (const XMLElement* d = a->FirstChildElement(); d; d = d->NextSiblingElement()) {
            const std::string dtag = d->Name();
            const std::string dwhat = awhat + " <dynamics>";
            if (keepsDefault(d) && (dtag == "damping" || dtag == "friction" ||
                                    dtag == "spring_reference" || dtag == "spring_stiffness"))
              continue;  // an empty value keeps its default (sdformat)
            if (dtag == "damping") j.damping = coefficient(d, dwhat);
            else if (dtag == "friction") j.friction = coefficient(d, dwhat);
            else if (dtag == "spring_reference")
              j.spring_reference = bounded(d, dwhat, limits::kPosition, "");
            else if (dtag == "spring_stiffness") j.spring_stiffness = coefficient(d, dwhat);
            else unsupported(d);
          }
        } else {
          unsupported(a);
        }
      }
    } else {
      unsupported(c);
    }
  }
  if (j.parent.empty() || j.child.empty()) fail(e, what + " needs <parent> and <child>");
  return j;
}

}  // namespace world_internal

using namespace world_internal;

WorldDescription loadWorldString(const std::string& xml, const std::string& source,
                                 const std::string& base_dir, const WorldLoadOptions& options) {
  Parser parser(source, base_dir, options);
  return parser.parse(xml);
}

ModelDescription loadModelString(const std::string& xml, const std::string& source,
                                 const std::string& base_dir, const WorldLoadOptions& options) {
  Parser parser(source, base_dir, options);
  return parser.parseModelFile(xml);
}

WorldDescription loadWorldFile(const std::string& path, const WorldLoadOptions& options) {
  if (path.empty()) throw WorldError("world file: empty path");
  if (isDir(path)) throw WorldError("world file '" + path + "' is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!isFile(path) || !in) throw WorldError("world file '" + path + "' does not exist");
  const auto dot = path.find_last_of('.');
  if (dot != std::string::npos && (path.substr(dot) == ".yaml" || path.substr(dot) == ".yml"))
    return loadMapWorld(path, options);
  std::stringstream ss;
  ss << in.rdbuf();
  return loadWorldString(ss.str(), path, dirName(path), options);
}

std::vector<std::string> shippedWorldNames() { return {"empty", "walled_room", "racetrack", "lane_track", "obstacles"}; }

std::string resolveWorld(const std::string& arg, const std::string& worlds_dir) {
  if (arg.empty()) throw WorldError("world: empty name");
  if (isFile(arg)) return arg;
  const bool looks_like_path =
      arg.find('/') != std::string::npos || arg.find('.') != std::string::npos;
  if (!looks_like_path) {
    const std::string shipped = join(worlds_dir, arg + ".world");
    if (isFile(shipped)) return shipped;
  }
  std::string names;
  for (const std::string& n : shippedWorldNames()) names += (names.empty() ? "" : ", ") + n;
  throw WorldError("world " + quoted(arg) + " is neither a shipped world (" + names + " in " +
                   worlds_dir + ") nor an existing file");
}

std::map<std::string, int> addToScene(const WorldDescription& world, Scene& scene) {
  std::map<std::string, int> added;
  if (world.ambient) scene.ambient = *world.ambient;
  if (world.background) scene.sky = *world.background;
  if (world.sun) scene.lights.push_back(*world.sun);
  for (const DirectionalLight& l : world.lights) scene.lights.push_back(l);
  if (world.ground_plane) {
    scene.ground_plane = true;
    SceneBody body;
    body.name = "ground_plane::link";
    body.model = "ground_plane";
    body.is_static = true;
    body.X_WB = world.X_WG;
    const int b = scene.addBody(body);
    added[body.name] = b;
    // Collision only: the renderer draws Scene::ground_plane itself.
    SceneItem item;
    item.body = b;
    item.shape.type = ShapeType::kPlane;
    item.shape.normal = Eigen::Vector3d::UnitZ();
    item.shape.size = Eigen::Vector3d(100.0, 100.0, 0.0);
    item.material = findGazeboMaterial("Gazebo/Grey")->material;
    item.visual = false;
    item.collision = true;
    scene.items.push_back(item);
  }
  // The actors' links are moving bodies too (updateActorScene moves them).
  std::vector<const ModelDescription*> models;
  for (const ModelDescription& m : world.models) models.push_back(&m);
  for (const ActorDescription& a : world.actors) models.push_back(&a.model);
  for (const ModelDescription* model : models) {
    const ModelDescription& m = *model;
    for (const LinkDescription& l : m.links) {
      SceneBody body;
      body.name = m.name + "::" + l.name;
      body.model = m.name;
      body.is_static = m.is_static;
      body.X_WB = m.X_WM * l.X_ML;
      const int b = scene.addBody(body);
      added[body.name] = b;
      for (const CollisionDescription& c : l.collisions) {
        SceneItem item;
        item.body = b;
        item.X_BS = c.X_LS;
        item.shape = c.shape;
        item.visual = false;
        item.collision = true;
        scene.items.push_back(item);
      }
      for (const VisualDescription& v : l.visuals) {
        SceneItem item;
        item.body = b;
        item.X_BS = v.X_LS;
        item.shape = v.shape;
        item.material = v.material;
        item.visual = true;
        item.collision = false;
        scene.items.push_back(item);
      }
    }
  }
  return added;
}

}  // namespace tianracer_sim

namespace tianracer_sim {

std::vector<ActorPlayer> actorPlayers(const WorldDescription& world, double dt) {
  std::vector<ActorPlayer> players;
  for (const ActorDescription& a : world.actors) players.emplace_back(a.script, a.model.X_WM, dt);
  return players;
}

void updateActorScene(const WorldDescription& world, std::vector<ActorPlayer>* players, double t,
                      Scene* scene) {
  for (std::size_t i = 0; i < world.actors.size() && i < players->size(); ++i) {
    const ModelDescription& m = world.actors[i].model;
    const Eigen::Isometry3d& X_WA = (*players)[i].poseAt(t);
    for (SceneBody& body : scene->bodies) {
      if (body.model != m.name || body.name.size() <= m.name.size() + 2) continue;
      const std::string link = body.name.substr(m.name.size() + 2);
      for (const LinkDescription& l : m.links) {
        if (l.name == link) body.X_WB = X_WA * l.X_ML;
      }
    }
  }
}

}  // namespace tianracer_sim
