// Shared by the replay runtime's tests: they load the runtime through the real OpenXR loader (XR_RUNTIME_JSON
// points at the built manifest), as any app would, and check what it answers against what the test wrote.
// Nothing here knows the runtime's internals; its documented constants are restated (docs/xr-runtime.md).
#pragma once

#include <catch2/catch.hpp>

#include <openxr/openxr.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "wedge/recordings/recording.hpp"

namespace xrtest {

// An OpenXR struct of type `type`, every other member zero (the spec's XrFoo x{XR_TYPE_FOO}, spelled so that
// -Wmissing-field-initializers has nothing to say).
template <class T>
T xr_struct(XrStructureType type) {
  T t{};
  t.type = type;
  return t;
}

// The runtime's documented clock: XrTime kEpoch is recording time 0, frame n is at kEpoch + round(n * 1e9 / 90).
inline constexpr XrTime kEpoch = 1'000'000'000;
XrTime frame_time(uint64_t n);         // computed in double, independently of the runtime's integer form
XrTime sample_time(double t_seconds);  // kEpoch + llround(t * 1e9)

// The test's environment: every WEDGE_XR_* variable cleared, then the given ones set.
void runtime_env(std::initializer_list<std::pair<const char*, std::string>> vars = {});
// A file name unique to this process under the test's binary folder.
std::string temp_path(const std::string& name);

// Recordings written by the tests.
wedge::recordings::HandSample hand(double t, wedge::recordings::Hand which, Eigen::Vector3d position,
                                   Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity(), double squeeze = 0.0,
                                   double trigger = 0.0, uint32_t buttons = 0, bool mode4d = false);
std::string write_test_recording(const std::string& name, const wedge::recordings::Recording& r);

// An instance through the loader (destroyed at scope exit), with the runtime's extensions as asked.
class Instance {
 public:
  explicit Instance(std::vector<const char*> extensions = {"XR_MND_headless"});
  ~Instance();
  Instance(const Instance&) = delete;
  Instance& operator=(const Instance&) = delete;
  XrInstance get() const { return handle_; }
  XrSystemId system() const;
  XrPath path(const char* s) const;
  std::string path_string(XrPath p) const;
  // Every event queued so far, in order.
  std::vector<XrEventDataBuffer> poll_events() const;
  template <class F>
  F proc(const char* name) const {
    PFN_xrVoidFunction f = nullptr;
    REQUIRE(xrGetInstanceProcAddr(handle_, name, &f) == XR_SUCCESS);
    return reinterpret_cast<F>(f);
  }

 private:
  XrInstance handle_ = XR_NULL_HANDLE;
};

// A headless session (XR_MND_headless), created and, with begin = true, begun (so FOCUSED).
class HeadlessSession {
 public:
  explicit HeadlessSession(const Instance& instance, bool begin = true);
  ~HeadlessSession();
  HeadlessSession(const HeadlessSession&) = delete;
  HeadlessSession& operator=(const HeadlessSession&) = delete;
  XrSession get() const { return handle_; }
  XrFrameState wait_frame() const;  // REQUIREs success
  XrSpace reference_space(XrReferenceSpaceType type) const;

 private:
  XrSession handle_ = XR_NULL_HANDLE;
};

// The session states in the events, in order.
std::vector<XrSessionState> states_of(const std::vector<XrEventDataBuffer>& events);

// The grip / aim poses of a Touch pair as an app sets them up: one action set "hands" with the Touch
// bindings suggested for pose, squeeze (float), trigger (float), A/X click (boolean), B/Y click (boolean),
// menu (boolean), squeeze-as-boolean, thumbstick (vector2f) and haptics, subaction paths left and right.
struct TouchActions {
  XrActionSet set = XR_NULL_HANDLE;
  XrAction grip = XR_NULL_HANDLE, aim = XR_NULL_HANDLE, squeeze = XR_NULL_HANDLE, trigger = XR_NULL_HANDLE,
           primary = XR_NULL_HANDLE, secondary = XR_NULL_HANDLE, squeeze_click = XR_NULL_HANDLE,
           thumbstick = XR_NULL_HANDLE, haptic = XR_NULL_HANDLE;
  XrPath left = XR_NULL_PATH, right = XR_NULL_PATH;
};
XrAction make_action(XrActionSet set, const char* name, XrActionType type, const std::vector<XrPath>& subactions);
TouchActions make_touch_actions(const Instance& instance);  // created and suggested, not attached
void attach(XrSession session, XrActionSet set);
XrResult sync(XrSession session, XrActionSet set, XrPath subaction = XR_NULL_PATH);
XrSpace action_space(XrSession session, XrAction action, XrPath subaction);

// Located pose of `space` in `base` at `time`.
XrSpaceLocation locate(XrSpace space, XrSpace base, XrTime time);

constexpr XrSpaceLocationFlags kTracked = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
                                          XR_SPACE_LOCATION_POSITION_TRACKED_BIT |
                                          XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;

const char* result_name(XrResult r);

}  // namespace xrtest

namespace Catch {
template <>
struct StringMaker<XrResult> {
  static std::string convert(XrResult r) { return xrtest::result_name(r); }
};
}  // namespace Catch
