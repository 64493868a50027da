// wedge view SCENE.json [--w W] [--size WxH] [--subdivisions S] [--play-subdivisions S]
//                        [--replay RECORDING... | --record FILE] [--mouse FILE] [--events FILE] [--contacts]
//                        [--no-joints] [--hash] [--frames N --screenshot FILE.png]
//
// The desktop viewer: a window (GLFW, OpenGL 3.3 core) drawing the scene's 3D slice with the same renderer
// as `wedge render`, and a Dear ImGui panel: play, pause, single step, reset, time scale, the slice
// offsets (w in 4D; two or three in 5D and 6D), the bodies and whether the slice meets them (a click
// moves the slice through one), joints and contacts on or off, the phone, the pulse log, and the frame time split
// into physics, slicing and drawing. The camera orbits (right drag), pans (middle drag) and zooms
// (wheel); the 3D view fills the window right of the panel. The mouse is a hand of the input layer
// (grab, drag, turn, throw); --replay drives the scene with recordings instead, as `wedge replay` does.
// Hands, haptic flashes, joints and contact points are drawn over the bodies (view_overlays.hpp). Without a
// display: --frames N draws N frames (each 1/60 s of simulated time while playing) and --screenshot
// writes the last one as PNG, for tests and pictures; with no display at all the viewer exits with code
// 2, naming DISPLAY.
//
// Each frame draws the current state, then advances it, so frame 1 shows step 0: right of the panel, the
// picture `wedge render --steps 0 --size (W-316)xH` draws.
//
// The viewer is four stages, tied together by Viewer below, whose frame loop reads
//   poll_input -> draw_scene -> draw_panel -> (the screenshot, on the last frame) -> advance:
//   - platform and mouse (view_platform.hpp, view_mouse.hpp): the window, GLFW's mouse and keys or the
//     --mouse script, the orbit camera, the mouse hand, the phone; poll_input;
//   - slice (view_slice.hpp): the slice meshes, the markers over them, the renderer's frame; draw_scene;
//   - panel (view_panel.hpp): the ImGui panel, which sets Controls and asks for steps, resets and slice
//     moves (PanelRequests); draw_panel;
//   - session (view_session.hpp): the world stepped through input::Session by the recordings or by the
//     mouse hand and the phone, the clock's accumulator, --record, --events and the pulse log, reset;
//     advance carries out what the panel asked, then takes the steps the clock owes.
#include <CLI/CLI.hpp>
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "fp_traps.hpp"
#include "interrupt.hpp"
#include "verbs.hpp"
#include "view_mouse.hpp"
#include "view_panel.hpp"
#include "view_platform.hpp"
#include "view_session.hpp"
#include "view_slice.hpp"
#include "wedge/render/renderer.hpp"

namespace wedge::cli {

namespace {

using namespace viewer;

// The viewer of one N-dimensional scene (N >= 3). Its members are built in the order they are declared:
// everything that can refuse the scene, the recordings or the --mouse script comes before the window.
template <int N>
class Viewer {
 public:
  Viewer(const Json& doc, const ViewOptions& o, const std::vector<double>& w0, int width, int height,
         std::int64_t frames, int subdivisions, int play_subdivisions)
      : o_(o),
        file_(o.scene),
        width_(width),
        height_(height),
        frames_(frames),
        subdivisions_(subdivisions),
        play_subdivisions_(play_subdivisions),
        scene_(load_scene<N>(doc, file_)),
        session_(scene_, file_, o.replay, o.record),
        view_(scene_, session_.world(), w0, subdivisions, play_subdivisions, file_, width, height),
        input_(checked_script()),
        window_(file_, width, height),
        gui_(window_.get()),
        orbit_{view_.fitted().camera},
        controls_{true, 1.0f, std::vector<float>(view_.offsets().begin(), view_.offsets().end()), o.contacts, !o.no_joints} {
    input_.start(window_.get());
    session_.start(view_.slices(), o.events);
  }

