#pragma once
//! \file cluster.h
//! What growth returns: the particles in attach order, as plain data for the exporters and
//! for analysis.

#include "dla/core/options.h"

#include <Eigen/Core>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

namespace dla {

//! One particle of the structure.
struct Particle {
  Vec3 position;
  std::int32_t parent;  //!< index of the particle it attached to (always earlier); -1 for a seed
  std::int32_t seed;    //!< which seed's tree it belongs to, 0-based in DlaOptions::seeds
};

//! A grown structure.
struct Cluster {
  std::vector<Particle> particles;  //!< seeds first, then in attach order
  std::size_t seed_count = 0;       //!< the first seed_count particles are the seeds
  Vec3 center = Vec3::Zero();       //!< centre of the seeds: the centre of the launch sphere
  double spacing = 1.0;
  int dimensions = 3;
  bool complete = true;             //!< false when growth was stopped before the count
};
// What growth counted (DLA's walks, the drops, the lines) each model returns beside the
// structure: DlaStats (walk.h), DropStats, BallisticStats.

//! Called as growth begins, about every 0.1 s as it goes on (model_shell.h), and at the end,
//! with the structure so far; returning false stops growth early and the cluster comes back
//! marked incomplete.
using ProgressFn = std::function<bool(const Cluster& so_far)>;

//! Set from another thread or a signal handler (a lock-free atomic store is async-signal-safe)
//! to stop growth within milliseconds. The cluster comes back marked incomplete, as when the
//! ProgressFn returns false.
using StopFlag = std::atomic<bool>;

//! Particles attached so far, seeds not counted.
inline std::size_t attached(const Cluster& cluster) { return cluster.particles.size() - cluster.seed_count; }

//! Largest distance of a particle centre from `cluster.center`.
inline double bounding_radius(const Cluster& cluster) {
  double r2 = 0.0;
  for (const Particle& p : cluster.particles)
    r2 = std::max(r2, (p.position - cluster.center).squaredNorm());
  return std::sqrt(r2);
}

//! Radius of gyration about their centre of mass of all particles, or with `seed` >= 0 of
//! that seed's tree only.
inline double radius_of_gyration(const Cluster& cluster, std::int32_t seed = -1) {
  Vec3 sum = Vec3::Zero();
  double sum2 = 0.0;
  std::size_t count = 0;
  for (const Particle& p : cluster.particles) {
    if (seed >= 0 && p.seed != seed) continue;
    sum += p.position;
    sum2 += p.position.squaredNorm();
    ++count;
  }
  if (count == 0) return 0.0;
  const double n = static_cast<double>(count);
  return std::sqrt(std::max(0.0, sum2 / n - (sum / n).squaredNorm()));
}

}  // namespace dla
