#define GL_GLEXT_PROTOTYPES 1  // (GL entry points called directly: libOSMesa exports them, as for the renderer)
#include "wedge/xr/graphics.hpp"

#include <GL/gl.h>
#include <GL/glext.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "platform.hpp"
#include "wedge/xr/check.hpp"

namespace wedge::xr {

namespace {
std::string g_glfw_error;
}

struct GlContext::Impl {
  GLFWwindow* window = nullptr;
  XrGraphicsBindingOpenGLXlibKHR binding{XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR};
};

GlContext::GlContext(const Instance& instance) : impl_(std::make_unique<Impl>()) {
  // The runtime's requirements first (the spec requires the call before xrCreateSession).
  auto requirements = reinterpret_cast<PFN_xrGetOpenGLGraphicsRequirementsKHR>(
      instance.function("xrGetOpenGLGraphicsRequirementsKHR"));
  XrGraphicsRequirementsOpenGLKHR req{XR_TYPE_GRAPHICS_REQUIREMENTS_OPENGL_KHR};
  check(instance.handle(), requirements(instance.handle(), instance.system(), &req),
        "xrGetOpenGLGraphicsRequirementsKHR");
  const XrVersion ours = XR_MAKE_VERSION(3, 3, 0);
  if (ours < req.minApiVersionSupported || (req.maxApiVersionSupported != 0 && ours > req.maxApiVersionSupported))
    throw XrError("the runtime needs OpenGL " + std::to_string(XR_VERSION_MAJOR(req.minApiVersionSupported)) + "." +
                      std::to_string(XR_VERSION_MINOR(req.minApiVersionSupported)) + " to " +
                      std::to_string(XR_VERSION_MAJOR(req.maxApiVersionSupported)) + "." +
                      std::to_string(XR_VERSION_MINOR(req.maxApiVersionSupported)) + "; Wedge draws with 3.3 core",
                  XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING);

  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw std::runtime_error("cannot make an OpenGL context for the headset: DISPLAY is not set (no X display; "
                             "headless, run under Xvfb: xvfb-run -a wedge xr ..., or use --headless)");
  glfwSetErrorCallback([](int, const char* message) { g_glfw_error = message; });
  if (!glfwInit()) throw std::runtime_error("cannot open DISPLAY=" + std::string(display) + ": " + g_glfw_error);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);  // the headset shows the frames; the window only holds the context
  impl_->window = glfwCreateWindow(64, 64, "wedge xr", nullptr, nullptr);
  if (!impl_->window) {
    glfwTerminate();
    throw std::runtime_error("cannot make an OpenGL 3.3 context on DISPLAY=" + std::string(display) + ": " + g_glfw_error);
  }
  glfwMakeContextCurrent(impl_->window);

  // The binding: the display, the context, its drawable, and the FBConfig and visual it was made with.
  // (read from GLX itself: GLFW's native-access header would need the Xrandr headers too)
  Display* x = glXGetCurrentDisplay();
  const GLXContext context = glXGetCurrentContext();
  int config_id = 0;
  glXQueryContext(x, context, GLX_FBCONFIG_ID, &config_id);
  const int attributes[] = {GLX_FBCONFIG_ID, config_id, 0};
  int count = 0;
  GLXFBConfig* configs = glXChooseFBConfig(x, DefaultScreen(x), attributes, &count);
  impl_->binding.xDisplay = x;
  impl_->binding.glxContext = context;
  impl_->binding.glxDrawable = glXGetCurrentDrawable();
  if (configs && count > 0) {
    impl_->binding.glxFBConfig = configs[0];
    if (XVisualInfo* visual = glXGetVisualFromFBConfig(x, configs[0])) {
      impl_->binding.visualid = std::uint32_t(visual->visualid);
      XFree(visual);
    }
  }
  if (configs) XFree(configs);
}

GlContext::~GlContext() {
  glfwDestroyWindow(impl_->window);
  glfwTerminate();
}

const void* GlContext::binding() const { return &impl_->binding; }

