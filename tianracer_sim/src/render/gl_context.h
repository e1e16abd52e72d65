// The process-wide OSMesa context (internal to the render library).
#ifndef TIANRACER_SIM_SRC_RENDER_GL_CONTEXT_H
#define TIANRACER_SIM_SRC_RENDER_GL_CONTEXT_H

#include "gl_api.h"

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

namespace tianracer_sim {
namespace render_internal {

// OSMesa binds a context to the calling thread, so every GL call goes through lock(): it takes
// the process-wide mutex and makes the context current.
class GlContext {
 public:
  /// The shared context, made on first use. Throws RenderError when OSMesa gives none.
  static std::shared_ptr<GlContext> acquire();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  std::unique_lock<std::recursive_mutex> lock();
  const std::string& info() const { return info_; }

 private:
  GlContext();
  static std::recursive_mutex& gl_mutex();

  OSMesaContext ctx_ = nullptr;
  uint32_t dummy_[1] = {0};  // OSMesa wants a colour buffer; we draw into FBOs only
  std::string info_;
};

}  // namespace render_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_RENDER_GL_CONTEXT_H
