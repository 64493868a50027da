// OpenGL 3.3 core: one streamed vertex buffer of de-indexed slice triangles (position + corner normal),
// one shader for meshes (Blinn-Phong with a key and a fill light and a sky/ground ambient), one for the
// procedural ground grid, which also draws the shadows: each mesh flattened onto the ground plane and
// drawn with the grid's own colour darkened, blended by GL_MIN. A pixel under several shadow triangles
// (front and back of a body, or two bodies) thus darkens once, without a stencil buffer. GL entry points
// are called directly (GL_GLEXT_PROTOTYPES): libOSMesa exports them offscreen, libGL/libOpenGL in a window.
#define GL_GLEXT_PROTOTYPES 1
#include "wedge/render/renderer.hpp"

#include <GL/gl.h>
#include <GL/glext.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "wedge/error.hpp"

namespace wedge::render {
namespace {

const char* kMeshVs = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view_proj;
out vec3 v_pos;
out vec3 v_normal;
void main() {
  v_pos = a_pos;
  v_normal = a_normal;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";

const char* kMeshFs = R"(#version 330 core
in vec3 v_pos;
in vec3 v_normal;
uniform vec3 u_color;
uniform vec3 u_light;   // direction towards the key light
uniform vec3 u_eye;
uniform vec3 u_up;      // world up, for the sky/ground ambient
out vec4 frag;
void main() {
  vec3 n = normalize(v_normal);
  vec3 v = normalize(u_eye - v_pos);
  if (dot(n, v) < 0.0) n = -n;  // seen from inside (a body cut by the near plane)
  float key = max(dot(n, u_light), 0.0);
  float fill = 0.35 * max(dot(n, normalize(-u_light + 2.0 * u_up)), 0.0);
  float hemi = 0.5 + 0.5 * dot(n, u_up);
  vec3 ambient = mix(vec3(0.22, 0.2, 0.18), vec3(0.32, 0.36, 0.42), hemi);
  vec3 h = normalize(u_light + v);
  float spec = pow(max(dot(n, h), 0.0), 48.0) * 0.35;
  vec3 c = u_color * (ambient + 0.75 * key + fill) + vec3(spec);
  frag = vec4(pow(c, vec3(1.0 / 2.2)), 1.0);
}
)";

const char* kGridVs = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
uniform mat4 u_view_proj;
out vec3 v_pos;
void main() {
  v_pos = a_pos;
  gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
)";

const char* kGridFs = R"(#version 330 core
in vec3 v_pos;
uniform vec3 u_origin;
uniform vec3 u_axis_u;
uniform vec3 u_axis_v;
uniform float u_spacing;
uniform float u_extent;
uniform vec3 u_color;
uniform vec3 u_line;
uniform vec3 u_background;
uniform float u_shade;  // 1 for the ground, less in a shadow
out vec4 frag;
void main() {
  vec2 p = vec2(dot(v_pos - u_origin, u_axis_u), dot(v_pos - u_origin, u_axis_v)) / u_spacing;
  vec2 w = fwidth(p);
  vec2 g = abs(fract(p - 0.5) - 0.5) / max(w, vec2(1e-6));
  float line = 1.0 - min(min(g.x, g.y), 1.0);
  vec3 c = mix(u_color, u_line, line * 0.8) * u_shade;
  float fade = smoothstep(0.45 * u_extent, u_extent, length(v_pos - u_origin));
  frag = vec4(mix(pow(c, vec3(1.0 / 2.2)), u_background, fade), 1.0);  // the clear colour is not gamma-encoded
}
)";

// Throws with the info log if `status` of the shader or program is not set (then deletes it).
template <class GetIv, class GetLog, class Delete>
void require_ok(GLuint object, GLenum status, GetIv get_iv, GetLog get_log, Delete del, const char* what) {
  GLint ok = 0;
  get_iv(object, status, &ok);
  if (ok) return;
  char log[2048];
  get_log(object, GLsizei(sizeof log), nullptr, log);
  del(object);
  throw Error(std::string("renderer: shader ") + what + " failed: " + log);
}

GLuint compile(GLenum type, const char* src) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  require_ok(s, GL_COMPILE_STATUS, glGetShaderiv, glGetShaderInfoLog, glDeleteShader, "compilation");
  return s;
}

GLuint link(const char* vs, const char* fs) {
  const GLuint v = compile(GL_VERTEX_SHADER, vs), f = compile(GL_FRAGMENT_SHADER, fs);
  const GLuint p = glCreateProgram();
  glAttachShader(p, v);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  glDeleteShader(f);
  require_ok(p, GL_LINK_STATUS, glGetProgramiv, glGetProgramInfoLog, glDeleteProgram, "link");
  return p;
}

void set_vec3(GLuint prog, const char* name, const Eigen::Vector3d& v) {
  glUniform3f(glGetUniformLocation(prog, name), float(v.x()), float(v.y()), float(v.z()));
}
void set_color(GLuint prog, const char* name, const Color& c) {
  glUniform3f(glGetUniformLocation(prog, name), c[0], c[1], c[2]);
}

}  // namespace

