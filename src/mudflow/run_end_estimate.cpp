// The expected end of a mud-flow run from the decay of its kinetic energy (run_end_estimate.hpp).
#include "talus/mudflow/run_end_estimate.hpp"

#include <algorithm>
#include <cmath>

namespace talus {
namespace {

// Coarse steps the decay fit spans at most: 8 s of flow at the default 0.5 s steps, long enough
// to smooth the surges of a flow down a gully, short enough to follow a decay rate that changes
// as the flow stops (on the sample scene 8 to 60 steps give the same shares done within 1%).
constexpr std::size_t kFitPoints = 16;
// The fewest points since the peak that make a decay rate.
constexpr std::size_t kFewestFitPoints = 3;
// The largest share reported before the run has ended.
constexpr double kMostBeforeEnd = 0.99;

}  // namespace

RunEndEstimate::RunEndEstimate(double duration, double stop_energy_fraction)
    : duration_(duration), stop_energy_fraction_(stop_energy_fraction), expected_end_(duration) {}

void RunEndEstimate::record(double time, double kinetic_energy, double wall_seconds) {
  time_ = time;
  if (kinetic_energy > 0.0) {
    points_.push_back({time, std::log(kinetic_energy), wall_seconds});
    if (kinetic_energy >= peak_energy_) {
      peak_energy_ = kinetic_energy;
      peak_ = points_.size() - 1;
    }
    expected_end_ = std::clamp(energy_end(), time, duration_);
  } else {
    expected_end_ = time;  // nothing moves: the energy criterion ends the run now
  }
  const double share = expected_end_ > 0.0 ? time / expected_end_ : 1.0;
  fraction_done_ = std::max(fraction_done_, std::min(share, kMostBeforeEnd));
}

// Least squares of ln E = a + b t over the points since the peak (at most kFitPoints), and the
// time t_end = t + (ln(stop_energy_fraction peak) - (a + b t)) / b at which the fitted line, at
// the latest point, reaches the threshold (b < 0).
double RunEndEstimate::energy_end() const {
  if (!(stop_energy_fraction_ > 0.0)) return duration_;
  const std::size_t first = std::max(peak_, points_.size() > kFitPoints ? points_.size() - kFitPoints : 0);
  const std::size_t n = points_.size() - first;
  if (n < kFewestFitPoints) return duration_;
  double mean_t = 0, mean_y = 0;
  for (std::size_t k = first; k < points_.size(); ++k) {
    mean_t += points_[k].time;
    mean_y += points_[k].log_energy;
  }
  mean_t /= static_cast<double>(n);
  mean_y /= static_cast<double>(n);
  double covariance = 0, variance = 0;
  for (std::size_t k = first; k < points_.size(); ++k) {
    covariance += (points_[k].time - mean_t) * (points_[k].log_energy - mean_y);
    variance += (points_[k].time - mean_t) * (points_[k].time - mean_t);
  }
  const double slope = covariance / variance;  // 1/s
  if (!(slope < 0.0)) return duration_;
  const double fitted_now = mean_y + slope * (time_ - mean_t);
  const double threshold = std::log(stop_energy_fraction_ * peak_energy_);
  return time_ + std::max(0.0, (threshold - fitted_now) / slope);
}

// (wall time / simulated time) over the last kFitPoints coarse steps x simulated time left.
double RunEndEstimate::wall_seconds_left() const {
  if (points_.empty()) return 0.0;
  const Point& last = points_.back();
  const Point& first = points_[points_.size() > kFitPoints ? points_.size() - kFitPoints : 0];
  const double simulated = last.time - first.time;
  const double rate = simulated > 0.0 ? (last.wall_seconds - first.wall_seconds) / simulated
                                      : (last.time > 0.0 ? last.wall_seconds / last.time : 0.0);
  return rate * std::max(0.0, expected_end_ - time_);
}

}  // namespace talus
