#include "tianracer_sim/render/renderer.h"

#include "gl_api.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "geometry.h"
#include "gl_context.h"
#include "shaders.h"
#include "tianracer_sim/common/text.h"
#include "tianracer_sim/mesh/mesh_loader.h"
#include "tianracer_sim/render/image_file.h"
#include "tianracer_sim/scene/materials.h"

namespace tianracer_sim {

namespace ri = render_internal;
using render_internal::GlContext;

namespace {

Eigen::Matrix4f toFloat(const Eigen::Matrix4d& m) { return m.cast<float>(); }

// STL files carry no materials or texture coordinates: they keep the positions-only load that
// physics shares (and exactly the geometry they had before materials were read).
bool mayHaveMaterials(const std::string& path) {
  if (path.size() < 4) return true;
  return lowerCase(path.substr(path.size() - 4)) != ".stl";
}

std::string shapeKey(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::kBox: return "box";
    case ShapeType::kCylinder: return "cylinder";
    case ShapeType::kSphere: return "sphere";
    case ShapeType::kPlane: return "quad";
    case ShapeType::kMesh: {
      std::ostringstream os;
      os.precision(17);
      os << "mesh:" << shape.mesh_path << '|' << shape.scale.x() << ',' << shape.scale.y() << ','
         << shape.scale.z() << '|' << shape.submesh << '|' << shape.center_submesh;
      return os.str();
    }
  }
  return "?";
}

// Unbounded planes are drawn as squares this large (metres), centred under the camera.
constexpr double kUnboundedPlaneSize = 2000.0;

}  // namespace

// -----------------------------------------------------------------------------------------------
struct Renderer::Impl {
  std::shared_ptr<GlContext> context;
  WarningSink warn;

  struct Uniforms {
    GLint model_view, projection, normal_matrix, model, to_light, ambient, diffuse, specular,
        shininess, uv_scale, texture;
  };
  struct Program {
    GLuint id = 0;
    Uniforms u{};
  };
  static constexpr int kMaxLights = 4;
  Program programs[kMaxLights + 1][2][2][2];  // by light count, grid, texture, flat probe; on first use

  GLuint vao = 0;
  GLuint vbo = 0;
  std::vector<ri::Vertex> vertices;  // CPU copy of the VBO (append, re-upload on growth)
  bool vbo_dirty = false;
  struct Range {
    GLint first = 0;
    GLsizei count = 0;
  };
  // A shape's triangles in the VBO: one part per mesh material (primitives: one, material -1).
  struct Part {
    Range range;
    int material = -1;  // index into the mesh's materials
  };
  struct Geometry {
    std::vector<Part> parts;
    std::shared_ptr<const TriangleMesh> mesh;  // for its materials (null for primitives, STL)
  };
  std::map<std::string, Geometry> geometry;  // shapeKey -> its parts in the VBO
  std::set<std::string> failed;              // shape keys that did not load (warned once)

  // Textures by file, uploaded once with mipmaps; 0 = the file could not be read (warned once).
  std::map<std::string, GLuint> textures;

