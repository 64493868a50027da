// The viewer's slice (`wedge view`: slicing and drawing): the world cut by the viewed 3-flat into one mesh per
// bounded body (slicing::WorldSlices), the frame the renderer draws of it right of the panel, as `wedge
// render --size (W-316)xH` draws its picture, and the markers over the bodies (view_overlays.hpp): hands,
// haptic flashes, joints, contacts.
#pragma once

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene_frame.hpp"
#include "scene_slices.hpp"
#include "view_mouse.hpp"
#include "view_overlays.hpp"
#include "view_platform.hpp"
#include "view_session.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/render/renderer.hpp"
#include "wedge/slicing/pick.hpp"

namespace wedge::cli::viewer {

template <int N>
class SliceView {
 public:
  // The slice at offsets `w` (missing ones 0) of the world as it starts, the camera fitted (fit) in the
  // view beside the panel of a width x height window, and the sizes the sliders and markers take from it.
  // Round shapes are cut at two levels: `subdivisions` when still, `play_subdivisions` while the scene plays.
  SliceView(const Scene<N>& scene, const World<N>& world, const std::vector<double>& w, int subdivisions,
            int play_subdivisions, const std::string& file, int width, int height)
      : offsets_(padded(w)),
        slices_(scene_slices<N>(world, offsets_, subdivisions, file, play_subdivisions)),
        width_(width),
        height_(height) {
    slices_.slice(world, meshes_);
    fit(scene, world);
    // The w sliders' range: every body's hidden coordinates, with room around them.
    for (int i = 0; i < world.body_count(); ++i)
      for (int a = 3; a < N; ++a)
        reach_ = std::max(reach_, std::abs(world.body(BodyId{std::uint32_t(i)}).center[a]) + 1.0);
    mark_ = mark_size(slices_);  // (contact and joint marks scale with the bodies)
  }

  // The camera fitted to what the world will do left alone: its cut now, and that cut carried along by
  // each body's centre every 0.1 s over the next kFitSeconds of a copy stepped without input, so that
  // bodies thrown up or falling stay in the picture (as `wedge render` fits its camera to every frame it
  // draws). The look-ahead moves the cuts instead of redoing them (slicing 30 states of a 6D scene took
  // seconds); a body the flat misses now is framed by its bounding ball once the ball meets the flat.
  // The view is the window right of the panel.
  void fit(const Scene<N>& scene, const World<N>& world) {
    std::vector<slicing::DisplayMesh<3>> cut;
    slices_.slice(world, cut);
    std::vector<Eigen::Vector3d> corners;
    add_box_corners(cut, corners);
    const JointMarks joints = joint_marks(world, slices_, meets_slice(cut));  // (a pendulum's pivot too)
    corners.insert(corners.end(), joints.anchors.begin(), joints.anchors.end());
    const auto& entries = slices_.entries();
    auto center = [&](const World<N>& w, std::size_t k) {
      return slices_.to_slice_point(w.body(BodyId{std::uint32_t(entries[k].body)}).center);
    };
    std::vector<std::vector<Eigen::Vector3d>> body_corners(entries.size());
    std::vector<Eigen::Vector3d> start(entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k) {
      if (!cut[k].empty()) add_box_corners(cut[k], body_corners[k]);
      start[k] = center(world, k);
    }
    World<N> ahead = world;
    const double h = scene.timestep;
    const int steps = int(std::lround(kFitSeconds / h)), every = std::max(1, int(std::lround(0.1 / h)));
    for (int step = 1; step <= steps; ++step) {
      ahead.step(h);
      if (step % every != 0) continue;
      const std::size_t before = corners.size();
      for (std::size_t k = 0; k < entries.size(); ++k) {
        if (!body_corners[k].empty()) {
          const Eigen::Vector3d shift = center(ahead, k) - start[k];
          for (const Eigen::Vector3d& p : body_corners[k]) corners.push_back(p + shift);
        } else if (const auto ball = slices_.slice_bound(ahead, k)) {
          for (int c = 0; c < 8; ++c)
            corners.push_back(ball->first + ball->second * Eigen::Vector3d((c & 1) ? 1 : -1, (c & 2) ? 1 : -1,
                                                                            (c & 4) ? 1 : -1));
        }
      }
      // A world that blows up within the window (the session will stop it with its own message) does
      // not move the camera to infinity.
      if (!std::all_of(corners.begin() + std::ptrdiff_t(before), corners.end(), [](const Eigen::Vector3d& p) {
            return all_finite(p) && p.norm() < 1e4;
          })) {
        corners.resize(before);
        break;
      }
    }
    fitted_ = fitted_frame(scene, world, slices_, corners, width_ - kViewLeft, height_);
  }

  const slicing::WorldSlices<N>& slices() const { return slices_; }
  const std::vector<double>& offsets() const { return offsets_; }  // x_{n-1} first, then x_{n-2} within it
  const render::FrameDesc& fitted() const { return fitted_; }
  double reach() const { return reach_; }  // m: the sliders' range, +-
  // The body of mesh k, and whether the slice meets it.
  BodyId body(std::size_t k) const { return BodyId{std::uint32_t(slices_.entries()[k].body)}; }
  std::size_t body_count() const { return meshes_.size(); }
  bool in_slice(std::size_t k) const { return !meshes_[k].empty(); }
  int in_slice_count() const { return in_slice_; }

  // The bounded body named `name`, if there is one.
  std::optional<BodyId> body_named(const World<N>& world, const std::string& name) const {
    for (const auto& e : slices_.entries())
      if (world.name(BodyId{std::uint32_t(e.body)}) == name) return BodyId{std::uint32_t(e.body)};
    return std::nullopt;
  }