  // The frame loop, until the window closes or --frames N are drawn. Each frame draws the current state,
  // then advances it; the last of --frames N is drawn at the fine level, written as the screenshot, and
  // not advanced.
  int run() {
    for (std::int64_t frame = 1; !glfwWindowShouldClose(window_.get()); ++frame) {
      throw_if_interrupted();
      glfwPollEvents();
      // While playing, round shapes are drawn at the coarse level; paused, and in a screenshot, at the fine one.
      const bool last_frame = frames_ > 0 && frame == frames_;
      const slicing::Detail detail =
          controls_.playing && !last_frame ? slicing::Detail::Coarse : slicing::Detail::Fine;
      poll_input(frame, detail);
      draw_scene(detail);
      const PanelRequests asked = draw_panel(detail);
      if (last_frame) {
        if (!o_.screenshot.empty()) write_screenshot(o_.screenshot, fb_width_, fb_height_);
        break;
      }
      glfwSwapBuffers(window_.get());
      advance(asked);
    }
    return finish();
  }

 private:
  // A --mouse script, checked against the scene before any window opens.
  MouseScript checked_script() const {
    if (o_.mouse.empty()) return {};
    MouseScript script = read_mouse_script(o_.mouse);
    check_mouse_script<N>(script, o_.mouse, file_,
                          [&](const std::string& name) { return view_.body_named(session_.world(), name); });
    return script;
  }

  // ---- Platform and mouse -------------------------------------------------------------------------

  // This frame's mouse and keys (GLFW's, or the script's when there is one), carried out: the script's
  // slice offsets, body to find, camera fit and phone tilt; C toggles the contact marks, J the joint
  // marks, F refits the camera, the arrow keys tilt the phone; the mouse moves the hand (when it drives
  // the world) and, while the hand holds nothing, the camera: right drag orbits, middle drag pans, the
  // wheel zooms.
  void poll_input(std::int64_t frame, slicing::Detail detail) {
    mouse_ = input_.read(window_.get(), frame);
    slice_request_ = false;  // the script moved a slider or asked for a body
    if (mouse_.w) {          // (sizes and names were checked with the script)
      for (std::size_t i = 0; i < controls_.w.size(); ++i)
        controls_.w[i] = i < mouse_.w->size() ? float((*mouse_.w)[i]) : 0.0f;
      slice_request_ = true;
    }
    if (mouse_.find) {
      find_body(*view_.body_named(session_.world(), *mouse_.find));
      slice_request_ = true;
    }
    phone_.take(mouse_, N >= 4);
    if (input_.contacts_key(window_.get())) controls_.show_contacts = !controls_.show_contacts;
    if (input_.joints_key(window_.get())) controls_.show_joints = !controls_.show_joints;
    fit_request_ = mouse_.fit || input_.fit_key(window_.get());
    input_.tilt_keys(window_.get(), phone_);
    const double dx = input_.dx(mouse_), dy = input_.dy(mouse_);
    if (session_.mouse_driven()) move_hand(dx, dy, detail);
    if (!hand_.holding) orbit_.follow(mouse_, dx, dy, height_);
    input_.end_frame(mouse_);
  }

  // The mouse on the hand: a left press grabs the body under the cursor (picked on the current state,
  // cut at this frame's detail), a left drag moves (and with the right button turns) what it holds,
  // letting go throws; Shift turns into w (the input layer's 4D mode).
  void move_hand(double dx, double dy, slicing::Detail detail) {
    const Ray ray = cursor_ray(orbit_.camera, mouse_.x, mouse_.y, kViewLeft, width_ - kViewLeft, height_);
    if (input_.pressed(mouse_)) {  // press: grab what is under the cursor
      view_.slice(session_.world(), detail);
      hand_.press(view_.pick(ray), orbit_.camera);
    } else if (mouse_.left && hand_.holding) {  // drag in the plane facing the camera; the wheel: depth
      hand_.drag(mouse_, ray, dx, dy, orbit_.camera);
    } else if (!mouse_.left) {
      hand_.holding = false;
    }
    hand_.mode4d = mouse_.shift;
  }

