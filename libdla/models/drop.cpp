// Random-drop aggregation's engine (drop.h), for the grid index and the brute-force one tests check it against.

#include "dla/models/drop.h"

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
class RandomDrop {
 public:
  RandomDrop(const DropOptions& o, const MeshConstraint* constraint, DropStats& stats)
      : o_(o), constraint_(constraint), stats_(stats), growth_(o.seeds, o.spacing, o.dimensions, o.particles, false),
        rng_(o.rng_seed, 0x64726f70ULL) {}  // a stream of its own: "drop"

  Cluster run(const ProgressFn& progress, const StopFlag* stop) {
    std::uint64_t failed = 0;  // drops in a row that attached nothing
    return growth_.run(o_.particles, progress, stop, [&] {
      if (drop_one()) {
        failed = 0;
        return Attempt::attached;
      }
      if (++failed < kMaxFailedDrops) return Attempt::failed;
      stats_.zone_full = true;
      return Attempt::done;
    });
  }

 private:
  //! One drop: true if it attached a particle.
  bool drop_one() {
    ++stats_.drops;
    Vec3 at = next_drop();
    const auto lost = [&] {
      if (!constraint_ || !constraint_->lost(at)) return false;
      ++stats_.lost;
      return true;
    };
    if (lost()) return false;
    Probe closest = growth_.index().nearest(at);
    while (closest.distance >= o_.spacing && o_.stickiness < 1.0 && rng_.uniform() >= o_.stickiness) {
      ++stats_.refused;
      at += o_.spacing * random_direction(rng_, o_.dimensions);
      if (lost()) return false;
      closest = growth_.index().nearest(at);
    }
    if (closest.distance < o_.spacing) {
      ++stats_.on_structure;
      return false;
    }
    const Vec3& parent = growth_.position(closest.nearest);
    Vec3 end = parent + (at - parent) * (o_.spacing / closest.distance);
    if (constraint_) {
      const BranchCheck check = constraint_->check_branch(parent, end);
      if (!check.accepted) {
        ++stats_.mesh_rejected;
        return false;
      }
      stats_.clipped += check.clipped;
      end = check.end;
    }
    growth_.attach(end, closest.nearest);
    return true;
  }

  const Vec3& center() const { return growth_.cluster().center; }

  double ball_radius() const {
    return o_.zone_radius > 0.0 ? o_.zone_radius : growth_.cluster_radius() + o_.zone_margin * o_.spacing;
  }

  Vec3 next_drop() {
    switch (o_.bias.pattern) {
      case DropPattern::uniform: return in_zone();
      case DropPattern::circle: return on_edge();
      case DropPattern::same:
        if (left_ == 0) place_ = in_zone(), left_ = o_.bias.count;
        --left_;
        return place_;
      case DropPattern::offset:
        if (left_ == 0) {
          place_ = in_zone();
          left_ = o_.bias.count;
        } else {
          place_ += o_.bias.offset_radius * in_unit_ball();
          --left_;
        }
        return place_;
    }
    return in_zone();
  }

  Vec3 in_unit_ball() {
    // One draw a statement: the order of a call's arguments is the compiler's to choose (GCC
    // and clang differ), and the radius came first in the files dla3d has written.
    const double radius = std::pow(rng_.uniform(), 1.0 / o_.dimensions);
    return random_direction(rng_, o_.dimensions) * radius;
  }

  //! The box zone: the given one, or the square or cube around the ball.
  Box box() const {
    if (o_.zone_box) return *o_.zone_box;
    const double r = ball_radius();
    Box b{center().array() - r, center().array() + r};
    if (o_.dimensions == 2) b.min.z() = b.max.z() = 0.0;
    return b;
  }

  Vec3 in_zone() {
    switch (o_.zone) {
      case DropZone::ball: return center() + ball_radius() * in_unit_ball();
      case DropZone::box: {
        const Box b = box();
        Vec3 p = Vec3::Zero();
        for (int a = 0; a < o_.dimensions; ++a) p[a] = b.min[a] + rng_.uniform() * (b.max[a] - b.min[a]);
        return p;
      }
      case DropZone::mesh: return constraint_->draw_inside(rng_);
    }
    return center();
  }

  Vec3 on_edge() {
    switch (o_.zone) {
      case DropZone::ball: return center() + ball_radius() * random_direction(rng_, o_.dimensions);
      case DropZone::box: {
        // A face (an edge in 2D) chosen by its area, then a uniform point on it.
        const Box b = box();
        const Vec3 size = b.max - b.min;
        std::array<double, 3> area{};
        double total = 0.0;
        for (int a = 0; a < o_.dimensions; ++a) {
          area[a] = 1.0;
          for (int other = 0; other < o_.dimensions; ++other)
            if (other != a) area[a] *= size[other];
          total += 2.0 * area[a];
        }
        double pick = rng_.uniform() * total;
        int axis = 0;
        while (axis + 1 < o_.dimensions && pick >= 2.0 * area[axis]) pick -= 2.0 * area[axis++];
        Vec3 p = Vec3::Zero();
        for (int a = 0; a < o_.dimensions; ++a) p[a] = b.min[a] + rng_.uniform() * size[a];
        p[axis] = pick < area[axis] ? b.min[axis] : b.max[axis];
        return p;
      }
      case DropZone::mesh: return constraint_->draw_near_surface(rng_);
    }
    return center();
  }

  const DropOptions& o_;
  const MeshConstraint* constraint_;
  DropStats& stats_;
  OneByOne<Index> growth_;  // no distance maps: only nearest() is asked
  Rng rng_;
  Vec3 place_ = Vec3::Zero();    // same, offset: the last drop point
  std::uint64_t left_ = 0;       // same, offset: drops left at or about place_
};

}  // namespace detail

template <class Index>
Cluster drop_with(const DropOptions& options, const MeshConstraint* constraint, const ProgressFn& progress,
                  const StopFlag* stop, DropStats* stats) {
  DropStats local;
  return detail::RandomDrop<Index>(options, constraint, stats ? *stats : local).run(progress, stop);
}

Cluster drop(const DropOptions& options, const MeshConstraint* constraint, const ProgressFn& progress, const StopFlag* stop,
             DropStats* stats) {
  if (constraint) validate(options, *constraint);
  else validate(options);
  if (options.zone == DropZone::mesh && !constraint) throw InvalidInput("the mesh zone drops inside a mesh: give one with `stl`");
  return drop_with<GridIndex>(options, constraint, progress, stop, stats);
}

template Cluster drop_with<GridIndex>(const DropOptions&, const MeshConstraint*, const ProgressFn&, const StopFlag*,
                                     DropStats*);
template Cluster drop_with<BruteForceIndex>(const DropOptions&, const MeshConstraint*, const ProgressFn&, const StopFlag*,
                                           DropStats*);

}  // namespace dla
