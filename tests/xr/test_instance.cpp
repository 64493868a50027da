// The runtime as the loader sees it: negotiation, the dispatch table, instance creation (extensions,
// settings, the recording), the system, the refusal switches, the string functions and the timespec clock.
#define XR_USE_GRAPHICS_API_OPENGL  // XrGraphicsRequirementsOpenGLKHR (no platform binding needed here)
#define XR_USE_TIMESPEC             // XR_KHR_convert_timespec_time
#include <dlfcn.h>
#include <fcntl.h>
#include <openxr/openxr_platform.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>

#include "loader_abi.hpp"
#include "xr_test_support.hpp"

using namespace xrtest;

namespace {

// The negotiation structs as the runtime declares them (xr/runtime/src/loader_abi.hpp, laid out as the loader's):
// the function is called through its own type, so UBSan's function-type check holds.
using LoaderInfo = XrNegotiateLoaderInfo;
using RuntimeRequest = XrNegotiateRuntimeRequest;
using Negotiate = XrResult (*)(const XrNegotiateLoaderInfo*, XrNegotiateRuntimeRequest*);

// The runtime library next to the manifest (the manifest's library_path is "./libwedge_xr_replay.so").
void* runtime_library() {
  std::string dir = WEDGE_XR_REPLAY_MANIFEST;
  dir = dir.substr(0, dir.rfind('/'));
  void* lib = dlopen((dir + "/libwedge_xr_replay.so").c_str(), RTLD_NOW | RTLD_LOCAL);
  REQUIRE(lib != nullptr);
  return lib;
}

// The runtime's own xrGetInstanceProcAddr, negotiated the way the loader does it.
PFN_xrGetInstanceProcAddr negotiated_gipa() {
  auto negotiate = reinterpret_cast<Negotiate>(dlsym(runtime_library(), "xrNegotiateLoaderRuntimeInterface"));
  REQUIRE(negotiate != nullptr);
  LoaderInfo info{XR_LOADER_INTERFACE_STRUCT_LOADER_INFO, 1, sizeof(LoaderInfo), 1, 1, XR_MAKE_VERSION(1, 0, 0),
                  XR_MAKE_VERSION(1, 0, 0xfff)};
  RuntimeRequest request{XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST, 1, sizeof(RuntimeRequest), 0, 0, nullptr};
  REQUIRE(negotiate(&info, &request) == XR_SUCCESS);
  CHECK(request.runtimeInterfaceVersion == 1);
  CHECK(XR_VERSION_MAJOR(request.runtimeApiVersion) == 1);
  CHECK(XR_VERSION_MINOR(request.runtimeApiVersion) == 0);
  REQUIRE(request.getInstanceProcAddr != nullptr);
  return request.getInstanceProcAddr;
}

template <class F>
F runtime_proc(PFN_xrGetInstanceProcAddr gipa, XrInstance instance, const char* name) {
  PFN_xrVoidFunction f = nullptr;
  REQUIRE(gipa(instance, name, &f) == XR_SUCCESS);
  return reinterpret_cast<F>(f);
}

// xrCreateInstance straight into the runtime (past the loader's own checks).
XrResult create_direct(PFN_xrGetInstanceProcAddr gipa, std::vector<const char*> extensions, XrInstance* out) {
  auto create = runtime_proc<PFN_xrCreateInstance>(gipa, XR_NULL_HANDLE, "xrCreateInstance");
  XrInstanceCreateInfo info = xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::strcpy(info.applicationInfo.applicationName, "direct");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.enabledExtensionNames = extensions.data();
  return create(&info, out);
}

// What the process writes to stderr while it lives.
class StderrCapture {
 public:
  StderrCapture() : path_(temp_path("stderr.txt")) {
    std::fflush(stderr);
    saved_ = dup(2);
    const int fd = open(path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 2);
    close(fd);
  }
  ~StderrCapture() { restore(); }
  std::string text() {
    restore();
    std::ifstream in(path_);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    saved_ = -1;
  }
  std::string path_;
  int saved_ = -1;
};

// Lines the runtime wrote (it starts each with its name).
int runtime_lines(const std::string& text) {
  int n = 0;
  for (std::size_t at = text.find("Wedge replay runtime: "); at != std::string::npos;
       at = text.find("Wedge replay runtime: ", at + 1))
    ++n;
  return n;
}

XrResult create_instance(std::vector<const char*> extensions, XrInstance* out) {
  XrInstanceCreateInfo info = xr_struct<XrInstanceCreateInfo>(XR_TYPE_INSTANCE_CREATE_INFO);
  std::strcpy(info.applicationInfo.applicationName, "wedge_xr_runtime_tests");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.enabledExtensionNames = extensions.data();
  return xrCreateInstance(&info, out);
}

// The core OpenXR 1.0 commands (the specification's list).
const char* const kCoreFunctions[] = {
    "xrGetInstanceProcAddr", "xrEnumerateApiLayerProperties", "xrEnumerateInstanceExtensionProperties",
    "xrCreateInstance", "xrDestroyInstance", "xrGetInstanceProperties", "xrPollEvent", "xrResultToString",
    "xrStructureTypeToString", "xrGetSystem", "xrGetSystemProperties", "xrEnumerateEnvironmentBlendModes",
    "xrCreateSession", "xrDestroySession", "xrEnumerateReferenceSpaces", "xrCreateReferenceSpace",
    "xrGetReferenceSpaceBoundsRect", "xrCreateActionSpace", "xrLocateSpace", "xrDestroySpace",
    "xrEnumerateViewConfigurations", "xrGetViewConfigurationProperties", "xrEnumerateViewConfigurationViews",
    "xrEnumerateSwapchainFormats", "xrCreateSwapchain", "xrDestroySwapchain", "xrEnumerateSwapchainImages",
    "xrAcquireSwapchainImage", "xrWaitSwapchainImage", "xrReleaseSwapchainImage", "xrBeginSession", "xrEndSession",
    "xrRequestExitSession", "xrWaitFrame", "xrBeginFrame", "xrEndFrame", "xrLocateViews", "xrStringToPath",
    "xrPathToString", "xrCreateActionSet", "xrDestroyActionSet", "xrCreateAction", "xrDestroyAction",
    "xrSuggestInteractionProfileBindings", "xrAttachSessionActionSets", "xrGetCurrentInteractionProfile",
    "xrGetActionStateBoolean", "xrGetActionStateFloat", "xrGetActionStateVector2f", "xrGetActionStatePose",
    "xrSyncActions", "xrEnumerateBoundSourcesForAction", "xrGetInputSourceLocalizedName", "xrApplyHapticFeedback",
    "xrStopHapticFeedback"};

}  // namespace