  // Moves the slice through body `id`'s centre (the panel's list, or a script's "find").
  void find_body(BodyId id) {  // (and turns the camera to it: the orbit's target moves to its centre)
    const World<N>& world = session_.world();
    for (std::size_t i = 0; i < controls_.w.size(); ++i) controls_.w[i] = float(world.body(id).center[N - 1 - int(i)]);
    const Eigen::Vector3d to = view_.slices().to_slice_point(world.body(id).center) - orbit_.camera.target;
    orbit_.camera.target += to;
    orbit_.camera.eye += to;
  }

  // ---- Slice and draw -----------------------------------------------------------------------------

  // The current state cut at `detail` (timed: the panel's "slicing") and drawn right of the panel by the
  // orbit camera, the markers over the bodies; the body under the cursor found for the panel.
  void draw_scene(slicing::Detail detail) {
    glfwGetFramebufferSize(window_.get(), &fb_width_, &fb_height_);
    const auto t0 = std::chrono::steady_clock::now();
    view_.slice(session_.world(), detail);
    slicing_time_ = seconds_since(t0);
    drawing_start_ = std::chrono::steady_clock::now();
    render::FrameDesc desc = view_.frame(scene_, orbit_.camera);
    view_.add_markers(desc, session_.world(), session_.recorded_hands(), hand_, session_.pulses(),
                      controls_.show_joints, controls_.show_contacts);
    find_hovered();
    view_.draw(renderer_, desc, width_, fb_width_, fb_height_);
  }

  // The body under the cursor (not while holding one), named beside it and marked in the panel's list.
  void find_hovered() {
    hovered_.clear();
    if (!hand_.holding && !mouse_.left && !mouse_.right && !mouse_.middle && mouse_.x >= kViewLeft &&
        (input_.scripted() || !ImGui::GetIO().WantCaptureMouse)) {
      const Ray ray = cursor_ray(orbit_.camera, mouse_.x, mouse_.y, kViewLeft, width_ - kViewLeft, height_);
      if (const auto hit = view_.pick(ray)) hovered_ = session_.world().name(view_.body(std::size_t(hit->mesh)));
    }
  }

  // ---- The panel ----------------------------------------------------------------------------------

  // The panel over the frame, and the hover label; what it asks for (with the script's slice requests)
  // is returned for advance(). Ends the frame's drawing (timed: the panel's "drawing").
  PanelRequests draw_panel(slicing::Detail detail) {
    const World<N>& world = session_.world();
    PanelRequests asked;
    asked.moved = slice_request_;
    begin_panel(fb_height_);
    panel_clock(file_, world, controls_, asked);
    asked.moved |= panel_slice_offsets<N>(controls_.w, view_.reach());
    ImGui::Separator();
    if (const std::optional<BodyId> clicked = panel_bodies(world, view_, hovered_, controls_)) {
      find_body(*clicked);
      asked.moved = true;
    }
    ImGui::Separator();
    const bool coarse = detail == slicing::Detail::Coarse;
    panel_frame_times(times_, coarse ? play_subdivisions_ : subdivisions_,
                      coarse && play_subdivisions_ != subdivisions_);
    if (session_.mouse_driven()) panel_phone(phone_, world);
    panel_pulses(session_.pulses().log);
    ImGui::End();
    if (!hovered_.empty())  // (drawn at the script's cursor too, so that tests and demos show it)
      hover_label(hovered_, mouse_, float(fb_width_) / float(width_), float(fb_height_) / float(height_));
    end_panel();
    drawing_time_ = seconds_since(drawing_start_);
    return asked;
  }

  // ---- The session: advance -----------------------------------------------------------------------

