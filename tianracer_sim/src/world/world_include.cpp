// <include>: model files, the model:// search path and merging included models; and a saved
// <state> applied over the models of the world.
#include "world_parser.h"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <tianracer_assets/paths.h>

namespace tianracer_sim {

namespace {

/// A shape scaled by a model's <state> <scale> as Gazebo 11 scales it (Model::SetScale ->
/// Link::SetScale -> Collision::SetScale and Link::UpdateVisualGeomSDF, from scale 1): a box's
/// size times the scale; a sphere's radius times its largest component; a cylinder's radius
/// times max(x, y), its length times z (SphereShape.cc, CylinderShape.cc); a mesh's <scale>
/// replaced by it (MeshShape::SetScale sets, not multiplies); a plane's size times x and y.
/// Placements, masses and inertias stay as they are, as in Gazebo.
Shape scaledAsGazebo(Shape s, const Eigen::Vector3d& scale) {
  switch (s.type) {
    case ShapeType::kBox:
      s.size = s.size.cwiseProduct(scale);
      break;
    case ShapeType::kSphere:
      s.radius *= scale.maxCoeff();
      break;
    case ShapeType::kCylinder:
      s.radius *= std::max(scale.x(), scale.y());
      s.length *= scale.z();
      break;
    case ShapeType::kMesh:
      s.scale = scale;
      break;
    case ShapeType::kPlane:
      s.size.x() *= scale.x();
      s.size.y() *= scale.y();
      break;
    default:
      break;
  }
  return s;
}

}  // namespace
namespace world_internal {

bool isFile(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

bool isDir(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

std::string join(const std::string& dir, const std::string& rest) {
  if (dir.empty()) return rest;
  if (dir.back() == '/') return dir + rest;
  return dir + "/" + rest;
}

std::string dirName(const std::string& path) {
  const auto slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

namespace {

/// SDF version "1.6" -> (1, 6), compared as versions are (sdformat's getBestSupportedModelVersion
/// compares gz::math::SemanticVersions: 1.10 is above 1.7); a patch level is not compared;
/// unreadable -> (0, 0).
std::pair<int, int> sdfVersion(const std::string& v) {
  const std::size_t dot = v.find('.');
  const std::string minor = dot == std::string::npos ? "0" : v.substr(dot + 1);
  const auto a = parseInteger(v.substr(0, dot));
  const auto b = parseInteger(minor.substr(0, minor.find('.')));
  return a && b ? std::make_pair(*a, *b) : std::make_pair(0, 0);
}

}  // namespace

ModelDescription Parser::parseModelFile(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  if (parseXmlDocument(xml, &doc) != tinyxml2::XML_SUCCESS)
    throw WorldError(source_ + ":" + std::to_string(doc.ErrorLineNum()) + ": malformed XML: " +
                     doc.ErrorName());
  const XMLElement* root = doc.RootElement();
  if (!root) throw WorldError(source_ + ":1: malformed XML: no root element");
  if (std::string(root->Name()) == "model") return parseModel(root);  // a bare <model>
  if (std::string(root->Name()) != "sdf")
    fail(root, "root element is <" + std::string(root->Name()) + ">, expected <sdf>");
  const XMLElement* m = root->FirstChildElement("model");
  if (!m) fail(root, "no <model> in this model file");
  for (const XMLElement* c = root->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (c != m) unsupported(c, "a model file holds one <model>");
  }
  return parseModel(m);
}

void Parser::applyState(const XMLElement* e, WorldDescription& world,
                        std::set<std::string>& names) {
  auto findModel = [&](const std::string& name) -> ModelDescription* {
    for (ModelDescription& m : world.models)
      if (m.name == name) return &m;
    return nullptr;
  };
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "sim_time" || tag == "wall_time" || tag == "real_time" || tag == "iterations" ||
        tag == "light") {
      continue;  // times and light states do not change what is simulated
    } else if (tag == "insertions") {
      for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement()) {
        if (std::string(k->Name()) != "model") {
          unsupported(k);
          continue;
        }
        ModelDescription m = parseModel(k);
        if (!names.insert(m.name).second) fail(k, "duplicate model name '" + m.name + "'");
        world.models.push_back(std::move(m));
        checkModelCount(k, world);
      }
    } else if (tag == "deletions") {
      for (const XMLElement* k = c->FirstChildElement("name"); k; k = k->NextSiblingElement("name")) {
        const std::string name = text(k);
        auto it = std::find_if(world.models.begin(), world.models.end(),
                               [&](const ModelDescription& m) { return m.name == name; });
        if (it == world.models.end()) {
          leftOut(k, "<state> <deletions> names model '" + name +
                         "', which the world does not have",
                  "nothing is deleted");
          continue;
        }
        world.models.erase(it);
        names.erase(name);
      }
    } else if (tag == "model") {
      const std::string name = attributeText(c, "name");
      ModelDescription* m = findModel(name);
      if (!m) {
        // Gazebo logs "Unable to find model[...]" and applies the rest (World::SetState).
        leftOut(c, "<state> names model '" + name + "', which the world does not have",
                "its state is ignored");
        continue;
      }
      const std::string what = "<state> of model '" + name + "'";
      if (const XMLElement* p = c->FirstChildElement("pose")) m->X_WM = pose(p, what, m->X_WM);
      for (const XMLElement* k = c->FirstChildElement(); k; k = k->NextSiblingElement()) {
        const std::string ktag = k->Name();
        if (ktag == "pose") continue;
        if (ktag == "scale") {
          const Eigen::Vector3d scale = vector3(k, what);
          if (!(scale.minCoeff() > 0.0) || scale.maxCoeff() > 1e3) {
            // Gazebo's shapes ignore a negative scale (BoxShape::SetScale returns); a zero one
            // would leave nothing to collide with.
            leftOut(k, what + ": <scale> '" + text(k) + "' must be > 0 and <= 1000 in x, y and z",
                    "the model keeps its size");
            continue;
          }
          for (LinkDescription& l : m->links) {
            for (CollisionDescription& col : l.collisions) col.shape = scaledAsGazebo(col.shape, scale);
            for (VisualDescription& v : l.visuals) v.shape = scaledAsGazebo(v.shape, scale);
          }
        } else if (ktag == "link") {
          const std::string lname = attributeText(k, "name");
          auto l = std::find_if(m->links.begin(), m->links.end(),
                                [&](const LinkDescription& d) { return d.name == lname; });
          if (l == m->links.end()) {
            // Gazebo: Model::SetState's "Unable to find link[...]".
            leftOut(k, what + " names link '" + lname + "', which the model does not have",
                    "its state is ignored");
            continue;
          }
          // A link's state pose is its world pose.
          if (const XMLElement* p = k->FirstChildElement("pose"))
            l->X_ML = m->X_WM.inverse() * pose(p, what + " link '" + lname + "'");
        } else if (ktag != "joint") {
          unsupported(k);
        }
      }
    } else {
      unsupported(c);
    }
  }
}

std::optional<Parser::IncludeSpec> Parser::parseIncludeSpec(const XMLElement* e) {
  IncludeSpec spec;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "uri") {
      spec.uri = text(c);
    } else if (tag == "pose") {
      // An empty one keeps the model's own pose (sdformat 9 parser.cc, readXml's <include>:
      // the pose is set only from text).
      spec.has_pose = !keepsDefault(c);
      if (spec.has_pose) spec.X = pose(c, "<include>");
    } else if (tag == "name") {
      spec.name = text(c);
    } else if (tag == "static") {
      if (!keepsDefault(c)) spec.is_static = boolean(c, "<include>");
    } else {
      unsupported(c);
    }
  }
  while (!spec.uri.empty() && spec.uri.back() == '/') spec.uri.pop_back();
  if (spec.uri.empty()) {
    // sdformat 9 (parser.cc resolveFileNameFromUri) reports "<include> element missing 'uri'
    // attribute" and skips the include; the rest loads. SDF 1.3's <include filename='...'>
    // (Gazebo's deprecated_worlds) is such an include.
    const char* filename = e->Attribute("filename");
    leftOut(e, filename ? "<include filename='" + std::string(filename) +
                              "'> has no <uri> (the filename attribute is SDF 1.3's, which sdformat "
                              "no longer reads)"
                        : std::string("<include> has no <uri>"),
            "the include is left out");
    return std::nullopt;
  }
  return spec;
}