TEST_CASE("xr runtime: the loader finds it, and it names itself and its extensions") {
  runtime_env();
  uint32_t n = 0;
  REQUIRE(xrEnumerateInstanceExtensionProperties(nullptr, 0, &n, nullptr) == XR_SUCCESS);
  std::vector<XrExtensionProperties> ext(n, xr_struct<XrExtensionProperties>(XR_TYPE_EXTENSION_PROPERTIES));
  REQUIRE(xrEnumerateInstanceExtensionProperties(nullptr, n, &n, ext.data()) == XR_SUCCESS);
  std::vector<std::string> names;
  for (const auto& e : ext) names.push_back(e.extensionName);
  // The runtime's three, plus the loader's own XR_EXT_debug_utils.
  for (const char* e : {"XR_KHR_opengl_enable", "XR_KHR_convert_timespec_time", "XR_MND_headless"})
    CHECK(std::count(names.begin(), names.end(), std::string(e)) == 1);
  CHECK(names.size() == 4);

  Instance instance({"XR_MND_headless", "XR_KHR_opengl_enable", "XR_KHR_convert_timespec_time"});
  XrInstanceProperties props = xr_struct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
  REQUIRE(xrGetInstanceProperties(instance.get(), &props) == XR_SUCCESS);
  CHECK(std::string(props.runtimeName) == "Wedge replay runtime");
  XrInstanceProperties wrong = xr_struct<XrInstanceProperties>(XR_TYPE_SYSTEM_PROPERTIES);
  CHECK(xrGetInstanceProperties(instance.get(), &wrong) == XR_ERROR_VALIDATION_FAILURE);
}

