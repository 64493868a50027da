// The picture of a scene's slice for `wedge render` and the viewer: the ground (the scene's half-space
// cut by the slice, else a grid under everything), and a camera that looks from an elevated
// three-quarter view with the scene's "down" (gravity, projected into the slice) pointing down the
// screen, at a distance that just fits, with a margin, the given points (the corners of the bodies'
// slices over the frames to be drawn) and their feet on the ground, unless the scene's "view" says
// otherwise (docs/scene-format.md).
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "scenes.hpp"
#include "wedge/render/renderer.hpp"
#include "wedge/slicing/world_slices.hpp"

namespace wedge::cli {

// The camera's view direction (from the target toward the eye) and screen axes for a given up.
struct ViewAxes {
  Eigen::Vector3d dir, right, screen_up;
};

inline ViewAxes default_view_axes(const Eigen::Vector3d& up) {
  // Toward the viewer: the slice axis least aligned with up (z when up is y), then right = up x it.
  Eigen::Index axis = 0;
  (Eigen::Vector3d(0.5, 0.5, 0.0) + up.cwiseAbs()).minCoeff(&axis);  // prefers z, then x
  Eigen::Vector3d toward = Eigen::Vector3d::Unit(axis) - up * up(axis);
  toward.normalize();
  const Eigen::Vector3d right = up.cross(toward);
  // About 30 degrees above the ground and 28 to the side: the ground and the shadows on it show well.
  const Eigen::Vector3d dir = (0.85 * toward + 0.55 * up + 0.45 * right).normalized();
  const Eigen::Vector3d f = -dir;  // as Camera::view() builds its axes
  const Eigen::Vector3d s = f.cross(up).normalized();
  return {dir, s, s.cross(f)};
}

// The distance from `target` along ax.dir at which every point lies within `fill` of the picture's half
// width and half height (tan_x, tan_y: tangents of the half fields of view), and at least `min_depth`
// in front of the eye.
inline double fit_distance(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& target, const ViewAxes& ax,
                    double tan_x, double tan_y, double fill, double min_depth) {
  double d = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = p - target;
    const double need = std::max({std::abs(ax.right.dot(q)) / (fill * tan_x),
                                  std::abs(ax.screen_up.dot(q)) / (fill * tan_y), min_depth});
    d = std::max(d, ax.dir.dot(q) + need);
  }
  return d;
}

// The eight corners of a non-empty mesh's bounding box, appended to `points`.
inline void add_box_corners(const slicing::DisplayMesh<3>& m, std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (const Eigen::Vector3d& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  for (int c = 0; c < 8; ++c)
    points.emplace_back((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
}

// The eight corners of each non-empty mesh's bounding box, appended to `points`.
inline void add_box_corners(const std::vector<slicing::DisplayMesh<3>>& meshes, std::vector<Eigen::Vector3d>& points) {
  for (const slicing::DisplayMesh<3>& m : meshes)
    if (!m.empty()) add_box_corners(m, points);
}

// The frame's ground and camera (no meshes yet) for a picture of width x height pixels.
template <int N>
render::FrameDesc fitted_frame(const Scene<N>& scene, const World<N>& world, const slicing::WorldSlices<N>& slices,
                               std::vector<Eigen::Vector3d> points, int width, int height) {
  render::FrameDesc frame;
  const bool any = !points.empty();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(any ? INFINITY : -1.0), hi = -lo;
  for (const Eigen::Vector3d& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double radius = std::max(0.5, (hi - lo).norm() / 2);  // the scene's size, for grid and margins

  // Up against gravity as seen in the slice.
  Eigen::Vector3d up = -slices.to_slice_vector(scene.settings.gravity);
  if (!(up.norm() > 1e-9 * std::max(1.0, scene.settings.gravity.norm()))) up = Eigen::Vector3d::UnitY();
  up.normalize();

  // Ground: the scene's halfspace, else a grid just below everything, across gravity. The camera
  // also frames the feet of the points on it, where the shadows fall.
  frame.ground.enabled = true;
  if (const auto g = slices.ground(world)) {
    frame.ground.normal = g->first;  // out of the solid {n . y <= offset}
    frame.ground.offset = g->second;
  } else {
    double low = any ? INFINITY : -radius;
    for (const Eigen::Vector3d& p : points) low = std::min(low, p.dot(up));
    frame.ground.normal = up;
    frame.ground.offset = low - 0.05 * radius;
  }
  frame.ground.spacing = std::pow(10.0, std::floor(std::log10(radius))) / 2;
  frame.ground.extent = 8 * radius;
  {
    const Eigen::Vector3d n = frame.ground.normal;
    const std::size_t count = points.size();
    for (std::size_t i = 0; i < count; ++i)
      points.push_back(points[i] - (n.dot(points[i]) - frame.ground.offset) * n);
  }

  // Camera: fitted to the points (90% of the narrower way), recentred on them in the picture.
  render::Camera camera;
  camera.up = up;
  camera.fov_y_degrees = scene.view.fov_degrees.value_or(40.0);
  const double tan_y = std::tan(camera.fov_y_degrees * M_PI / 360.0), tan_x = tan_y * double(width) / height;
  const double fill = 0.9, min_depth = 0.05 * radius;
  auto vec3 = [](const std::array<double, 3>& a) { return Eigen::Vector3d(a[0], a[1], a[2]); };
  camera.target = scene.view.target ? vec3(*scene.view.target) : Eigen::Vector3d((lo + hi) / 2);
  if (scene.view.eye) {
    camera.eye = vec3(*scene.view.eye);
  } else if (!any) {
    camera.eye = camera.target + default_view_axes(up).dir * 6.0;
  } else {
    const ViewAxes ax = default_view_axes(up);
    double d = fit_distance(points, camera.target, ax, tan_x, tan_y, fill, min_depth);
    // Perspective makes the fitted picture lopsided about the target: move the target across the view
    // by the middle of the points' angular extent (a fixed point iteration; it settles in a few rounds).
    for (int round = 0; round < 6 && !scene.view.target; ++round) {
      double u_lo = INFINITY, u_hi = -INFINITY, v_lo = INFINITY, v_hi = -INFINITY;
      for (const Eigen::Vector3d& p : points) {
        const Eigen::Vector3d q = p - camera.target;
        const double depth = d - ax.dir.dot(q);
        const double u = ax.right.dot(q) / depth / tan_x, v = ax.screen_up.dot(q) / depth / tan_y;
        u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u), v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
      }
      camera.target += d * ((u_lo + u_hi) / 2 * tan_x * ax.right + (v_lo + v_hi) / 2 * tan_y * ax.screen_up);
      d = fit_distance(points, camera.target, ax, tan_x, tan_y, fill, min_depth);
    }
    camera.eye = camera.target + ax.dir * d;
  }
  const double dist = (camera.eye - camera.target).norm();
  double nearest = dist;
  for (const Eigen::Vector3d& p : points)
    nearest = std::min(nearest, (p - camera.eye).dot(camera.target - camera.eye) / dist);
  camera.near_plane = std::max(1e-3, std::min(0.02 * dist, 0.5 * nearest));
  camera.far_plane = 10 * dist + 10 * frame.ground.extent;
  frame.camera = camera;
  return frame;
}

}  // namespace wedge::cli
