#include "wedge/xr/check.hpp"

#include <openxr/openxr_reflection.h>

namespace wedge::xr {

namespace {
const char* header_name(XrResult result) {
  switch (result) {
#define WEDGE_XR_RESULT_CASE(name, value) \
  case name:                              \
    return #name;
    XR_LIST_ENUM_XrResult(WEDGE_XR_RESULT_CASE)
#undef WEDGE_XR_RESULT_CASE
    default:
      return nullptr;
  }
}
}  // namespace

std::string result_name(XrInstance instance, XrResult result) {
  if (instance != XR_NULL_HANDLE) {
    char text[XR_MAX_RESULT_STRING_SIZE] = {};
    if (XR_SUCCEEDED(xrResultToString(instance, result, text)) && text[0] != '\0') return text;
  }
  if (const char* name = header_name(result)) return name;
  return "XrResult(" + std::to_string(int(result)) + ")";
}

XrResult check(XrInstance instance, XrResult result, const char* call) {
  if (XR_FAILED(result)) throw XrError(std::string(call) + ": " + result_name(instance, result), result);
  return result;
}

}  // namespace wedge::xr
