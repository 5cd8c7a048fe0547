#pragma once
//! \file ballistic.h
//! Ballistic aggregation (Roberts 2001, "Sticky Pixels", section 3.4; Vold 1963): particles fly
//! along straight lines and stick where they first touch the structure. Lines come from
//! uniformly random directions, or all along one direction (deposition), spread uniformly over
//! the disk across them that the structure can touch. Each line is traced with the index's
//! bound on the distance to the structure (sphere tracing), and only next to the structure in
//! short stretches tested exactly. The result is the Cluster every model returns. See
//! docs/ballistic.md.

#include "dla/core/cluster.h"
#include "dla/core/errors.h"
#include "dla/core/options.h"
#include "dla/core/random.h"
#include "dla/index/grid_index.h"
#include "dla/models/one_by_one.h"
#include "dla/models/walk.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace dla {

//! Options of a ballistic run. Lengths are in scene units; the spacing sets the scale.
struct BallisticOptions {
  std::size_t particles = 10000;  //!< particles to attach, seeds not counted
  double spacing = 1.0;           //!< contact distance and distance to the parent, [1e-25, 1e25]
  std::uint64_t rng_seed = 1;     //!< seeds every random choice of the run
  int dimensions = 3;             //!< 3, or 2 for growth in the plane z = 0
  std::vector<Vec3> seeds = {Vec3::Zero()};  //!< one tree per seed
  //! Deposition: every particle flies along this direction (any length but 0; in z = 0 for
  //! 2D). Zero: each from a uniformly random direction.
  Vec3 direction = Vec3::Zero();
};

//! How the lines went, for the summary and the JSON record.
struct BallisticStats {
  std::uint64_t launched = 0;    //!< lines flown
  std::uint64_t missed = 0;      //!< lines that passed the structure without touching it
  std::uint64_t far_steps = 0;   //!< sphere-tracing steps, by the index's distance bound
  std::uint64_t near_steps = 0;  //!< short stretches next to the structure, tested exactly
};

inline void validate(const BallisticOptions& o) {
  detail::validate_seeded(o.particles, o.seeds, o.spacing, o.dimensions);
  if (!o.direction.allFinite()) throw InvalidInput("the direction is not finite");
  if (o.dimensions == 2 && o.direction.z() != 0.0)
    throw InvalidInput("the direction has a z component but growth in 2 dimensions is in the plane z = 0");
}

namespace detail {

template <class Index>
class Ballistic {
 public:
  Ballistic(const BallisticOptions& o, BallisticStats& stats)
      : o_(o), stats_(stats), growth_(o.seeds, o.spacing, o.dimensions, o.particles, true),
        rng_(o.rng_seed, 0x62616c6cULL) {}  // a stream of its own: "ball"

  Cluster run(const ProgressFn& progress, const StopFlag* stop) {
    return growth_.run(o_.particles, progress, stop, [&] { return fly() ? Attempt::attached : Attempt::failed; });
  }

 private:
  //! One line: true if it ended in a new particle.
  bool fly() {
    ++stats_.launched;
    const double contact = o_.spacing;
    const Vec3 u = o_.direction.squaredNorm() > 0.0 ? Vec3(o_.direction.normalized())
                                                      : random_direction(rng_, o_.dimensions);
    // Lines farther than `reach` from the centre cannot touch: spread them over the disk (the
    // segment, in 2D) of that radius across u, starting behind the structure.
    const double reach = growth_.cluster_radius() + contact;
    Vec3 across;
    if (o_.dimensions == 2) {
      across = Vec3(-u.y(), u.x(), 0.0) * (reach * (2.0 * rng_.uniform() - 1.0));
    } else {
      double a, b;
      do {
        a = 2.0 * rng_.uniform() - 1.0;
        b = 2.0 * rng_.uniform() - 1.0;
      } while (a * a + b * b > 1.0);
      const Vec3 e1 = orthogonal_unit(u), e2 = u.cross(e1);
      across = reach * (a * e1 + b * e2);
    }
    const Vec3 start = growth_.cluster().center - (reach + contact) * u + across;
    const double length = 2.0 * (reach + contact);
    const double stretch = 2.0 * contact;  // a near step's length
    for (double t = 0.0; t < length;) {
      const Vec3 x = start + t * u;
      const double free = growth_.index().bound(x) - contact;
      if (free > 0.5 * contact) {
        ++stats_.far_steps;
        t += free;
        continue;
      }
      ++stats_.near_steps;
      // Every particle this stretch touches lies within a spacing of it: in the ball about its
      // midpoint through its ends, a spacing wider. Where the line first touches a particle is
      // solved from the line's start, so it does not depend on where the stretches fall.
      double first = std::numeric_limits<double>::infinity();
      std::int32_t touched = -1;
      growth_.index().for_each_within(x + (0.5 * stretch) * u, contact + 0.5 * stretch, [&](std::int32_t id, double) {
        const Vec3 w = start - growth_.position(id);
        const double b = w.dot(u), disc = b * b - (w.squaredNorm() - contact * contact);
        if (disc < 0.0) return;
        const double hit = -b - std::sqrt(disc);
        if (hit <= t + stretch && (hit < first || (hit == first && id < touched))) first = hit, touched = id;
      });
      if (touched < 0) {
        t += stretch;
        continue;
      }
      const Vec3& parent = growth_.position(touched);
      const Vec3 end = parent + (start + first * u - parent).normalized() * contact;
      growth_.attach(end, touched);
      return true;
    }
    ++stats_.missed;
    return false;
  }

  const BallisticOptions& o_;
  BallisticStats& stats_;
  OneByOne<Index> growth_;
  Rng rng_;
};

}  // namespace detail

//! Grows a structure by ballistic aggregation with a given index (GridIndex, or BruteForceIndex
//! to test against). Does not validate. Calls `progress` every 256 particles and at the end;
//! `stop` ends growth early, the cluster marked incomplete. Throws PartialGrowth if the
//! structure outgrows the index.
template <class Index>
Cluster ballistic_with(const BallisticOptions& options, const ProgressFn& progress = {}, const StopFlag* stop = nullptr,
                       BallisticStats* stats = nullptr) {
  BallisticStats local;
  return detail::Ballistic<Index>(options, stats ? *stats : local).run(progress, stop);
}

//! Validates the options and grows with the grid index.
inline Cluster ballistic(const BallisticOptions& options, const ProgressFn& progress = {},
                         const StopFlag* stop = nullptr, BallisticStats* stats = nullptr) {
  validate(options);
  return ballistic_with<GridIndex>(options, progress, stop, stats);
}

}  // namespace dla