  GLuint textureFor(const std::string& path, const std::string& who) {
    const auto it = textures.find(path);
    if (it != textures.end()) return it->second;
    GLuint id = 0;
    try {
      const RgbaImage image = readImageFile(path);
      glGenTextures(1, &id);
      glBindTexture(GL_TEXTURE_2D, id);
      glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
      // Rows bottom-up, so that v = 0 is the bottom of the image (OpenGL's and the mesh
      // files' convention).
      glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA,
                   GL_UNSIGNED_BYTE, image.bottomUp().data());
      glGenerateMipmap(GL_TEXTURE_2D);
      // Trilinear, no anisotropy: llvmpipe's anisotropic path more than doubles the time of
      // a textured 800x800 frame (measured 8 -> 19 ms CPU for the lane track at 2x or 8x).
      // Markings far ahead on a floor blur along the view as a result.
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    } catch (const std::exception& e) {
      id = 0;
      if (warn) warn("renderer: " + who + ": " + e.what() + "; drawing its diffuse colour instead");
    }
    textures[path] = id;
    return id;
  }

  // What each scene item resolved to, by item index. Checked against the item's shape every
  // frame (cheap comparisons, no allocation) so that any change of the scene is picked up;
  // poses, scales and colours are read from the scene every frame.
  struct Slot {
    bool resolved = false;
    bool drawable = false;
    ShapeType type = ShapeType::kBox;
    std::string mesh_path;
    Eigen::Vector3d mesh_scale = Eigen::Vector3d::Ones();
    std::string mesh_submesh;
    bool mesh_center = false;
    const Geometry* geometry = nullptr;  // into `geometry` (std::map: stable addresses)
    std::string material_name;
    float material_shininess = -2.0f;
    float shininess = kDefaultShininess;
    std::string texture_path;
    GLuint texture = 0;                 // the item material's texture (0: none)
    std::vector<GLuint> mesh_textures;  // per mesh material (0: none)
    bool size_warned = false;
  };
  std::vector<Slot> slots;
  bool lights_warned = false;

  bool matches(const Slot& slot, const Shape& shape) const {
    if (!slot.resolved || slot.type != shape.type) return false;
    if (shape.type != ShapeType::kMesh) return true;
    return slot.mesh_path == shape.mesh_path && slot.mesh_scale == shape.scale &&
           slot.mesh_submesh == shape.submesh && slot.mesh_center == shape.center_submesh;
  }

  Slot& slotFor(std::size_t i, const SceneItem& item) {
    Slot& slot = slots[i];
    if (!matches(slot, item.shape)) {
      slot.resolved = true;
      slot.type = item.shape.type;
      slot.mesh_path = item.shape.mesh_path;
      slot.mesh_scale = item.shape.scale;
      slot.mesh_submesh = item.shape.submesh;
      slot.mesh_center = item.shape.center_submesh;
      slot.geometry = geometryFor(item.shape);
      slot.drawable = slot.geometry != nullptr;
      slot.size_warned = false;
      slot.mesh_textures.clear();
      if (slot.geometry && slot.geometry->mesh) {
        for (const MeshMaterial& mm : slot.geometry->mesh->materials) {
          GLuint id = 0;
          if (!mm.texture.empty()) {
            id = textureFor(mm.texture, "mesh '" + item.shape.mesh_path + "' material '" + mm.name +
                                            "' texture '" + mm.texture_uri + "'");
          } else if (!mm.texture_error.empty() && warn) {
            warn("renderer: mesh '" + item.shape.mesh_path + "' material '" + mm.name + "': " +
                 mm.texture_error + "; drawing its diffuse colour instead");
          }
          slot.mesh_textures.push_back(id);
        }
      }
    }
    if (slot.material_name != item.material.name || slot.material_shininess != item.material.shininess) {
      slot.material_name = item.material.name;
      slot.material_shininess = item.material.shininess;
      const auto gz = item.material.name.empty() ? std::nullopt : findGazeboMaterial(item.material.name);
      slot.shininess = item.material.shininess >= 0.0f ? item.material.shininess
                       : gz                            ? gz->shininess
                                                       : kDefaultShininess;
    }
    if (slot.texture_path != item.material.texture) {
      slot.texture_path = item.material.texture;
      slot.texture = slot.texture_path.empty()
                         ? 0
                         : textureFor(slot.texture_path, "texture '" + slot.texture_path + "'");
    }
    return slot;
  }

  struct Target {
    GLuint fbo = 0, color = 0, depth_color = 0, depth = 0;
  };
  std::map<std::pair<int, int>, Target> targets;

  Program& program(int num_lights, bool grid, bool texture, bool flat = false) {
    Program& p = programs[num_lights][grid ? 1 : 0][texture ? 1 : 0][flat ? 1 : 0];
    if (p.id != 0) return p;
    const std::string defines = "#version 330 core\n#define NUM_LIGHTS " + std::to_string(num_lights) +
                                "\n#define GRID " + (grid ? "1" : "0") + "\n#define TEXTURE " +
                                (texture ? "1" : "0") + "\n#define FLAT " + (flat ? "1" : "0") + "\n";
    const GLuint id = ri::linkProgram(defines);
    auto loc = [&](const char* name) { return glGetUniformLocation(id, name); };
    p.u.model_view = loc("u_model_view");
    p.u.projection = loc("u_projection");
    p.u.normal_matrix = loc("u_normal_matrix");
    p.u.model = loc("u_model");
    p.u.to_light = loc("u_to_light");
    p.u.ambient = loc("u_ambient");
    p.u.diffuse = loc("u_diffuse");
    p.u.specular = loc("u_specular");
    p.u.shininess = loc("u_shininess");
    p.u.uv_scale = loc("u_uv_scale");
    p.u.texture = loc("u_texture");
    if (texture) {
      glUseProgram(id);
      glUniform1i(p.u.texture, 0);  // texture unit 0
    }
    p.id = id;
    return p;
  }

  const Geometry* addGeometry(const std::string& key, const ri::Soup& soup,
                              const std::vector<ri::MeshPart>& mesh_parts = {},
                              std::shared_ptr<const TriangleMesh> mesh = nullptr) {
    const GLint base = static_cast<GLint>(vertices.size());
    Geometry g;
    if (mesh_parts.empty()) {
      g.parts.push_back(Part{Range{base, static_cast<GLsizei>(soup.size())}, -1});
    } else {
      for (const ri::MeshPart& mp : mesh_parts) {
        g.parts.push_back(Part{Range{base + static_cast<GLint>(mp.first), static_cast<GLsizei>(mp.count)},
                               mp.material});
      }
    }
    g.mesh = std::move(mesh);
    vertices.insert(vertices.end(), soup.begin(), soup.end());
    vbo_dirty = true;
    return &(geometry[key] = std::move(g));
  }

  void uploadIfDirty() {
    if (!vbo_dirty) return;
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices.size() * sizeof(ri::Vertex)),
                 vertices.data(), GL_STATIC_DRAW);
    vbo_dirty = false;
  }

  // Returns null when the shape cannot be drawn (warned once per mesh).
  const Geometry* geometryFor(const Shape& shape) {
    const std::string key = shapeKey(shape);
    const auto it = geometry.find(key);
    if (it != geometry.end()) return &it->second;
    if (failed.count(key)) return nullptr;
    if (shape.type != ShapeType::kMesh) return nullptr;  // primitives are made up front
    try {
      if (!mayHaveMaterials(shape.mesh_path)) {
        const auto mesh = meshOf(shape);
        return addGeometry(key, ri::meshSoup(*mesh));
      }
      const auto mesh = meshWithMaterialsOf(shape);
      std::vector<ri::MeshPart> parts;
      const ri::Soup soup = ri::meshSoup(*mesh, 40.0, &parts);
      return addGeometry(key, soup, parts, mesh);
    } catch (const std::exception& e) {
      failed.insert(key);
      if (warn) warn(std::string("renderer: skipping a visual: ") + e.what());
      return nullptr;
    }
  }

  Target& target(int w, int h) {
    auto it = targets.find({w, h});
    if (it != targets.end()) return it->second;
    Target t;
    glGenFramebuffers(1, &t.fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
    GLuint rb[3];
    glGenRenderbuffers(3, rb);
    t.color = rb[0];
    t.depth_color = rb[1];
    t.depth = rb[2];
    glBindRenderbuffer(GL_RENDERBUFFER, t.color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, t.color);
    glBindRenderbuffer(GL_RENDERBUFFER, t.depth_color);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_R32F, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, t.depth_color);
    glBindRenderbuffer(GL_RENDERBUFFER, t.depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, t.depth);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      glDeleteFramebuffers(1, &t.fbo);
      glDeleteRenderbuffers(3, rb);
      std::ostringstream os;
      os << "offscreen target " << w << "x" << h << " incomplete (status 0x" << std::hex << status
         << ")";
      throw RenderError(os.str());
    }
    return targets.emplace(std::make_pair(w, h), t).first->second;
  }
};