  // Advance: the clock's time (scaled) while playing, one step on request; input from recordings or the
  // mouse hand and the phone. First the slice moves (the panel's sliders or list, the script) and a reset
  // happens; with --frames each frame is 1/60 s of simulated time, else the clock's (at most 0.1 s).
  void advance(const PanelRequests& asked) {
    const TrappedSteps trapped;  // WEDGE_FP_TRAPS=1: the steps run with traps on, the drawing without
    const auto t0 = std::chrono::steady_clock::now();
    const double elapsed = std::min(seconds_since(last_advance_), 0.1);
    last_advance_ = std::chrono::steady_clock::now();
    if (asked.moved) {
      view_.set_offsets(controls_.w);
      if (!hand_.holding) session_.follow_slice();  // the hand moves with the slice
    }
    if (asked.reset) {
      session_.reset();
      hand_ = MouseHand{};
    }
    if (asked.fit || fit_request_) {  // (the camera frames the state drawn and the next kFitSeconds)
      view_.fit(scene_, session_.world());
      orbit_ = Orbit{view_.fitted().camera};
    }
    if (controls_.playing) session_.owe((frames_ > 0 ? kFrameTime : elapsed) * controls_.time_scale);
    const int steps = session_.steps_owed(asked.single);
    for (int s = 0; s < steps; ++s) session_.step(hand_, phone_);
    times_.add(seconds_since(t0), slicing_time_, drawing_time_);
  }

  // On exit: the --events and --record files written, the --hash line printed.
  int finish() {
    session_.finish();
    const World<N>& world = session_.world();
    if (o_.hash)
      std::printf("%lld steps; state hash %016llx\n", (long long)world.step_count(),
                  (unsigned long long)world.state_hash());
    return kExitOk;
  }

