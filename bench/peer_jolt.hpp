// Jolt Physics (jrouwe/JoltPhysics) as a peer of wedge_bench_peers, built from a local source checkout
// (-DWEDGE_JOLT_DIR=...; never vendored, never needed by CI) with Jolt's own CMake defaults (AVX2 and the
// rest where the compiler has them) but without its profiler and debug renderer, as in Jolt's
// Distribution build. The boxes come as plain numbers (BoxPose) copied from a Wedge 3D world
// (bench_peers.cpp), so that this header includes neither Jolt nor Eigen: see peer_jolt.cpp. Everything
// else is Jolt's default: 10 velocity and 2 position iterations, one collision step per update, box shapes
// with their default convex radius, friction combined as the geometric mean (0.6 for 0.6 and 0.6, as
// Wedge's), restitution 0. One thread (JobSystemSingleThreaded), or Jolt's JobSystemThreadPool with
// threads - 1 workers beside the calling thread (as Jolt's samples run it). The ground is a static box
// of half size 500 x 1 x 500 m under y = 0.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace wedge::bench {

struct BoxPose {
  double position[3];  // m
  double rotation[4];  // unit quaternion w, x, y, z
};

struct JoltSettings {
  double half = 0.5;        // m, every box's half extent
  double density = 1000.0;  // kg/m^3
  double friction = 0.6;
  double gravity = 9.81;    // m/s^2 along -y
  double dt = 1.0 / 60.0;   // s per step
  bool sleep = false;
  int threads = 1;          // the calling thread included
};

class JoltScene {
 public:
  JoltScene(const std::vector<BoxPose>& boxes, const JoltSettings& settings);
  ~JoltScene();
  JoltScene(const JoltScene&) = delete;
  JoltScene& operator=(const JoltScene&) = delete;

  void step();
  double max_speed() const;        // m/s, the fastest box's centre
  int moving(double speed) const;  // boxes faster than `speed`
  double height(std::size_t k) const;  // m, box k's centre's y
  std::size_t count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wedge::bench
