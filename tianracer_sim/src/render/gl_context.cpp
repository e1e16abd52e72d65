#include "gl_context.h"

#include "gl_api.h"

#include "tianracer_sim/render/renderer.h"  // RenderError

namespace tianracer_sim {
namespace render_internal {

std::shared_ptr<GlContext> GlContext::acquire() {
  static std::mutex mutex;
  static std::weak_ptr<GlContext> shared;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto existing = shared.lock()) return existing;
  auto created = std::shared_ptr<GlContext>(new GlContext());
  shared = created;
  return created;
}

GlContext::~GlContext() {
  if (ctx_ != nullptr) OSMesaDestroyContext(ctx_);
}

std::unique_lock<std::recursive_mutex> GlContext::lock() {
  std::unique_lock<std::recursive_mutex> guard(gl_mutex());
  if (OSMesaGetCurrentContext() != ctx_) {
    if (!OSMesaMakeCurrent(ctx_, dummy_, GL_UNSIGNED_BYTE, 1, 1)) {
      throw RenderError("OSMesaMakeCurrent failed");
    }
  }
  return guard;
}

GlContext::GlContext() {
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS,
                         0, OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION,
                         3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
  ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
  if (ctx_ == nullptr) ctx_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (ctx_ == nullptr) {
    throw RenderError("OSMesa could not create an OpenGL 3.3 context (is libOSMesa / Mesa's "
                      "llvmpipe installed?)");
  }
  std::lock_guard<std::recursive_mutex> guard(gl_mutex());
  if (!OSMesaMakeCurrent(ctx_, dummy_, GL_UNSIGNED_BYTE, 1, 1)) {
    OSMesaDestroyContext(ctx_);
    ctx_ = nullptr;
    throw RenderError("OSMesa: could not make the context current");
  }
  auto str = [](GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  info_ = "OpenGL " + str(GL_VERSION) + ", " + str(GL_RENDERER);
  GLint major = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  if (major < 3) {
    OSMesaDestroyContext(ctx_);
    ctx_ = nullptr;
    throw RenderError("OSMesa gives " + info_ + "; OpenGL 3.3 is needed");
  }
}

std::recursive_mutex& GlContext::gl_mutex() {
  static std::recursive_mutex m;
  return m;
}

}  // namespace render_internal
}  // namespace tianracer_sim
