// The viewer's panel (`wedge view`): a Dear ImGui window at the left edge with play, pause,
// single step, reset, time scale, the slice offsets (w in 4D; two or three in 5D and 6D), the bodies and
// whether the slice meets them (a click moves the slice through one), contacts on or off, the frame time
// split, the phone and the pulse log; and the name of the body under the cursor beside it. The panel
// only sets Controls and asks (PanelRequests); Viewer::advance (view.cpp) carries the requests out.
#pragma once

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <optional>
#include <string>
#include <vector>

#include "view_mouse.hpp"
#include "view_platform.hpp"
#include "view_slice.hpp"

namespace wedge::cli::viewer {

// What the panel's user sets, read by the other stages.
struct Controls {
  bool playing = true;
  float time_scale = 1.0f;
  std::vector<float> w;  // the slice offsets as the sliders hold them; the slice takes them when moved
  bool show_contacts = false;
  bool show_joints = true;
};

// What the user asked for in one frame (the panel, or the script's slice fields), done after the frame
// is drawn.
struct PanelRequests {
  bool single = false;         // one step, playing or not
  bool reset = false;          // back to the scene's start
  bool moved = false;          // the slice offsets changed
  bool fit = false;            // refit the camera to what the scene does next
  std::optional<BodyId> find;  // a body clicked in the list (4D and up): move the slice through it
};

// A new ImGui frame and the panel's window, fb_height px high (framebuffer px).
inline void begin_panel(int fb_height) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(fb_height) - 16), ImGuiCond_Always);
  ImGui::Begin("Wedge", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
}

// The scene and its clock: play or pause, one step, reset, the camera refitted, the time scale.
template <int N>
void panel_clock(const std::string& file, const World<N>& world, Controls& controls, PanelRequests& asked) {
  ImGui::TextWrapped("%s (%dD)", file.c_str(), N);
  ImGui::Text("t = %.3f s, step %lld", world.time(), (long long)world.step_count());
  if (ImGui::Button(controls.playing ? "Pause" : "Play")) controls.playing = !controls.playing;
  ImGui::SameLine();
  asked.single = ImGui::Button("Step");
  ImGui::SameLine();
  asked.reset = ImGui::Button("Reset");
  ImGui::SameLine();
  asked.fit = ImGui::Button("Fit camera");
  ImGui::SliderFloat("time scale", &controls.time_scale, 0.05f, 4.0f, "%.2fx", ImGuiSliderFlags_Logarithmic);
}

// The slice offsets' sliders, +-reach m; whether one moved.
template <int N>
bool panel_slice_offsets(std::vector<float>& w, double reach) {
  bool moved = false;
  for (std::size_t i = 0; i < w.size(); ++i) {  // offsets: x_{n-1} first, then x_{n-2} within it
    const int axis = N - 1 - int(i);
    static const char* const kLabels[] = {"x3", "x4", "x5"};
    moved |= ImGui::SliderFloat(N == 4 ? "w" : kLabels[axis - 3], &w[i], float(-reach), float(reach), "%.3f m");
  }
  return moved;
}

// The joint and contact marks' switches and the bodies, each marked when the slice misses it or the cursor
// is over it; a body clicked (4D and up: a 3D scene has no slice to move) is returned.
template <int N>
std::optional<BodyId> panel_bodies(const World<N>& world, const SliceView<N>& view, const std::string& hovered,
                                   Controls& controls) {
  if (world.joint_count() > 0) {
    ImGui::Checkbox("joints (J)", &controls.show_joints);
    ImGui::SameLine();
  }
  ImGui::Checkbox("contacts (C)", &controls.show_contacts);
  ImGui::Text("%d of %d bodies in the slice", view.in_slice_count(), int(view.body_count()));
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("(click a body to move the slice through its centre)");
  ImGui::PopStyleColor();
  std::optional<BodyId> clicked;
  for (std::size_t k = 0; k < view.body_count(); ++k) {
    const BodyId id = view.body(k);
    std::string label = world.name(id);
    if (!view.in_slice(k)) label += "  (out of the slice)";
    label += "##" + std::to_string(k);
    if (ImGui::Selectable(label.c_str(), world.name(id) == hovered) && N > 3) clicked = id;
  }
  return clicked;
}

// The frame time split, the tessellation of round shapes now drawn, and how the mouse works.
inline void panel_frame_times(const FrameTimes& times, int subdivisions, bool playing_level) {
  ImGui::Text("physics %.2f ms", 1e3 * times.physics);
  ImGui::Text("slicing %.2f ms", 1e3 * times.slicing);
  ImGui::Text("drawing %.2f ms", 1e3 * times.drawing);
  ImGui::Text("round shapes: %d subdivisions%s", subdivisions, playing_level ? " (playing)" : "");
  ImGui::TextWrapped("Left drag on a body: grab and move it (wheel: depth; right drag: turn it, with Shift into "
                     "w). Release throws. Right drag: orbit. Middle drag: pan. Wheel: zoom. F: refit the camera.");
}

// The phone: tilts gravity through the input layer, as an accelerometer would.
template <int N>
void panel_phone(Phone& phone, const World<N>& world) {
  ImGui::Separator();
  ImGui::Text("phone (tilts gravity; arrow keys too)");
  phone.active |= ImGui::SliderFloat("roll", &phone.roll, -90.0f, 90.0f, "%.0f deg");
  phone.active |= ImGui::SliderFloat("pitch", &phone.pitch, -90.0f, 90.0f, "%.0f deg");
  if (N >= 4) phone.active |= ImGui::Checkbox("tilt toward w", &phone.tilt_w);
  const Vec<N> g = world.gravity();
  ImGui::Text("gravity |g| %.2f m/s^2, %s", g.norm(), phone.active ? "from the phone" : "the scene's");
}

// The last eight haptic pulses.
inline void panel_pulses(const std::vector<std::string>& log) {
  ImGui::Separator();
  ImGui::Text("haptic pulses (a mouse cannot feel them):");
  for (std::size_t i = log.size() > 8 ? log.size() - 8 : 0; i < log.size(); ++i)
    ImGui::TextWrapped("%s", log[i].c_str());
}

// `name` on a dark box beside the cursor (window px; the framebuffer's may differ: scale sx, sy).
inline void hover_label(const std::string& name, const MouseState& mouse, float sx, float sy) {
  const ImVec2 at(float(mouse.x) * sx + 14.0f, float(mouse.y) * sy + 10.0f);
  const ImVec2 size = ImGui::CalcTextSize(name.c_str());
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  dl->AddRectFilled(ImVec2(at.x - 4, at.y - 2), ImVec2(at.x + size.x + 4, at.y + size.y + 2), IM_COL32(20, 20, 30, 220), 3.0f);
  dl->AddText(at, IM_COL32(255, 255, 255, 255), name.c_str());
}

// The ImGui frame drawn over the 3D view.
inline void end_panel() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace wedge::cli::viewer
