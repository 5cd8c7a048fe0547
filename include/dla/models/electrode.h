#pragma once
//! \file electrode.h
//! The breakdown model's target electrode as DLA's walk sees it (dla.h, breakdown.h): how far a
//! walker is from it, where walkers leave it, and how far they may wander before they count as
//! gone to the far boundary. Internal to the engine.

#include "dla/core/random.h"
#include "dla/models/breakdown.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace dla::detail {

class Electrode {
 public:
  //! `side` is a point on the structure's side of a plane (the seeds' centre).
  Electrode(const Target& target, const Vec3& side, double spacing, int dimensions)
      : target_(target), spacing_(spacing), dimensions_(dimensions) {
    if (target.kind == TargetKind::plane) {
      const int a = static_cast<int>(target.axis);
      normal_ = Vec3::Zero();
      normal_[a] = side[a] >= target.at ? 1.0 : -1.0;
    }
  }

  //! From the electrode's surface, positive on the structure's side.
  double distance(const Vec3& x) const {
    if (target_.kind == TargetKind::plane)
      return normal_[static_cast<int>(target_.axis)] * (x[static_cast<int>(target_.axis)] - target_.at);
    if (target_.kind == TargetKind::mesh) return target_.mesh->distance_to_surface(x);
    return (x - target_.point).norm() - ball_radius();
  }

  //! The structure has a particle at `p`: called for every particle, before walkers start
  //! and between their batches, never while they walk.
  void grown(const Vec3& p) {
    const double d = distance(p);
    nearest_ = std::min(nearest_, d);
    farthest_ = std::max(farthest_, d);
    low_ = low_.cwiseMin(p);
    high_ = high_.cwiseMax(p);
  }

  //! A walker's start. Walkers leaving a plane cross every parallel plane uniformly, and
  //! walkers leaving a ball every concentric sphere: they start on the one two spacings short
  //! of the structure's nearest particle (nearer when it is close), which is exact, but that a plane's is cut to a disk
  //! (a strip in 2D) around the structure, kLaunchWidths times its height above it wider.
  //! A mesh's walkers start half a spacing off its surface on its growing side, at a point
  //! drawn uniformly by area: to first order in that offset the excursion measure, whose weight
  //! at each point (the field there) comes out as the chance of not coming straight back, high
  //! at a rod's tip.
  Vec3 draw_start(Rng& rng) const {
    if (target_.kind == TargetKind::mesh) return target_.mesh->draw_near_surface(rng);
    // Clear of every particle's contact ball: a spacing short of the nearest, or halfway to it.
    const double start = std::max({nearest_ - 2.0 * spacing_, 0.5 * (nearest_ - spacing_), 2.0 * absorbs()});
    if (target_.kind == TargetKind::point)
      return target_.point + (ball_radius() + start) * random_direction(rng, dimensions_);
    const int a = static_cast<int>(target_.axis);
    Vec3 x = 0.5 * (low_ + high_);
    x[a] = target_.at + normal_[a] * start;
    const double reach = lateral_reach();
    if (dimensions_ == 2) {
      x[1 - a] += reach * (2.0 * rng.uniform() - 1.0);
      return x;
    }
    const Vec3 disk = random_in_disk(rng);
    x[(a + 1) % 3] += reach * disk.x();
    x[(a + 2) % 3] += reach * disk.y();
    return x;
  }

  //! Walkers farther than this from `center` are gone to the far boundary (grounded, as the
  //! structure is) and start again.
  double far_away(const Vec3& center, double radius) const {
    if (target_.kind == TargetKind::mesh)
      return 2.0 * ((center - target_.mesh->center()).norm() + target_.mesh->radius() + radius) + 64.0 * spacing_;
    const double reach = target_.kind == TargetKind::plane ? lateral_reach() : 0.0;
    return 2.0 * (std::abs(distance(center)) + radius + reach) + 64.0 * spacing_;
  }

  //! A walker this close is back on the electrode.
  double absorbs() const { return 0.05 * spacing_; }

 private:
  static constexpr double kLaunchWidths = 2.0;
  double ball_radius() const { return 0.5 * spacing_; }

  //! Half the width of a plane's launch disk: the structure's half width across the axis, and
  //! kLaunchWidths times its height above the plane.
  double lateral_reach() const {
    Vec3 half = 0.5 * (high_ - low_);
    half[static_cast<int>(target_.axis)] = 0.0;
    return half.norm() + kLaunchWidths * (farthest_ + spacing_);
  }

  static Vec3 random_in_disk(Rng& rng) {
    for (;;) {
      const double u = 2.0 * rng.uniform() - 1.0, v = 2.0 * rng.uniform() - 1.0;
      if (u * u + v * v <= 1.0) return {u, v, 0.0};
    }
  }

  Target target_;
  double spacing_;
  int dimensions_;
  Vec3 normal_ = Vec3::Zero();  // plane: towards the structure
  // The structure so far (grown()): its nearest and farthest distance, and its box.
  double nearest_ = std::numeric_limits<double>::infinity();
  double farthest_ = 0.0;
  Vec3 low_ = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high_ = Vec3::Constant(-std::numeric_limits<double>::infinity());
};

}  // namespace dla::detail