void Parser::parseInclude(const XMLElement* e, WorldDescription& world) {
  const std::optional<IncludeSpec> given = parseIncludeSpec(e);
  if (!given) return;  // left out, reported
  const IncludeSpec& spec = *given;
  if (spec.uri == "model://ground_plane") {
    if (world.ground_plane) warn(e, "model://ground_plane included twice; using the last pose");
    world.ground_plane = true;
    world.X_WG = spec.X;
  } else if (spec.uri == "model://sun") {
    DirectionalLight sun;  // Gazebo's sun model (sun/model.sdf): the defaults of DirectionalLight
    sun.name = "sun";
    sun.attenuation = {0.9, 0.01, 0.001};
    if (spec.has_pose) sun.direction = spec.X.linear() * sun.direction;
    world.sun = sun;
  } else if (std::optional<ModelDescription> m = includeModel(e, spec)) {
    world.models.push_back(std::move(*m));
  }
}

std::vector<std::string> Parser::modelDirs() const {
  std::vector<std::string> extra = options_.model_paths;
  extra.insert(extra.end(), model_roots_.begin(), model_roots_.end());
  extra.push_back(base_dir_);
  extra.push_back(join(base_dir_, "models"));
  return tianracer_assets::modelSearchPath(extra);
}

tianracer_assets::UriResolver Parser::uriResolver() const {
  tianracer_assets::UriResolver resolver;
  resolver.find_package = options_.find_package;
  resolver.base_dir = base_dir_;
  resolver.model_paths = options_.model_paths;
  resolver.model_paths.insert(resolver.model_paths.end(), model_roots_.begin(), model_roots_.end());
  resolver.model_paths.push_back(base_dir_);
  resolver.model_paths.push_back(join(base_dir_, "models"));
  return resolver;
}

