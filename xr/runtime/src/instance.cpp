// Instances: the extensions offered, xrCreateInstance (settings and the recording are read here, once),
// instance properties, and XR_KHR_convert_timespec_time (clock.hpp has the map).
#include <filesystem>
#include <string_view>

#include "api.hpp"
#include "registry.hpp"
#include "validate.hpp"
#include "wedge/recordings/recording.hpp"

namespace wedge::xr_replay {

namespace {

struct Extension {
  const char* name;
  uint32_t version;
};
const Extension kExtensions[] = {
    {XR_KHR_OPENGL_ENABLE_EXTENSION_NAME, XR_KHR_opengl_enable_SPEC_VERSION},
    {XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME, XR_KHR_convert_timespec_time_SPEC_VERSION},
    {XR_MND_HEADLESS_EXTENSION_NAME, XR_MND_headless_SPEC_VERSION},
};

bool offered(std::string_view name) {
  for (const Extension& e : kExtensions)
    if (name == e.name) return true;
  return false;
}

// The settings and the recording, as xrCreateInstance takes them. Returns "" or the line to print.
std::string load(Instance& in) {
  std::string problem = read_config(in.config);
  if (!problem.empty()) return problem;
  if (!in.config.replay_path.empty()) {
    try {
      const recordings::Recording rec = recordings::read_recording(in.config.replay_path);
      for (const std::string& w : rec.warnings) report("WEDGE_XR_REPLAY: " + w);
      in.playback = Playback(rec, in.config.lose_tracking);
    } catch (const std::exception& e) {
      return std::string("WEDGE_XR_REPLAY: ") + e.what();  // wedge::Error's message starts with the path
    }
  }
  if (!in.config.frames_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(in.config.frames_dir, ec);
    if (ec || !std::filesystem::is_directory(in.config.frames_dir))
      return "WEDGE_XR_FRAMES=" + in.config.frames_dir + ": cannot create the folder";
  }
  in.haptics.set_path(in.config.haptics_log);
  return "";
}

XrResult create_instance(const XrInstanceCreateInfo* info, XrInstance* out) {
  if (!has_type(info, XR_TYPE_INSTANCE_CREATE_INFO) || out == nullptr || info->createFlags != 0)
    return XR_ERROR_VALIDATION_FAILURE;
  if (!is_nonempty_cstring(info->applicationInfo.applicationName)) return XR_ERROR_NAME_INVALID;
  const XrVersion v = info->applicationInfo.apiVersion;
  if (XR_VERSION_MAJOR(v) != 1 || XR_VERSION_MINOR(v) != 0) return XR_ERROR_API_VERSION_UNSUPPORTED;
  if (info->enabledExtensionCount > 0 && info->enabledExtensionNames == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  auto in = std::make_unique<Instance>();
  for (uint32_t i = 0; i < info->enabledExtensionCount; ++i) {
    const char* name = info->enabledExtensionNames[i];
    if (name == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (!offered(name)) return XR_ERROR_EXTENSION_NOT_PRESENT;
    const std::string_view n(name);
    in->opengl_enabled = in->opengl_enabled || n == XR_KHR_OPENGL_ENABLE_EXTENSION_NAME;
    in->timespec_enabled = in->timespec_enabled || n == XR_KHR_CONVERT_TIMESPEC_TIME_EXTENSION_NAME;
    in->headless_enabled = in->headless_enabled || n == XR_MND_HEADLESS_EXTENSION_NAME;
  }
  // API layers named here were the loader's business; the runtime has none of its own.
  const std::string problem = load(*in);
  if (!problem.empty()) {
    report(problem);
    return XR_ERROR_RUNTIME_FAILURE;
  }
  in->timespec = TimespecMap::now();  // "now" is kEpoch on the timespec clock
  *out = handle_of<XrInstance>(add(std::move(in))->id);
  return XR_SUCCESS;
}

}  // namespace

XrResult xrEnumerateApiLayerProperties(uint32_t capacity, uint32_t* count, XrApiLayerProperties* properties) {
  return guarded("xrEnumerateApiLayerProperties", [&] {
    return two_call_structs(capacity, count, properties, 0, XR_TYPE_API_LAYER_PROPERTIES,
                            [](uint32_t, XrApiLayerProperties&) {});
  });
}

XrResult xrEnumerateInstanceExtensionProperties(const char* layerName, uint32_t capacity, uint32_t* count,
                                                XrExtensionProperties* properties) {
  return guarded("xrEnumerateInstanceExtensionProperties", [&]() -> XrResult {
    if (layerName != nullptr) return XR_ERROR_API_LAYER_NOT_PRESENT;
    const uint32_t n = uint32_t(sizeof(kExtensions) / sizeof(kExtensions[0]));
    return two_call_structs(capacity, count, properties, n, XR_TYPE_EXTENSION_PROPERTIES,
                            [](uint32_t i, XrExtensionProperties& p) {
                              copy_string(p.extensionName, kExtensions[i].name);
                              p.extensionVersion = kExtensions[i].version;
                            });
  });
}

XrResult xrCreateInstance(const XrInstanceCreateInfo* createInfo, XrInstance* instance) {
  return guarded("xrCreateInstance", [&] { return create_instance(createInfo, instance); });
}

XrResult xrDestroyInstance(XrInstance instance) {
  return guarded("xrDestroyInstance", [&]() -> XrResult {
    Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    destroy(in);
    return XR_SUCCESS;
  });
}

XrResult xrGetInstanceProperties(XrInstance instance, XrInstanceProperties* properties) {
  return guarded("xrGetInstanceProperties", [&]() -> XrResult {
    if (find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (!has_type(properties, XR_TYPE_INSTANCE_PROPERTIES)) return XR_ERROR_VALIDATION_FAILURE;
    properties->runtimeVersion = XR_MAKE_VERSION(WEDGE_XR_RUNTIME_VERSION_MAJOR, WEDGE_XR_RUNTIME_VERSION_MINOR,
                                                 WEDGE_XR_RUNTIME_VERSION_PATCH);
    copy_string(properties->runtimeName, "Wedge replay runtime");
    return XR_SUCCESS;
  });
}

XrResult xrConvertTimespecTimeToTimeKHR(XrInstance instance, const struct timespec* timespecTime, XrTime* time) {
  return guarded("xrConvertTimespecTimeToTimeKHR", [&]() -> XrResult {
    const Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (timespecTime == nullptr || time == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const XrTime t = in->timespec.to_xr(*timespecTime);
    if (t <= 0) return XR_ERROR_TIME_INVALID;  // more than kEpoch before the instance was created
    *time = t;
    return XR_SUCCESS;
  });
}

XrResult xrConvertTimeToTimespecTimeKHR(XrInstance instance, XrTime time, struct timespec* timespecTime) {
  return guarded("xrConvertTimeToTimespecTimeKHR", [&]() -> XrResult {
    const Instance* in = find(instance);
    if (in == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (timespecTime == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    if (time <= 0) return XR_ERROR_TIME_INVALID;
    *timespecTime = in->timespec.to_timespec(time);
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay
