// The dielectric breakdown model (breakdown.h): DLA's walkers measure the field before each
// particle, and the growth site is drawn by its contacts to the power eta.

#include "dla/models/breakdown.h"

#include "dla/index/grid_index.h"
#include "models/aggregation.h"
#include "dla/models/electrode.h"
#include "dla/models/model_shell.h"
#include "models/breakdown_charges.h"
#include "models/breakdown_conductor.h"
#include "models/crew.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <optional>
#include <vector>

namespace dla {

void validate(const BreakdownOptions& o, const DlaOptions& walk) {
  // What is DLA's alone, before DLA's own checks of its values.
  if (walk.drift.squaredNorm() > 0.0) throw InvalidInput("`drift` is DLA's: the field of the breakdown model has none");
  if (walk.rotate_degrees != 0.0) throw InvalidInput("`rotate` is DLA's, not the breakdown model's");
  if (walk.fill != 0.0) throw InvalidInput("`fill` grows DLA until a mesh is full; a discharge grows to its count or its strike");
  validate(walk);
  require_in_ranges(breakdown_option_table(), o);
  if (o.field != BreakdownField::walkers) {
    // What only walkers have: the point-charge fields send none.
    const std::string none = "; the " + std::string(to_string(o.field)) + " field sends none";
    if (o.walkers != 0) throw InvalidInput("`walkers` measure the walkers field" + none);
    if (walk.stickiness != 1.0) throw InvalidInput("`stickiness` is a walker's" + none);
    if (walk.spawn != SpawnMode::sphere) throw InvalidInput("`spawn` is where walkers start" + none);
  }
  // In 2D, G = ln(R/r) leaves the charges of a structure's inside nearly free, and growth by
  // them fills in (docs/dev/breakdown-field.md).
  if (o.field == BreakdownField::conductor && walk.dimensions == 2)
    throw InvalidInput("`field` conductor grows 3D discharges; in 2D give walkers or charges");
  const Target& t = o.target;
  if (t.kind == TargetKind::none) return;
  if (t.kind == TargetKind::point) detail::require_representable("`target_point`", t.point, walk.spacing);
  if (t.kind == TargetKind::plane) {
    if (walk.dimensions == 2 && t.axis == Axis::z)
      throw InvalidInput("`target_plane` across z is the growth plane itself in 2D: give x or y");
    if (!(std::abs(t.at) <= kMaxCoordinate * walk.spacing))
      throw InvalidInput("`target_plane` at " + detail::format_number(t.at) + " is not within " +
                         detail::format_number(kMaxCoordinate) + " spacings of the origin");
  }
  if (walk.dimensions == 2 && t.kind == TargetKind::point && t.point.z() != 0.0)
    throw InvalidInput("`target_point` is off the plane z = 0 of 2D growth");
  if (t.kind == TargetKind::mesh) {
    if (!t.mesh) throw InvalidInput("`target_mesh` is missing: the target is a mesh, but none is given");
    if (walk.dimensions == 2)
      throw InvalidInput("`target_mesh` is for 3D growth; in 2D give `target_point` or `target_plane` (a line)");
  }
  const detail::Electrode electrode(t, detail::seeded(walk.seeds, walk.spacing, walk.dimensions).center, walk.spacing,
                                    walk.dimensions);
  for (std::size_t i = 0; i < walk.seeds.size(); ++i) {
    const double d = electrode.distance(walk.seeds[i]);
    if (d <= walk.spacing)
      throw InvalidInput("seed " + std::to_string(i + 1) + (d < 0.0 ? " is beyond" : " touches") +
                         " the target (within a spacing of it): the electrodes must be apart");
    if (t.kind == TargetKind::mesh && !t.mesh->on_growth_side(walk.seeds[i]))
      throw InvalidInput("seed " + std::to_string(i + 1) + " is inside the target: the electrodes must be apart");
  }
}

namespace {

//! The choice among contacts draws from streams of their own, apart from every walker's.
constexpr std::uint64_t kChoiceStreams = std::uint64_t{1} << 63;

class Discharge {
 public:
  Discharge(const DlaOptions& walk, const BreakdownOptions& o, const MeshConstraint* constraint,
            const StopFlag* stop, BreakdownStats& stats)
      : walk_(walk),
        options_(o),
        walkers_(static_cast<std::size_t>(walkers_for(o))),
        stop_(stop),
        stats_(stats),
        dla_stats_{{}, 0, 0.0, stats.feed},
        electrode_(o.target.kind == TargetKind::none
                       ? std::nullopt
                       : std::optional<detail::Electrode>(std::in_place, o.target,
                                                          detail::seeded(walk.seeds, walk.spacing, walk.dimensions).center,
                                                          walk.spacing, walk.dimensions)),
        aggregation_(walk_, constraint, nullptr, stop, dla_stats_, electrode_ ? &*electrode_ : nullptr),
        crew_(walk.threads) {}

