// Offscreen OpenGL rendering of a Scene through OSMesa (Mesa llvmpipe, no X server, no GPU).
// One GL context serves every Renderer of the process; each Renderer keeps its geometry in GL
// buffers (uploaded once) and one offscreen target per image size. ROS-free.
#ifndef TIANRACER_SIM_RENDER_RENDERER_H
#define TIANRACER_SIM_RENDER_RENDERER_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "tianracer_sim/common/step_profile.h"
#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/render/camera_intrinsics.h"
#include "tianracer_sim/scene/scene.h"

namespace tianracer_sim {

/// No GL context (OSMesa missing or failing), a shader that does not compile, bad intrinsics.
using RenderError = InputError;

class Renderer {
 public:
  /// Makes (or joins) the process-wide OSMesa context. Throws RenderError with the reason when
  /// there is none; set TIANRACER_SIM_NO_GL=1 to get that error on purpose (tests, and hosts
  /// whose Mesa misbehaves). Mesa's thread count is LP_NUM_THREADS, read at the first context.
  explicit Renderer(WarningSink warn = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Uploads the geometry of the scene's visual items not seen before (meshes through the
  /// shared MeshCache, primitives tessellated). A mesh that fails to load is skipped with one
  /// warning; the other items still render. renderView() calls it every frame: items are
  /// matched by index and shape, so a scene may gain, lose or change items at any time.
  void prepare(const Scene& scene);

  /// Renders the scene's visual items, its ground plane and sky from camera pose X_WC (camera
  /// link convention: x forward, y left, z up) using the bodies' current poses.
  ///  - rgb: W*H*3 bytes, row-major, rows top to bottom (may be null);
  ///  - depth: W*H floats, distance along the optical axis in metres (the z of the optical
  ///    frame, as Gazebo's depth camera), +inf where nothing was hit (may be null).
  /// Both come from one pass. Nothing is allocated once a target of this size exists.
  void renderView(const Scene& scene, const Eigen::Isometry3d& X_WC, const CameraIntrinsics& K,
                  uint8_t* rgb, float* depth = nullptr);

  /// Frames rendered so far (by this renderer).
  uint64_t frameCount() const { return frames_; }

  /// What the last renderView() drew: glDrawArrays calls, triangles handed to GL (before
  /// clipping and culling; the ground plane's two included) and glUseProgram switches.
  struct FrameStats {
    int draw_calls = 0;
    std::size_t triangles = 0;
    int program_switches = 0;
  };
  const FrameStats& lastFrameStats() const { return stats_; }

  /// A cost probe for render_bench, not a camera feature: with `flat` every surface is drawn
  /// in its ambient colour (no lighting, grid or texture sampling), so that the fragment
  /// shader's share of a frame can be measured on the same geometry. Off by default.
  void setFlatShadingProbe(bool flat) { flat_probe_ = flat; }
  /// "OpenGL 4.5 (Compatibility Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)".
  std::string glInfo() const;

  /// Times each frame's drawing (up to glFinish: llvmpipe rasterises on the flush) and its
  /// read-back (glReadPixels) into `profile` (common/step_profile.h); null: not timed, and
  /// no glFinish (glReadPixels waits for the drawing anyway).
  void setProfile(StepProfile* profile);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  uint64_t frames_ = 0;
  FrameStats stats_;
  bool flat_probe_ = false;
  StepProfile* profile_ = nullptr;
  int draw_row_ = -1, readback_row_ = -1;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_RENDER_RENDERER_H