  // The slice moved to the sliders' offsets.
  void set_offsets(const std::vector<float>& w) {
    for (std::size_t i = 0; i < w.size(); ++i) offsets_[i] = w[i];
    slices_.set_offsets(offsets_);
  }

  // The world's current state cut at `detail`.
  void slice(const World<N>& world, slicing::Detail detail) { slices_.slice(world, meshes_, detail); }

  // The nearest body along `ray` in the current cut.
  std::optional<slicing::Pick> pick(const Ray& ray) const { return slicing::pick(meshes_, ray.origin, ray.direction); }

  // The frame of the current cut seen by `camera`: the fitted frame's ground and light, each body's
  // slice in its colour (the scene's, else the palette's), the bodies in the slice counted.
  render::FrameDesc frame(const Scene<N>& scene, const render::Camera& camera) {
    render::FrameDesc desc = fitted_;
    desc.camera = camera;
    in_slice_ = 0;
    for (std::size_t k = 0; k < meshes_.size(); ++k) {
      const SceneBody<N>& sb = scene.bodies[std::size_t(slices_.entries()[k].body)];
      render::Color color = render::palette_color(int(k));
      if (sb.color) color = {float((*sb.color)[0]), float((*sb.color)[1]), float((*sb.color)[2])};
      desc.meshes.push_back({&meshes_[k], color});
      in_slice_ += !meshes_[k].empty();
    }
    return desc;
  }

  // Markers: the hands (recorded ones, or the mouse while it holds: left cyan, right magenta) and, for
  // a quarter second after a haptic pulse, yellow at its contact point and on the hand's marker, grown
  // by half: a mouse and a screen cannot feel them. Optionally the joints (joint_marks) and the
  // contacts: orange points, dark normals. They are added to `desc` as overlays; the meshes live until
  // the next frame's markers.
  void add_markers(render::FrameDesc& desc, const World<N>& world, const input::Interaction<N>* recorded,
                   const MouseHand& hand, PulseDisplay<N>& pulses, bool show_joints, bool show_contacts) {
    markers_.clear();
    marker_colors_.clear();
    if (show_joints) add_joint_meshes(joint_marks(world, slices_, meets_slice(meshes_)), mark_, markers_, marker_colors_);
    mark_hands(world, recorded, hand, pulses);
    if (show_contacts) mark_contacts(world);
    for (std::size_t k = 0; k < markers_.size(); ++k) desc.meshes.push_back({&markers_[k], marker_colors_[k], true});
  }

  // Clears the window and draws `desc` in the view right of the panel (window px `width` wide; the
  // framebuffer's px, fb_width x fb_height, may differ).
  void draw(render::Renderer& renderer, const render::FrameDesc& desc, int width, int fb_width, int fb_height) const {
    glViewport(0, 0, fb_width, fb_height);
    glClearColor(desc.background[0], desc.background[1], desc.background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    const int left = std::min(kViewLeft * fb_width / width, fb_width - 1);  // (framebuffer px may differ)
    renderer.draw(desc, fb_width - left, fb_height, left, 0);
  }

 private:
  // The offsets given, missing ones 0.
  static std::vector<double> padded(std::vector<double> w) {
    w.resize(std::size_t(std::max(N - 3, 0)), 0.0);
    return w;
  }

  void add_marker(slicing::DisplayMesh<3> m, render::Color c) {
    markers_.push_back(std::move(m));
    marker_colors_.push_back(c);
  }

  // The hands, and the flashes of the pulses still shown (those run out are dropped).
  void mark_hands(const World<N>& world, const input::Interaction<N>* recorded, const MouseHand& hand,
                  PulseDisplay<N>& pulses) {
    std::erase_if(pulses.flashes, [&](const auto& f) { return f.second <= world.time(); });
    for (int k = 0; k < input::kHandCount; ++k) {
      std::optional<Eigen::Vector3d> at;
      if (recorded && recorded->tracked(k)) at = slices_.to_slice_point(recorded->hand_point(k));
      if (!recorded && k == 1 && hand.holding) at = hand.point;
      if (!at) continue;
      const bool flash = pulses.hand_flash[std::size_t(k)] > world.time();
      add_marker(marker_cube(*at, flash ? 0.06 : 0.04), hand_color(k, false, flash));
    }
    for (const auto& f : pulses.flashes) add_marker(marker_cube(slices_.to_slice_point(f.first), 0.05), kFlashColor);
  }

  // The contacts of the last step that the slice shows (contact_marks), sized by `mark_`.
  void mark_contacts(const World<N>& world) {
    const ContactMarks contacts = contact_marks(world, slices_, meets_slice(meshes_));
    for (const auto& [p, n] : contacts.normals) add_marker(needle(p, n, 8 * mark_, 0.3 * mark_), {0.1f, 0.1f, 0.3f});
    for (const Eigen::Vector3d& p : contacts.points) add_marker(marker_cube(p, mark_), {1.0f, 0.2f, 0.0f});
  }

  std::vector<double> offsets_;  // the slice offsets, N-3 of them
  slicing::WorldSlices<N> slices_;
  std::vector<slicing::DisplayMesh<3>> meshes_;  // the current cut, one per bounded body (entries() order)
  int width_, height_;                           // window px
  render::FrameDesc fitted_;                     // ground, light and the camera (fit)
  double reach_ = 1.0;                           // m
  double mark_ = 0.05;                           // m: the half size of a contact point's cube (mark_size)
  int in_slice_ = 0;                             // bodies the current cut meets
  std::vector<slicing::DisplayMesh<3>> markers_;
  std::vector<render::Color> marker_colors_;
};

}  // namespace wedge::cli::viewer
