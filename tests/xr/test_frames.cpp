// An OpenGL session (XR_KHR_opengl_enable) on an offscreen OSMesa context: swapchains made in the app's
// context, the acquire / wait / release and wait / begin / end order rules, layer checks, and the frames
// written out by WEDGE_XR_FRAMES read back (PNG pixels, sidecar JSON) against what the test drew and
// submitted. The runtime only needs a current context: the Xlib binding's handles stay unused.
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <png.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "xr_test_support.hpp"

// openxr_platform.h's Xlib binding names Xlib / GLX types; opaque stand-ins (the test never includes X11).
typedef struct _XDisplay Display;
typedef unsigned long XID;
typedef XID GLXDrawable;
typedef struct __GLXFBConfigRec* GLXFBConfig;
typedef struct __GLXcontextRec* GLXContext;
#define XR_USE_PLATFORM_XLIB
#define XR_USE_GRAPHICS_API_OPENGL
#include <openxr/openxr_platform.h>

using namespace xrtest;

namespace {

constexpr int kWidth = 64, kHeight = 48;

class OffscreenContext {
 public:
  OffscreenContext() : buffer_(16 * 16 * 4) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                           OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    REQUIRE(ctx_ != nullptr);
    REQUIRE(OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 16, 16));
  }
  ~OffscreenContext() { OSMesaDestroyContext(ctx_); }

 private:
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
};

XrSwapchain make_swapchain(XrSession s, int64_t format) {
  XrSwapchainCreateInfo info = xr_struct<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
  info.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT | XR_SWAPCHAIN_USAGE_SAMPLED_BIT;
  info.format = format;
  info.sampleCount = 1;
  info.width = kWidth;
  info.height = kHeight;
  info.faceCount = 1;
  info.arraySize = 1;
  info.mipCount = 1;
  XrSwapchain sc = XR_NULL_HANDLE;
  REQUIRE(xrCreateSwapchain(s, &info, &sc) == XR_SUCCESS);
  return sc;
}

std::vector<GLuint> images_of(XrSwapchain sc) {
  uint32_t n = 0;
  REQUIRE(xrEnumerateSwapchainImages(sc, 0, &n, nullptr) == XR_SUCCESS);
  std::vector<XrSwapchainImageOpenGLKHR> images(n, xr_struct<XrSwapchainImageOpenGLKHR>(XR_TYPE_SWAPCHAIN_IMAGE_OPENGL_KHR));
  REQUIRE(xrEnumerateSwapchainImages(sc, n, &n, reinterpret_cast<XrSwapchainImageBaseHeader*>(images.data())) ==
          XR_SUCCESS);
  std::vector<GLuint> out;
  for (const auto& i : images) out.push_back(i.image);
  return out;
}

// Acquires, fills the image with `rgb` and a blue 8x8 square in its top-left corner, releases.
void draw(XrSwapchain sc, const std::vector<GLuint>& images, float r, float g, float b) {
  uint32_t index = 0;
  REQUIRE(xrAcquireSwapchainImage(sc, nullptr, &index) == XR_SUCCESS);
  XrSwapchainImageWaitInfo wait = xr_struct<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
  wait.timeout = XR_INFINITE_DURATION;
  REQUIRE(xrWaitSwapchainImage(sc, &wait) == XR_SUCCESS);
  GLuint fbo = 0;
  glGenFramebuffers(1, &fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, images[index], 0);
  REQUIRE(glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
  glViewport(0, 0, kWidth, kHeight);
  glClearColor(r, g, b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, kHeight - 8, 8, 8);  // GL's rows go bottom up: this is the top-left corner
  glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDeleteFramebuffers(1, &fbo);
  REQUIRE(xrReleaseSwapchainImage(sc, nullptr) == XR_SUCCESS);
}

struct Png {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba;
  const uint8_t* at(uint32_t x, uint32_t y) const { return rgba.data() + (std::size_t(y) * width + x) * 4; }
};

Png read_png(const std::string& path) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&image, path.c_str()) != 0);
  image.format = PNG_FORMAT_RGBA;
  Png out;
  out.width = image.width;
  out.height = image.height;
  out.rgba.resize(PNG_IMAGE_SIZE(image));
  REQUIRE(png_image_finish_read(&image, nullptr, out.rgba.data(), 0, nullptr) != 0);
  return out;
}