  // The command line.
  const ViewOptions& o_;
  const std::string& file_;
  const int width_, height_;  // window px
  const std::int64_t frames_;  // --frames N, or 0: until the window closes
  const int subdivisions_, play_subdivisions_;
  // The stages, in the order they are built.
  const Scene<N> scene_;
  ViewSession<N> session_;     // the world and what steps it
  SliceView<N> view_;          // its slice and the frame drawn of it
  MouseInput input_;           // GLFW's mouse and keys, or the --mouse script
  Window window_;              // (and after it everything that needs its GL context)
  render::Renderer renderer_;  // needs the window's context
  Gui gui_;
  Orbit orbit_;  // the camera, fitted at the start
  MouseHand hand_;
  Phone phone_;
  Controls controls_;  // what the panel sets
  // This frame.
  MouseState mouse_;
  bool slice_request_ = false;  // the script moved a slider or asked for a body
  bool fit_request_ = false;    // F or the script asked for the camera to be refitted
  std::string hovered_;         // the name of the body under the cursor
  int fb_width_ = 0, fb_height_ = 0;
  // The frame time split into physics, slicing and drawing.
  FrameTimes times_;
  std::chrono::steady_clock::time_point last_advance_ = std::chrono::steady_clock::now(), drawing_start_;
  double slicing_time_ = 0.0, drawing_time_ = 0.0;
};

template <int N>
int view(const Json& doc, const ViewOptions& o, const std::vector<double>& w0, int width, int height,
         std::int64_t frames, int subdivisions, int play_subdivisions) {
  if constexpr (N < 3) {
    (void)doc, (void)w0, (void)width, (void)height, (void)frames, (void)subdivisions, (void)play_subdivisions;
    throw Failure(o.scene + ": a 2D scene has no 3D slice to view (view needs a 3D..6D scene)");
  } else {
    const MesaArithmetic mesa;  // the window draws through Mesa; advance() traps the steps (fp_traps.hpp)
    Viewer<N> viewer(doc, o, w0, width, height, frames, subdivisions, play_subdivisions);
    return viewer.run();
  }
}

}  // namespace

CLI::App* add_view_verb(CLI::App& app, ViewOptions& o) {
  CLI::App* cmd = app.add_subcommand("view", kViewSummary);
  cmd->add_option("scene", o.scene, "Scene file (JSON, docs/scene-format.md)")->required()->type_name("SCENE.json");
  cmd->add_option("--w", o.w, "Slice offsets: W in 4D, W1,W2 in 5D, three in 6D (default 0)")->type_name("W");
  cmd->add_option("--size", o.size, "Window size in pixels (default 1280x720)")->type_name("WxH");
  cmd->add_option("--subdivisions", o.subdivisions, "Tessellation of round shapes (default by dimension)")
      ->type_name("S");
  cmd->add_option("--play-subdivisions", o.play_subdivisions,
                  "Tessellation of round shapes while the scene plays (default 5/8 of --subdivisions: 5 in 4D); "
                  "paused frames and screenshots use --subdivisions")
      ->type_name("S");
  cmd->add_option("--replay", o.replay, "Recordings that drive the scene through the input layer")
      ->type_name("RECORDING...")
      ->expected(1, -1);
  cmd->add_option("--mouse", o.mouse,
                  "Play mouse events from FILE (JSON Lines {\"frame\", \"x\", \"y\", \"left\", \"right\", \"shift\", "
                  "\"wheel\"}) instead of the real mouse")
      ->type_name("FILE");
  cmd->add_option("--record", o.record,
                  "Record the mouse hand to FILE (docs/recording-format.md) on exit; `wedge replay SCENE FILE` "
                  "gives the same state")
      ->type_name("FILE");
  cmd->add_flag("--contacts", o.contacts, "Show contact points and normals from the start (key C toggles them)");
  cmd->add_flag("--no-joints", o.no_joints, "Start without the joint marks (key J toggles them)");
  cmd->add_option("--events", o.events,
                  "Write grabs, releases and haptic pulses to FILE (JSON Lines, as wedge replay --events) on exit")
      ->type_name("FILE");
  cmd->add_flag("--hash", o.hash, "On exit print the number of steps and the final state hash");
  cmd->add_option("--frames", o.frames, "Draw N frames (1/60 s of simulated time each) and exit")->type_name("N");
  cmd->add_option("--screenshot", o.screenshot, "With --frames: write the last frame to FILE.png")
      ->type_name("FILE.png");
  cmd->footer(kExitCodesText);
  return cmd;
}

int run_view(const ViewOptions& o) {
  std::int64_t frames = 0;
  if (!o.frames.empty() && (!parse_int64(o.frames, frames) || frames < 1))
    throw Failure(o.scene + ": --frames must be an integer >= 1 (got '" + o.frames + "')");
  if (!o.record.empty() && !o.replay.empty())
    throw Failure(o.scene + ": --record records the mouse, which --replay replaces: give one of them");
  if (!o.events.empty() && (o.events == o.record || o.events == o.screenshot))
    throw Failure(o.scene + ": --events must name a file of its own");
  if (!o.screenshot.empty() && frames == 0)
    throw Failure(o.scene + ": --screenshot needs --frames N (the screenshot is of frame N)");
  const Json doc = read_json_file(o.scene);
  const int n = read_dim(doc, o.scene);
  const std::vector<double> w = parse_slice_offsets(o.scene, o.w, n);
  const int subdivisions = parse_subdivisions(o.scene, o.subdivisions, n);
  const int play_subdivisions = o.play_subdivisions.empty()
                                    ? default_play_subdivisions(subdivisions)
                                    : parse_subdivisions(o.scene, o.play_subdivisions, n, "--play-subdivisions");
  const Size size = parse_size(o.scene, o.size, 480, 240);  // (room for the panel)
  const int width = size.width, height = size.height;
  return with_dim(n, [&](auto dim) {
    return view<decltype(dim)::value>(doc, o, w, width, height, frames, subdivisions, play_subdivisions);
  });
}

}  // namespace wedge::cli
