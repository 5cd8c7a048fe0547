#pragma once
//! \file analysis.h
//! Measures of a grown structure: the fractal dimension from how the radius of gyration grows
//! with the number of particles over the growth history.

#include "dla/cluster.h"

#include <cmath>
#include <cstddef>
#include <vector>

namespace dla {

//! Radius of gyration of the first n particles.
struct GyrationSample {
  std::size_t n;
  double radius;
};

//! The radius of gyration of the first n particles (in attach order) for `samples` values of n
//! spaced evenly in log n from n_min to all particles.
inline std::vector<GyrationSample> gyration_history(const Cluster& cluster, std::size_t n_min = 100,
                                                    std::size_t samples = 40) {
  std::vector<GyrationSample> history;
  const std::size_t total = cluster.particles.size();
  if (total < 2 || n_min >= total || samples < 2) return history;
  Vec3 sum = Vec3::Zero();
  double sum2 = 0.0;
  std::size_t next = 0;
  const double ratio = std::log(static_cast<double>(total) / n_min) / (samples - 1);
  for (std::size_t i = 0; i < total; ++i) {
    sum += cluster.particles[i].position;
    sum2 += cluster.particles[i].position.squaredNorm();
    const std::size_t n = i + 1;
    const auto target = static_cast<std::size_t>(std::llround(n_min * std::exp(ratio * next)));
    if (n >= target && next < samples) {
      const double m = static_cast<double>(n);
      history.push_back({n, std::sqrt(std::max(0.0, sum2 / m - (sum / m).squaredNorm()))});
      while (next < samples && std::llround(n_min * std::exp(ratio * next)) <= static_cast<long long>(n))
        ++next;
    }
  }
  return history;
}

//! Fractal dimension D from a least-squares fit of log Rg = log n / D + c.
struct FractalFit {
  double dimension = 0.0;
  std::size_t samples = 0;  //!< points in the fit
};

inline FractalFit fractal_dimension_by_gyration(const Cluster& cluster, std::size_t n_min = 100) {
  const std::vector<GyrationSample> history = gyration_history(cluster, n_min);
  FractalFit fit;
  fit.samples = history.size();
  if (history.size() < 2) return fit;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const GyrationSample& s : history) {
    const double x = std::log(static_cast<double>(s.n)), y = std::log(s.radius);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double m = static_cast<double>(history.size());
  const double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  fit.dimension = 1.0 / slope;
  return fit;
}

}  // namespace dla