std::optional<ModelDescription> Parser::includeModel(const XMLElement* e, const IncludeSpec& spec) {
  // The model's folder: model://NAME in the model folders, or a file:// / plain path.
  std::string dir;
  std::vector<std::string> tried;
  try {
    tianracer_assets::UriResolver::Found found =
        uriResolver().find(spec.uri, tianracer_assets::UriResolver::Want::kFolder);
    dir = found.path;
    // For model://, the message lists the folders searched; otherwise the path tried.
    tried = startsWith(spec.uri, "model://") ? modelDirs() : found.tried;
  } catch (const InputError& err) {
    leftOut(e, "<include> of '" + spec.uri + "': " + err.what(), "the model is left out");
    return std::nullopt;
  }
  if (dir.empty()) {
    std::string msg = "<include> of '" + spec.uri + "': model not found; searched:";
    for (const std::string& t : tried) msg += " " + t;
    if (startsWith(spec.uri, "model://"))
      msg += " (set GAZEBO_MODEL_PATH, or export gazebo_model_path from a ROS package)";
    // Gazebo's sdformat parser reports "Unable to find uri[...]" and goes on without it.
    leftOut(e, msg, "the model is left out");
    return std::nullopt;
  }
  // model.config names the model file(s): the highest SDF version we read (<= 1.7) wins.
  std::string file;
  const std::string config = join(dir, "model.config");
  if (isFile(config)) {
    // Read as every other XML file here (parseXmlDocument, elementText): an error names the
    // line of model.config.
    std::ifstream in(config, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    tinyxml2::XMLDocument doc;
    if (!in || parseXmlDocument(text.str(), &doc) != tinyxml2::XML_SUCCESS)
      fail(e, "<include> of '" + spec.uri + "': " + formatLocation(config, doc.ErrorLineNum()) +
                  "is not valid XML" + (doc.Error() ? std::string(" (") + doc.ErrorName() + ")" : ""));
    const XMLElement* root = doc.RootElement();
    std::pair<int, int> best{-1, -1};
    for (const XMLElement* s = root ? root->FirstChildElement("sdf") : nullptr; s;
         s = s->NextSiblingElement("sdf")) {
      const std::pair<int, int> v = sdfVersion(attributeText(s, "version"));
      if (v <= std::make_pair(1, 7) && v > best && !elementText(s).empty()) {
        best = v;
        file = join(dir, elementText(s));
      }
    }
    if (file.empty())
      fail(e, "<include> of '" + spec.uri + "': " + config + " names no <sdf> file of version <= 1.7");
  } else if (isFile(join(dir, "model.sdf"))) {
    file = join(dir, "model.sdf");
  } else {
    leftOut(e, "<include> of '" + spec.uri + "': " + dir + " has neither model.config nor model.sdf",
            "the model is left out");
    return std::nullopt;
  }
  std::string canonical = file;
  std::error_code ec;
  const auto c = std::filesystem::weakly_canonical(file, ec);
  if (!ec) canonical = c.string();
  if (std::find(include_stack_.begin(), include_stack_.end(), canonical) != include_stack_.end()) {
    std::string chain;
    for (const std::string& f : include_stack_) chain += f + " -> ";
    fail(e, "<include> loop: " + chain + canonical);
  }
  std::ifstream in(file);
  if (!in) fail(e, "<include> of '" + spec.uri + "': cannot read " + file);
  std::stringstream ss;
  ss << in.rdbuf();
  Parser sub(file, dir, options_);  // a strict world is strict in its models too
  sub.include_stack_ = include_stack_;
  sub.include_stack_.push_back(canonical);
  sub.model_roots_ = model_roots_;
  // Its siblings, and what the including file could reach, resolve its model:// URIs too.
  sub.model_roots_.push_back(dirName(dir));
  sub.model_roots_.push_back(base_dir_);
  sub.model_roots_.push_back(join(base_dir_, "models"));
  ModelDescription m = sub.parseModelFile(ss.str());
  if (!spec.name.empty()) m.name = spec.name;
  if (spec.has_pose) m.X_WM = spec.X;
  if (spec.is_static) m.is_static = *spec.is_static;
  return m;
}

void Parser::mergeSubModel(ModelDescription* m, const ModelDescription& sub,
                           const Eigen::Isometry3d& X_MS) {
  for (LinkDescription l : sub.links) {
    l.name = sub.name + "::" + l.name;
    for (SensorSpec& sensor : l.sensors) sensor.link = l.name;
    l.X_ML = X_MS * l.X_ML;
    m->links.push_back(std::move(l));
  }
  for (PluginSpec p : sub.plugins) {
    auto body = p.params.find("bodyName");
    if (body != p.params.end() && !body->second.empty()) body->second = sub.name + "::" + body->second;
    m->plugins.push_back(std::move(p));
  }
  for (JointDescription j : sub.joints) {
    j.name = sub.name + "::" + j.name;
    if (j.parent != "world") j.parent = sub.name + "::" + j.parent;
    if (j.child != "world") j.child = sub.name + "::" + j.child;
    m->joints.push_back(std::move(j));
  }
}

}  // namespace world_internal
}  // namespace tianracer_sim
