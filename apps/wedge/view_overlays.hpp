// What the viewer draws over the slice besides the bodies: small boxes for hands, haptic flashes and
// contact points, and needles for contact normals. All in slice coordinates (the 3-flat's frame), as
// DisplayMesh<3>s the renderer draws like bodies.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "wedge/render/renderer.hpp"
#include "wedge/slicing/world_slices.hpp"
#include "wedge/world.hpp"

namespace wedge::cli {

// The marks' colours, the same in every picture (`wedge render --replay`, `wedge view`, `wedge xr`): a
// hand is cyan (left) or magenta (right), green while it holds a body, and yellow while a haptic pulse
// plays, as is the point where the held body hit.
inline constexpr render::Color kFlashColor{1.0f, 0.85f, 0.0f};
inline render::Color hand_color(int hand, bool holding, bool flash) {
  if (flash) return kFlashColor;
  if (holding) return {0.1f, 0.9f, 0.2f};
  return hand == 0 ? render::Color{0.0f, 0.9f, 0.9f} : render::Color{1.0f, 0.1f, 0.8f};
}

// A box about `center` with edges along the columns of `axes` (orthonormal, right-handed) and these half
// extents: twelve outward triangles with flat normals.
inline slicing::DisplayMesh<3> marker_box(const Eigen::Vector3d& center, const Eigen::Matrix3d& axes,
                                          const Eigen::Vector3d& half) {
  slicing::DisplayMesh<3> m;
  for (int c = 0; c < 8; ++c)
    m.vertices.push_back(center + axes * Eigen::Vector3d(c & 1 ? half[0] : -half[0], c & 2 ? half[1] : -half[1],
                                                         c & 4 ? half[2] : -half[2]));
  // Two triangles per face: axis a, side s (corner bits), counterclockwise seen from outside.
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, c = (a + 2) % 3, base = side << a;
      const int q[4] = {base, base | (1 << b), base | (1 << b) | (1 << c), base | (1 << c)};
      const Eigen::Vector3d n = axes.col(a) * (side ? 1.0 : -1.0);
      for (const auto& t : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
        std::array<int, 3> cell = t;
        if (side == 0) std::swap(cell[1], cell[2]);
        m.cells.push_back(cell);
        m.normals.push_back({n, n, n});
      }
    }
  return m;
}

// A small axis-aligned cube (a hand, a haptic flash, a contact point).
inline slicing::DisplayMesh<3> marker_cube(const Eigen::Vector3d& center, double half) {
  return marker_box(center, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Constant(half));
}

// A needle from `from` along the unit vector `dir`, `length` long and `thickness` wide.
inline slicing::DisplayMesh<3> needle(const Eigen::Vector3d& from, const Eigen::Vector3d& dir, double length,
                                      double thickness) {
  Eigen::Matrix3d axes;
  axes.col(0) = dir;
  axes.col(1) = dir.unitOrthogonal();
  axes.col(2) = axes.col(0).cross(axes.col(1));
  return marker_box(from + 0.5 * length * dir, axes, Eigen::Vector3d(0.5 * length, 0.5 * thickness, 0.5 * thickness));
}

// The contacts of the last step that the slice shows: every touching pair whose bodies are both in the
// slice (or one of them unsliced, the ground), each point projected onto the 3-flat, with the pair's
// normal (from the first body toward the second) where its part in the flat is not negligible. A 4D
// face contact's points lie off the slice in w; projected, they mark the corners of the contact region's
// cut. in_slice[k]: entry k's slice is not empty.
struct ContactMarks {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> normals;  // point, unit direction
};
template <int N>
ContactMarks contact_marks(const World<N>& world, const slicing::WorldSlices<N>& slices,
                           const std::vector<bool>& in_slice) {
  std::vector<int> entry(std::size_t(world.body_count()), -1);
  for (std::size_t k = 0; k < slices.entries().size(); ++k) entry[std::size_t(slices.entries()[k].body)] = int(k);
  auto shown = [&](BodyId id) {
    const int k = entry[id.index];
    return k < 0 || in_slice[std::size_t(k)];
  };
  ContactMarks marks;
  for (const ContactInfo<N>& c : world.contacts()) {
    if (!c.touching || !shown(c.a) || !shown(c.b) || (entry[c.a.index] < 0 && entry[c.b.index] < 0)) continue;
    const Eigen::Vector3d n = slices.to_slice_vector(c.manifold.normal);
    const bool normal_shown = n.norm() > 0.3;  // (a normal mostly along w would be a dot)
    for (int i = 0; i < c.manifold.count; ++i) {
      const Eigen::Vector3d p = slices.to_slice_point(c.manifold.points[std::size_t(i)].point);
      if (std::find_if(marks.points.begin(), marks.points.end(), [&](const Eigen::Vector3d& q) {
            return (q - p).squaredNorm() < 1e-8;
          }) != marks.points.end())
        continue;  // (two points differing only in w project to one)
      marks.points.push_back(p);
      if (normal_shown) marks.normals.emplace_back(p, n.normalized());
    }
  }
  return marks;
}

}  // namespace wedge::cli
