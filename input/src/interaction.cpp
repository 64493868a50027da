// The input layer's stages (interaction.hpp). Every loop runs over hands in index order and over the
// World's event arrays in their sorted order, so a replay is a pure function of its input frames.
#include "wedge/input/interaction.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "wedge/error.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/frames.hpp"
#include "wedge/dimensions.hpp"
#include "wedge/softness.hpp"

namespace wedge::input {

namespace {
void require(bool ok, const std::string& what) {
  if (!ok) throw Error("interaction settings: " + what);
}
bool positive(double x) { return x > 0.0 && std::isfinite(x); }

// The rotor of a rotation matrix (columns: the turned axes), by the paper's successive simple rotors.
template <int N>
Rotor<N> rotor_of(const Mat<N>& m) {
  return rotor_between_frames<N>(Mat<N>::Identity(), m);
}
}  // namespace

double pulse_amplitude(double approach_speed, double full_speed, double min_amplitude) {
  const double s = std::clamp(approach_speed / full_speed, 0.0, 1.0);
  return min_amplitude + (1.0 - min_amplitude) * s;
}

template <int N>
Vec<N> gravity_from_device(const Eigen::Vector3d& direction, double magnitude, bool tilt_on, double tilt_degrees) {
  Vec<N> d = Vec<N>::Zero();
  for (int i = 0; i < std::min(N, 3); ++i) d[i] = direction[i];
  const double length = d.norm();
  if (!(length > 0.0)) return Vec<N>::Zero();
  d /= length;
  if (tilt_on) {
    if (N < 4) throw Error("the gravity tilt turns gravity toward w, which a " + std::to_string(N) + "D world lacks");
    const double a = tilt_degrees * M_PI / 180.0;
    d *= std::cos(a);
    d[N - 1] = std::sin(a);
  }
  return magnitude * d;
}

template <int N>
Interaction<N>::Interaction(World<N>& world, const InteractionSettings<N>& s) : world_(world), settings_(s) {
  require(all_finite(s.tracking.origin) && positive(s.tracking.scale), "tracking origin finite and scale > 0");
  require(s.squeeze_off >= 0.0 && s.squeeze_off < s.squeeze_on && s.squeeze_on <= 1.0,
          "0 <= squeeze_off < squeeze_on <= 1");
  require(s.grab_radius >= 0.0 && std::isfinite(s.grab_radius), "grab_radius finite and >= 0 (m)");
  require(positive(s.follow_frequency) && positive(s.turn_frequency), "follow and turn frequencies > 0 (Hz)");
  require(s.follow_damping_ratio >= 0.0 && s.turn_damping_ratio >= 0.0 && std::isfinite(s.follow_damping_ratio) &&
              std::isfinite(s.turn_damping_ratio),
          "damping ratios finite and >= 0");
  require(positive(s.follow_max_acceleration) && positive(s.turn_max_acceleration), "acceleration limits > 0");
  require(positive(s.pulse_full_speed) && positive(s.pulse_duration) && s.pulse_min_interval >= 0.0 &&
              s.pulse_min_amplitude >= 0.0 && s.pulse_min_amplitude <= 1.0,
          "pulse settings (full speed and duration > 0, interval >= 0, min amplitude in [0, 1])");
  require(s.gravity_tilt_degrees >= 0.0 && s.gravity_tilt_degrees <= 90.0, "gravity_tilt in [0, 90] degrees");
  require(!s.gravity_tilt_on || N >= 4, "gravity_tilt_on needs a w axis (4D and up)");
  require(positive(s.gravity_time_constant) && positive(s.gravity_time_constant_accel_only),
          "gravity time constants > 0 (s)");
  tilt_on_ = s.gravity_tilt_on;
  gravity_magnitude_ = world.gravity().norm();
  events_.reserve(2 * kHandCount);
  pulses_.reserve(8);
}

template <int N>
void Interaction<N>::set_tracking_origin(const Vec<N>& origin) {
  if (!all_finite(origin)) throw Error("set_tracking_origin: the origin must be finite");
  const Vec<N> change = origin - settings_.tracking.origin;
  settings_.tracking.origin = origin;
  for (HandState& hs : hands_) hs.point += change;  // (the next frame's difference is the hand's own motion)
}

template <int N>
std::optional<BodyId> Interaction<N>::held(int hand) const {
  return hands_[hand].holding ? std::optional<BodyId>(hands_[hand].body) : std::nullopt;
}
template <int N>
std::optional<GrabId> Interaction<N>::grab(int hand) const {
  return hands_[hand].holding ? std::optional<GrabId>(hands_[hand].grab) : std::nullopt;
}

template <int N>
void Interaction<N>::before_step(const InputFrame& frame, double h) {
  if (!(h > 0.0) || !std::isfinite(frame.t)) throw Error("before_step: h must be > 0 and t finite");
  events_.clear();
  t_ = frame.t;
  h_ = h;
  update_gravity(frame);
  track_hands(frame, h);
  grab_and_release(frame);
  drive_held(h);
}

// Each accelerometer sample goes through the filter at its own time; the estimate after the last one
// sets the world's gravity. The filter's time constant is chosen by the first sample: with a gyro the
// slow one, without it the quick one (nothing else removes the hand's shaking).
template <int N>
void Interaction<N>::update_gravity(const InputFrame& frame) {
  if (frame.motion.empty()) return;
  for (const MotionSample& m : frame.motion) {
    if (!filter_) {
      GravityFilterSettings fs;
      fs.time_constant =
          m.has_rotation_rate ? settings_.gravity_time_constant : settings_.gravity_time_constant_accel_only;
      filter_.emplace(fs);
      last_motion_t_ = m.t;
    }
    filter_->update(m.acceleration, m.has_rotation_rate ? m.rotation_rate : Eigen::Vector3d::Zero(),
                    std::max(m.t - last_motion_t_, 0.0));
    last_motion_t_ = m.t;
    tilt_on_ = m.tilt || settings_.gravity_tilt_on;
  }
  const Vec<N> g = gravity_from_device<N>(filter_->direction(), gravity_magnitude_, tilt_on_,
                                          settings_.gravity_tilt_degrees);
  if (g.squaredNorm() > 0.0) world_.set_gravity(g);
}

// Hand points and N-D frames. A turn of the controller since the last frame (in its own axes) is applied
// to the hand's frame in the controller's axes: as it is, or in 4D mode, a turn by phi about the
// controller's x, y or z axis becomes a turn by phi carrying that axis toward +w (the plane of the axis
// and w). The hand's velocity and spin are the differences over the step (the drives' damping targets).
template <int N>
void Interaction<N>::track_hands(const InputFrame& frame, double h) {
  for (int k = 0; k < kHandCount; ++k) {
    HandState& hs = hands_[k];
    const HandInput& in = frame.hands[k];
    if (!in.tracked) {
      hs.velocity.setZero();
      hs.spin = Bivector<N>{};
      continue;
    }
    const Vec<N> point = settings_.tracking.point(in.position);
    const Eigen::Quaterniond q = in.orientation.normalized();
    if (!hs.tracked) {
      hs.tracked = true;
      hs.point = point;
      hs.frame = rotor_of<N>(TrackingSpace<N>::frame(q));
      hs.last_orientation = q;
      hs.velocity.setZero();
      hs.spin = Bivector<N>{};
      continue;
    }
    const Eigen::Quaterniond delta = hs.last_orientation.conjugate() * q;  // in the controller's axes
    Rotor<N> turn = Rotor<N>::identity();
    if (in.mode4d && N >= 4) {
      const Eigen::AngleAxisd aa(delta);
      const Eigen::Vector3d phi = aa.angle() * aa.axis();
      Bivector<N> plane;
      for (int i = 0; i < 3; ++i) plane.c[Bivector<N>::index(i, N - 1)] = phi[i];
      turn = exp<N>(plane * -0.5);  // exp(-B/2) with B_{iw} = phi_i turns e_i toward e_w by phi_i
    } else {
      turn = rotor_of<N>(TrackingSpace<N>::frame(delta));
    }
    Rotor<N> next = hs.frame * turn;
    next *= 1.0 / next.norm();
    // The spin w with exp(-h w / 2) = next ~frame, to second order: w = -2 <next ~frame>_2 / h.
    Rotor<N> d = next * reverse(hs.frame);
    if (d.scalar() < 0.0) d *= -1.0;
    hs.spin = d.bivector() * (-2.0 / h);
    hs.velocity = (point - hs.point) / h;
    hs.point = point;
    hs.frame = next;
    hs.last_orientation = q;
  }
}

template <int N>
void Interaction<N>::grab_and_release(const InputFrame& frame) {
  for (int k = 0; k < kHandCount; ++k) {
    HandState& hs = hands_[k];
    const HandInput& in = frame.hands[k];
    const bool was = hs.pressed;
    if (!in.tracked)
      hs.pressed = false;
    else if (in.squeeze >= settings_.squeeze_on)
      hs.pressed = true;
    else if (in.squeeze <= settings_.squeeze_off)
      hs.pressed = false;
    if (was && !hs.pressed && hs.holding) release(k);
    if (!was && hs.pressed && !hs.holding) {
      const std::optional<BodyPointHit<N>> hit = world_.query_point(hs.point, settings_.grab_radius, false);
      if (!hit || !world_.body(hit->body).is_dynamic()) continue;  // (kinematic bodies are not grabbed)
      const Body<N>& b = world_.body(hit->body);
      const Vec<N> at = hit->inside ? hs.point : hit->closest;
      GrabDef<N> def;
      def.body = hit->body;
      def.local_point = rotate_inverse(b.rotor, Vec<N>(at - b.position()));
      def.target = hs.point;
      def.target_velocity = hs.velocity;
      def.frequency = settings_.follow_frequency;
      def.damping_ratio = settings_.follow_damping_ratio;
      def.max_acceleration = settings_.follow_max_acceleration;
      hs.grab = world_.add_grab(def);
      hs.body = hit->body;
      hs.holding = true;
      hs.offset = reverse(hs.frame) * b.rotor;
      InteractionEvent<N>& e = new_event(InteractionEvent<N>::Kind::Grab, k, hit->body);
      e.point = at;
      e.local_point = def.local_point;
    }
  }
}

template <int N>
InteractionEvent<N>& Interaction<N>::new_event(typename InteractionEvent<N>::Kind kind, int hand, BodyId body) {
  InteractionEvent<N>& e = events_.emplace_back();
  e.kind = kind;
  e.hand = hand;
  e.body = body;
  e.t = t_;
  e.step = world_.step_count();
  return e;
}

template <int N>
void Interaction<N>::release(int hand) {
  HandState& hs = hands_[hand];
  world_.remove_grab(hs.grab);
  hs.holding = false;
  const Body<N>& b = world_.body(hs.body);
  InteractionEvent<N>& e = new_event(InteractionEvent<N>::Kind::Release, hand, hs.body);
  e.velocity = b.velocity;
  e.angular_velocity = b.angular_velocity;
}

// The grab spring pulls the grab point to the hand (solved with the contacts, in the step); the turn is
// a PD torque toward the hand's frame composed with the offset taken at the grab. Its error is the
// paper's: the rotor carrying the body's frame onto the target frame by successive simple rotors, whose
// bivector part B gives the plane and angle (theta = -2 B to second order; the shorter way round).
template <int N>
void Interaction<N>::drive_held(double h) {
  const Softness turn = make_softness(settings_.turn_frequency, settings_.turn_damping_ratio, h);
  for (int k = 0; k < kHandCount; ++k) {
    HandState& hs = hands_[k];
    if (!hs.holding) continue;
    world_.set_grab_target(hs.grab, hs.point, hs.velocity);
    const Body<N>& b = world_.body(hs.body);
    const Rotor<N> target = hs.frame * hs.offset;
    Rotor<N> error = rotor_between_frames<N>(to_matrix(b.rotor), to_matrix(target));
    if (error.scalar() < 0.0) error *= -1.0;
    const Bivector<N> theta = error.bivector() * -2.0;
    Bivector<N> dw = (theta * turn.bias_rate - (b.angular_velocity - hs.spin)) * turn.mass_scale;
    const double limit = settings_.turn_max_acceleration * h;
    if (dw.norm() > limit) dw *= limit / dw.norm();
    world_.apply_torque(hs.body, Bivector<N>::from(b.world_inertia() * dw.c) * (1.0 / h));
  }
}

template <int N>
void Interaction<N>::after_step() {
  pulses_.clear();
  const std::int64_t step = world_.step_count() - 1;
  // A world's first step reports the contacts the scene starts with as beginning: a body held from the
  // start while resting on something has hit nothing.
  if (step == 0) return;
  for (const ContactBeginEvent<N>& e : world_.contact_begin_events()) {
    for (int k = 0; k < kHandCount; ++k) {
      HandState& hs = hands_[k];
      if (!hs.holding || !(hs.body == e.a || hs.body == e.b)) continue;
      if (t_ - hs.last_pulse < settings_.pulse_min_interval) {
        ++dropped_pulses_;
        continue;
      }
      hs.last_pulse = t_;
      HapticPulse<N> p;
      p.hand = k;
      p.amplitude = pulse_amplitude(e.approach_speed, settings_.pulse_full_speed, settings_.pulse_min_amplitude);
      p.duration = settings_.pulse_duration;
      p.held = hs.body;
      p.other = hs.body == e.a ? e.b : e.a;
      p.point = e.point;
      p.approach_speed = e.approach_speed;
      p.t = t_;
      p.step = step;
      pulses_.push_back(p);
    }
  }
}

#define WEDGE_INSTANTIATE(N)                                                                            \
  template class Interaction<N>;                                                                        \
  template Vec<N> gravity_from_device<N>(const Eigen::Vector3d&, double, bool, double);
WEDGE_FOR_EACH_DIM(WEDGE_INSTANTIATE)
#undef WEDGE_INSTANTIATE

}  // namespace wedge::input
