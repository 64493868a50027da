// xrResultToString and xrStructureTypeToString, from openxr_reflection.h's enum lists; values it does not
// know are spelled as the spec says (XR_UNKNOWN_SUCCESS_n, XR_UNKNOWN_FAILURE_n, XR_UNKNOWN_STRUCTURE_TYPE_n).
#include <openxr/openxr_reflection.h>

#include <string>

#include "api.hpp"
#include "registry.hpp"
#include "validate.hpp"

namespace wedge::xr_replay {

namespace {

#define WEDGE_XR_ENUM_CASE(name, value) \
  case name:                            \
    return #name;

const char* result_name(XrResult r) {
  switch (r) {
    XR_LIST_ENUM_XrResult(WEDGE_XR_ENUM_CASE) default : return nullptr;
  }
}

const char* structure_type_name(XrStructureType t) {
  switch (t) {
    XR_LIST_ENUM_XrStructureType(WEDGE_XR_ENUM_CASE) default : return nullptr;
  }
}

#undef WEDGE_XR_ENUM_CASE

}  // namespace

XrResult xrResultToString(XrInstance instance, XrResult value, char buffer[XR_MAX_RESULT_STRING_SIZE]) {
  return guarded("xrResultToString", [&]() -> XrResult {
    if (find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const char* name = result_name(value);
    const std::string s = name != nullptr ? std::string(name)
                                          : (value >= 0 ? "XR_UNKNOWN_SUCCESS_" : "XR_UNKNOWN_FAILURE_") +
                                                std::to_string(int(value));
    copy_string(buffer, XR_MAX_RESULT_STRING_SIZE, s);
    return XR_SUCCESS;
  });
}

XrResult xrStructureTypeToString(XrInstance instance, XrStructureType value, char buffer[XR_MAX_STRUCTURE_NAME_SIZE]) {
  return guarded("xrStructureTypeToString", [&]() -> XrResult {
    if (find(instance) == nullptr) return XR_ERROR_HANDLE_INVALID;
    if (buffer == nullptr) return XR_ERROR_VALIDATION_FAILURE;
    const char* name = structure_type_name(value);
    const std::string s = name != nullptr ? std::string(name) : "XR_UNKNOWN_STRUCTURE_TYPE_" + std::to_string(int(value));
    copy_string(buffer, XR_MAX_STRUCTURE_NAME_SIZE, s);
    return XR_SUCCESS;
  });
}

}  // namespace wedge::xr_replay
