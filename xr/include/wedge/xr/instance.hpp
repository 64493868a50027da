// The OpenXR instance and the headset system: the first thing `wedge xr` makes, through the standard
// loader (Debian's libopenxr-loader1), whatever runtime is active (SteamVR, Monado, Wedge's own replay
// runtime, ...). Extensions: XR_KHR_opengl_enable to render (required unless headless), XR_MND_headless
// for a session without frames (required with --headless), XR_KHR_convert_timespec_time for the runtime's
// clock (used when the runtime's frame times cannot be: see clock.hpp).
#pragma once

#include <openxr/openxr.h>

#include <string>
#include <vector>

namespace wedge::xr {

struct InstanceOptions {
  bool headless = false;                 // input, physics and haptics without frames (XR_MND_headless)
  std::string application = "wedge xr";  // the name the runtime shows
};

class Instance {
 public:
  // Throws XrError: with no runtime installed, one line naming XR_RUNTIME_JSON and the active-runtime
  // files the loader looked for; with an extension missing, the extension; with no headset, that.
  explicit Instance(const InstanceOptions& options);
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;

  XrInstance handle() const { return instance_; }
  XrSystemId system() const { return system_; }
  bool headless() const { return headless_; }
  bool enabled(const char* extension) const;
  const std::string& runtime_name() const { return runtime_name_; }
  const std::string& system_name() const { return system_name_; }

  // The runtime's time now (XR_KHR_convert_timespec_time of CLOCK_MONOTONIC), or 0 without the extension.
  XrTime now() const;

  // An extension function, by name (throws XrError if the runtime has none).
  PFN_xrVoidFunction function(const char* name) const;

  // The path <-> string maps.
  XrPath path(const std::string& text) const;
  std::string path_string(XrPath path) const;

 private:
  XrInstance instance_ = XR_NULL_HANDLE;
  XrSystemId system_ = XR_NULL_SYSTEM_ID;
  bool headless_ = false;
  std::vector<std::string> enabled_;
  std::string runtime_name_, system_name_;
  PFN_xrVoidFunction convert_timespec_ = nullptr;
};

// The loader's places for the active runtime, as a sentence for messages: XR_RUNTIME_JSON (with its value
// when set) and the active_runtime.json files under XDG_CONFIG_HOME, XDG_CONFIG_DIRS and /etc.
std::string runtime_search_text();

}  // namespace wedge::xr
