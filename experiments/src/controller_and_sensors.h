#pragma once
// The dVRK side of the loop: a discrete PID position controller and the
// sensors it reads (encoders, effort from motor current, a tracker).

#include <Eigen/Core>
#include <boost/random/mersenne_twister.hpp>
#include <boost/random/normal_distribution.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "pliant/experiments/scenario.h"

namespace pliant::experiments::detail {

inline double Quantise(double value, double step) {
  return step > 0.0 ? step * std::round(value / step) : value;
}

/// u = Kp·e + I + Kd·(v_cmd − v), saturated; I integrates Ki·e with a limit
/// (anti-windup); v is the encoder's difference, low-pass filtered as the
/// dVRK filters its velocity estimate.
class PidController {
 public:
  PidController(const ControllerSettings& s, const Eigen::Vector2d& command_rad,
                const Eigen::Vector2d& encoder_rad, const Eigen::Vector2d& integral_nm)
      : s_(s),
        period_s_(1.0 / s.rate_hz),
        alpha_(1.0 - std::exp(-2.0 * 3.14159265358979323846 * s.velocity_filter_hz * period_s_)),
        previous_command_(command_rad),
        previous_encoder_(encoder_rad),
        integral_nm_(integral_nm.cwiseMax(-s.integral_limit_nm).cwiseMin(s.integral_limit_nm)) {}

  Eigen::Vector2d Update(const Eigen::Vector2d& command_rad, const Eigen::Vector2d& encoder_rad) {
    velocity_ += alpha_ * ((encoder_rad - previous_encoder_) / period_s_ - velocity_);
    const Eigen::Vector2d command_velocity = (command_rad - previous_command_) / period_s_;
    previous_encoder_ = encoder_rad;
    previous_command_ = command_rad;
    const Eigen::Vector2d error = command_rad - encoder_rad;
    integral_nm_ += (s_.ki_nm_per_rad_s.cwiseProduct(error) * period_s_);
    integral_nm_ = integral_nm_.cwiseMax(-s_.integral_limit_nm).cwiseMin(s_.integral_limit_nm);
    const Eigen::Vector2d u = s_.kp_nm_per_rad.cwiseProduct(error) + integral_nm_ +
                              s_.kd_nm_s_per_rad.cwiseProduct(command_velocity - velocity_);
    return u.cwiseMax(-s_.effort_limit_nm).cwiseMin(s_.effort_limit_nm);
  }

  const Eigen::Vector2d& velocity_rad_s() const { return velocity_; }

 private:
  ControllerSettings s_;
  double period_s_;
  double alpha_;
  Eigen::Vector2d previous_command_;
  Eigen::Vector2d previous_encoder_;
  Eigen::Vector2d integral_nm_;
  Eigen::Vector2d velocity_ = Eigen::Vector2d::Zero();
};

/// Encoder and effort sampling. The effort is the controller output plus
/// Gaussian noise, quantised to the current ADC step, and optionally delayed
/// against the encoder (linear interpolation between controller samples).
class Sensors {
 public:
  Sensors(const SensorSettings& s, double period_s, std::uint64_t seed)
      : s_(s), rng_(seed), effort_noise_(0.0, 1.0), tracker_noise_(0.0, 1.0) {
    delay_periods_ = s.effort_delay_s / period_s;
    history_.assign(static_cast<std::size_t>(std::ceil(delay_periods_)) + 2,
                    Eigen::Vector2d::Constant(std::nan("")));
  }

  Eigen::Vector2d Encoder(const Eigen::Vector2d& angle_rad) const {
    return {Quantise(angle_rad[0], s_.encoder_count_rad),
            Quantise(angle_rad[1], s_.encoder_count_rad)};
  }
  double Depth(double depth_m) const { return Quantise(depth_m, s_.depth_count_m); }

  Eigen::Vector2d Effort(const Eigen::Vector2d& controller_output_nm) {
    Eigen::Vector2d measured;
    for (int j = 0; j < 2; ++j) {
      measured[j] = Quantise(controller_output_nm[j] + s_.effort_noise_sd_nm * effort_noise_(rng_),
                             s_.effort_count_nm);
    }
    // history_[0] is now, history_[k] k periods ago; before the first samples
    // reach the delay the oldest available stands in.
    for (std::size_t k = history_.size() - 1; k > 0; --k) history_[k] = history_[k - 1];
    history_[0] = measured;
    ++count_;
    const double lag = std::min(delay_periods_, double(count_ - 1));
    const auto k = static_cast<std::size_t>(std::floor(lag));
    const double w = lag - double(k);
    return w == 0.0 ? history_[k] : (1.0 - w) * history_[k] + w * history_[k + 1];
  }

  Eigen::Vector2d Tracker(const Eigen::Vector2d& true_angle_rad) {
    return true_angle_rad +
           s_.tracker_noise_sd_rad * Eigen::Vector2d(tracker_noise_(rng_), tracker_noise_(rng_));
  }

 private:
  SensorSettings s_;
  boost::random::mt19937_64 rng_;
  boost::random::normal_distribution<double> effort_noise_;
  boost::random::normal_distribution<double> tracker_noise_;
  double delay_periods_ = 0.0;
  std::vector<Eigen::Vector2d> history_;
  long count_ = 0;
};

}  // namespace pliant::experiments::detail