std::vector<XrView> locate_views(XrSession s, XrSpace space, XrTime time) {
  XrViewLocateInfo info = xr_struct<XrViewLocateInfo>(XR_TYPE_VIEW_LOCATE_INFO);
  info.viewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  info.displayTime = time;
  info.space = space;
  XrViewState state = xr_struct<XrViewState>(XR_TYPE_VIEW_STATE);
  std::vector<XrView> views(2, xr_struct<XrView>(XR_TYPE_VIEW));
  uint32_t n = 0;
  REQUIRE(xrLocateViews(s, &info, &state, 2, &n, views.data()) == XR_SUCCESS);
  return views;
}

// A projection layer over the two swapchains, with the located views.
struct Layer {
  std::vector<XrCompositionLayerProjectionView> views;
  XrCompositionLayerProjection projection = xr_struct<XrCompositionLayerProjection>(XR_TYPE_COMPOSITION_LAYER_PROJECTION);
  const XrCompositionLayerBaseHeader* header = nullptr;
  Layer(XrSpace space, const std::vector<XrView>& located, XrSwapchain left, XrSwapchain right) {
    for (int i = 0; i < 2; ++i) {
      XrCompositionLayerProjectionView v = xr_struct<XrCompositionLayerProjectionView>(XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW);
      v.pose = located[i].pose;
      v.fov = located[i].fov;
      v.subImage.swapchain = i == 0 ? left : right;
      v.subImage.imageRect = {{0, 0}, {kWidth, kHeight}};
      views.push_back(v);
    }
    projection.space = space;
    projection.viewCount = 2;
    projection.views = views.data();
    header = reinterpret_cast<const XrCompositionLayerBaseHeader*>(&projection);
  }
};

XrResult end_frame(XrSession s, XrTime time, const Layer* layer) {
  XrFrameEndInfo end = xr_struct<XrFrameEndInfo>(XR_TYPE_FRAME_END_INFO);
  end.displayTime = time;
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  end.layerCount = layer != nullptr ? 1 : 0;
  end.layers = layer != nullptr ? &layer->header : nullptr;
  return xrEndFrame(s, &end);
}

// The OpenGL session the tests start from: an offscreen context current, an instance with
// XR_KHR_opengl_enable, a session over the Xlib binding, two RGBA8 eye swapchains and a depth one.
struct GlSession {
  OffscreenContext context;
  Instance instance{{"XR_KHR_opengl_enable"}};
  XrSession session = XR_NULL_HANDLE;
  XrSwapchain left = XR_NULL_HANDLE, right = XR_NULL_HANDLE, depth = XR_NULL_HANDLE;
  std::vector<GLuint> left_images, right_images;

  GlSession() {
    XrGraphicsBindingOpenGLXlibKHR binding =
        xr_struct<XrGraphicsBindingOpenGLXlibKHR>(XR_TYPE_GRAPHICS_BINDING_OPENGL_XLIB_KHR);
    XrSessionCreateInfo create = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    create.next = &binding;
    create.systemId = instance.system();
    // The spec's order: the graphics requirements are asked for before the session.
    CHECK(xrCreateSession(instance.get(), &create, &session) == XR_ERROR_GRAPHICS_REQUIREMENTS_CALL_MISSING);
    XrGraphicsRequirementsOpenGLKHR req =
        xr_struct<XrGraphicsRequirementsOpenGLKHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_OPENGL_KHR);
    auto requirements = instance.proc<PFN_xrGetOpenGLGraphicsRequirementsKHR>("xrGetOpenGLGraphicsRequirementsKHR");
    REQUIRE(requirements(instance.get(), create.systemId, &req) == XR_SUCCESS);
    REQUIRE(xrCreateSession(instance.get(), &create, &session) == XR_SUCCESS);
    left = make_swapchain(session, GL_RGBA8);
    right = make_swapchain(session, GL_RGBA8);
    depth = make_swapchain(session, GL_DEPTH_COMPONENT24);
    left_images = images_of(left);
    right_images = images_of(right);
  }
  ~GlSession() { xrDestroySession(session); }
  GlSession(const GlSession&) = delete;
  GlSession& operator=(const GlSession&) = delete;

  XrSpace local_space() const {
    XrReferenceSpaceCreateInfo info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
    info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
    info.poseInReferenceSpace.orientation.w = 1.0f;
    XrSpace space = XR_NULL_HANDLE;
    REQUIRE(xrCreateReferenceSpace(session, &info, &space) == XR_SUCCESS);
    return space;
  }
};

