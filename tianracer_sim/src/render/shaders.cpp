#include "shaders.h"

#include <string>

#include "tianracer_sim/render/renderer.h"  // RenderError

namespace tianracer_sim {
namespace render_internal {

// Shaders. Lighting is Ogre's fixed-function model, per pixel, in eye space:
//   c = A_scene * m_ambient + sum_l [ D_l * m_diffuse * max(N.L, 0)
//                                     + S_l * m_specular * max(N.H, 0)^shininess (if N.L > 0) ]
// clamped to [0, 1]; L = -light direction, H = normalize(L + V), V towards the eye.
// Output 1 is the depth along the optical axis (-z of the GL eye frame), interpolated
// perspective-correctly from the vertices in float: exact to float rounding at any range.
// Both shaders are compiled once per (light count, GRID, TEXTURE) with those #defined in front:
// only the ground plane runs the grid code and only textured surfaces sample (llvmpipe
// evaluates both sides of a branch on a uniform).
const char* const kVertexShader = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;
out vec3 v_eye_position;
out vec3 v_eye_normal;
#if GRID
uniform mat4 u_model;   // for the ground grid (world x, y)
out vec2 v_world_xy;
#endif
#if TEXTURE
uniform vec2 u_uv_scale;  // 1 / the texture_unit's scale
out vec2 v_uv;
#endif
void main() {
  vec4 eye = u_model_view * vec4(a_position, 1.0);
  v_eye_position = eye.xyz;
  v_eye_normal = u_normal_matrix * a_normal;
#if GRID
  v_world_xy = (u_model * vec4(a_position, 1.0)).xy;
#endif
#if TEXTURE
  v_uv = (a_uv - 0.5) * u_uv_scale + 0.5;
#endif
  gl_Position = u_projection * eye;
}
)";

// The light count is a compile-time constant (one program per count): llvmpipe runs a loop
// with a uniform bound at about half the speed of an unrolled one.
const char* const kFragmentShader = R"(
in vec3 v_eye_position;
in vec3 v_eye_normal;
#if GRID
in vec2 v_world_xy;
#endif
#if TEXTURE
in vec2 v_uv;
uniform sampler2D u_texture;
#endif
layout(location = 0) out vec4 o_color;
layout(location = 1) out float o_depth;
// Products of light and material colours are made once per draw, on the CPU.
#if NUM_LIGHTS > 0
uniform vec3 u_to_light[NUM_LIGHTS];  // eye frame, towards the light (-direction)
uniform vec3 u_diffuse[NUM_LIGHTS];   // light diffuse * material diffuse
uniform vec3 u_specular[NUM_LIGHTS];  // light specular * material specular
#endif
uniform vec3 u_ambient;               // scene ambient * material ambient
uniform float u_shininess;
void main() {
#if FLAT
  // render_bench's probe of the shading cost: the ambient colour only.
  o_color = vec4(u_ambient, 1.0);
  o_depth = -v_eye_position.z;
  return;
#endif
  vec3 n = normalize(v_eye_normal);
  if (!gl_FrontFacing) n = -n;
  float k = 1.0;  // the grid's darkening of ambient and diffuse
#if GRID
  {
    // 1 m grid lines about 2 cm wide, anti-aliased with the screen-space footprint, and a
    // faint 1 m checker so that motion is visible between lines.
    vec2 cell = abs(fract(v_world_xy - 0.5) - 0.5);
    vec2 fw = max(fwidth(v_world_xy), vec2(1e-6));
    vec2 line = 1.0 - smoothstep(vec2(0.01), vec2(0.01) + 1.5 * fw, cell);
    float on_line = max(line.x, line.y);
    vec2 checker_cell = floor(v_world_xy);
    // mod(x, 2.0) of an integer, without mod's division: exact.
    float checker = 2.0 * fract(0.5 * (checker_cell.x + checker_cell.y)) * 0.06;
    k = (1.0 - checker) * (1.0 - 0.55 * on_line);
  }
#endif
  vec3 v = normalize(-v_eye_position);
  vec3 c = k * u_ambient;
  vec3 spec = vec3(0.0);
#if NUM_LIGHTS > 0
  for (int i = 0; i < NUM_LIGHTS; ++i) {
    vec3 l = u_to_light[i];
    float ndl = dot(n, l);
    if (ndl > 0.0) {
      c += (k * ndl) * u_diffuse[i];
      vec3 h = normalize(l + v);
      spec += u_specular[i] * pow(max(dot(n, h), 0.0), u_shininess);
    }
  }
#endif
#if TEXTURE
  // Ogre's default colour_op (modulate): the texture scales the ambient and diffuse light.
  c *= texture(u_texture, v_uv).rgb;
#endif
  c += spec;
  // No clamp(): GL clamps what is written to a normalized fixed-point (RGBA8) buffer to [0, 1].
  o_color = vec4(c, 1.0);
  o_depth = -v_eye_position.z;
}
)";

namespace {

// A shader's or a program's status (compile / link): on failure the object is deleted and
// RenderError carries GL's log.
template <class GetIv, class GetLog, class Delete>
void check(GLuint id, GLenum status, GetIv get_iv, GetLog get_log, Delete destroy,
           const char* failed) {
  GLint ok = 0;
  get_iv(id, status, &ok);
  if (ok) return;
  char log[4096];
  get_log(id, sizeof(log), nullptr, log);
  destroy(id);
  throw RenderError(std::string(failed) + log);
}

}  // namespace

GLuint compile(GLenum type, const std::string& src) {
  GLuint s = glCreateShader(type);
  const char* text = src.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  check(s, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader,
        "shader compilation failed: ");
  return s;
}

GLuint linkProgram(const std::string& defines) {
  const GLuint vs = compile(GL_VERTEX_SHADER, defines + kVertexShader);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, defines + kFragmentShader);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  const GLuint id = glCreateProgram();
  glAttachShader(id, vs);
  glAttachShader(id, fs);
  glLinkProgram(id);
  glDeleteShader(vs);
  glDeleteShader(fs);
  check(id, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram,
        "shader link failed: ");
  return id;
}

}  // namespace render_internal
}  // namespace tianracer_sim
