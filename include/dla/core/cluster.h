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

//! A link between two particles beside the tree: a branch that joins another (links.h, closed
//! venation). `later` is the one whose arrival made the link, so a structure's first k particles
//! hold the links whose `later` is below k.
struct Link {
  std::int32_t earlier;
  std::int32_t later;  //!< above `earlier`
  bool operator==(const Link& other) const { return earlier == other.earlier && later == other.later; }
};

//! A grown structure.
struct Cluster {
  std::vector<Particle> particles;  //!< seeds first, then in attach order
  //! Links beside the tree, in order of `later` (then as made); the tree's measures (depth,
  //! descendants, Strahler order, the pipe model) ignore them.
  std::vector<Link> links;
  std::size_t seed_count = 0;       //!< the first seed_count particles are the seeds
  Vec3 center = Vec3::Zero();       //!< centre of the seeds: the centre of the launch sphere
  double spacing = 1.0;
  int dimensions = 3;
  bool complete = true;             //!< false when growth was stopped before the count
  //! Each particle's own radius, in scene units, when the model sizes particles one by one
  //! (an aggregate's monomers); the look's `particle` radius model draws them. Empty: none.
  std::vector<double> radii;
  //! The breakdown model's strike (breakdown.h): the particle that came within a spacing of
  //! its target electrode, the end of the main channel; -1: none (every other model).
  std::int32_t strike = -1;
};
// What growth counted (DLA's walks, the drops, the lines) each model returns beside the
// structure: DlaStats (walk.h), DropStats, BallisticStats.

//! Called as growth begins, about every 0.05 s as it goes on (kProgressSeconds, model_shell.h),
//! and at the end, with the structure so far; returning false stops growth early and the
//! cluster comes back marked incomplete.
using ProgressFn = std::function<bool(const Cluster& so_far)>;

//! Set from another thread or a signal handler (a lock-free atomic store is async-signal-safe)
//! to stop growth within milliseconds. The cluster comes back marked incomplete, as when the
//! ProgressFn returns false.
using StopFlag = std::atomic<bool>;

//! Particles attached so far, seeds not counted.
inline std::size_t attached(const Cluster& cluster) { return cluster.particles.size() - cluster.seed_count; }

//! The structure's first `count` particles, with the links among them: as it was when they had
//! attached.
inline Cluster first_particles(const Cluster& cluster, std::size_t count) {
  Cluster part;
  part.particles.assign(cluster.particles.begin(), cluster.particles.begin() + static_cast<std::ptrdiff_t>(count));
  for (const Link& link : cluster.links)
    if (static_cast<std::size_t>(link.later) < count) part.links.push_back(link);
  if (!cluster.radii.empty())
    part.radii.assign(cluster.radii.begin(), cluster.radii.begin() + static_cast<std::ptrdiff_t>(count));
  part.seed_count = std::min(cluster.seed_count, count);
  part.center = cluster.center;
  part.spacing = cluster.spacing;
  part.dimensions = cluster.dimensions;
  part.complete = cluster.complete;
  part.strike = cluster.strike >= 0 && static_cast<std::size_t>(cluster.strike) < count ? cluster.strike : -1;
  return part;
}

//! Independent cycles of the tree with its links (the cycle rank E - V + C): each link closes
//! one, except a link that joins two seeds' trees for the first time.
inline std::size_t cycle_count(const Cluster& cluster) {
  std::vector<std::int32_t> root(cluster.particles.size());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = static_cast<std::int32_t>(i);
  const auto find = [&](std::int32_t v) {
    while (root[static_cast<std::size_t>(v)] != v) v = root[static_cast<std::size_t>(v)] = root[static_cast<std::size_t>(root[static_cast<std::size_t>(v)])];
    return v;
  };
  for (std::size_t i = 0; i < root.size(); ++i)
    if (cluster.particles[i].parent >= 0) root[i] = find(cluster.particles[i].parent);  // parents come first
  std::size_t cycles = 0;
  for (const Link& link : cluster.links) {
    const std::int32_t a = find(link.earlier), b = find(link.later);
    if (a == b) ++cycles;
    else root[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  return cycles;
}

//! Largest distance of a particle centre from `cluster.center`.
inline double bounding_radius(const Cluster& cluster) {
  double r2 = 0.0;
  for (const Particle& p : cluster.particles)
    r2 = std::max(r2, (p.position - cluster.center).squaredNorm());
  return std::sqrt(r2);
}

//! Radius of gyration about their centre of mass of all particles, or with `seed` >= 0 of
//! that seed's tree only.
//! Radius of gyration of `points` about their centroid (0 for none).
inline double radius_of_gyration(const std::vector<Vec3>& points) {
  if (points.empty()) return 0.0;
  Vec3 sum = Vec3::Zero();
  double sum2 = 0.0;
  for (const Vec3& p : points) {
    sum += p;
    sum2 += p.squaredNorm();
  }
  const double n = static_cast<double>(points.size());
  return std::sqrt(std::max(0.0, sum2 / n - (sum / n).squaredNorm()));
}

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
