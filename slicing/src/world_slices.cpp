// WorldSlices (world_slices.hpp): a World's bodies prepared for slicing, and their slices.
#include "wedge/slicing/world_slices.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "wedge/error.hpp"
#include "wedge/slicing/display_mesh.hpp"

namespace wedge::slicing {

template <int N>
void WorldSlices<N>::set_offsets(const std::vector<double>& w) {
  std::array<double, std::size_t(N - 3)> offsets{};
  for (std::size_t i = 0; i < w.size() && i < offsets.size(); ++i) offsets[i] = w[i];
  chain_ = SliceChain<N>::axes(offsets);
  flat_ = chain_.flat();
}

template <int N>
WorldSlices<N>::WorldSlices(const World<N>& world, const std::vector<double>& w, int subdivisions,
                            int coarse_subdivisions) {
  set_offsets(w);
  for (int i = 0; i < world.body_count(); ++i) {
    const BodyId id{std::uint32_t(i)};
    const Shape<N>* shape = world.shape(id);
    if (!shape) continue;
    if (!shape->bounded()) {
      if (!ground_body_ && world.body(id).type == BodyType::Static) ground_body_ = i;
      continue;
    }
    DisplayMesh<N> mesh, coarse;
    try {
      mesh = display_mesh<N>(*shape, subdivisions);
      if (coarse_subdivisions > 0 && coarse_subdivisions != subdivisions)
        coarse = display_mesh<N>(*shape, coarse_subdivisions);
    } catch (const Error& e) {
      throw Error("bodies[" + std::to_string(i) + "].shape: " + e.what());
    }
    double r = 0.0;
    for (const DisplayMesh<N>* m : {&mesh, &coarse})
      for (const Vec<N>& v : m->vertices) r = std::max(r, (v - world.body(id).local_center).norm());
    std::optional<BodySlicer<N>> coarse_slicer;
    if (!coarse.empty() && coarse.cells.size() != mesh.cells.size()) coarse_slicer.emplace(coarse);
    entries_.push_back(Entry{i, BodySlicer<N>(mesh), std::move(coarse_slicer), r});
  }
}

template <int N>
void WorldSlices<N>::slice(const World<N>& world, std::vector<DisplayMesh<3>>& out, Detail detail) {
  out.resize(entries_.size());
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    const Body<N>& b = world.body(BodyId{std::uint32_t(entries_[k].body)});
    if (misses(b.center, entries_[k].radius)) {  // (most bodies of a 4D scene lie off the slice)
      out[k].vertices.clear();
      out[k].cells.clear();
      out[k].normals.clear();
      continue;
    }
    BodySlicer<N>& slicer =
        detail == Detail::Coarse && entries_[k].coarse ? *entries_[k].coarse : entries_[k].slicer;
    slicer.slice(Placement<N>{to_matrix(b.rotor), b.position()}, chain_, out[k]);
  }
}

template <int N>
Vec<N> WorldSlices<N>::off_flat(const Vec<N>& x) const {
  // (Subtracting the in-flat part, not |x|^2 - |y|^2: no cancellation for points far along the flat.)
  const Vec<N> rel = x - flat_.origin;
  return rel - flat_.frame * (flat_.frame.transpose() * rel);
}

template <int N>
bool WorldSlices<N>::misses(const Vec<N>& center, double radius) const {
  // The centre's distance from the flat beyond the bounding radius, with a margin of 1e-9 m so that a mesh
  // vertex exactly on the flat (whose zero-area pieces the slicer would keep) is never culled.
  return off_flat(center).norm() > radius + 1e-9;
}

template <int N>
std::optional<std::pair<Eigen::Vector3d, double>> WorldSlices<N>::slice_bound(const World<N>& world,
                                                                              std::size_t k) const {
  const Vec<N>& center = world.body(BodyId{std::uint32_t(entries_[k].body)}).center;
  const double r2 = entries_[k].radius * entries_[k].radius - off_flat(center).squaredNorm();
  if (!(r2 > 0.0)) return std::nullopt;
  return std::make_pair(to_slice_point(center), std::sqrt(r2));
}

template <int N>
std::optional<std::pair<Eigen::Vector3d, double>> WorldSlices<N>::ground(const World<N>& world) const {
  if (!ground_body_) return std::nullopt;
  const BodyId id{std::uint32_t(*ground_body_)};
  const auto& hs = world.shape(id)->template as<shapes::Halfspace<N>>();
  const Body<N>& b = world.body(id);
  const Vec<N> n = rotate(b.rotor, hs.normal);
  const double offset = hs.offset + n.dot(b.position()) - n.dot(flat_.origin);
  const Eigen::Vector3d n3 = flat_.frame.transpose() * n;
  const double len = n3.norm();
  if (!(len > 1e-9)) return std::nullopt;
  return std::make_pair(Eigen::Vector3d(n3 / len), offset / len);
}

template class WorldSlices<3>;
template class WorldSlices<4>;
template class WorldSlices<5>;
template class WorldSlices<6>;

}  // namespace wedge::slicing
