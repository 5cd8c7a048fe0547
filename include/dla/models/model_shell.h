#pragma once
//! \file model_shell.h
//! What every growth model grows in: a structure started from its seeds, progress reported at
//! a pace in time whatever the model's speed, the stop flag, and what grew kept when growth
//! fails part way (PartialGrowth, errors.h).

#include "dla/core/cluster.h"
#include "dla/core/errors.h"

#include <chrono>
#include <cstdint>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace dla {

//! Growth calls its ProgressFn as it begins, then about this often, and at the end: twenty
//! times a second, so that a live view (`--stream`, the studio) shows at least ten updates a
//! second even when a call comes late.
inline constexpr double kProgressSeconds = 0.05;

namespace detail {

//! A structure of `seeds`, a tree each, the first particles; its centre theirs.
inline Cluster seeded(const std::vector<Vec3>& seeds, double spacing, int dimensions) {
  Cluster cluster;
  cluster.spacing = spacing;
  cluster.dimensions = dimensions;
  cluster.seed_count = seeds.size();
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    cluster.particles.push_back({seeds[i], -1, static_cast<std::int32_t>(i)});
    cluster.center += seeds[i];
  }
  if (!seeds.empty()) cluster.center /= static_cast<double>(seeds.size());
  return cluster;
}

//! The progress calls and the stop flag of one growth run.
class ModelShell {
 public:
  //! `steps_per_look` is how many steps go by between looks at the clock: for models whose
  //! steps take a microsecond or so (a drop), a look each would show.
  ModelShell(const ProgressFn& progress, const StopFlag* stop, std::uint32_t steps_per_look = 1)
      : progress_(progress), stop_(stop), steps_per_look_(steps_per_look), steps_(steps_per_look - 1) {}

  //! Between two steps of growth (particles, sites, iterations): whether growth goes on. It
  //! ends when `stop` is set or `progress`, called at the first look at the clock and then
  //! about every kProgressSeconds, returns false; the caller then marks it incomplete.
  bool go_on(const Cluster& so_far) {
    return go_on_making([&]() -> const Cluster& { return so_far; });
  }

  //! As go_on(), for a model whose structure so far takes work to make (an aggregate's
  //! clusters): `so_far()` makes it only when a progress call is due.
  template <class SoFar>
  bool go_on_making(SoFar&& so_far) {
    if (stop_ && stop_->load(std::memory_order_relaxed)) return stop();
    if (!progress_ || ++steps_ < steps_per_look_) return true;
    steps_ = 0;
    const Clock::time_point now = Clock::now();
    if (now < next_) return true;
    next_ = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kProgressSeconds));
    return progress_(so_far()) || stop();
  }

  //! At the end: the last progress call, unless growth was stopped.
  void finish(const Cluster& grown) const {
    if (progress_ && !stopped_) progress_(grown);
  }

  //! Growth stopped on its own terms (DLA's walkers see the stop flag in their walk): no last
  //! progress call.
  bool stop() {
    stopped_ = true;
    return false;
  }

  //! In a catch (...) block around a model's growth of `cluster`: growth that failed part way
  //! (GrowthError, memory run out) throws PartialGrowth with what grew, marked incomplete;
  //! anything else goes on up as it was.
  [[noreturn]] static void keep_what_grew(Cluster& cluster) {
    try {
      throw;
    } catch (const PartialGrowth&) {
      throw;
    } catch (const GrowthError& e) {
      cluster.complete = false;
      throw PartialGrowth(e.what(), std::move(cluster));
    } catch (const std::bad_alloc&) {
      cluster.complete = false;
      const std::string grown = std::to_string(cluster.particles.size() - cluster.seed_count);
      throw PartialGrowth("out of memory after " + grown + " particles", std::move(cluster));
    }
  }

 private:
  using Clock = std::chrono::steady_clock;

  const ProgressFn& progress_;
  const StopFlag* stop_;
  const std::uint32_t steps_per_look_;
  std::uint32_t steps_;       // since the last look at the clock; the first step looks
  Clock::time_point next_{};  // the next progress call is due: the first is at once
  bool stopped_ = false;
};

}  // namespace detail

}  // namespace dla