TEST_CASE("xr runtime: an app may also enable the loader's own XR_EXT_debug_utils") {
  runtime_env();
  Instance instance({"XR_MND_headless", "XR_EXT_debug_utils"});
  PFN_xrVoidFunction f = nullptr;
  CHECK(xrGetInstanceProcAddr(instance.get(), "xrCreateDebugUtilsMessengerEXT", &f) == XR_SUCCESS);
  CHECK(f != nullptr);
}

TEST_CASE("xr runtime: negotiation refuses what is not the loader's ABI") {
  auto negotiate = reinterpret_cast<Negotiate>(dlsym(runtime_library(), "xrNegotiateLoaderRuntimeInterface"));
  REQUIRE(negotiate != nullptr);
  LoaderInfo info{XR_LOADER_INTERFACE_STRUCT_LOADER_INFO, 1, sizeof(LoaderInfo), 1, 1, XR_MAKE_VERSION(1, 0, 0),
                  XR_MAKE_VERSION(1, 0, 0xfff)};
  RuntimeRequest request{XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST, 1, sizeof(RuntimeRequest), 0, 0, nullptr};
  LoaderInfo wrong_type = info;
  wrong_type.structType = XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST;
  CHECK(negotiate(&wrong_type, &request) == XR_ERROR_INITIALIZATION_FAILED);
  LoaderInfo wrong_size = info;
  wrong_size.structSize = 16;
  CHECK(negotiate(&wrong_size, &request) == XR_ERROR_INITIALIZATION_FAILED);
  LoaderInfo interface2 = info;
  interface2.minInterfaceVersion = interface2.maxInterfaceVersion = 2;
  CHECK(negotiate(&interface2, &request) == XR_ERROR_INITIALIZATION_FAILED);
  LoaderInfo openxr2 = info;
  openxr2.minApiVersion = openxr2.maxApiVersion = XR_MAKE_VERSION(2, 0, 0);
  CHECK(negotiate(&openxr2, &request) == XR_ERROR_INITIALIZATION_FAILED);
  CHECK(request.getInstanceProcAddr == nullptr);
  CHECK(negotiate(&info, &request) == XR_SUCCESS);
  CHECK(request.getInstanceProcAddr != nullptr);
}

TEST_CASE("xr runtime: xrGetInstanceProcAddr answers every core function, and the enabled extensions'") {
  runtime_env();
  const PFN_xrGetInstanceProcAddr gipa = negotiated_gipa();
  PFN_xrVoidFunction f = nullptr;
  // Without an instance: only what makes one.
  CHECK(gipa(XR_NULL_HANDLE, "xrCreateInstance", &f) == XR_SUCCESS);
  CHECK(f != nullptr);
  CHECK(gipa(XR_NULL_HANDLE, "xrEnumerateInstanceExtensionProperties", &f) == XR_SUCCESS);
  CHECK(gipa(XR_NULL_HANDLE, "xrGetSystem", &f) == XR_ERROR_HANDLE_INVALID);
  CHECK(f == nullptr);

  XrInstance instance = XR_NULL_HANDLE;
  REQUIRE(create_direct(gipa, {"XR_MND_headless", "XR_KHR_convert_timespec_time"}, &instance) == XR_SUCCESS);
  for (const char* name : kCoreFunctions) {
    INFO(name);
    f = nullptr;
    CHECK(gipa(instance, name, &f) == XR_SUCCESS);
    CHECK(f != nullptr);
  }
  CHECK(sizeof(kCoreFunctions) / sizeof(kCoreFunctions[0]) == 55);
  CHECK(gipa(instance, "xrConvertTimespecTimeToTimeKHR", &f) == XR_SUCCESS);
  CHECK(gipa(instance, "xrConvertTimeToTimespecTimeKHR", &f) == XR_SUCCESS);
  // XR_KHR_opengl_enable was not enabled: its function is not there; unknown names never are.
  f = reinterpret_cast<PFN_xrVoidFunction>(gipa);  // not null: the call must clear it
  CHECK(gipa(instance, "xrGetOpenGLGraphicsRequirementsKHR", &f) == XR_ERROR_FUNCTION_UNSUPPORTED);
  CHECK(f == nullptr);
  f = reinterpret_cast<PFN_xrVoidFunction>(gipa);  // not null: the call must clear it
  CHECK(gipa(instance, "xrGetVulkanGraphicsRequirementsKHR", &f) == XR_ERROR_FUNCTION_UNSUPPORTED);
  CHECK(f == nullptr);
  CHECK(gipa(instance, "xrNoSuchFunction", &f) == XR_ERROR_FUNCTION_UNSUPPORTED);
  CHECK(gipa(instance, nullptr, &f) == XR_ERROR_VALIDATION_FAILURE);
  CHECK(gipa(instance, "xrGetSystem", nullptr) == XR_ERROR_VALIDATION_FAILURE);
  auto destroy = runtime_proc<PFN_xrDestroyInstance>(gipa, instance, "xrDestroyInstance");
  REQUIRE(destroy(instance) == XR_SUCCESS);
  // A destroyed instance is no instance.
  CHECK(gipa(instance, "xrGetSystem", &f) == XR_ERROR_HANDLE_INVALID);
  CHECK(destroy(instance) == XR_ERROR_HANDLE_INVALID);
}

