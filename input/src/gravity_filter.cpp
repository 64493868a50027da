#include "wedge/input/gravity_filter.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "wedge/error.hpp"
#include "wedge/ga/types.hpp"

namespace wedge::input {

GravityFilter::GravityFilter(const GravityFilterSettings& settings) : settings_(settings) {
  if (!(settings_.time_constant > 0.0) || !std::isfinite(settings_.time_constant))
    throw Error("GravityFilter: time_constant must be finite and > 0 (s)");
}

void GravityFilter::update(const Eigen::Vector3d& acceleration, const Eigen::Vector3d& rotation_rate, double dt) {
  if (!all_finite(acceleration) || !all_finite(rotation_rate) || !std::isfinite(dt) || dt < 0.0)
    throw Error("GravityFilter::update: acceleration, rotation rate and dt must be finite, dt >= 0");
  if (!ready_) {
    gravity_ = acceleration;
    ready_ = true;
    return;
  }
  const double rate = rotation_rate.norm();
  if (rate > 0.0) gravity_ = Eigen::AngleAxisd(-rate * dt, rotation_rate / rate) * gravity_;
  gravity_ += (1.0 - std::exp(-dt / settings_.time_constant)) * (acceleration - gravity_);
}

Eigen::Vector3d GravityFilter::direction() const {
  const double n = gravity_.norm();
  return n > 0.0 ? Eigen::Vector3d(gravity_ / n) : Eigen::Vector3d::Zero();
}

}  // namespace wedge::input
