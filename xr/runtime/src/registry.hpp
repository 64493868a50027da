// Handles <-> objects. Every object gets an id from one counter that never goes back, and its handle is
// that id; lookups check the kind, so a destroyed handle, another kind's handle or a made-up value are all
// XR_ERROR_HANDLE_INVALID. One mutex guards everything: each entry point runs under it (guarded()), so apps
// may call from any thread and the runtime's state only changes in call order.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <new>
#include <string>

#include "objects.hpp"

namespace wedge::xr_replay {

struct Registry {
  uint64_t next_id = 0x100;  // handle values start above small integers an app might pass by mistake
  std::map<uint64_t, std::unique_ptr<Instance>> instances;
  std::map<uint64_t, std::unique_ptr<Session>> sessions;
  std::map<uint64_t, std::unique_ptr<Space>> spaces;
  std::map<uint64_t, std::unique_ptr<ActionSet>> action_sets;
  std::map<uint64_t, std::unique_ptr<Action>> actions;
  std::map<uint64_t, std::unique_ptr<Swapchain>> swapchains;
};

Registry& registry();

template <class H>
uint64_t id_of(H handle) {
  return reinterpret_cast<uint64_t>(handle);
}
template <class H>
H handle_of(uint64_t id) {
  return reinterpret_cast<H>(id);
}

// Null when the handle is not a live object of that kind.
Instance* find(XrInstance h);
Session* find(XrSession h);
Space* find(XrSpace h);
ActionSet* find(XrActionSet h);
Action* find(XrAction h);
Swapchain* find(XrSwapchain h);

// Adds an object, giving it its id. Returns the object.
Instance* add(std::unique_ptr<Instance> o);
Session* add(std::unique_ptr<Session> o);
Space* add(std::unique_ptr<Space> o);
ActionSet* add(std::unique_ptr<ActionSet> o);
Action* add(std::unique_ptr<Action> o);
Swapchain* add(std::unique_ptr<Swapchain> o);

// Destroys an object and everything it owns (instance: sessions and action sets; session: spaces and
// swapchains; action set: actions).
void destroy(Instance* o);
void destroy(Session* o);
void destroy(Space* o);
void destroy(ActionSet* o);
void destroy(Action* o);
void destroy(Swapchain* o);

std::mutex& api_mutex();

// Runs an entry point's body under the runtime's lock; no exception crosses into the app.
template <class F>
XrResult guarded(const char* name, F&& body) noexcept {
  try {
    std::lock_guard<std::mutex> lock(api_mutex());
    return body();
  } catch (const std::bad_alloc&) {
    return XR_ERROR_OUT_OF_MEMORY;
  } catch (const std::exception& e) {
    report(std::string(name) + ": " + e.what());
    return XR_ERROR_RUNTIME_FAILURE;
  }
}

}  // namespace wedge::xr_replay