struct Renderer::Impl {
  GLuint mesh_prog = 0, grid_prog = 0;
  GLuint vao = 0, vbo = 0, grid_vao = 0, grid_vbo = 0;
  std::vector<float> scratch;
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  if (version == nullptr) throw Error("renderer: no current OpenGL context");
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 33) throw Error(std::string("renderer: needs OpenGL 3.3, the context has ") + version);
  impl_->mesh_prog = link(kMeshVs, kMeshFs);
  impl_->grid_prog = link(kGridVs, kGridFs);
  glGenVertexArrays(1, &impl_->vao);
  glGenBuffers(1, &impl_->vbo);
  glBindVertexArray(impl_->vao);
  glBindBuffer(GL_ARRAY_BUFFER, impl_->vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(0));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
  glGenVertexArrays(1, &impl_->grid_vao);
  glGenBuffers(1, &impl_->grid_vbo);
  glBindVertexArray(impl_->grid_vao);
  glBindBuffer(GL_ARRAY_BUFFER, impl_->grid_vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), reinterpret_cast<void*>(0));
  glBindVertexArray(0);
}

Renderer::~Renderer() {
  glDeleteBuffers(1, &impl_->vbo);
  glDeleteBuffers(1, &impl_->grid_vbo);
  glDeleteVertexArrays(1, &impl_->vao);
  glDeleteVertexArrays(1, &impl_->grid_vao);
  glDeleteProgram(impl_->mesh_prog);
  glDeleteProgram(impl_->grid_prog);
}

