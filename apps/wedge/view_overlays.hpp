// What the viewer draws over the slice besides the bodies: small boxes for hands, haptic flashes and
// contact points, needles for contact normals, and the joints (anchors, rods, a revolute joint's plane, a
// prismatic joint's axis). All in slice coordinates (the 3-flat's frame), as DisplayMesh<3>s the renderer
// draws like bodies.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstddef>
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

// Per body of a cut (WorldSlices::slice): whether the slice meets it.
inline std::vector<bool> meets_slice(const std::vector<slicing::DisplayMesh<3>>& cut) {
  std::vector<bool> in(cut.size());
  for (std::size_t k = 0; k < cut.size(); ++k) in[k] = !cut[k].empty();
  return in;
}

// The marks' size (m): a twentieth of the median bounding radius of the sliced bodies (5 cm for a unit
// tesseract), so that they scale with the scene.
template <int N>
double mark_size(const slicing::WorldSlices<N>& slices) {
  std::vector<double> r;
  for (const auto& e : slices.entries()) r.push_back(e.radius);
  if (r.empty()) return 0.05;
  std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
  return 0.05 * r[r.size() / 2];
}

// The joints the slice shows: each joint whose bodies the slice meets (the world, or a body not sliced,
// counts as met), in slice coordinates: its two anchors; a rod between them where they are apart (a
// distance joint's rope or spring, or a joint pulled open); a revolute joint's plane of rotation as the
// flat sees it, about anchor a, with body b's vector in it (the joint's angle); a prismatic joint's axis
// through anchor a. A plane or axis mostly across the flat (less than 0.3 of a unit vector in it) is left
// out: it would be drawn as a sliver or a dot.
struct JointMarks {
  struct Plane {
    Eigen::Vector3d center, u, v;  // u, v: orthonormal
    Eigen::Vector3d turned;        // unit, in the plane; zero if body b's vector is mostly across the flat
    double reach = 0.0;            // m: body b's centre from the anchor (how far the plane is drawn)
  };
  std::vector<Eigen::Vector3d> anchors;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> rods;  // from, to
  std::vector<Plane> planes;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> axes;  // point, unit direction
};
template <int N>
JointMarks joint_marks(const World<N>& world, const slicing::WorldSlices<N>& slices, const std::vector<bool>& in_slice) {
  std::vector<int> entry(std::size_t(world.body_count()), -1);
  for (std::size_t k = 0; k < slices.entries().size(); ++k) entry[std::size_t(slices.entries()[k].body)] = int(k);
  auto shown = [&](std::optional<BodyId> body) {
    return !body || entry[body->index] < 0 || in_slice[std::size_t(entry[body->index])];
  };
  constexpr double kSeen = 0.3;
  JointMarks marks;
  for (const JointId id : world.joint_ids()) {
    const JointGeometry<N> g = world.joint_geometry(id);
    if (!shown(g.body_a) || !shown(g.body_b)) continue;
    const Eigen::Vector3d a = slices.to_slice_point(g.anchor_a), b = slices.to_slice_point(g.anchor_b);
    marks.anchors.push_back(a);
    if ((b - a).norm() > 1e-9) {
      marks.anchors.push_back(b);
      marks.rods.emplace_back(a, b);
    }
    if (g.type == JointType::Revolute) {
      const Eigen::Vector3d u = slices.to_slice_vector(g.plane_u), v0 = slices.to_slice_vector(g.plane_v);
      if (u.norm() < kSeen) continue;
      const Eigen::Vector3d un = u.normalized(), v = v0 - v0.dot(un) * un;
      if (v.norm() < kSeen) continue;
      const Eigen::Vector3d vn = v.normalized(), t0 = slices.to_slice_vector(g.plane_u_b);
      const Eigen::Vector3d t = t0.dot(un) * un + t0.dot(vn) * vn;  // (its part in the plane drawn)
      marks.planes.push_back({a, un, vn, t.norm() < kSeen ? Eigen::Vector3d::Zero() : Eigen::Vector3d(t.normalized()),
                              (world.body(g.body_b).center - g.anchor_a).norm()});
    }
    if (g.type == JointType::Prismatic) {
      const Eigen::Vector3d d = slices.to_slice_vector(g.axis);
      if (d.norm() >= kSeen) marks.axes.emplace_back(a, d.normalized());
    }
  }
  return marks;
}

// The meshes of joint marks of size `size` (m, mark_size): a light cube at each anchor, dark rods, a blue
// square outline for a revolute joint's plane, as far out as body b's centre (3 to 20 times `size`), with
// a needle along body b's vector, a blue line for a prismatic joint's axis; appended with their colours.
inline void add_joint_meshes(const JointMarks& marks, double size, std::vector<slicing::DisplayMesh<3>>& meshes,
                             std::vector<render::Color>& colors) {
  const render::Color anchor{0.95f, 0.95f, 0.95f}, rod{0.2f, 0.2f, 0.2f}, plane{0.2f, 0.45f, 0.95f};
  auto add = [&](slicing::DisplayMesh<3> m, render::Color c) {
    meshes.push_back(std::move(m));
    colors.push_back(c);
  };
  for (const auto& [from, to] : marks.rods) add(needle(from, (to - from).normalized(), (to - from).norm(), 0.4 * size), rod);
  for (const JointMarks::Plane& p : marks.planes) {
    const double half = std::clamp(p.reach, 3.0 * size, 20.0 * size), edge = 0.25 * size;
    for (const double s : {-1.0, 1.0}) {  // the square's four edges
      add(needle(p.center + s * half * p.u - half * p.v, p.v, 2.0 * half, edge), plane);
      add(needle(p.center + s * half * p.v - half * p.u, p.u, 2.0 * half, edge), plane);
    }
    if (p.turned != Eigen::Vector3d::Zero()) add(needle(p.center, p.turned, half, 0.5 * size), plane);
  }
  for (const auto& [at, dir] : marks.axes) add(needle(at - 8.0 * size * dir, dir, 16.0 * size, 0.3 * size), plane);
  for (const Eigen::Vector3d& p : marks.anchors) add(marker_cube(p, 0.8 * size), anchor);
}

}  // namespace wedge::cli