// Frame 1 of the frames test: a second begin discards the first, bad layers are refused, a good one is not.
void frame_with_bad_layers(const GlSession& g, XrSpace local) {
  XrFrameState frame = xr_struct<XrFrameState>(XR_TYPE_FRAME_STATE);
  REQUIRE(xrWaitFrame(g.session, nullptr, &frame) == XR_SUCCESS);
  REQUIRE(xrBeginFrame(g.session, nullptr) == XR_SUCCESS);
  REQUIRE(xrWaitFrame(g.session, nullptr, &frame) == XR_SUCCESS);
  CHECK(xrBeginFrame(g.session, nullptr) == XR_FRAME_DISCARDED);
  draw(g.left, g.left_images, 1.0f, 1.0f, 0.0f);
  draw(g.right, g.right_images, 1.0f, 1.0f, 0.0f);
  const XrTime time = frame.predictedDisplayTime;
  Layer layer(local, locate_views(g.session, local, time), g.left, g.right);
  layer.projection.viewCount = 1;
  CHECK(end_frame(g.session, time, &layer) == XR_ERROR_VALIDATION_FAILURE);
  layer.projection.viewCount = 2;
  layer.views[1].subImage.imageRect = {{8, 0}, {kWidth, kHeight}};
  CHECK(end_frame(g.session, time, &layer) == XR_ERROR_SWAPCHAIN_RECT_INVALID);
  layer.views[1].subImage.imageRect = {{0, 0}, {kWidth, kHeight}};
  layer.views[1].subImage.swapchain = g.depth;  // never released
  CHECK(end_frame(g.session, time, &layer) == XR_ERROR_LAYER_INVALID);
  layer.views[1].subImage.swapchain = g.right;
  uint32_t index = 0;
  REQUIRE(xrAcquireSwapchainImage(g.right, nullptr, &index) == XR_SUCCESS);  // held by the app: not submittable
  CHECK(end_frame(g.session, time, &layer) == XR_ERROR_LAYER_INVALID);
  XrSwapchainImageWaitInfo wait = xr_struct<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
  wait.timeout = XR_INFINITE_DURATION;
  REQUIRE(xrWaitSwapchainImage(g.right, &wait) == XR_SUCCESS);
  REQUIRE(xrReleaseSwapchainImage(g.right, nullptr) == XR_SUCCESS);
  REQUIRE(end_frame(g.session, time, &layer) == XR_SUCCESS);
  CHECK(end_frame(g.session, time, &layer) == XR_ERROR_CALL_ORDER_INVALID);
}

