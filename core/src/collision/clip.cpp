// Face clipping in N dimensions and manifold reduction.
#include <algorithm>
#include <cmath>

#include "collision/narrow.hpp"
#include "wedge/dimensions.hpp"

namespace wedge::collision {
namespace {

// Cap on the points of a face while it is clipped: far above any face of the shapes we ship (a 5-cube
// facet of a 6-cube clipped by ten planes), it only bounds the work on pathological input.
constexpr std::size_t kMaxClipPoints = 1024;

int shared(const std::uint64_t a_own, const std::uint64_t a_clip, const std::uint64_t b_own, const std::uint64_t b_clip) {
  return bit_count(a_own & b_own) + bit_count(a_clip & b_clip);
}

}  // namespace

template <int N>
void clip_face(std::vector<ClipPoint<N>>& face, const std::vector<Vec<N>>& normals, const std::vector<double>& offsets,
               double eps) {
  // Scratch kept per thread: the narrow phase runs this for every face pair of every step.
  thread_local std::vector<ClipPoint<N>> next;
  thread_local std::vector<double> dist;
  for (std::size_t p = 0; p < normals.size() && !face.empty(); ++p) {
    const std::uint64_t bit = std::uint64_t(1) << (p % 64);  // more than 64 planes alias: extra points only
    dist.resize(face.size());
    bool any_out = false;
    for (std::size_t i = 0; i < face.size(); ++i) {
      dist[i] = normals[p].dot(face[i].x) - offsets[p];
      any_out |= dist[i] > eps;
    }
    if (!any_out) {  // nothing to cut; points on the plane still learn that they are
      for (std::size_t i = 0; i < face.size(); ++i)
        if (dist[i] >= -eps) face[i].clip |= bit;
      continue;
    }
    next.clear();
    for (std::size_t i = 0; i < face.size(); ++i) {
      if (dist[i] > eps) continue;
      ClipPoint<N> q = face[i];
      if (dist[i] >= -eps) q.clip |= bit;
      next.push_back(q);
    }
    for (std::size_t i = 0; i < face.size(); ++i) {
      if (!(dist[i] < -eps)) continue;
      for (std::size_t j = 0; j < face.size() && next.size() < kMaxClipPoints; ++j) {
        if (!(dist[j] > eps)) continue;
        if (shared(face[i].own, face[i].clip, face[j].own, face[j].clip) < N - 2) continue;
        const double t = dist[i] / (dist[i] - dist[j]);
        next.push_back({face[i].x + t * (face[j].x - face[i].x), face[i].own & face[j].own,
                        (face[i].clip & face[j].clip) | bit});
      }
    }
    face.swap(next);
  }
}

template <int N>
void face_contact(std::vector<ClipPoint<N>>& incident, const std::vector<Vec<N>>& side_normals,
                  const std::vector<double>& side_offsets, const Vec<N>& ref_normal, double ref_offset,
                  double margin, double scale, std::uint64_t feature_id, std::vector<ContactPoint<N>>& out) {
  clip_face<N>(incident, side_normals, side_offsets, 1e-12 * scale);
  for (const ClipPoint<N>& c : incident) {
    const double depth = ref_offset - ref_normal.dot(c.x);
    if (depth < -margin) continue;
    // Halfway between the incident point and its projection on the reference face.
    out.push_back({c.x + (0.5 * depth) * ref_normal, depth, mix_id(mix_id(feature_id, c.own), c.clip)});
  }
}

template <int N>
void reduce_into(const std::vector<ContactPoint<N>>& points, Manifold<N>& m) {
  m.count = 0;
  if (points.empty()) return;
  if (int(points.size()) <= kMaxManifoldPoints<N>) {
    for (const ContactPoint<N>& p : points) m.add(p);
    return;
  }
  std::size_t first = 0;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i].depth > points[first].depth) first = i;
  thread_local std::vector<double> gap;  // distance to the nearest kept point (kept: no allocation per call)
  gap.assign(points.size(), INFINITY);
  std::size_t pick = first;
  while (m.count < kMaxManifoldPoints<N>) {
    m.add(points[pick]);
    gap[pick] = -1.0;
    std::size_t far = points.size();
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (gap[i] < 0.0) continue;
      gap[i] = std::min(gap[i], (points[i].point - points[pick].point).norm());
      if (far == points.size() || gap[i] > gap[far]) far = i;
    }
    if (far == points.size() || gap[far] <= 0.0) break;  // only duplicates left
    pick = far;
  }
}

#define WEDGE_INSTANTIATE(N)                                                                                       \
  template void clip_face<N>(std::vector<ClipPoint<N>>&, const std::vector<Vec<N>>&, const std::vector<double>&,    \
                             double);                                                                              \
  template void face_contact<N>(std::vector<ClipPoint<N>>&, const std::vector<Vec<N>>&, const std::vector<double>&, \
                                const Vec<N>&, double, double, double, std::uint64_t,                               \
                                std::vector<ContactPoint<N>>&);                                                     \
  template void reduce_into<N>(const std::vector<ContactPoint<N>>&, Manifold<N>&);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::collision
