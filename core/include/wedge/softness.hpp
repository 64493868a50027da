// A soft constraint's spring: a frequency and a damping ratio turned into the coefficients one step of
// length h applies (the "soft step" of Catto 2011, Box2D v3's b2MakeSoft). Contacts, grabs and the input
// layer's turn drive all use it.
//
// With w = 2 pi f, a1 = 2 z + h w and a2 = h w a1, a constraint with error C, rigid effective mass and
// accumulated impulse j_acc applies, per pass,
//   j = -mass_scale m (v + bias_rate C) - impulse_scale j_acc   (m = the rigid effective mass),
//   bias_rate = w / a1,  mass_scale = a2 / (1 + a2),  impulse_scale = 1 / (1 + a2),
// which is implicit Euler on a damped spring of natural frequency f and damping ratio z, whatever the
// bodies' masses: stable at any step. A frequency of 0 means rigid: no bias, full mass, no relaxation.
#pragma once

#include <numbers>

namespace wedge {

struct Softness {
  double bias_rate = 0.0;      // 1/s: the velocity asked for per unit of error
  double mass_scale = 1.0;     // the share of the rigid impulse applied
  double impulse_scale = 0.0;  // the share of the accumulated impulse taken back each pass
};

// frequency in Hz (>= 0; 0 = rigid), damping_ratio >= 0 (1 = critical), h in s (> 0).
inline Softness make_softness(double frequency, double damping_ratio, double h) {
  if (frequency <= 0.0) return {0.0, 1.0, 0.0};
  const double omega = 2.0 * std::numbers::pi * frequency;
  const double a1 = 2.0 * damping_ratio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return {omega / a1, a2 * a3, a3};
}

}  // namespace wedge
