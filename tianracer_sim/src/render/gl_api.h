// The OpenGL API as the render library uses it: OSMesa, GL and the extension prototypes
// (glGenFramebuffers, the shader calls). Every file of the library includes GL through this
// header, so the prototypes are declared whichever file includes GL first (a unity build
// puts several of them in one translation unit). Internal to the render library.
#ifndef TIANRACER_SIM_SRC_RENDER_GL_API_H
#define TIANRACER_SIM_SRC_RENDER_GL_API_H

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#endif
#include <GL/osmesa.h>
#include <GL/gl.h>
#include <GL/glext.h>

#endif  // TIANRACER_SIM_SRC_RENDER_GL_API_H