  Cluster run(const ProgressFn& progress) {
    detail::ModelShell shell(progress, stop_);
    Cluster& cluster = aggregation_.structure();
    if (electrode_)
      for (const Particle& p : cluster.particles) electrode_->grown(p.position);
    try {
      for (std::size_t k = attached(cluster); k < walk_.particles; ++k) {
        std::optional<Particle> next = grow_one(k);
        if (!next) {
          cluster.complete = false;
          shell.stop();
          break;
        }
        aggregation_.attach(*next);
        if (electrode_) {
          electrode_->grown(next->position);
          if (cluster.strike < 0 && electrode_->distance(next->position) <= walk_.spacing) {
            cluster.strike = static_cast<std::int32_t>(cluster.particles.size() - 1);
            if (options_.stop_at_strike) break;
            // A ball touched is at the structure's potential, and soon buried in it: walkers
            // come from far away from now on. A plane, too wide to bury, goes on sending them.
            if (options_.target.kind == TargetKind::point) aggregation_.leave_target();
          }
        }
        if (k + 1 < walk_.particles && !shell.go_on(cluster)) {
          cluster.complete = false;
          break;
        }
      }
    } catch (...) {
      finish_stats(cluster);
      detail::ModelShell::keep_what_grew(cluster);
    }
    finish_stats(cluster);
    shell.finish(cluster);
    return std::move(cluster);
  }

 private:
  //! Walker m of particle k draws from stream k + m * 2^40: walker 0 from DLA's walker k's.
  static constexpr std::uint64_t kWalkerStride = std::uint64_t{1} << 40;
  //! Walkers a particle at most: then the plain h^eta weighs sites whose count is below eta.
  static constexpr std::size_t kMaxWalkersPerParticle = std::size_t{1} << 20;

  //! The next particle, by the contacts of walkers run against the structure of k particles
  //! in batches of `walkers`, until a site has weight: site j, a parent touched h_j times,
  //! weighs h_j! / (h_j - eta)! (zero for h_j < eta), whose mean is M^eta p_j^eta for whole
  //! eta (the factorial moments), so that the field's power is not blunted by few walkers.
  //! One site is drawn by weight, then one of its contacts at random: at eta 1, one contact
  //! drawn uniformly, and with one walker that walker's, DLA's. Empty when stopped.
  std::optional<Particle> grow_one(std::size_t k) {
    contacts_.clear();
    for (;;) {
      // Batches double, so that weighing them all costs a few times weighing the last.
      const std::size_t first = contacts_.size();
      if (!measure(k, first, std::max(walkers_, first))) return std::nullopt;
      if (walkers_ == 1 && options_.eta == 1.0) return contacts_[0];
      const bool last = contacts_.size() >= kMaxWalkersPerParticle;
      if (weigh(last)) break;
    }
    stats_.sites += sites_.size();
    Rng rng(walk_.rng_seed, kChoiceStreams + k);
    const double u = rng.uniform() * sites_.back().cumulative;
    const Site* site = &sites_.back();
    for (const Site& s : sites_)
      if (u < s.cumulative) {
        site = &s;
        break;
      }
    const std::size_t hits = site->end - site->begin;
    const std::size_t pick = site->begin + std::min(hits - 1, static_cast<std::size_t>(rng.uniform() * static_cast<double>(hits)));
    return contacts_[order_[pick]];
  }

