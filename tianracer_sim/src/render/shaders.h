// The renderer's GLSL sources and their compilation (internal to the render library).
#ifndef TIANRACER_SIM_SRC_RENDER_SHADERS_H
#define TIANRACER_SIM_SRC_RENDER_SHADERS_H

#include "gl_api.h"

#include <string>

namespace tianracer_sim {
namespace render_internal {

/// Vertex and fragment shader bodies; compiled with "#version 330 core" and the defines
/// NUM_LIGHTS (0..4) and GRID (0/1) in front (see shaders.cpp for the lighting model).
extern const char* const kVertexShader;
extern const char* const kFragmentShader;

/// Compiles one shader stage. Throws RenderError with the compiler's log.
GLuint compile(GLenum type, const std::string& src);

/// Compiles both stages with `defines` in front and links them into a program. Throws
/// RenderError with the compiler's or linker's log (nothing is left allocated then).
GLuint linkProgram(const std::string& defines);

}  // namespace render_internal
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_RENDER_SHADERS_H