TEST_CASE("xr runtime: an instance asking for an extension the runtime lacks is refused") {
  runtime_env();
  XrInstance instance = XR_NULL_HANDLE;
  // Through the loader (which checks first), and straight into the runtime.
  CHECK(create_instance({"XR_KHR_vulkan_enable"}, &instance) == XR_ERROR_EXTENSION_NOT_PRESENT);
  const PFN_xrGetInstanceProcAddr gipa = negotiated_gipa();
  CHECK(create_direct(gipa, {"XR_MND_headless", "XR_KHR_vulkan_enable"}, &instance) == XR_ERROR_EXTENSION_NOT_PRESENT);
  CHECK(create_direct(gipa, {"XR_EXT_hand_tracking"}, &instance) == XR_ERROR_EXTENSION_NOT_PRESENT);
}

TEST_CASE("xr runtime: an unreadable recording fails xrCreateInstance with one line naming it") {
  const std::string missing = temp_path("no_such_recording.jsonl");
  const std::string broken = temp_path("broken_recording.jsonl");
  {
    std::ofstream out(broken);
    out << "{\"format\":\"wedge-recording\",\"version\":1,\"source\":\"script\",\"units\":{\"time\":\"s\",\"position\":"
           "\"m\",\"acceleration\":\"g\",\"rotation_rate\":\"rad/s\"},\"conventions\":{}}\n"
        << "{\"t\":0.0,\"type\":\"hand\",\"hand\":\"middle\"}\n";
  }
  for (const std::string& path : {missing, broken}) {
    INFO(path);
    runtime_env({{"WEDGE_XR_REPLAY", path}});
    XrInstance instance = XR_NULL_HANDLE;
    StderrCapture capture;
    CHECK(create_instance({"XR_MND_headless"}, &instance) == XR_ERROR_RUNTIME_FAILURE);
    const std::string err = capture.text();
    INFO(err);
    CHECK(err.find(path) != std::string::npos);
    CHECK(runtime_lines(err) == 1);  // (the loader may add lines of its own)
    if (path == broken) CHECK(err.find(broken + ":2:") != std::string::npos);
  }
  // A readable one makes an instance.
  wedge::recordings::Recording r;
  r.source = "script";
  r.hands.push_back(hand(0.0, wedge::recordings::Hand::Right, {0, 1, 0}));
  runtime_env({{"WEDGE_XR_REPLAY", write_test_recording("ok.jsonl", r)}});
  Instance ok;
}

