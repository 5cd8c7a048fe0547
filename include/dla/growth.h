#pragma once
//! \file growth.h
//! Off-lattice diffusion-limited aggregation: walkers launched one after another walk in
//! continuous space until they touch the structure and stick. See docs/algorithm.md.

#include "dla/cluster.h"
#include "dla/constraint.h"
#include "dla/options.h"
#include "dla/random.h"
#include "dla/spawn.h"
#include "dla/spatial_index.h"
#include "dla/walk.h"

#include <cmath>
#include <cstddef>
#include <functional>

namespace dla {

//! Called as growth goes on, every 256 particles and at the end, with the structure so far;
//! returning false stops growth early and the cluster comes back marked incomplete (it can be
//! saved and grown on with resume()).
using ProgressFn = std::function<bool(const Cluster& so_far)>;

//! Grows a structure with the index chosen in options.index. Validates the options first.
//! Defined in libdla (it instantiates grow_with for every index).
Cluster grow(const GrowthOptions& options, const ProgressFn& progress = {});

//! Grows a structure constrained by a mesh (see constraint.h). Validates the options and
//! checks them against the constraint: the same spacing, 3 dimensions, seeds on the growing
//! side, a spawn mode that can start walkers there.
Cluster grow(const GrowthOptions& options, const MeshConstraint& constraint, const ProgressFn& progress = {});

//! Grows on a structure that growth with the same options (and constraint) stopped early, up
//! to options.particles. The result is the one growth without the stop gives, byte for byte:
//! walker k draws from its own random stream, whenever it runs. Throws InvalidInput if
//! `partial` cannot have come from these options.
Cluster resume(const GrowthOptions& options, const Cluster& partial, const ProgressFn& progress = {});
Cluster resume(const GrowthOptions& options, const MeshConstraint& constraint, const Cluster& partial,
               const ProgressFn& progress = {});

//! Throws InvalidInput where the options and the constraint cannot work together.
void validate(const GrowthOptions& options, const MeshConstraint& constraint);

//! Grows a structure with a given index type (see spatial_index.h), constrained by a mesh if
//! `constraint` is set, going on from `partial` if it is set. Does not validate.
template <class Index>
Cluster grow_with(const GrowthOptions& options, const ProgressFn& progress = {},
                  const MeshConstraint* constraint = nullptr, const Cluster* partial = nullptr);

// ---------------------------------------------------------------------------------------------

namespace detail {

template <class Index>
class Aggregation {
 public:
  Aggregation(const GrowthOptions& options, const MeshConstraint* constraint, const Cluster* partial)
      : opt_(options),
        constraint_(constraint),
        contact_(options.spacing),
        near_step_(options.min_step * options.spacing),
        drift_scale_(1.0 / (1.0 + options.drift.norm())),
        index_(cluster_.particles, options.spacing, options.dimensions) {
    cluster_.spacing = options.spacing;
    cluster_.dimensions = options.dimensions;
    cluster_.seed_count = options.seeds.size();
    cluster_.particles.reserve(options.seeds.size() + options.particles);
    for (const Vec3& s : options.seeds) cluster_.center += s;
    cluster_.center /= static_cast<double>(options.seeds.size());
    if (partial) {
      // The same particles added in the same order rebuild the same index and radii.
      for (const Particle& p : partial->particles) add(p);
      cluster_.stats = partial->stats;
      return;
    }
    for (std::size_t i = 0; i < options.seeds.size(); ++i)
      add({options.seeds[i], -1, static_cast<std::int32_t>(i)});
  }

  Cluster run(const ProgressFn& progress) {
    constexpr std::size_t report_every = 256;
    for (std::size_t k = attached(cluster_); k < opt_.particles; ++k) {
      add(walk(k));
      if (progress && ((k + 1) % report_every == 0 || k + 1 == opt_.particles) && !progress(cluster_)) {
        cluster_.complete = k + 1 == opt_.particles;
        break;
      }
    }
    return std::move(cluster_);
  }

 private:
  bool drifting() const { return opt_.drift.squaredNorm() > 0.0; }

  void add(const Particle& p) {
    cluster_.particles.push_back(p);
    index_.insert(static_cast<std::int32_t>(cluster_.particles.size() - 1));
    cluster_radius_ = std::max(cluster_radius_, (p.position - cluster_.center).norm());
    // Walkers are put back on this sphere from outside; two spacings of margin keep a returned
    // walker clear of every contact ball.
    return_radius_ = cluster_radius_ + 2.0 * contact_;
    index_.cover(cluster_.center, return_radius_);
  }