// What WEDGE_XR_FRAMES wrote for frame 0: the colours drawn (the blue square at the top left: rows were
// flipped to top-down) and, in the sidecar, what was submitted.
void check_frame_0(const std::string& dir, const std::vector<XrView>& submitted) {
  const Png eye0 = read_png(dir + "/frame_000000_eye0.png"), eye1 = read_png(dir + "/frame_000000_eye1.png");
  REQUIRE(eye0.width == uint32_t(kWidth));
  REQUIRE(eye0.height == uint32_t(kHeight));
  CHECK(eye0.at(2, 2)[2] == 255);
  CHECK(eye0.at(2, 2)[0] == 0);
  CHECK(eye0.at(40, 30)[0] == 255);
  CHECK(eye0.at(2, kHeight - 3)[0] == 255);  // the bottom-left corner is the clear colour
  CHECK(eye1.at(40, 30)[1] == 255);
  CHECK(eye1.at(40, 30)[0] == 0);
  std::ifstream in(dir + "/frame_000000.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  CHECK(doc["frame"] == 0);
  CHECK(doc["display_time_ns"] == frame_time(0));
  CHECK(doc["space"]["type"] == "LOCAL");
  CHECK(doc["space"]["located"] == true);
  REQUIRE(doc["eyes"].size() == 2);
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& e = doc["eyes"][i];
    CHECK(e["image"] == "frame_000000_eye" + std::to_string(i) + ".png");
    CHECK(e["pose"]["position"][0].get<float>() == submitted[i].pose.position.x);
    CHECK(e["pose"]["position"][1].get<float>() == submitted[i].pose.position.y);
    CHECK(e["pose"]["orientation"][3].get<float>() == submitted[i].pose.orientation.w);
    CHECK(e["fov"]["angle_left"].get<float>() == submitted[i].fov.angleLeft);
    CHECK(e["fov"]["angle_up"].get<float>() == submitted[i].fov.angleUp);
    CHECK(e["image_rect"] == nlohmann::json::parse(R"({"x":0,"y":0,"width":64,"height":48})"));
    CHECK(e["format"] == GL_RGBA8);
    CHECK(e["format_name"] == "GL_RGBA8");
  }
}

}  // namespace

TEST_CASE("xr runtime: OpenGL swapchains are made in the app's context and deleted with the swapchain") {
  runtime_env({{"WEDGE_XR_EYE_SIZE", "64x48"}});
  GlSession g;
  uint32_t n = 0;
  REQUIRE(xrEnumerateSwapchainFormats(g.session, 0, &n, nullptr) == XR_SUCCESS);
  std::vector<int64_t> formats(n);
  REQUIRE(xrEnumerateSwapchainFormats(g.session, n, &n, formats.data()) == XR_SUCCESS);
  CHECK(formats.front() == GL_SRGB8_ALPHA8);
  for (int64_t f : {GL_RGBA8, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT32F})
    CHECK(std::count(formats.begin(), formats.end(), f) == 1);
  XrSwapchainCreateInfo bad = xr_struct<XrSwapchainCreateInfo>(XR_TYPE_SWAPCHAIN_CREATE_INFO);
  bad.format = GL_RGB565;
  bad.sampleCount = bad.faceCount = bad.arraySize = bad.mipCount = 1;
  bad.width = bad.height = 16;
  XrSwapchain sc = XR_NULL_HANDLE;
  CHECK(xrCreateSwapchain(g.session, &bad, &sc) == XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED);
  REQUIRE(g.left_images.size() == 3);
  for (GLuint t : g.left_images) CHECK(glIsTexture(t) == GL_TRUE);
  std::vector<XrSwapchainImageOpenGLKHR> untyped(3);
  CHECK(xrEnumerateSwapchainImages(g.left, 3, &n, reinterpret_cast<XrSwapchainImageBaseHeader*>(untyped.data())) ==
        XR_ERROR_VALIDATION_FAILURE);
  REQUIRE(xrDestroySwapchain(g.left) == XR_SUCCESS);
  for (GLuint t : g.left_images) CHECK(glIsTexture(t) == GL_FALSE);
  CHECK(xrDestroySwapchain(g.left) == XR_ERROR_HANDLE_INVALID);
}