Renderer::Renderer(WarningSink warn) : impl_(new Impl) {
  const char* no_gl = std::getenv("TIANRACER_SIM_NO_GL");
  if (no_gl != nullptr && *no_gl != '\0' && std::string(no_gl) != "0") {
    throw RenderError("rendering disabled by TIANRACER_SIM_NO_GL");
  }
  impl_->warn = std::move(warn);
  impl_->context = GlContext::acquire();
  auto lock = impl_->context->lock();
  Impl& m = *impl_;

  m.program(1, false, false);  // the common case, and a check that the shaders build here
  m.program(1, true, false);

  glGenVertexArrays(1, &m.vao);
  glGenBuffers(1, &m.vbo);
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(ri::Vertex),
                        reinterpret_cast<void*>(offsetof(ri::Vertex, p)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(ri::Vertex),
                        reinterpret_cast<void*>(offsetof(ri::Vertex, n)));
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(ri::Vertex),
                        reinterpret_cast<void*>(offsetof(ri::Vertex, t)));

  m.addGeometry("box", ri::unitBox());
  m.addGeometry("cylinder", ri::unitCylinder());
  m.addGeometry("sphere", ri::unitSphere());
  m.addGeometry("quad", ri::unitQuad());
  m.uploadIfDirty();
}

Renderer::~Renderer() {
  if (!impl_ || !impl_->context) return;
  try {
    auto lock = impl_->context->lock();
    for (auto& kv : impl_->targets) {
      Impl::Target& t = kv.second;
      glDeleteFramebuffers(1, &t.fbo);
      GLuint rb[3] = {t.color, t.depth_color, t.depth};
      glDeleteRenderbuffers(3, rb);
    }
    glDeleteBuffers(1, &impl_->vbo);
    glDeleteVertexArrays(1, &impl_->vao);
    for (const auto& kv : impl_->textures) {
      if (kv.second != 0) glDeleteTextures(1, &kv.second);
    }
    for (const auto& by_grid : impl_->programs) {
      for (const auto& by_texture : by_grid) {
        for (const auto& by_flat : by_texture) {
          for (const auto& p : by_flat) {
            if (p.id != 0) glDeleteProgram(p.id);
          }
        }
      }
    }
  } catch (...) {
    // The context is going away with us; nothing else to release.
  }
}