  //! Runs walker number k from launch to contact and returns the particle it becomes.
  Particle walk(std::size_t k) {
    WalkStats& stats = cluster_.stats;
    ++stats.walkers;
    Rng rng(opt_.rng_seed, k);
    const Vec3& center = cluster_.center;
    Vec3 x = launch(rng);
    // Bounds that turn a setup where nothing can stick into an error rather than a hang.
    constexpr std::uint64_t max_lost = 10'000'000, max_rejected = 1'000'000;
    std::uint64_t lost = 0, rejected = 0;
    for (;;) {
      ++stats.steps;
      const Vec3 offset = x - center;
      const double r2 = offset.squaredNorm();
      // Walkers put on the return sphere sit on it up to rounding: they count as inside.
      if (r2 > return_radius_ * return_radius_ * (1.0 + 1e-9)) {
        if (!drifting()) {
          const ReturnPoint back = return_to_sphere(offset, return_radius_, rng, opt_.dimensions);
          if (back.returned) {
            ++stats.returns;
            x = center + back.offset;
          } else {
            ++stats.relaunches;
            x = launch(rng);
          }
          continue;
        }
        // With drift there is no closed-form return: walk on, with the distance to the
        // bounding sphere as the free radius, and start afresh far away.
        const double kill = std::max(3.0 * return_radius_, return_radius_ + 64.0 * contact_);
        if (r2 > kill * kill) {
          ++stats.relaunches;
          x = launch(rng);
          continue;
        }
        x += jump(rng, std::sqrt(r2) - cluster_radius_ - contact_);
        continue;
      }

      if (constraint_ && constraint_->lost(x)) {
        ++stats.lost;
        if (++lost == max_lost)
          throw GrowthError("walker " + std::to_string(k + 1) + " left the growing side of the mesh " +
                            std::to_string(max_lost) + " times: walkers cannot reach the seeds");
        x = launch(rng);
        continue;
      }

      // Outside the sphere around every particle, its distance is a bound the index may not beat.
      const double free = std::max(index_.probe(x).distance, std::sqrt(r2) - cluster_radius_) - contact_;
      if (free > near_step_) {
        x += jump(rng, free);
        continue;
      }

      // Next to the structure: a short straight step, stopped at the first contact.
      ++stats.near_steps;
      const Vec3 step = near_step_ * (random_direction(rng, opt_.dimensions) + opt_.drift);
      double first = 2.0;
      std::int32_t touched = -1;
      index_.for_each_within(x, contact_ + step.norm(), [&](std::int32_t id, double) {
        const double t = contact_along(x, step, position(id), contact_);
        if (t >= 0.0 && t < first) {
          first = t;
          touched = id;
        }
      });
      if (touched < 0) {
        x += step;
        continue;
      }
      ++stats.contacts;
      x += first * step;
      if (opt_.stickiness < 1.0 && rng.uniform() >= opt_.stickiness) continue;
      const Vec3& parent = position(touched);
      Vec3 end = parent + (x - parent).normalized() * opt_.spacing;
      if (constraint_) {
        const BranchCheck check = constraint_->check_branch(parent, end);
        if (!check.accepted) {
          ++stats.rejected;
          if (++rejected == max_rejected)
            throw GrowthError("the mesh refused " + std::to_string(max_rejected) + " branches of walker " +
                              std::to_string(k + 1) + ": are the seeds within a spacing of the surface?");
          continue;
        }
        stats.clipped += check.clipped;
        end = check.end;
      }
      return {end, touched, cluster_.particles[static_cast<std::size_t>(touched)].seed};
    }
  }

  //! A step to a uniform point on the sphere of radius `free` (less any drift), which lies in
  //! a ball free of contacts: the walk-on-spheres move.
  Vec3 jump(Rng& rng, double free) {
    return free * drift_scale_ * (random_direction(rng, opt_.dimensions) + opt_.drift);
  }

  const Vec3& position(std::int32_t id) const {
    return cluster_.particles[static_cast<std::size_t>(id)].position;
  }

  //! A walker's start. Starts beyond the return sphere are fine: the walk's first step applies
  //! the return rule. A start within contact of the structure, or lost, is drawn again.
  Vec3 launch(Rng& rng) {
    const Vec3& center = cluster_.center;
    const double R2 = return_radius_ * return_radius_;
    constexpr int max_draws = 1'000'000;
    for (int draw = 0; draw < max_draws; ++draw) {
      const Vec3 x = draw_start(rng);
      if (constraint_ && constraint_->lost(x)) continue;
      if ((x - center).squaredNorm() >= R2 || index_.probe(x).distance >= contact_) return x;
    }
    throw GrowthError("no free start in " + std::to_string(max_draws) + " draws from the " +
                      std::string(to_string(opt_.spawn)) + " spawn" +
                      (constraint_ ? " on the growing side of the mesh" : ": the structure fills it"));
  }

  Vec3 draw_start(Rng& rng) const {
    if (constraint_) {
      switch (opt_.spawn) {
        case SpawnMode::inside: return constraint_->draw_inside(rng);
        case SpawnMode::radial: return constraint_->draw_radial(rng);
        case SpawnMode::sphere: {  // around the mesh and the structure
          const Vec3& c = constraint_->center();
          const double R = std::max(constraint_->radius(), (c - cluster_.center).norm() + return_radius_);
          return draw_spawn(opt_, c, R, rng);
        }
        default: break;
      }
    }
    return draw_spawn(opt_, cluster_.center, return_radius_, rng);
  }

  const GrowthOptions& opt_;
  const MeshConstraint* constraint_;  // null: unconstrained
  const double contact_;      // centre distance at which a walker touches a particle
  const double near_step_;    // step length next to the structure
  const double drift_scale_;  // keeps a drifted jump inside its free ball
  Cluster cluster_;
  Index index_;
  double cluster_radius_ = 0.0;  // largest particle distance from the centre
  double return_radius_ = 0.0;
};

}  // namespace detail

template <class Index>
Cluster grow_with(const GrowthOptions& options, const ProgressFn& progress, const MeshConstraint* constraint,
                  const Cluster* partial) {
  return detail::Aggregation<Index>(options, constraint, partial).run(progress);
}

}  // namespace dla