TEST_CASE("xr runtime: malformed settings refuse the instance") {
  for (auto [name, value] : {std::pair<const char*, const char*>{"WEDGE_XR_EYE_SIZE", "640by720"},
                             {"WEDGE_XR_EYE_SIZE", "0x720"},
                             {"WEDGE_XR_FRAMES_EVERY", "0"},
                             {"WEDGE_XR_REFUSE", "everything"}}) {
    INFO(name << "=" << value);
    runtime_env({{name, value}});
    XrInstance instance = XR_NULL_HANDLE;
    StderrCapture capture;
    CHECK(create_instance({"XR_MND_headless"}, &instance) == XR_ERROR_RUNTIME_FAILURE);
    CHECK(capture.text().find(name) != std::string::npos);
  }
}

TEST_CASE("xr runtime: one head-mounted system, its stereo views and OpenGL requirements") {
  runtime_env({{"WEDGE_XR_EYE_SIZE", "320x240"}});
  Instance instance({"XR_KHR_opengl_enable"});
  XrSystemGetInfo get = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  get.formFactor = XR_FORM_FACTOR_HANDHELD_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  CHECK(xrGetSystem(instance.get(), &get, &system) == XR_ERROR_FORM_FACTOR_UNSUPPORTED);
  system = instance.system();
  XrSystemProperties props = xr_struct<XrSystemProperties>(XR_TYPE_SYSTEM_PROPERTIES);
  REQUIRE(xrGetSystemProperties(instance.get(), system, &props) == XR_SUCCESS);
  CHECK(props.trackingProperties.orientationTracking == XR_TRUE);
  CHECK(props.trackingProperties.positionTracking == XR_TRUE);
  CHECK(xrGetSystemProperties(instance.get(), system + 1, &props) == XR_ERROR_SYSTEM_INVALID);

  uint32_t n = 0;
  REQUIRE(xrEnumerateViewConfigurations(instance.get(), system, 0, &n, nullptr) == XR_SUCCESS);
  REQUIRE(n == 1);
  XrViewConfigurationType type{};
  REQUIRE(xrEnumerateViewConfigurations(instance.get(), system, 1, &n, &type) == XR_SUCCESS);
  CHECK(type == XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO);
  // Two-call idiom: capacity 0 gives the count, too small a capacity is refused.
  REQUIRE(xrEnumerateViewConfigurationViews(instance.get(), system, type, 0, &n, nullptr) == XR_SUCCESS);
  CHECK(n == 2);
  std::vector<XrViewConfigurationView> views(2, xr_struct<XrViewConfigurationView>(XR_TYPE_VIEW_CONFIGURATION_VIEW));
  CHECK(xrEnumerateViewConfigurationViews(instance.get(), system, type, 1, &n, views.data()) == XR_ERROR_SIZE_INSUFFICIENT);
  REQUIRE(xrEnumerateViewConfigurationViews(instance.get(), system, type, 2, &n, views.data()) == XR_SUCCESS);
  for (const auto& v : views) {
    CHECK(v.recommendedImageRectWidth == 320);
    CHECK(v.recommendedImageRectHeight == 240);
    CHECK(v.recommendedSwapchainSampleCount == 1);
  }
  std::vector<XrViewConfigurationView> untyped(2);
  CHECK(xrEnumerateViewConfigurationViews(instance.get(), system, type, 2, &n, untyped.data()) ==
        XR_ERROR_VALIDATION_FAILURE);
  CHECK(xrEnumerateViewConfigurationViews(instance.get(), system, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_MONO, 0, &n,
                                          nullptr) == XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED);
  XrEnvironmentBlendMode mode{};
  REQUIRE(xrEnumerateEnvironmentBlendModes(instance.get(), system, type, 1, &n, &mode) == XR_SUCCESS);
  CHECK(n == 1);
  CHECK(mode == XR_ENVIRONMENT_BLEND_MODE_OPAQUE);

  auto requirements = instance.proc<PFN_xrGetOpenGLGraphicsRequirementsKHR>("xrGetOpenGLGraphicsRequirementsKHR");
  XrGraphicsRequirementsOpenGLKHR req = xr_struct<XrGraphicsRequirementsOpenGLKHR>(XR_TYPE_GRAPHICS_REQUIREMENTS_OPENGL_KHR);
  REQUIRE(requirements(instance.get(), system, &req) == XR_SUCCESS);
  CHECK(req.minApiVersionSupported == XR_MAKE_VERSION(3, 3, 0));
  CHECK(req.maxApiVersionSupported == XR_MAKE_VERSION(4, 6, 0));
}

