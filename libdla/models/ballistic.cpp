// Ballistic aggregation's engine (ballistic.h), for the grid index and the brute-force one tests check it against.

#include "dla/models/ballistic.h"

#include "dla/index/grid_index.h"
#include "dla/index/spatial_index.h"
#include "dla/models/one_by_one.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace dla {

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

template <class Index>
Cluster ballistic_with(const BallisticOptions& options, const ProgressFn& progress, const StopFlag* stop,
                       BallisticStats* stats) {
  BallisticStats local;
  return detail::Ballistic<Index>(options, stats ? *stats : local).run(progress, stop);
}

Cluster ballistic(const BallisticOptions& options, const ProgressFn& progress, const StopFlag* stop, BallisticStats* stats) {
  validate(options);
  return ballistic_with<GridIndex>(options, progress, stop, stats);
}

template Cluster ballistic_with<GridIndex>(const BallisticOptions&, const ProgressFn&, const StopFlag*, BallisticStats*);
template Cluster ballistic_with<BruteForceIndex>(const BallisticOptions&, const ProgressFn&, const StopFlag*,
                                                 BallisticStats*);

}  // namespace dla