void Renderer::draw(const FrameDesc& frame, int width, int height, int x, int y) {
  glViewport(x, y, width, height);
  glClearColor(frame.background[0], frame.background[1], frame.background[2], 1.0f);
  glClearDepth(1.0);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // slices are closed; drawing both sides also covers bodies cut by the near plane
  glEnable(GL_SCISSOR_TEST);  // clear the viewport only (a window may have a panel beside it)
  glScissor(x, y, width, height);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);

  const Eigen::Matrix4f view_proj =
      (frame.camera.projection(double(width) / double(height)) * frame.camera.view()).cast<float>();
  Eigen::Vector3d up = frame.camera.up.normalized();
  const Eigen::Vector3d light = -frame.light_direction.normalized();

  // Ground grid: a square of side 2 extent in the plane, centred below the camera target.
  if (frame.ground.enabled) {
    const Ground& g = frame.ground;
    const Eigen::Vector3d n = g.normal.normalized();
    const Eigen::Vector3d origin = frame.camera.target - (n.dot(frame.camera.target) - g.offset) * n;
    Eigen::Vector3d u = n.cross(Eigen::Vector3d::UnitX());
    if (u.squaredNorm() < 1e-6) u = n.cross(Eigen::Vector3d::UnitZ());
    u.normalize();
    const Eigen::Vector3d v = n.cross(u);
    // Snap the quad's centre to the grid so lines stay put when the target moves.
    const Eigen::Vector3d c = origin - std::fmod(origin.dot(u), g.spacing) * u - std::fmod(origin.dot(v), g.spacing) * v;
    float quad[18];
    const double e = g.extent;
    const Eigen::Vector3d corners[6] = {c - e * u - e * v, c + e * u - e * v, c + e * u + e * v,
                                        c - e * u - e * v, c + e * u + e * v, c - e * u + e * v};
    for (int i = 0; i < 6; ++i)
      for (int k = 0; k < 3; ++k) quad[3 * i + k] = float(corners[i][k]);
    glUseProgram(impl_->grid_prog);
    glUniformMatrix4fv(glGetUniformLocation(impl_->grid_prog, "u_view_proj"), 1, GL_FALSE, view_proj.data());
    set_vec3(impl_->grid_prog, "u_origin", c);
    set_vec3(impl_->grid_prog, "u_axis_u", u);
    set_vec3(impl_->grid_prog, "u_axis_v", v);
    glUniform1f(glGetUniformLocation(impl_->grid_prog, "u_spacing"), float(g.spacing));
    glUniform1f(glGetUniformLocation(impl_->grid_prog, "u_extent"), float(g.extent));
    set_color(impl_->grid_prog, "u_color", g.color);
    set_color(impl_->grid_prog, "u_line", g.line_color);
    set_color(impl_->grid_prog, "u_background", frame.background);
    glUniform1f(glGetUniformLocation(impl_->grid_prog, "u_shade"), 1.0f);
    glBindVertexArray(impl_->grid_vao);
    glBindBuffer(GL_ARRAY_BUFFER, impl_->grid_vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, 6);

    // Shadows: every triangle projected straight down onto the plane. Pulled toward the camera by a
    // polygon offset so they win the depth test against the ground they lie on, and not written to
    // depth, so bodies drawn later are unaffected.
    if (g.shadows && g.shadow_strength > 0.0) {
      std::vector<float>& buf = impl_->scratch;
      buf.clear();
      std::vector<std::pair<GLint, GLsizei>> ranges;
      std::vector<float> shades;
      for (const MeshDraw& d : frame.meshes) {
        if (d.mesh == nullptr || d.mesh->cells.empty() || d.overlay) continue;
        double lowest = INFINITY;
        for (const Eigen::Vector3d& p : d.mesh->vertices) lowest = std::min(lowest, std::abs(n.dot(p) - g.offset));
        const double fade = g.shadow_fade > 0.0 ? g.shadow_fade / (g.shadow_fade + lowest) : 1.0;
        const GLint first = GLint(buf.size() / 3);
        for (const auto& cell : d.mesh->cells)
          for (int q = 0; q < 3; ++q) {
            const Eigen::Vector3d& p = d.mesh->vertices[std::size_t(cell[std::size_t(q)])];
            const Eigen::Vector3d f = p - (n.dot(p) - g.offset) * n;
            buf.insert(buf.end(), {float(f.x()), float(f.y()), float(f.z())});
          }
        ranges.push_back({first, GLsizei(buf.size() / 3) - first});
        shades.push_back(float(1.0 - std::min(1.0, g.shadow_strength) * fade));
      }
      glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(buf.size() * sizeof(float)), buf.data(), GL_STREAM_DRAW);
      glEnable(GL_BLEND);
      glBlendEquation(GL_MIN);
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(-1.0f, -4.0f);
      glDepthFunc(GL_LEQUAL);
      glDepthMask(GL_FALSE);
      for (std::size_t i = 0; i < ranges.size(); ++i) {
        glUniform1f(glGetUniformLocation(impl_->grid_prog, "u_shade"), shades[i]);
        glDrawArrays(GL_TRIANGLES, ranges[i].first, ranges[i].second);
      }
      glDepthMask(GL_TRUE);
      glDepthFunc(GL_LESS);
      glDisable(GL_POLYGON_OFFSET_FILL);
      glBlendEquation(GL_FUNC_ADD);
      glDisable(GL_BLEND);
    }
  }

  // Meshes: one buffer, one draw per body.
  std::vector<float>& buf = impl_->scratch;
  buf.clear();
  std::vector<std::pair<GLint, GLsizei>> ranges;
  for (const MeshDraw& d : frame.meshes) {
    const GLint first = GLint(buf.size() / 6);
    if (d.mesh != nullptr)
      for (std::size_t c = 0; c < d.mesh->cells.size(); ++c)
        for (int q = 0; q < 3; ++q) {
          const Eigen::Vector3d& p = d.mesh->vertices[std::size_t(d.mesh->cells[c][std::size_t(q)])];
          const Eigen::Vector3d& nq = d.mesh->normals[c][std::size_t(q)];
          buf.insert(buf.end(), {float(p.x()), float(p.y()), float(p.z()), float(nq.x()), float(nq.y()), float(nq.z())});
        }
    ranges.push_back({first, GLsizei(buf.size() / 6) - first});
  }
  glUseProgram(impl_->mesh_prog);
  glUniformMatrix4fv(glGetUniformLocation(impl_->mesh_prog, "u_view_proj"), 1, GL_FALSE, view_proj.data());
  set_vec3(impl_->mesh_prog, "u_light", light);
  set_vec3(impl_->mesh_prog, "u_eye", frame.camera.eye);
  set_vec3(impl_->mesh_prog, "u_up", up);
  glBindVertexArray(impl_->vao);
  glBindBuffer(GL_ARRAY_BUFFER, impl_->vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(buf.size() * sizeof(float)), buf.data(), GL_STREAM_DRAW);
  for (const bool overlays : {false, true}) {
    if (overlays) {  // overlays see only each other's depth, in this viewport
      glEnable(GL_SCISSOR_TEST);
      glClear(GL_DEPTH_BUFFER_BIT);
      glDisable(GL_SCISSOR_TEST);
    }
    for (std::size_t i = 0; i < frame.meshes.size(); ++i) {
      if (ranges[i].second == 0 || frame.meshes[i].overlay != overlays) continue;
      set_color(impl_->mesh_prog, "u_color", frame.meshes[i].color);
      glDrawArrays(GL_TRIANGLES, ranges[i].first, ranges[i].second);
    }
  }
  glBindVertexArray(0);
  glUseProgram(0);
}

Color palette_color(int i) {
  static const Color kPalette[] = {{0.85f, 0.33f, 0.24f}, {0.22f, 0.52f, 0.82f}, {0.95f, 0.70f, 0.18f},
                                   {0.30f, 0.68f, 0.40f}, {0.58f, 0.40f, 0.74f}, {0.20f, 0.70f, 0.72f},
                                   {0.88f, 0.45f, 0.62f}, {0.55f, 0.55f, 0.55f}};
  constexpr int n = int(sizeof kPalette / sizeof kPalette[0]);
  return kPalette[((i % n) + n) % n];
}

}  // namespace wedge::render