TEST_CASE("xr runtime: WEDGE_XR_REFUSE=system and =session make the runtime refuse") {
  {
    runtime_env({{"WEDGE_XR_REFUSE", "system"}});
    Instance instance;
    XrSystemGetInfo get = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
    get.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    XrSystemId system = XR_NULL_SYSTEM_ID;
    StderrCapture capture;
    CHECK(xrGetSystem(instance.get(), &get, &system) == XR_ERROR_FORM_FACTOR_UNAVAILABLE);
    CHECK(capture.text().find("WEDGE_XR_REFUSE=system") != std::string::npos);
  }
  {
    runtime_env({{"WEDGE_XR_REFUSE", "session"}});
    Instance instance;
    XrSessionCreateInfo info = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
    info.systemId = instance.system();
    XrSession session = XR_NULL_HANDLE;
    StderrCapture capture;
    CHECK(xrCreateSession(instance.get(), &info, &session) == XR_ERROR_RUNTIME_FAILURE);
    const std::string err = capture.text();
    CHECK(err.find("WEDGE_XR_REFUSE=session") != std::string::npos);
    CHECK(runtime_lines(err) == 1);
  }
}

TEST_CASE("xr runtime: results and structure types by name") {
  runtime_env();
  Instance instance;
  char buffer[XR_MAX_RESULT_STRING_SIZE];
  REQUIRE(xrResultToString(instance.get(), XR_ERROR_SESSION_NOT_STOPPING, buffer) == XR_SUCCESS);
  CHECK(std::string(buffer) == "XR_ERROR_SESSION_NOT_STOPPING");
  REQUIRE(xrResultToString(instance.get(), XrResult(-999), buffer) == XR_SUCCESS);
  CHECK(std::string(buffer) == "XR_UNKNOWN_FAILURE_-999");
  char name[XR_MAX_STRUCTURE_NAME_SIZE];
  REQUIRE(xrStructureTypeToString(instance.get(), XR_TYPE_ACTIONS_SYNC_INFO, name) == XR_SUCCESS);
  CHECK(std::string(name) == "XR_TYPE_ACTIONS_SYNC_INFO");
}

TEST_CASE("xr runtime: XR_KHR_convert_timespec_time maps CLOCK_MONOTONIC linearly, now at creation = kEpoch") {
  runtime_env();
  timespec before{}, after{};
  clock_gettime(CLOCK_MONOTONIC, &before);
  Instance instance({"XR_KHR_convert_timespec_time"});
  clock_gettime(CLOCK_MONOTONIC, &after);
  auto to_time = instance.proc<PFN_xrConvertTimespecTimeToTimeKHR>("xrConvertTimespecTimeToTimeKHR");
  auto to_timespec = instance.proc<PFN_xrConvertTimeToTimespecTimeKHR>("xrConvertTimeToTimespecTimeKHR");
  XrTime t0 = 0, t1 = 0;
  REQUIRE(to_time(instance.get(), &before, &t0) == XR_SUCCESS);
  REQUIRE(to_time(instance.get(), &after, &t1) == XR_SUCCESS);
  CHECK(t0 <= kEpoch);  // "now" at creation lies between the two readings
  CHECK(t1 >= kEpoch);
  const int64_t span = (after.tv_sec - before.tv_sec) * 1'000'000'000ll + (after.tv_nsec - before.tv_nsec);
  CHECK(t1 - t0 == span);  // linear with slope 1
  timespec back{};
  REQUIRE(to_timespec(instance.get(), t1, &back) == XR_SUCCESS);
  CHECK(back.tv_sec == after.tv_sec);
  CHECK(back.tv_nsec == after.tv_nsec);
  CHECK(to_timespec(instance.get(), 0, &back) == XR_ERROR_TIME_INVALID);
}
