#include "tianracer_sim/world/sdf_material.h"
#include "tianracer_sim/common/xml_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <tianracer_assets/paths.h>

#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/scene/ogre_material.h"

namespace tianracer_sim {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

bool exists(const std::string& p) {
  std::error_code ec;
  return !p.empty() && fs::exists(p, ec);
}

std::string joinPath(const std::string& a, const std::string& b) {
  if (a.empty()) return b;
  return (fs::path(a) / b).lexically_normal().string();
}

class MaterialParser {
 public:
  // Messages read "<source>:<line>: <what>: ...".
  explicit MaterialParser(const SdfMaterialContext& ctx)
      : ctx_(ctx), xml_(ctx.source, ctx.warn, ctx.what + ": ") {}

  void warn(const XMLElement* e, const std::string& msg) { xml_.warn(e, msg); }
  void unsupported(const XMLElement* e) { xml_.unsupported(e); }

  // One message for every bad colour (not XmlReader::color's "not a list of numbers").
  Eigen::Vector4f color(const XMLElement* e) const {
    std::vector<double> v = parseNumbers(elementText(e)).value_or(std::vector<double>(99));
    if (!std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); })) v.resize(99);
    if (v.size() != 3 && v.size() != 4) {
      xml_.fail(e, "<" + std::string(e->Name()) + "> '" + elementText(e) +
                   "' is not a colour \"r g b [a]\"");
    }
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]),
            v.size() == 4 ? static_cast<float>(v[3]) : 1.0f};
  }

  // Resolves a texture URI (albedo_map) or warns and returns "".
  std::string texture(const XMLElement* e, const std::string& uri) {
    std::vector<std::string> tried;
    const std::string path = resolveMaterialUri(uri, ctx_, &tried);
    if (path.empty()) {
      std::string msg = "texture '" + uri + "' not found (tried";
      for (const auto& t : tried) msg += " " + t;
      warn(e, msg + "); the diffuse colour is drawn instead");
    }
    return path;
  }

  void script(const XMLElement* e, Material* m) {
    std::vector<std::string> folders;
    std::string name;
    const XMLElement* name_e = e;
    for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      if (tag == "uri") {
        const std::string uri = elementText(c);
        std::vector<std::string> tried;
        const std::string p = resolveMaterialUri(uri, ctx_, &tried);
        // Gazebo's own media folders are not shipped: only a model's URIs are worth a warning.
        if (!p.empty()) folders.push_back(p);
        else if (uri.rfind("file://media/", 0) != 0) warn(c, "<script><uri> '" + uri + "' not found");
      } else if (tag == "name") {
        name = elementText(c);
        name_e = c;
      } else {
        unsupported(c);
      }
    }
    if (name.empty()) return;
    if (auto g = findGazeboMaterial(name)) {
      *m = g->material;
      m->specified = true;
      return;
    }
    const auto ogre = findOgreMaterial(name, folders, ctx_.warn);
    if (!ogre) {
      std::string msg = "unknown material '" + name + "' (not a Gazebo stock name";
      msg += folders.empty() ? ", and no <uri> folder was found" : ", and not in the scripts of";
      for (const auto& f : folders) msg += " " + f;
      warn(name_e, msg + "), using the default grey");
      m->name = name;
      m->specified = true;
      return;
    }
    m->name = name;
    m->specified = true;
    // Ogre's defaults for what the script leaves out: ambient and diffuse white, no specular.
    m->ambient = ogre->ambient.value_or(Eigen::Vector4f(1, 1, 1, 1));
    m->diffuse = ogre->diffuse.value_or(Eigen::Vector4f(1, 1, 1, 1));
    m->specular = ogre->specular.value_or(Eigen::Vector4f(0, 0, 0, 1));
    m->shininess = ogre->shininess;
    if (ogre->texture.empty()) return;
    m->texture_scale = ogre->texture_scale;
    std::vector<std::string> dirs = folders;
    const std::string script_dir = fs::path(ogre->file).parent_path().string();
    dirs.push_back(script_dir);
    dirs.push_back(joinPath(script_dir, "../textures"));
    std::string msg;
    for (const auto& d : dirs) {
      const std::string p = fs::is_directory(d) ? joinPath(d, ogre->texture) : std::string();
      if (!p.empty() && exists(p)) {
        m->texture = p;
        return;
      }
      if (!p.empty()) msg += " " + p;
    }
    xml_.warn(formatLocation(ogre->file, ogre->line) + "material " + name + ": texture '" +
              ogre->texture + "' not found (tried" + msg + ") for " + ctx_.what + " (" +
              ctx_.source + ":" + std::to_string(name_e->GetLineNum()) +
              "); the diffuse colour is drawn instead");
  }

  void pbr(const XMLElement* e, Material* m) {
    for (const XMLElement* w = e->FirstChildElement(); w; w = w->NextSiblingElement()) {
      const std::string workflow = w->Name();
      if (workflow != "metal" && workflow != "specular") {
        unsupported(w);
        continue;
      }
      for (const XMLElement* c = w->FirstChildElement(); c; c = c->NextSiblingElement()) {
        if (std::string(c->Name()) == "albedo_map") {
          const std::string uri = elementText(c);
          const std::string p = uri.empty() ? std::string() : texture(c, uri);
          if (!p.empty()) {
            m->texture = p;
            m->texture_scale = Eigen::Vector2f(1.0f, 1.0f);
            m->specified = true;
          }
        } else {
          unsupported(c);
        }
      }
    }
  }

 private:
  const SdfMaterialContext& ctx_;
  XmlReader xml_;
};

}  // namespace

std::string resolveMaterialUri(const std::string& uri, const SdfMaterialContext& ctx,
                               std::vector<std::string>* tried) {
  tianracer_assets::UriResolver::Found found;
  try {
    found = ctx.resolver.find(uri, tianracer_assets::UriResolver::Want::kAny);
  } catch (const InputError&) {
    return "";  // a malformed URI is not found: the caller warns with the URI
  }
  if (tried) tried->insert(tried->end(), found.tried.begin(), found.tried.end());
  return found.path;
}

Material parseSdfMaterial(const XMLElement* e, const SdfMaterialContext& ctx) {
  MaterialParser r(ctx);
  Material m;
  // A script sets the base colours (and texture); explicit colours override them, as in Gazebo.
  for (const XMLElement* c = e->FirstChildElement("script"); c; c = c->NextSiblingElement("script")) {
    r.script(c, &m);
  }
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string tag = c->Name();
    if (tag == "script") continue;
    if (tag == "ambient") m.ambient = r.color(c);
    else if (tag == "diffuse") m.diffuse = r.color(c);
    else if (tag == "specular") m.specular = r.color(c);
    else if (tag == "pbr") r.pbr(c, &m);
    else {
      r.unsupported(c);
      continue;
    }
    m.specified = true;
  }
  return m;
}

}  // namespace tianracer_sim
