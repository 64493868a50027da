// World step, body construction and diagnostics; explicitly instantiated for N = 2..6.
#include "wedge/world.hpp"

#include <Eigen/LU>
#include <cmath>
#include <cstring>

#include "wedge/error.hpp"
#include "wedge/ga/exp_log.hpp"
#include "wedge/ga/factorize.hpp"

namespace wedge {

namespace {
template <class M>
bool finite(const M& m) {
  return m.allFinite();
}
}  // namespace

template <int N>
Body<N> make_body(const BodyDef<N>& def) {
  const std::string who = def.name.empty() ? std::string("body") : "body '" + def.name + "'";
  if (!finite(def.position) || !finite(def.velocity) || !def.rotor.all_finite() ||
      !def.angular_velocity.all_finite())
    throw Error(who + ": position, rotor and velocities must be finite");
  const Rotor<N> rr = def.rotor * reverse(def.rotor);
  if ((rr - Rotor<N>::identity()).norm() > 1e-6)
    throw Error(who + ": rotor is not a rotation (R ~R differs from 1 by " +
                std::to_string((rr - Rotor<N>::identity()).norm()) + ")");
  if (!(def.linear_drag >= 0.0) || !(def.angular_drag >= 0.0) || !std::isfinite(def.linear_drag) ||
      !std::isfinite(def.angular_drag))
    throw Error(who + ": drag coefficients must be finite and >= 0");
  Body<N> b;
  b.type = def.type;
  b.rotor = repair(def.rotor);
  b.local_center = def.local_center;
  b.center = def.position + rotate(b.rotor, def.local_center);
  b.linear_drag = def.linear_drag;
  b.angular_drag = def.angular_drag;
  if (def.type == BodyType::Static) return b;  // never moves: velocities stay zero
  b.velocity = def.velocity;
  b.angular_velocity = def.angular_velocity;
  if (def.type == BodyType::Kinematic) return b;
  if (!(def.mass > 0.0) || !std::isfinite(def.mass))
    throw Error(who + ": mass must be positive and finite (got " + std::to_string(def.mass) + ")");
  if (!finite(def.inertia) || (def.inertia - def.inertia.transpose()).norm() > 1e-9 * def.inertia.norm())
    throw Error(who + ": inertia must be a finite symmetric matrix");
  Eigen::SelfAdjointEigenSolver<BivMat<N>> eig(def.inertia, Eigen::EigenvaluesOnly);
  if (!(eig.eigenvalues()[0] > 1e-12 * eig.eigenvalues()[kBiv<N> - 1]))
    throw Error(who + ": inertia must be positive definite");
  b.mass = def.mass;
  b.inv_mass = 1.0 / def.mass;
  b.inertia = 0.5 * (def.inertia + def.inertia.transpose());
  b.inv_inertia = b.inertia.inverse();
  b.inv_inertia = 0.5 * (b.inv_inertia + b.inv_inertia.transpose()).eval();
  return b;
}

template <int N>
Bivector<N> gyroscopic_step(const BivMat<N>& inertia, const Bivector<N>& w, double h, GyroscopicMethod method) {
  const bool euler = method == GyroscopicMethod::ImplicitEuler;
  const double t = euler ? 1.0 : 0.5;
  const int iterations = euler ? 1 : 2;
  Bivector<N> w2 = w;
  for (int i = 0; i < iterations; ++i) {
    const Bivector<N> m = euler ? w2 : (w + w2) * 0.5;
    const Bivector<N> im = Bivector<N>::from(inertia * m.c);
    const Bivector<N> g = Bivector<N>::from(inertia * (w2 - w).c) - commutator(m, im) * h;
    const BivMat<N> jac = inertia - (t * h) * (commutator_matrix(m) * inertia - commutator_matrix(im));
    w2 -= Bivector<N>::from(jac.partialPivLu().solve(g.c));
  }
  if (!euler) {
    const double e0 = w.c.dot(inertia * w.c), e1 = w2.c.dot(inertia * w2.c);
    if (e1 > e0) w2 *= std::sqrt(e0 / e1);
  }
  return w2;
}

template <int N>
World<N>::World(const WorldSettings<N>& settings) : settings_(settings) {
  if (!settings_.gravity.allFinite()) throw Error("gravity must be finite");
  if (settings_.rotor_repair_interval < 1) throw Error("rotor_repair_interval must be >= 1");
}

template <int N>
BodyId World<N>::add_body(const BodyDef<N>& def) {
  bodies_.push_back(make_body(def));
  names_.push_back(def.name);
  return BodyId{std::uint32_t(bodies_.size() - 1)};
}

template <int N>
void World<N>::apply_force(BodyId id, const Vec<N>& f) {
  bodies_[id.index].force += f;
}
template <int N>
void World<N>::apply_force_at(BodyId id, const Vec<N>& f, const Vec<N>& p) {
  Body<N>& b = bodies_[id.index];
  b.force += f;
  b.torque += outer<N>(p - b.center, f);
}
template <int N>
void World<N>::apply_torque(BodyId id, const Bivector<N>& t) {
  bodies_[id.index].torque += t;
}
template <int N>
void World<N>::apply_impulse_at(BodyId id, const Vec<N>& j, const Vec<N>& p) {
  Body<N>& b = bodies_[id.index];
  if (!b.is_dynamic()) return;
  b.velocity += j * b.inv_mass;
  b.angular_velocity.c += b.world_inv_inertia() * (wedge_matrix<N>(p - b.center) * j);
}
template <int N>
void World<N>::apply_angular_impulse(BodyId id, const Bivector<N>& j) {
  Body<N>& b = bodies_[id.index];
  if (!b.is_dynamic()) return;
  b.angular_velocity.c += b.world_inv_inertia() * j.c;
}

template <int N>
void World<N>::step(double h) {
  integrate_velocities(h);
  integrate_positions(h);
  clear_forces();
  ++steps_;
  time_ = double(steps_) * h;
}

// Symplectic Euler, velocity half: v += h (g + F/m), w += h I'^-1 tau, then the gyroscopic term
// implicitly in the body frame, then drag as an implicit decay 1/(1 + h c) (stable for any h).
template <int N>
void World<N>::integrate_velocities(double h) {
  for (Body<N>& b : bodies_) {
    if (!b.is_dynamic()) continue;
    b.velocity += h * (settings_.gravity + b.force * b.inv_mass);
    // In the body frame, where the inertia is constant: w_b += h I^-1 ~R tau R, then the gyroscopic step.
    Bivector<N> wb = rotate_inverse(b.rotor, b.angular_velocity);
    wb.c += h * (b.inv_inertia * rotate_inverse(b.rotor, b.torque).c);
    if (settings_.gyroscopic) wb = gyroscopic_step<N>(b.inertia, wb, h, settings_.gyroscopic_method);
    b.angular_velocity = rotate(b.rotor, wb);
    b.velocity *= 1.0 / (1.0 + h * b.linear_drag);
    b.angular_velocity *= 1.0 / (1.0 + h * b.angular_drag);
  }
}

// Position half, with the new velocities: x += h v, R <- exp(-h w/2) R (exact for constant w over the
// step), and every rotor_repair_interval steps R is rebuilt from unit-vector factors.
template <int N>
void World<N>::integrate_positions(double h) {
  const bool repair_now = (steps_ + 1) % settings_.rotor_repair_interval == 0;
  for (Body<N>& b : bodies_) {
    if (b.type == BodyType::Static) continue;
    b.center += h * b.velocity;
    b.rotor = exp<N>(b.angular_velocity * (-0.5 * h)) * b.rotor;
    if (repair_now) b.rotor = repair(b.rotor);
  }
}

template <int N>
void World<N>::clear_forces() {
  for (Body<N>& b : bodies_) {
    b.force.setZero();
    b.torque = Bivector<N>{};
  }
}

template <int N>
double World<N>::kinetic_energy() const {
  double e = 0.0;
  for (const Body<N>& b : bodies_) e += b.kinetic_energy();
  return e;
}
template <int N>
double World<N>::potential_energy() const {
  double e = 0.0;
  for (const Body<N>& b : bodies_)
    if (b.is_dynamic()) e -= b.mass * settings_.gravity.dot(b.center);
  return e;
}
template <int N>
Vec<N> World<N>::linear_momentum() const {
  Vec<N> p = Vec<N>::Zero();
  for (const Body<N>& b : bodies_)
    if (b.is_dynamic()) p += b.mass * b.velocity;
  return p;
}
template <int N>
Bivector<N> World<N>::angular_momentum() const {
  Bivector<N> l;
  for (const Body<N>& b : bodies_)
    if (b.is_dynamic()) l += outer<N>(b.center, b.mass * b.velocity) + b.angular_momentum();
  return l;
}

template <int N>
std::uint64_t World<N>::state_hash() const {
  std::uint64_t hash = 14695981039346656037ull;
  auto mix = [&hash](const double* data, int count) {
    unsigned char bytes[sizeof(double)];
    for (int i = 0; i < count; ++i) {
      const double v = data[i] == 0.0 ? 0.0 : data[i];  // -0 and +0 hash alike
      std::memcpy(bytes, &v, sizeof v);
      for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
    }
  };
  for (const Body<N>& b : bodies_) {
    mix(b.center.data(), N);
    mix(b.rotor.c.data(), kEven<N>);
    mix(b.velocity.data(), N);
    mix(b.angular_velocity.c.data(), kBiv<N>);
  }
  return hash;
}

#define WEDGE_INSTANTIATE(N)                                                                    \
  template Body<N> make_body<N>(const BodyDef<N>&);                                            \
  template Bivector<N> gyroscopic_step<N>(const BivMat<N>&, const Bivector<N>&, double, GyroscopicMethod); \
  template class World<N>;
WEDGE_INSTANTIATE(2)
WEDGE_INSTANTIATE(3)
WEDGE_INSTANTIATE(4)
WEDGE_INSTANTIATE(5)
WEDGE_INSTANTIATE(6)
#undef WEDGE_INSTANTIATE

}  // namespace wedge