TEST_CASE("xr runtime: swapchain images are acquired, waited and released in order") {
  runtime_env();
  GlSession g;
  XrSwapchainImageWaitInfo wait = xr_struct<XrSwapchainImageWaitInfo>(XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO);
  wait.timeout = XR_INFINITE_DURATION;
  CHECK(xrWaitSwapchainImage(g.depth, &wait) == XR_ERROR_CALL_ORDER_INVALID);
  CHECK(xrReleaseSwapchainImage(g.depth, nullptr) == XR_ERROR_CALL_ORDER_INVALID);
  uint32_t index = 99;
  for (uint32_t i = 0; i < 3; ++i) {
    REQUIRE(xrAcquireSwapchainImage(g.depth, nullptr, &index) == XR_SUCCESS);
    CHECK(index == i);
  }
  CHECK(xrAcquireSwapchainImage(g.depth, nullptr, &index) == XR_ERROR_CALL_ORDER_INVALID);
  REQUIRE(xrWaitSwapchainImage(g.depth, &wait) == XR_SUCCESS);
  CHECK(xrWaitSwapchainImage(g.depth, &wait) == XR_ERROR_CALL_ORDER_INVALID);
  for (int i = 0; i < 3; ++i) {
    if (i > 0) REQUIRE(xrWaitSwapchainImage(g.depth, &wait) == XR_SUCCESS);
    REQUIRE(xrReleaseSwapchainImage(g.depth, nullptr) == XR_SUCCESS);
  }
  REQUIRE(xrAcquireSwapchainImage(g.depth, nullptr, &index) == XR_SUCCESS);
  CHECK(index == 0);
}

TEST_CASE("xr runtime: OpenGL frames follow the order rules, layers are checked, and every K-th is written out") {
  const std::string dir = temp_path("frames");
  std::filesystem::remove_all(dir);
  runtime_env({{"WEDGE_XR_FRAMES", dir}, {"WEDGE_XR_FRAMES_EVERY", "2"}, {"WEDGE_XR_EYE_SIZE", "64x48"}});
  GlSession g;
  XrSessionBeginInfo begin = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
  begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  REQUIRE(xrBeginSession(g.session, &begin) == XR_SUCCESS);
  const XrSpace local = g.local_space();
  CHECK(xrBeginFrame(g.session, nullptr) == XR_ERROR_CALL_ORDER_INVALID);  // no xrWaitFrame yet
  CHECK(end_frame(g.session, kEpoch, nullptr) == XR_ERROR_CALL_ORDER_INVALID);

  // Submitted frame 0: written.
  XrFrameState frame = xr_struct<XrFrameState>(XR_TYPE_FRAME_STATE);
  REQUIRE(xrWaitFrame(g.session, nullptr, &frame) == XR_SUCCESS);
  CHECK(frame.shouldRender == XR_TRUE);
  CHECK(frame.predictedDisplayTime == frame_time(0));
  REQUIRE(xrBeginFrame(g.session, nullptr) == XR_SUCCESS);
  draw(g.left, g.left_images, 1.0f, 0.0f, 0.0f);
  draw(g.right, g.right_images, 0.0f, 1.0f, 0.0f);
  const std::vector<XrView> views0 = locate_views(g.session, local, frame.predictedDisplayTime);
  const Layer layer0(local, views0, g.left, g.right);
  REQUIRE(end_frame(g.session, frame.predictedDisplayTime, &layer0) == XR_SUCCESS);
  // Submitted frame 1: not written (every second frame).
  frame_with_bad_layers(g, local);
  // Submitted frame 2: written.
  REQUIRE(xrWaitFrame(g.session, nullptr, &frame) == XR_SUCCESS);
  CHECK(frame.predictedDisplayTime == frame_time(3));
  REQUIRE(xrBeginFrame(g.session, nullptr) == XR_SUCCESS);
  draw(g.left, g.left_images, 0.0f, 1.0f, 1.0f);
  draw(g.right, g.right_images, 1.0f, 0.0f, 1.0f);
  const Layer layer2(local, locate_views(g.session, local, frame.predictedDisplayTime), g.left, g.right);
  REQUIRE(end_frame(g.session, frame.predictedDisplayTime, &layer2) == XR_SUCCESS);

  CHECK(std::filesystem::exists(dir + "/frame_000000.json"));
  CHECK_FALSE(std::filesystem::exists(dir + "/frame_000001.json"));
  CHECK_FALSE(std::filesystem::exists(dir + "/frame_000001_eye0.png"));
  check_frame_0(dir, views0);
  CHECK(views0[0].pose.position.x == Approx(-0.0315));
  const Png later = read_png(dir + "/frame_000002_eye1.png");
  CHECK(later.at(40, 30)[0] == 255);
  CHECK(later.at(40, 30)[2] == 255);
}
