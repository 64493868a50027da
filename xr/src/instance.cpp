#include "wedge/xr/instance.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "platform.hpp"
#include "wedge/xr/check.hpp"

namespace wedge::xr {

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

// The instance extensions the runtime offers (throws XrError naming the loader's search when there is
// no runtime to ask).
std::vector<std::string> offered_extensions() {
  // The loader prints its own errors to stderr; ours say the same in one line. XR_LOADER_DEBUG, when the
  // user sets it, still has the loader speak.
  ::setenv("XR_LOADER_DEBUG", "none", 0);
  std::uint32_t count = 0;
  const XrResult r = xrEnumerateInstanceExtensionProperties(nullptr, 0, &count, nullptr);
  if (XR_FAILED(r))
    throw XrError("no OpenXR runtime (" + result_name(XR_NULL_HANDLE, r) + "): " + runtime_search_text(), r);
  std::vector<XrExtensionProperties> props(count, {XR_TYPE_EXTENSION_PROPERTIES, nullptr, {}, 0});
  check(XR_NULL_HANDLE, xrEnumerateInstanceExtensionProperties(nullptr, count, &count, props.data()),
        "xrEnumerateInstanceExtensionProperties");
  std::vector<std::string> names;
  for (const XrExtensionProperties& p : props) names.emplace_back(p.extensionName);
  return names;
}

}  // namespace

std::string runtime_search_text() {
  const std::string json = env("XR_RUNTIME_JSON");
  if (!json.empty())
    return "XR_RUNTIME_JSON=" + json + " names no loadable runtime manifest (XR_LOADER_DEBUG=error shows the loader's reasons)";
  std::string home = env("XDG_CONFIG_HOME");
  if (home.empty()) home = env("HOME") + "/.config";
  std::string dirs = env("XDG_CONFIG_DIRS");
  if (dirs.empty()) dirs = "/etc/xdg";
  std::string places = home + "/openxr/1/active_runtime.json";
  for (std::size_t begin = 0; begin <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', begin), dirs.size());
    if (end > begin) places += ", " + dirs.substr(begin, end - begin) + "/openxr/1/active_runtime.json";
    begin = end + 1;
  }
  places += ", /etc/openxr/1/active_runtime.json";
  return "XR_RUNTIME_JSON is not set and there is no active runtime (looked for " + places +
         "); install one (SteamVR, Monado) or set XR_RUNTIME_JSON to a runtime's manifest (XR_LOADER_DEBUG=error "
         "shows the loader's reasons)";
}

Instance::Instance(const InstanceOptions& options) : headless_(options.headless) {
  const std::vector<std::string> offered = offered_extensions();
  auto offers = [&](const char* name) { return std::find(offered.begin(), offered.end(), name) != offered.end(); };
  const char* needed = options.headless ? XR_MND_HEADLESS_EXTENSION_NAME : XR_KHR_OPENGL_ENABLE_EXTENSION_NAME;
  if (!offers(needed))
    throw XrError(std::string("the OpenXR runtime does not offer ") + needed +
                      (options.headless ? " (needed by --headless)" : " (needed to render with OpenGL)"),
                  XR_ERROR_EXTENSION_NOT_PRESENT);
  enabled_.emplace_back(needed);
  if (offers(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME)) enabled_.emplace_back(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME);

  std::vector<const char*> names;
  for (const std::string& e : enabled_) names.push_back(e.c_str());
  XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
  std::strncpy(info.applicationInfo.applicationName, options.application.c_str(), XR_MAX_APPLICATION_NAME_SIZE - 1);
  std::strncpy(info.applicationInfo.engineName, "Wedge", XR_MAX_ENGINE_NAME_SIZE - 1);
  info.applicationInfo.applicationVersion = 1;
  info.applicationInfo.engineVersion = 1;
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);  // (XR_CURRENT_API_VERSION would ask for the header's patch)
  info.enabledExtensionCount = std::uint32_t(names.size());
  info.enabledExtensionNames = names.data();
  check(XR_NULL_HANDLE, xrCreateInstance(&info, &instance_), "xrCreateInstance");

  try {
    XrInstanceProperties props{XR_TYPE_INSTANCE_PROPERTIES};
    check(instance_, xrGetInstanceProperties(instance_, &props), "xrGetInstanceProperties");
    runtime_name_ = props.runtimeName;
    XrSystemGetInfo system_info{XR_TYPE_SYSTEM_GET_INFO};
    system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    const XrResult r = xrGetSystem(instance_, &system_info, &system_);
    if (r == XR_ERROR_FORM_FACTOR_UNAVAILABLE)
      throw XrError("the OpenXR runtime '" + runtime_name_ + "' has no headset connected (xrGetSystem: " +
                        result_name(instance_, r) + ")",
                    r);
    check(instance_, r, "xrGetSystem");
    XrSystemProperties sys{XR_TYPE_SYSTEM_PROPERTIES};
    check(instance_, xrGetSystemProperties(instance_, system_, &sys), "xrGetSystemProperties");
    system_name_ = sys.systemName;
    if (enabled(XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME))
      convert_timespec_ = function("xrConvertTimespecTimeToTimeKHR");
  } catch (...) {
    xrDestroyInstance(instance_);
    throw;
  }
}

Instance::~Instance() {
  if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
}

bool Instance::enabled(const char* extension) const {
  return std::find(enabled_.begin(), enabled_.end(), extension) != enabled_.end();
}

PFN_xrVoidFunction Instance::function(const char* name) const {
  PFN_xrVoidFunction f = nullptr;
  check(instance_, xrGetInstanceProcAddr(instance_, name, &f), (std::string("xrGetInstanceProcAddr(") + name + ")").c_str());
  if (!f) throw XrError(std::string("xrGetInstanceProcAddr(") + name + "): no function", XR_ERROR_FUNCTION_UNSUPPORTED);
  return f;
}

XrTime Instance::now() const {
  if (!convert_timespec_) return 0;
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  XrTime t = 0;
  check(instance_, reinterpret_cast<PFN_xrConvertTimespecTimeToTimeKHR>(convert_timespec_)(instance_, &ts, &t),
        "xrConvertTimespecTimeToTimeKHR");
  return t;
}

XrPath Instance::path(const std::string& text) const {
  XrPath p = XR_NULL_PATH;
  check(instance_, xrStringToPath(instance_, text.c_str(), &p), ("xrStringToPath(" + text + ")").c_str());
  return p;
}

std::string Instance::path_string(XrPath p) const {
  if (p == XR_NULL_PATH) return "(none)";
  char text[XR_MAX_PATH_LENGTH] = {};
  std::uint32_t n = 0;
  check(instance_, xrPathToString(instance_, p, XR_MAX_PATH_LENGTH, &n, text), "xrPathToString");
  return text;
}

}  // namespace wedge::xr
