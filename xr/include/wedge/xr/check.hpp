// OpenXR results as errors a person can read: every call's XrResult is checked, and a failure names the
// call and the result (xrResultToString's name, e.g. "xrCreateSession: XR_ERROR_GRAPHICS_DEVICE_INVALID").
#pragma once

#include <openxr/openxr.h>

#include <stdexcept>
#include <string>

namespace wedge::xr {

class XrError : public std::runtime_error {
 public:
  XrError(const std::string& what, XrResult result) : std::runtime_error(what), result_(result) {}
  XrResult result() const { return result_; }

 private:
  XrResult result_;
};

// The result's name: from the runtime (xrResultToString) when there is an instance, else from the
// headers' own list; "XrResult(-123)" for a code neither knows.
std::string result_name(XrInstance instance, XrResult result);

// Throws XrError "CALL: NAME" when the result is a failure; returns the result (successes such as
// XR_SESSION_LOSS_PENDING or XR_FRAME_DISCARDED are the caller's to look at).
XrResult check(XrInstance instance, XrResult result, const char* call);

}  // namespace wedge::xr