EyeSwapchains::EyeSwapchains(const Instance& instance, const Session& session)
    : instance_(instance), session_(session) {
  const XrInstance inst = instance.handle();
  std::uint32_t count = 0;
  check(inst, xrEnumerateViewConfigurationViews(inst, instance.system(), Session::kViewConfiguration, 0, &count, nullptr),
        "xrEnumerateViewConfigurationViews");
  std::vector<XrViewConfigurationView> config(count, {XR_TYPE_VIEW_CONFIGURATION_VIEW});
  check(inst, xrEnumerateViewConfigurationViews(inst, instance.system(), Session::kViewConfiguration, count, &count,
                                                config.data()),
        "xrEnumerateViewConfigurationViews");
  if (count != kEyes) throw XrError("the runtime's stereo view has " + std::to_string(count) + " views, not 2", XR_ERROR_VALIDATION_FAILURE);

  // The colour format: plain RGBA8 (what `wedge render` writes) where offered, else sRGB.
  check(inst, xrEnumerateSwapchainFormats(session.handle(), 0, &count, nullptr), "xrEnumerateSwapchainFormats");
  std::vector<std::int64_t> formats(count);
  check(inst, xrEnumerateSwapchainFormats(session.handle(), count, &count, formats.data()), "xrEnumerateSwapchainFormats");
  for (std::int64_t f : {std::int64_t(GL_RGBA8), std::int64_t(GL_SRGB8_ALPHA8)})
    if (std::find(formats.begin(), formats.end(), f) != formats.end()) {
      format_ = f;
      break;
    }
  if (format_ == 0) throw XrError("the runtime offers no RGBA8 or SRGB8_ALPHA8 swapchain", XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);

  for (int e = 0; e < kEyes; ++e) {
    Eye& eye = eyes_[std::size_t(e)];
    eye.width = int(config[std::size_t(e)].recommendedImageRectWidth);
    eye.height = int(config[std::size_t(e)].recommendedImageRectHeight);
    XrSwapchainCreateInfo info{XR_TYPE_SWAPCHAIN_CREATE_INFO};
    info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_SAMPLED_BIT;
    info.format = format_;
    info.sampleCount = 1;
    info.width = std::uint32_t(eye.width);
    info.height = std::uint32_t(eye.height);
    info.faceCount = 1;
    info.arraySize = 1;
    info.mipCount = 1;
    check(inst, xrCreateSwapchain(session.handle(), &info, &eye.swapchain), "xrCreateSwapchain");
    check(inst, xrEnumerateSwapchainImages(eye.swapchain, 0, &count, nullptr), "xrEnumerateSwapchainImages");
    std::vector<XrSwapchainImageOpenGLKHR> images(count, {XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR});
    check(inst,
          xrEnumerateSwapchainImages(eye.swapchain, count, &count, reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())),
          "xrEnumerateSwapchainImages");
    for (const auto& image : images) eye.textures.push_back(image.image);
    glGenFramebuffers(1, &eye.framebuffer);
    glGenRenderbuffers(1, &eye.depth);
    glBindRenderbuffer(GL_RENDERBUFFER, eye.depth);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, eye.width, eye.height);
  }
  for (XrView& v : views_) v = {XR_TYPE_VIEW};
  layer_ = {XR_TYPE_COMPOSITION_LAYER_PROJECTION};
}

EyeSwapchains::~EyeSwapchains() {
  for (Eye& eye : eyes_) {
    if (eye.framebuffer) glDeleteFramebuffers(1, &eye.framebuffer);
    if (eye.depth) glDeleteRenderbuffers(1, &eye.depth);
    if (eye.swapchain != XR_NULL_HANDLE) xrDestroySwapchain(eye.swapchain);
  }
}

bool EyeSwapchains::locate(XrTime display_time) {
  XrViewLocateInfo info{XR_TYPE_VIEW_LOCATE_INFO};
  info.viewConfigurationType = Session::kViewConfiguration;
  info.displayTime = display_time;
  info.space = session_.space();
  XrViewState state{XR_TYPE_VIEW_STATE};
  std::uint32_t count = 0;
  check(instance_.handle(), xrLocateViews(session_.handle(), &info, &state, kEyes, &count, views_.data()), "xrLocateViews");
  const XrViewStateFlags both = XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT;
  return count == kEyes && (state.viewStateFlags & both) == both;
}

void EyeSwapchains::begin_eye(int e) {
  Eye& eye = eyes_[std::size_t(e)];
  const XrInstance inst = instance_.handle();
  std::uint32_t index = 0;
  XrSwapchainImageAcquireInfo acquire{XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO};
  check(inst, xrAcquireSwapchainImage(eye.swapchain, &acquire, &index), "xrAcquireSwapchainImage");
  XrSwapchainImageWaitInfo wait{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
  wait.timeout = XR_INFINITE_DURATION;
  check(inst, xrWaitSwapchainImage(eye.swapchain, &wait), "xrWaitSwapchainImage");
  glBindFramebuffer(GL_FRAMEBUFFER, eye.framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, eye.textures[index], 0);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, eye.depth);
  glViewport(0, 0, eye.width, eye.height);

  XrCompositionLayerProjectionView& pv = projection_views_[std::size_t(e)];
  pv = {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW};
  pv.pose = views_[std::size_t(e)].pose;
  pv.fov = views_[std::size_t(e)].fov;
  pv.subImage.swapchain = eye.swapchain;
  pv.subImage.imageRect = {{0, 0}, {eye.width, eye.height}};
  pv.subImage.imageArrayIndex = 0;
}

void EyeSwapchains::end_eye(int e) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  XrSwapchainImageReleaseInfo release{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO};
  check(instance_.handle(), xrReleaseSwapchainImage(eyes_[std::size_t(e)].swapchain, &release), "xrReleaseSwapchainImage");
}

const XrCompositionLayerBaseHeader* EyeSwapchains::layer() {
  layer_ = {XR_TYPE_COMPOSITION_LAYER_PROJECTION};
  layer_.space = session_.space();
  layer_.viewCount = kEyes;
  layer_.views = projection_views_.data();
  return reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer_);
}

}  // namespace wedge::xr
