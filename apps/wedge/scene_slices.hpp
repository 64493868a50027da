// The 3D view of a scene for `wedge render` and `wedge slice`: display meshes of its bounded bodies,
// the chain of slicing hyperplanes from --w (x_{n-1} = w1 in the world, then x_{n-2} = w2 in that
// slice, ..), and the slices of a world's bodies in the final 3D frame. Halfspaces are not sliced:
// the first static one becomes the ground plane of the picture.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "scene_json.hpp"
#include "step_options.hpp"
#include "wedge/ga/products.hpp"
#include "wedge/slicing/slicer.hpp"

namespace wedge::cli {

// Default tessellation levels for display (finer than the core's mass-property default): 24576
// tetrahedra per 4-ball, 61440 4-simplices per 5-ball.
constexpr int default_display_subdivisions(int n) { return n <= 3 ? 16 : (n == 4 ? 8 : (n == 5 ? 4 : 2)); }

// "W" or "W1,W2,..": up to n-3 slice offsets (m); missing ones are 0. Throws Failure naming the scene.
inline std::vector<double> parse_slice_offsets(const std::string& scene, const std::string& text, int n) {
  std::vector<double> w;
  if (text.empty()) return w;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string part = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double v = 0.0;
    if (!parse_double(part, v) || !std::isfinite(v))
      throw Failure(scene + ": --w must be a number, or comma-separated numbers for 5D and 6D (got '" + text + "')");
    w.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (int(w.size()) > std::max(n - 3, 0))
    throw Failure(scene + ": --w takes " + (n <= 3 ? std::string("no offsets in a ") + std::to_string(n) + "D scene (it is shown as it is)"
                                                   : "at most " + std::to_string(n - 3) + " offset(s) in a " + std::to_string(n) + "D scene") +
                  " (got '" + text + "')");
  return w;
}

inline int parse_subdivisions(const std::string& scene, const std::string& text, int n) {
  if (text.empty()) return default_display_subdivisions(n);
  std::int64_t s = 0;
  if (!parse_int64(text, s) || s < 1 || s > 64)
    throw Failure(scene + ": --subdivisions must be an integer in 1..64 (got '" + text + "')");
  return int(s);
}

template <int N>
class SceneSlices {
 public:
  struct Entry {
    int body = 0;                 // index in the scene
    slicing::BodySlicer<N> slicer;
    double radius = 0.0;          // m, of a ball about the centre of mass holding the whole mesh
  };

  SceneSlices(const Scene<N>& scene, const std::vector<double>& w, int subdivisions, const std::string& file) {
    std::array<double, std::size_t(N - 3)> offsets{};
    for (std::size_t i = 0; i < w.size() && i < offsets.size(); ++i) offsets[i] = w[i];
    chain_ = slicing::SliceChain<N>::axes(offsets);
    flat_ = chain_.flat();
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const SceneBody<N>& b = scene.bodies[i];
      if (!b.shape.bounded()) {
        if (!ground_body_ && b.def.type == BodyType::Static) ground_body_ = int(i);
        continue;
      }
      const slicing::DisplayMesh<N> mesh = with_file_context(file, index_path("bodies", i) + ".shape", [&] {
        return slicing::display_mesh<N>(b.shape, subdivisions);
      });
      double r = 0.0;
      for (const Vec<N>& v : mesh.vertices) r = std::max(r, (v - b.def.local_center).norm());
      entries_.push_back(Entry{int(i), slicing::BodySlicer<N>(mesh), r});
    }
  }

  const std::vector<Entry>& entries() const { return entries_; }
  const slicing::Flat3<N>& flat() const { return flat_; }

  // The slice of each bounded body (entries() order) in the world's current state.
  void slice(const World<N>& world, std::vector<slicing::DisplayMesh<3>>& out) {
    out.resize(entries_.size());
    for (std::size_t k = 0; k < entries_.size(); ++k) {
      const Body<N>& b = world.body(BodyId{std::uint32_t(entries_[k].body)});
      out[k] = entries_[k].slicer.slice(slicing::Placement<N>{to_matrix(b.rotor), b.position()}, chain_);
    }
  }

  // A ball in slice coordinates holding body k's slice (absent if the slice misses the body): the
  // body lies in the ball of `radius` about its centre, whose cut by the 3-flat is the ball of radius
  // sqrt(radius^2 - d^2) about the centre's foot point, d the centre's distance from the flat.
  std::optional<std::pair<Eigen::Vector3d, double>> slice_bound(const World<N>& world, std::size_t k) const {
    const Vec<N> rel = world.body(BodyId{std::uint32_t(entries_[k].body)}).center - flat_.origin;
    const Eigen::Vector3d y = flat_.frame.transpose() * rel;
    const double d2 = std::max(0.0, rel.squaredNorm() - y.squaredNorm());
    const double r2 = entries_[k].radius * entries_[k].radius - d2;
    if (!(r2 > 0.0)) return std::nullopt;
    return std::make_pair(y, std::sqrt(r2));
  }

  // A world vector in slice coordinates (its projection onto the 3-flat).
  Eigen::Vector3d to_slice_vector(const Vec<N>& v) const { return flat_.frame.transpose() * v; }

  // The ground: the first static halfspace {n . x <= offset}, placed by its body, cut by the flat:
  // {y : (F^T n) . y <= offset - n . origin}, normalised. Absent if there is none or it is parallel.
  std::optional<std::pair<Eigen::Vector3d, double>> ground(const Scene<N>& scene, const World<N>& world) const {
    if (!ground_body_) return std::nullopt;
    const auto& hs = scene.bodies[std::size_t(*ground_body_)].shape.template as<shapes::Halfspace<N>>();
    const Body<N>& b = world.body(BodyId{std::uint32_t(*ground_body_)});
    const Vec<N> n = rotate(b.rotor, hs.normal);
    const double offset = hs.offset + n.dot(b.position()) - n.dot(flat_.origin);
    const Eigen::Vector3d n3 = flat_.frame.transpose() * n;
    const double len = n3.norm();
    if (!(len > 1e-9)) return std::nullopt;
    return std::make_pair(Eigen::Vector3d(n3 / len), offset / len);
  }

 private:
  slicing::SliceChain<N> chain_;
  slicing::Flat3<N> flat_;
  std::vector<Entry> entries_;
  std::optional<int> ground_body_;
};

}  // namespace wedge::cli
