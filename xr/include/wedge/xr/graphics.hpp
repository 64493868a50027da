// Drawing to a headset through XR_KHR_opengl_enable on Xlib/GLX. GlContext is an OpenGL 3.3 core context
// of our own (a hidden GLFW window's): the renderer draws in it, and the runtime gets it as the session's
// XrGraphicsBindingOpenGLXlibKHR. EyeSwapchains holds one colour swapchain per eye (GL textures the runtime
// made in that context), a depth buffer and a framebuffer per eye, and the frame's projection layer.
//
//   per frame: locate(display time) -> for each eye: begin_eye (acquire, wait, bind) -> draw -> end_eye
//              (release) -> layer() into xrEndFrame
#pragma once

#include <openxr/openxr.h>

#include <array>
#include <memory>
#include <vector>

#include "wedge/xr/instance.hpp"
#include "wedge/xr/session.hpp"

namespace wedge::xr {

class GlContext {
 public:
  // Checks the runtime's OpenGL requirements (xrGetOpenGLGraphicsRequirementsKHR) against 3.3 and makes the
  // context current. Throws XrError, or std::runtime_error with no X display (naming DISPLAY).
  explicit GlContext(const Instance& instance);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  const void* binding() const;  // the XrGraphicsBindingOpenGLXlibKHR for xrCreateSession's next chain

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class EyeSwapchains {
 public:
  static constexpr int kEyes = 2;

  EyeSwapchains(const Instance& instance, const Session& session);  // throws XrError
  ~EyeSwapchains();
  EyeSwapchains(const EyeSwapchains&) = delete;
  EyeSwapchains& operator=(const EyeSwapchains&) = delete;

  int width(int eye) const { return eyes_[std::size_t(eye)].width; }
  int height(int eye) const { return eyes_[std::size_t(eye)].height; }
  std::int64_t format() const { return format_; }  // the GL internal format chosen

  // The eyes' views (pose in the session's tracking space, fov) at a display time; false when the runtime
  // does not know where the head is (then nothing is drawn that frame).
  bool locate(XrTime display_time);
  const XrView& view(int eye) const { return views_[std::size_t(eye)]; }

  // Acquires and waits for the eye's next image and binds its framebuffer (colour + depth), viewport set.
  void begin_eye(int eye);
  void end_eye(int eye);  // releases the image
  // The projection layer of this frame's views, for xrEndFrame.
  const XrCompositionLayerBaseHeader* layer();

 private:
  struct Eye {
    XrSwapchain swapchain = XR_NULL_HANDLE;
    int width = 0, height = 0;
    std::vector<std::uint32_t> textures;
    std::uint32_t framebuffer = 0, depth = 0;
  };
  const Instance& instance_;
  const Session& session_;
  std::array<Eye, kEyes> eyes_;
  std::array<XrView, kEyes> views_{};
  std::array<XrCompositionLayerProjectionView, kEyes> projection_views_{};
  XrCompositionLayerProjection layer_{};
  std::int64_t format_ = 0;
};

}  // namespace wedge::xr
