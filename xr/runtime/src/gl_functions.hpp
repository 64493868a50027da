// The few GL entry points the runtime needs (to make, read back and delete swapchain textures), resolved for
// the context the app has current. Nothing GL is linked into the runtime: a GLX context (hello_xr, GLFW;
// glvnd's libGLX) is reached through glXGetProcAddressARB, an OSMesa context (libOSMesa, whose gl* exports
// dispatch to the current Mesa context) through OSMesaGetProcAddress.
#pragma once

#include <GL/gl.h>
#include <GL/glext.h>

#include <string>

namespace wedge::xr_replay {

struct GlFunctions {
  bool loaded = false;
  const char* api = "";                       // "GLX" or "OSMesa"
  void* (*current_context)() = nullptr;       // glXGetCurrentContext / OSMesaGetCurrentContext
  void (*GenTextures)(GLsizei, GLuint*) = nullptr;
  void (*DeleteTextures)(GLsizei, const GLuint*) = nullptr;
  void (*BindTexture)(GLenum, GLuint) = nullptr;
  void (*TexImage2D)(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void*) = nullptr;
  void (*TexImage3D)(GLenum, GLint, GLint, GLsizei, GLsizei, GLsizei, GLint, GLenum, GLenum, const void*) = nullptr;
  void (*TexParameteri)(GLenum, GLenum, GLint) = nullptr;
  void (*GetIntegerv)(GLenum, GLint*) = nullptr;
  void (*GetTexImage)(GLenum, GLint, GLenum, GLenum, void*) = nullptr;
  void (*PixelStorei)(GLenum, GLint) = nullptr;
  void (*BindBuffer)(GLenum, GLuint) = nullptr;
  GLenum (*GetError)() = nullptr;

  bool context_current() const { return loaded && current_context != nullptr && current_context() != nullptr; }
};

// Resolves `gl` for the context current on this thread. Returns "" on success, else the problem (no GLX or
// OSMesa context is current, or an entry point is missing).
std::string load_current_gl(GlFunctions& gl);

}  // namespace wedge::xr_replay