std::string Renderer::glInfo() const { return impl_->context->info(); }

void Renderer::prepare(const Scene& scene) {
  auto lock = impl_->context->lock();
  Impl& m = *impl_;
  m.slots.resize(scene.items.size());
  for (std::size_t i = 0; i < scene.items.size(); ++i) {
    if (scene.items[i].visual) m.slotFor(i, scene.items[i]);
  }
  m.uploadIfDirty();
}

void Renderer::setProfile(StepProfile* profile) {
  profile_ = profile;
  draw_row_ = profileRow(profile, "frame worker: renders / GL draw to glFinish");
  readback_row_ = profileRow(profile, "frame worker: renders / glReadPixels");
}

void Renderer::renderView(const Scene& scene, const Eigen::Isometry3d& X_WC,
                          const CameraIntrinsics& K, uint8_t* rgb, float* depth) {
  if (K.width <= 0 || K.height <= 0 || K.width > 16384 || K.height > 16384) {
    throw RenderError("renderView: bad image size " + std::to_string(K.width) + "x" +
                      std::to_string(K.height));
  }
  if (!(K.fx > 0.0) || !(K.fy > 0.0) || !(K.near_clip > 0.0) || !(K.far_clip > K.near_clip)) {
    throw RenderError("renderView: bad intrinsics (f must be > 0 and 0 < near < far)");
  }
  Impl& m = *impl_;
  auto lock = m.context->lock();
  const StepProfile::Clock::time_point draw_start =
      profile_ ? StepProfile::Clock::now() : StepProfile::Clock::time_point();
  prepare(scene);
  Impl::Target& t = m.target(K.width, K.height);

  // View: world -> GL eye (x right, y up, z backward) = optical with y and z negated.
  Eigen::Isometry3d X_CE = opticalFromLinkRotation();
  X_CE.linear() = X_CE.linear() * Eigen::Vector3d(1, -1, -1).asDiagonal();
  const Eigen::Isometry3d X_EW = (X_WC * X_CE).inverse();

  // Projection (see CameraIntrinsics): NDC x = (2 (u + 0.5) / W - 1), and NDC y with rows
  // counted from the top, so that GL's bottom-up read-back gives top-down rows directly.
  const double W = K.width, H = K.height, n = K.near_clip, f = K.far_clip;
  Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
  P(0, 0) = 2.0 * K.fx / W;
  P(0, 2) = -(2.0 * (K.cx + 0.5) / W - 1.0);
  P(1, 1) = -2.0 * K.fy / H;
  P(1, 2) = -(2.0 * (K.cy + 0.5) / H - 1.0);
  P(2, 2) = -(f + n) / (f - n);
  P(2, 3) = -2.0 * f * n / (f - n);
  P(3, 2) = -1.0;
  const Eigen::Matrix4f Pf = toFloat(P);

  glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
  const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glDrawBuffers(depth != nullptr ? 2 : 1, buffers);
  glViewport(0, 0, K.width, K.height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_DITHER);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CW);  // the y-flipped projection mirrors the winding
  const float sky[4] = {scene.sky[0], scene.sky[1], scene.sky[2], 1.0f};
  glClearBufferfv(GL_COLOR, 0, sky);
  if (depth != nullptr) {
    const float inf[4] = {std::numeric_limits<float>::infinity(), 0, 0, 0};
    glClearBufferfv(GL_COLOR, 1, inf);
  }
  glClear(GL_DEPTH_BUFFER_BIT);

  const int num_lights = static_cast<int>(std::min<std::size_t>(scene.lights.size(), Impl::kMaxLights));
  if (scene.lights.size() > Impl::kMaxLights && !m.lights_warned) {
    m.lights_warned = true;
    if (m.warn) m.warn("renderer: the scene has " + std::to_string(scene.lights.size()) +
                       " directional lights; only the first 4 are drawn");
  }
  glBindVertexArray(m.vao);
  float to_light[12];
  for (int i = 0; i < num_lights; ++i) {
    const DirectionalLight& L = scene.lights[i];
    Eigen::Vector3d d = L.direction.norm() > 0 ? L.direction.normalized() : Eigen::Vector3d(0, 0, -1);
    d = X_EW.linear() * d;
    for (int k = 0; k < 3; ++k) to_light[3 * i + k] = -static_cast<float>(d[k]);
  }
  // The items' programs (untextured, textured), then the ground's (with the grid); the
  // per-frame uniforms go to each when it is first used in this frame.
  const Impl::Uniforms* current = nullptr;
  int current_kind = -1;       // 0 plain, 1 textured, 2 grid
  bool frame_uniforms[3] = {false, false, false};
  stats_ = FrameStats{};
  auto use = [&](bool grid, bool texture) {
    const int kind = grid ? 2 : (texture ? 1 : 0);
    if (kind == current_kind) return;
    const Impl::Program& prog = m.program(num_lights, grid, texture, flat_probe_);
    const Impl::Uniforms& u = prog.u;
    glUseProgram(prog.id);
    ++stats_.program_switches;
    if (!frame_uniforms[kind]) {
      glUniformMatrix4fv(u.projection, 1, GL_FALSE, Pf.data());
      if (num_lights > 0) glUniform3fv(u.to_light, num_lights, to_light);
      frame_uniforms[kind] = true;
    }
    current = &u;
    current_kind = kind;
  };
  use(false, false);

  auto draw = [&](const Eigen::Isometry3d& X_WS, const Eigen::Vector3d& scale,
                  const Impl::Range& range, const Eigen::Vector3f& amb, const Eigen::Vector3f& dif,
                  const Eigen::Vector3f& spe, float shininess) {
    const Impl::Uniforms& u = *current;
    const Eigen::Matrix4d M = X_WS.matrix() * Eigen::Vector4d(scale.x(), scale.y(), scale.z(), 1.0).asDiagonal();
    const Eigen::Matrix4d MV = X_EW.matrix() * M;
    const Eigen::Matrix3f N = MV.topLeftCorner<3, 3>().inverse().transpose().cast<float>();
    const Eigen::Matrix4f MVf = MV.cast<float>(), Mf = M.cast<float>();
    glUniformMatrix4fv(u.model_view, 1, GL_FALSE, MVf.data());
    if (u.model >= 0) glUniformMatrix4fv(u.model, 1, GL_FALSE, Mf.data());
    glUniformMatrix3fv(u.normal_matrix, 1, GL_FALSE, N.data());
    // The colour products the shader would otherwise form at every pixel.
    const Eigen::Vector3f a = scene.ambient.head<3>().cwiseProduct(amb);
    float d[12], sp[12];
    for (int i = 0; i < num_lights; ++i) {
      for (int k = 0; k < 3; ++k) {
        d[3 * i + k] = scene.lights[i].diffuse[k] * dif[k];
        sp[3 * i + k] = scene.lights[i].specular[k] * spe[k];
      }
    }
    glUniform3fv(u.ambient, 1, a.data());
    if (num_lights > 0) {
      glUniform3fv(u.diffuse, num_lights, d);
      glUniform3fv(u.specular, num_lights, sp);
    }
    glUniform1f(u.shininess, std::max(shininess, 1.0f));
    glDrawArrays(GL_TRIANGLES, range.first, range.count);
    ++stats_.draw_calls;
    stats_.triangles += static_cast<std::size_t>(range.count / 3);
  };

  for (std::size_t i = 0; i < scene.items.size(); ++i) {
    const SceneItem& item = scene.items[i];
    if (!item.visual) continue;
    Impl::Slot& slot = m.slots[i];
    if (!slot.drawable) continue;
    if (item.body < 0 || item.body >= static_cast<int>(scene.bodies.size())) {
      if (!slot.size_warned && m.warn) {
        m.warn("renderer: visual item " + std::to_string(i) + " refers to body " +
               std::to_string(item.body) + " of " + std::to_string(scene.bodies.size()) + "; skipped");
      }
      slot.size_warned = true;
      continue;
    }
    const Shape& s = item.shape;
    Eigen::Isometry3d X_BS = item.X_BS;
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();  // meshes are scaled when loaded
    switch (s.type) {
      case ShapeType::kBox: scale = s.size; break;
      case ShapeType::kCylinder: scale = Eigen::Vector3d(s.radius, s.radius, s.length); break;
      case ShapeType::kSphere: scale = Eigen::Vector3d::Constant(s.radius); break;
      case ShapeType::kPlane: {
        // Turn the quad's +z onto the plane's normal; unbounded planes get a large square.
        const double len = s.normal.norm();
        if (len > 0.0) {
          // Basis with z = normal and x as close to the plane frame's x as possible.
          const Eigen::Vector3d z = s.normal / len;
          Eigen::Vector3d x = std::fabs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
          x = (x - z * z.dot(x)).normalized();
          Eigen::Matrix3d R;
          R.col(0) = x;
          R.col(1) = z.cross(x);
          R.col(2) = z;
          X_BS.linear() = X_BS.linear() * R;
        }
        const bool unbounded = s.size.x() <= 0.0 || s.size.y() <= 0.0;
        scale = unbounded ? Eigen::Vector3d(kUnboundedPlaneSize, kUnboundedPlaneSize, 1.0)
                          : Eigen::Vector3d(s.size.x(), s.size.y(), 1.0);
        break;
      }
      case ShapeType::kMesh: break;
    }
    if (!scale.allFinite() || scale.minCoeff() <= 0.0) {
      if (!slot.size_warned && m.warn) {
        m.warn("renderer: visual item " + std::to_string(i) + " of body '" +
               scene.bodies[item.body].name + "' has a zero or invalid size; skipped");
      }
      slot.size_warned = true;
      continue;
    }
    const Material& mat = item.material;
    const Impl::Geometry& g = *slot.geometry;
    const Eigen::Isometry3d X_WS = scene.bodies[item.body].X_WB * X_BS;
    if (g.parts.size() == 1 && g.parts[0].material < 0 && slot.texture == 0) {
      // The common untextured case: one draw, as before materials and textures.
      use(false, false);
      draw(X_WS, scale, g.parts[0].range, mat.ambient.head<3>(), mat.diffuse.head<3>(),
           mat.specular.head<3>(), slot.shininess);
      continue;
    }
    // A material the user wrote (or a URDF colour) replaces the mesh file's colours; the
    // mesh's own textures stay unless the material brings one.
    const bool explicit_material = mat.specified || !mat.name.empty();
    for (const Impl::Part& part : g.parts) {
      const MeshMaterial* mm =
          g.mesh && part.material >= 0 && part.material < static_cast<int>(g.mesh->materials.size())
              ? &g.mesh->materials[part.material]
              : nullptr;
      Eigen::Vector3f amb = mat.ambient.head<3>(), dif = mat.diffuse.head<3>();
      if (mm && !explicit_material) {
        if (mm->has_diffuse) dif = mm->diffuse.head<3>();
        // COLLADA exporters often write a black ambient: Gazebo then shows the diffuse colour
        // under the scene's ambient light, which is what a black ambient would hide here.
        amb = mm->has_ambient && mm->ambient.head<3>().maxCoeff() > 0.0f ? mm->ambient.head<3>() : dif;
      }
      GLuint tex = slot.texture;
      Eigen::Vector2f uv_scale = mat.texture_scale;
      if (tex == 0 && mm && part.material < static_cast<int>(slot.mesh_textures.size())) {
        tex = slot.mesh_textures[part.material];
        uv_scale = Eigen::Vector2f(1.0f, 1.0f);
      }
      use(false, tex != 0);
      if (tex != 0) {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, tex);
        const float inv[2] = {1.0f / uv_scale.x(), 1.0f / uv_scale.y()};
        glUniform2fv(current->uv_scale, 1, inv);
      }
      draw(X_WS, scale, part.range, amb, dif, mat.specular.head<3>(), slot.shininess);
    }
  }

  // The ground plane last, so that the depth test skips shading what the items hide: a square
  // under the camera reaching the far clip, light grey, with a 1 m grid.
  if (scene.ground_plane) {
    Eigen::Isometry3d X_WG = Eigen::Isometry3d::Identity();
    X_WG.translation() = Eigen::Vector3d(std::round(X_WC.translation().x()),
                                         std::round(X_WC.translation().y()), 0.0);
    const double size = 2.0 * f + 2.0;
    const auto grey = findGazeboMaterial("Gazebo/Grey");
    use(true, false);
    draw(X_WG, Eigen::Vector3d(size, size, 1.0), m.geometry.at("quad").parts[0].range,
         Eigen::Vector3f(0.8f, 0.8f, 0.8f), Eigen::Vector3f(0.8f, 0.8f, 0.8f),
         grey->material.specular.head<3>(), grey->shininess);
  }

  std::optional<StepProfile::Scope> readback;
  if (profile_) {
    glFinish();
    profile_->add(draw_row_, StepProfile::Clock::now() - draw_start);
    readback.emplace(profile_, readback_row_);
  }
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (rgb != nullptr) {
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, K.width, K.height, GL_RGB, GL_UNSIGNED_BYTE, rgb);
  }
  if (depth != nullptr) {
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, K.width, K.height, GL_RED, GL_FLOAT, depth);
  }
  const GLenum err = glGetError();
  if (err != GL_NO_ERROR) {
    std::ostringstream os;
    os << "OpenGL error 0x" << std::hex << err << " while rendering";
    throw RenderError(os.str());
  }
  ++frames_;
}

}  // namespace tianracer_sim
