// Resolving GL entry points for the app's current context (gl_functions.hpp).
#include "gl_functions.hpp"

#include <dlfcn.h>

namespace wedge::xr_replay {

namespace {

// glXGetProcAddressARB and OSMesaGetProcAddress, both taking a name and giving a function address (their
// declared return types differ only in the function pointer type).
using GetProc = void* (*)(const char*);

// A library the app already loaded (RTLD_NOLOAD: the runtime never brings a GL library in itself).
void* loaded_library(const char* const* names) {
  for (const char* const* n = names; *n != nullptr; ++n)
    if (void* h = dlopen(*n, RTLD_LAZY | RTLD_NOLOAD)) return h;
  return nullptr;
}

template <class F>
bool resolve(F& f, GetProc get, void* lib, const char* name) {
  void* p = lib != nullptr ? dlsym(lib, name) : nullptr;
  if (p == nullptr) p = get(name);
  f = reinterpret_cast<F>(p);
  return f != nullptr;
}

bool resolve_all(GlFunctions& gl, GetProc get, void* lib) {
  return resolve(gl.GenTextures, get, lib, "glGenTextures") && resolve(gl.DeleteTextures, get, lib, "glDeleteTextures") &&
         resolve(gl.BindTexture, get, lib, "glBindTexture") && resolve(gl.TexImage2D, get, lib, "glTexImage2D") &&
         resolve(gl.TexImage3D, get, lib, "glTexImage3D") && resolve(gl.TexParameteri, get, lib, "glTexParameteri") &&
         resolve(gl.GetIntegerv, get, lib, "glGetIntegerv") && resolve(gl.GetTexImage, get, lib, "glGetTexImage") &&
         resolve(gl.PixelStorei, get, lib, "glPixelStorei") && resolve(gl.BindBuffer, get, lib, "glBindBuffer") &&
         resolve(gl.GetError, get, lib, "glGetError");
}

}  // namespace

std::string load_current_gl(GlFunctions& gl) {
  gl = GlFunctions{};
  // GLX first: through glvnd, its gl* dispatch to whichever vendor owns the current context. Lookups go
  // through glXGetProcAddressARB only (glvnd's libGLX exports no gl* of its own).
  static const char* const glx_names[] = {"libGLX.so.0", "libGL.so.1", nullptr};
  if (void* glx = loaded_library(glx_names)) {
    auto current = reinterpret_cast<void* (*)()>(dlsym(glx, "glXGetCurrentContext"));
    auto get = reinterpret_cast<GetProc>(dlsym(glx, "glXGetProcAddressARB"));
    if (current != nullptr && get != nullptr && current() != nullptr) {
      if (!resolve_all(gl, get, nullptr)) return "glXGetProcAddressARB lacks a GL 3.3 entry point";
      gl.current_context = current;
      gl.api = "GLX";
      gl.loaded = true;
      return "";
    }
  }
  // OSMesa: its exports are Mesa's own gl*, dispatching to the current Mesa context.
  static const char* const osmesa_names[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so", nullptr};
  if (void* osmesa = loaded_library(osmesa_names)) {
    auto current = reinterpret_cast<void* (*)()>(dlsym(osmesa, "OSMesaGetCurrentContext"));
    auto get = reinterpret_cast<GetProc>(dlsym(osmesa, "OSMesaGetProcAddress"));
    if (current != nullptr && get != nullptr && current() != nullptr) {
      if (!resolve_all(gl, get, osmesa)) return "libOSMesa lacks a GL 3.3 entry point";
      gl.current_context = current;
      gl.api = "OSMesa";
      gl.loaded = true;
      return "";
    }
  }
  return "no OpenGL context is current on this thread (neither GLX nor OSMesa); make the session's context "
         "current before creating swapchains";
}

}  // namespace wedge::xr_replay
