// Where a step's time went: wall-clock seconds per stage of the last World::step (World::profile()),
// as Box2D v3's b2Profile and Jolt's profiler report theirs. The clock is read between stages and
// never by the simulation, so the profile changes no result. With the paper's solver, solve is
// process_collisions, integrate_velocities and process_contacts, and relax and finish stay 0.
#pragma once

#include <chrono>

namespace wedge {

struct StepProfile {
  double step = 0.0;                 // s, the whole step
  double broad_phase = 0.0;          // s, the bodies' boxes moved and the pair list merged
  double narrow_phase = 0.0;         // s, the pairs' manifolds, collided or recycled
  double constraints = 0.0;          // s, built, coloured, prepared and packed into lanes
  double solve = 0.0;                // s, every sub-step's velocity update, warm start and solve pass
  double integrate_positions = 0.0;  // s, every sub-step's position update
  double relax = 0.0;                // s, every sub-step's relax pass
  double finish = 0.0;               // s, impulses kept, restitution, velocities stored
  double continuous = 0.0;           // s, fast bodies swept against static ones
  double islands = 0.0;              // s, islands and sleep
  double events = 0.0;               // s, contact begin and end events
};

// Laps of a steady clock: lap() gives the seconds since the last lap (or since construction).
class StageClock {
 public:
  StageClock() : last_(std::chrono::steady_clock::now()) {}
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_;
};

}  // namespace wedge
