// The handle registry (registry.hpp).
#include "registry.hpp"

#include <algorithm>

namespace wedge::xr_replay {

namespace {

template <class T, class H>
T* find_in(std::map<uint64_t, std::unique_ptr<T>>& map, H h) {
  const auto it = map.find(id_of(h));
  return it == map.end() ? nullptr : it->second.get();
}

template <class T>
T* add_to(std::map<uint64_t, std::unique_ptr<T>>& map, std::unique_ptr<T> o) {
  o->id = registry().next_id++;
  T* p = o.get();
  map.emplace(p->id, std::move(o));
  return p;
}

void erase_id(std::vector<uint64_t>& v, uint64_t id) { v.erase(std::remove(v.begin(), v.end(), id), v.end()); }

}  // namespace

Registry& registry() {
  static Registry r;
  return r;
}

std::mutex& api_mutex() {
  static std::mutex m;
  return m;
}

Instance* find(XrInstance h) { return find_in(registry().instances, h); }
Session* find(XrSession h) { return find_in(registry().sessions, h); }
Space* find(XrSpace h) { return find_in(registry().spaces, h); }
ActionSet* find(XrActionSet h) { return find_in(registry().action_sets, h); }
Action* find(XrAction h) { return find_in(registry().actions, h); }
Swapchain* find(XrSwapchain h) { return find_in(registry().swapchains, h); }

Instance* add(std::unique_ptr<Instance> o) { return add_to(registry().instances, std::move(o)); }
Session* add(std::unique_ptr<Session> o) {
  Session* s = add_to(registry().sessions, std::move(o));
  s->instance->sessions.push_back(s->id);
  return s;
}
Space* add(std::unique_ptr<Space> o) {
  Space* s = add_to(registry().spaces, std::move(o));
  s->session->spaces.push_back(s->id);
  return s;
}
ActionSet* add(std::unique_ptr<ActionSet> o) {
  ActionSet* s = add_to(registry().action_sets, std::move(o));
  s->instance->action_sets.push_back(s->id);
  return s;
}
Action* add(std::unique_ptr<Action> o) {
  Action* a = add_to(registry().actions, std::move(o));
  a->set->actions.push_back(a->id);
  return a;
}
Swapchain* add(std::unique_ptr<Swapchain> o) {
  Swapchain* s = add_to(registry().swapchains, std::move(o));
  s->session->swapchains.push_back(s->id);
  return s;
}

void destroy(Swapchain* o) {
  // The textures were made in the app's context; they can only be deleted while a context of the same API
  // is current (xrDestroySession without one leaves them to the context's own destruction).
  const GlFunctions& gl = o->session->gl;
  if (!o->textures.empty() && gl.context_current())
    gl.DeleteTextures(GLsizei(o->textures.size()), o->textures.data());
  erase_id(o->session->swapchains, o->id);
  registry().swapchains.erase(o->id);
}

void destroy(Space* o) {
  erase_id(o->session->spaces, o->id);
  registry().spaces.erase(o->id);
}

void destroy(Session* o) {
  for (uint64_t id : std::vector<uint64_t>(o->spaces)) destroy(registry().spaces.at(id).get());
  for (uint64_t id : std::vector<uint64_t>(o->swapchains)) destroy(registry().swapchains.at(id).get());
  o->instance->events.drop_session(handle_of<XrSession>(o->id));
  erase_id(o->instance->sessions, o->id);
  registry().sessions.erase(o->id);
}

void destroy(Action* o) {
  erase_id(o->set->actions, o->id);
  registry().actions.erase(o->id);
}

void destroy(ActionSet* o) {
  for (uint64_t id : std::vector<uint64_t>(o->actions)) destroy(registry().actions.at(id).get());
  erase_id(o->instance->action_sets, o->id);
  registry().action_sets.erase(o->id);
}

void destroy(Instance* o) {
  for (uint64_t id : std::vector<uint64_t>(o->sessions)) destroy(registry().sessions.at(id).get());
  for (uint64_t id : std::vector<uint64_t>(o->action_sets)) destroy(registry().action_sets.at(id).get());
  registry().instances.erase(o->id);
}

}  // namespace wedge::xr_replay