  //! The sites of the contacts so far and their cumulative weights; false if none weighs.
  //! With `plain`, h^eta, which every touched site has.
  bool weigh(bool plain) {
    order_.resize(contacts_.size());
    for (std::size_t m = 0; m < order_.size(); ++m) order_[m] = static_cast<std::uint32_t>(m);
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
      return contacts_[a].parent != contacts_[b].parent ? contacts_[a].parent < contacts_[b].parent : a < b;
    });
    sites_.clear();
    double total = 0.0;
    for (std::size_t i = 0; i < order_.size();) {
      std::size_t j = i;
      while (j < order_.size() && contacts_[order_[j]].parent == contacts_[order_[i]].parent) ++j;
      const double h = static_cast<double>(j - i);
      const double weight = plain ? std::pow(h, options_.eta) : falling_power(h, options_.eta);
      if (weight > 0.0) {
        total += weight;
        sites_.push_back({i, j, total});
      }
      i = j;
    }
    return total > 0.0;
  }

  //! h! / (h - eta)!, by the gamma function; 0 where h < eta.
  static double falling_power(double h, double eta) {
    if (h < eta) return 0.0;
    if (eta == 0.0) return 1.0;
    return std::exp(std::lgamma(h + 1.0) - std::lgamma(h + 1.0 - eta));
  }

  //! A batch of `count` more walkers, contacts `first` on of particle k, each on its own
  //! stream, so the contacts are the same on any thread count. False when stopped.
  bool measure(std::size_t k, std::size_t first, std::size_t count) {
    contacts_.resize(first + count);
    walks_.assign(count, WalkStats{});
    walked_.assign(count, 0);
    errors_.assign(count, nullptr);
    crew_.run(count, [&](std::size_t m) {
      try {
        walked_[m] = aggregation_.trial(k + (first + m) * kWalkerStride, walks_[m], contacts_[first + m]) ? 1 : 0;
      } catch (...) {
        walked_[m] = 2;
        errors_[m] = std::current_exception();
      }
    });
    for (std::size_t m = 0; m < count; ++m) {
      accumulate(stats_.walk, walks_[m]);
      if (walked_[m] == 2) std::rethrow_exception(errors_[m]);  // the first walker's error
    }
    return std::all_of(walked_.begin(), walked_.end(), [](char w) { return w == 1; });
  }

  void finish_stats(const Cluster& cluster) {
    stats_.absorbed = stats_.walk.absorbed;
    stats_.strike = cluster.strike;
    stats_.channel = detail::channel_length(cluster);
  }

  struct Site {
    std::size_t begin, end;  // in order_
    double cumulative;       // the weights up to and with this one
  };

  const DlaOptions& walk_;
  const BreakdownOptions& options_;
  const std::size_t walkers_;
  const StopFlag* stop_;
  BreakdownStats& stats_;
  DlaStats dla_stats_;
  std::optional<detail::Electrode> electrode_;
  detail::Aggregation<GridIndex> aggregation_;
  detail::Crew crew_;
  std::vector<Particle> contacts_;
  std::vector<WalkStats> walks_;
  std::vector<char> walked_;  // per walker of a batch: 1 contact, 0 stopped, 2 threw
  std::vector<std::exception_ptr> errors_;  // per walker of a batch, when it threw
  std::vector<std::uint32_t> order_;  // contacts by site
  std::vector<Site> sites_;
};

}  // namespace

Cluster breakdown(const DlaOptions& walk, const BreakdownOptions& options, const MeshConstraint* constraint,
                  const ProgressFn& progress, const StopFlag* stop, BreakdownStats* stats) {
  if (constraint) validate(walk, *constraint);
  validate(options, walk);
  if (spawns_from_mesh(walk.spawn) && !constraint)
    throw InvalidInput("spawn " + std::string(to_string(walk.spawn)) + " needs a constraint mesh");
  BreakdownStats own;
  BreakdownStats& counted = stats ? *stats : own;
  ParticleFeed* feed = counted.feed;
  counted = {};
  counted.feed = feed;
  if (options.field == BreakdownField::charges)
    return detail::grow_by_charges(walk, options, constraint, progress, stop, counted);
  if (options.field == BreakdownField::conductor)
    return detail::grow_by_conductor(walk, options, constraint, progress, stop, counted);
  Discharge discharge(walk, options, constraint, stop, counted);
  return discharge.run(progress);
}

}  // namespace dla
