// What `wedge xr` shows in the headset: the scene's 3D slice drawn for each eye from where that eye is.
// The tracking space maps into the world as the input layer maps the hands (input/tracking_space.hpp):
// tracking point p is the world point origin + scale (p_x, p_y, p_z, 0, ...), which the slicer places in
// the slice's 3D coordinates, so the bodies appear where the hands can grab them. Each frame draws the
// bodies' slices, the floor (the scene's ground, as `wedge render` draws it), both hands (left cyan, right
// magenta, the holding one green and larger, yellow for a quarter second after a haptic pulse, with a
// yellow mark where the hit was), and one gauge per slice offset: a post beside the table whose knob rises
// with the offset (w in 4D) across the range the bodies span.
#pragma once

#include <openxr/openxr.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <vector>

#include "scene_frame.hpp"
#include "scene_slices.hpp"
#include "view_overlays.hpp"
#include "wedge/input/interaction.hpp"
#include "wedge/render/renderer.hpp"
#include "wedge/scenes/interaction.hpp"

namespace wedge::cli {

template <int N>
class HeadsetView {
 public:
  HeadsetView(const Scene<N>& scene, const World<N>& world, const std::vector<double>& offsets, int subdivisions,
              const std::string& file)
      : tracking_(scenes::interaction_settings(scene).tracking),
        slices_(scene_slices<N>(world, offsets, subdivisions, file)),
        offsets_(offsets) {
    slices_.slice(world, meshes_);
    for (std::size_t k = 0; k < slices_.entries().size(); ++k) {  // the scene's colour, else the palette's
      const SceneBody<N>& sb = scene.bodies[std::size_t(slices_.entries()[k].body)];
      body_colors_.push_back(sb.color ? render::Color{float((*sb.color)[0]), float((*sb.color)[1]), float((*sb.color)[2])}
                                      : render::palette_color(int(k)));
    }
    std::vector<Eigen::Vector3d> corners;
    add_box_corners(meshes_, corners);
    ground_ = fitted_frame(scene, world, slices_, corners, 640, 720).ground;
    for (int i = 0; i < world.body_count(); ++i)
      for (int a = 3; a < N; ++a)
        reach_ = std::max(reach_, std::abs(world.body(BodyId{std::uint32_t(i)}).center[a]) + 0.5);
  }

  // Moves the slice along its first offset (w in 4D) at `rate` (in [-1, 1]) of kSliceSpeed for dt seconds,
  // kept within reach of the bodies; returns whether it moved. Offsets as `wedge view --w` takes them.
  bool move_offsets(double rate, double dt) {
    if (offsets_.empty() || rate == 0.0 || !(dt > 0.0)) return false;
    const double before = offsets_[0];
    offsets_[0] = std::clamp(offsets_[0] + rate * kSliceSpeed * dt, -reach_, reach_);
    slices_.set_offsets(offsets_);
    return offsets_[0] != before;
  }
  const std::vector<double>& offsets() const { return offsets_; }

  // The meshes of this frame: the bodies' slices and the overlays (hands, hits, gauges).
  void update(const World<N>& world, const input::Interaction<N>& hands, const std::array<double, 2>& flash_until,
              const std::vector<Vec<N>>& hits) {
    slices_.slice(world, meshes_);
    overlays_.clear();
    colors_.clear();
    for (int k = 0; k < input::kHandCount; ++k) {
      if (!hands.tracked(k)) continue;
      const bool flash = flash_until[std::size_t(k)] > world.time(), holding = hands.held(k).has_value();
      add(marker_cube(slices_.to_slice_point(hands.hand_point(k)), flash || holding ? 0.035 : 0.025),
          hand_color(k, holding, flash));
    }
    for (const Vec<N>& p : hits) add(marker_cube(slices_.to_slice_point(p), 0.03), kFlashColor);
    add_gauges();
  }

  // One eye's frame: its camera from the eye's pose and field of view (both in tracking space).
  render::FrameDesc eye(const XrView& view) const {
    render::FrameDesc frame;
    frame.ground = ground_;
    frame.background = {0.16f, 0.17f, 0.2f};
    const Eigen::Quaterniond q(view.pose.orientation.w, view.pose.orientation.x, view.pose.orientation.y,
                               view.pose.orientation.z);
    const Eigen::Vector3d p(view.pose.position.x, view.pose.position.y, view.pose.position.z);
    render::Camera& c = frame.camera;
    c.eye = to_slice(p);
    c.target = c.eye + slices_.to_slice_vector(tracking_.vector(q * Eigen::Vector3d(0, 0, -1)));
    c.up = slices_.to_slice_vector(tracking_.vector(q * Eigen::Vector3d(0, 1, 0)));
    c.frustum = std::array<double, 4>{std::tan(view.fov.angleLeft), std::tan(view.fov.angleRight),
                                      std::tan(view.fov.angleDown), std::tan(view.fov.angleUp)};
    c.near_plane = 0.02 * tracking_.scale;
    c.far_plane = 100.0 * tracking_.scale;
    for (std::size_t k = 0; k < meshes_.size(); ++k)
      frame.meshes.push_back({&meshes_[k], body_colors_[k], false});
    for (std::size_t k = 0; k < overlays_.size(); ++k) frame.meshes.push_back({&overlays_[k], colors_[k], true});
    return frame;
  }

  // A tracking-space point in the slice's coordinates.
  Eigen::Vector3d to_slice(const Eigen::Vector3d& p) const { return slices_.to_slice_point(tracking_.point(p)); }

 private:
  static constexpr double kSliceSpeed = 0.5;  // m/s of slice offset at full stick

  void add(slicing::DisplayMesh<3> m, render::Color c) {
    overlays_.push_back(std::move(m));
    colors_.push_back(c);
  }

  // A post 0.6 m high for offset i, left of the tracking origin and a little ahead (from (-0.75 - 0.12 i,
  // -0.8, -0.3) in tracking space, about table height up to chest height), its knob at the offset's place
  // in [-reach, reach]: w is read off the knob's height, as off a thermometer.
  void add_gauges() {
    for (std::size_t i = 0; i < offsets_.size(); ++i) {
      const Eigen::Vector3d foot(-0.75 - 0.12 * double(i), -0.8, -0.3);
      const double u = (offsets_[i] + reach_) / (2 * reach_);
      const Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
      add(marker_box(to_slice(foot + Eigen::Vector3d(0, 0.3, 0)), axes,
                     tracking_.scale * Eigen::Vector3d(0.006, 0.3, 0.006)),
          {0.85f, 0.85f, 0.9f});
      add(marker_box(to_slice(foot + Eigen::Vector3d(0, 0.6 * u, 0)), axes, tracking_.scale * Eigen::Vector3d::Constant(0.025)),
          {1.0f, 0.45f, 0.0f});
    }
  }

  input::TrackingSpace<N> tracking_;
  slicing::WorldSlices<N> slices_;
  std::vector<double> offsets_;
  double reach_ = 1.0;
  render::Ground ground_;
  std::vector<slicing::DisplayMesh<3>> meshes_, overlays_;
  std::vector<render::Color> colors_, body_colors_;
};

}  // namespace wedge::cli
