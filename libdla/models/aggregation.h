#pragma once
// DLA's engine (dla.h's grow_with): walkers on one thread or several, each drawing from its own
// random stream, attached in launch order so that every thread count grows the same structure.
// Private to libdla: dla.cpp instantiates it for every index, and the breakdown model walks
// with it (breakdown.cpp).

#include "dla/models/dla.h"

#include "dla/core/cluster.h"
#include "dla/core/huge_pages.h"
#include "dla/core/particle_feed.h"
#include "dla/mesh/constraint.h"
#include "dla/core/options.h"
#include "dla/core/random.h"
#include "dla/models/electrode.h"
#include "dla/models/fill.h"
#include "dla/models/model_shell.h"
#include "dla/models/spawn.h"
#include "dla/index/spatial_index.h"
#include "dla/models/walk.h"

#include <Eigen/Geometry>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace dla {

namespace detail {

//! What a walker reads of the structure besides the index: the sphere around every particle
//! and the sphere walkers are put back on. A new value is a new object, so a walker that ran
//! ahead can tell whether it saw the one its turn would have.
struct Sight {
  double cluster_radius = 0.0;  // largest particle distance from the centre
  double return_radius = 0.0;
};

//! A walker running ahead of earlier ones records, for each look-up, the box outside which no
//! particle attached meanwhile could have changed the answer, and the box where only one that
//! opened a cell could have (see Probe).
struct Read {
  Vec3 min, max;
  Vec3 opening_min, opening_max;
};

//! Walkers on other threads stop at their next step while the grid's domain grows.
class Pause {
 public:
  void check() {
    if (requested_.load(std::memory_order_relaxed)) park();
  }
  //! Around a walk on a worker thread.
  void enter() {
    active_.fetch_add(1);
    if (requested_.load()) park();
  }
  void leave() { active_.fetch_sub(1); }
  //! Stops every walker in a walk, calls `f`, and lets them go on.
  template <class F>
  void while_stopped(F&& f) {
    requested_.store(true);
    while (active_.load() != 0) std::this_thread::yield();
    // Let them go on even if f throws (the domain cannot grow): they must see the stop.
    struct Release {
      std::atomic<bool>& requested;
      ~Release() { requested.store(false); }
    } release{requested_};
    f();
  }

 private:
  void park() {
    active_.fetch_sub(1);
    while (requested_.load()) std::this_thread::yield();
    active_.fetch_add(1);
    if (requested_.load()) park();
  }
  alignas(64) std::atomic<bool> requested_{false};  // read at every step: a line of its own
  alignas(64) std::atomic<int> active_{0};
};

template <class Index>
class Aggregation {
 public:
  //! With `target`, walkers leave it and start again when they come back (breakdown.h).
  Aggregation(const DlaOptions& options, const MeshConstraint* constraint, const Cluster* partial,
              const StopFlag* stop, DlaStats& stats, const Electrode* target = nullptr)
      : opt_(options),
        stats_(stats),
        constraint_(constraint),
        target_(target),
        stop_(stop),
        contact_(options.spacing),
        near_step_(options.min_step * options.spacing),
        drift_scale_(1.0 / (1.0 + options.drift.norm())),
        radians_per_walker_(options.rotate_degrees * (3.141592653589793238462643383279502884 / 180.0) / 1000.0),
        cluster_(seeded(options.seeds, options.spacing, options.dimensions)),
        index_(cluster_.particles, options.spacing, options.dimensions) {
    // The seeds, or the stopped run's particles: added one by one, in the same order, they
    // build the same index and radii.
    const std::vector<Particle> first = partial ? partial->particles : std::move(cluster_.particles);
    cluster_.particles.clear();
    // Walkers on other threads read particles while one is appended: the store never moves.
    cluster_.particles.reserve(options.seeds.size() + options.particles);
    advise_huge_pages(cluster_.particles.data(), cluster_.particles.capacity() * sizeof(Particle));
    if (options.threads > 1) opened_.reserve(options.seeds.size() + options.particles);
    index_.reserve(options.seeds.size() + options.particles);
    if (constraint && options.fill > 0.0)
      fill_ = std::make_unique<FillGauge>(*constraint, options.fill_distance * options.spacing);
    for (const Particle& p : first) add(p);
  }

  Cluster run(const ProgressFn& progress) {
    ModelShell shell(progress, stop_);
    try {
      if (opt_.threads > 1) {
        if (!filled()) run_in_parallel(shell);
      } else {
        for (std::size_t k = attached(cluster_); k < opt_.particles && !filled(); ++k) {
          add(walk(k, *sight_, stats_.walk, nullptr));
          if (!go_on(k, shell)) break;
        }
      }
    } catch (const Stopped&) {
      cluster_.complete = false;
      shell.stop();
    } catch (...) {
      ModelShell::keep_what_grew(cluster_);
    }
    shell.finish(cluster_);
    return std::move(cluster_);
  }

  // For models that choose among several walkers' contacts (breakdown.h): one walker on
  // `stream` run against the structure as it is, without attaching, safe on several threads
  // at once while nothing attaches; false when the stop flag ended it.
  bool trial(std::uint64_t stream, WalkStats& stats, Particle& contact) {
    try {
      contact = walk(stream, *sight_, stats, nullptr);
      return true;
    } catch (const Stopped&) {
      return false;
    }
  }
  void attach(const Particle& p) { add(p); }
  Cluster& structure() { return cluster_; }
  //! From the next walker on, walkers come from the spawn rather than the target.
  void leave_target() { target_ = nullptr; }

 private:
  //! Thrown out of a walk when the stop flag is set.
  struct Stopped {};

  //! Every this many steps a walk looks at the stop flag: ~0.1-1 ms of walking.
  static constexpr std::uint64_t kStopCheckSteps = 4096;
  // Walkers in a shell start afresh after this many steps, this many times at most.
  static constexpr std::uint64_t kShellRestartSteps = 1'000'000, kMaxShellRestarts = 64;

  //! After walker k's particle: whether growth goes on (the shell's say, model_shell.h); when
  //! it does not, the cluster is marked incomplete.
  bool go_on(std::size_t k, ModelShell& shell) {
    if (k + 1 == opt_.particles || filled() || shell.go_on(cluster_)) return true;
    cluster_.complete = false;
    return false;
  }

  //! The most reads a worker's vector keeps between walks: 6 MB.
  static constexpr std::size_t kReadsKept = std::size_t{1} << 16;

  //! Walker k's result as it ran on a worker thread (a cache line of its own).
  struct alignas(64) Slot {
    std::atomic<bool> done{false};
    bool failed = false;            // threw (it runs again in turn, where the error is real),
                                    // or a particle attached since it started changed its path
    std::size_t seen = 0;           // particles attached when it started, then when it was
                                    // last checked
    const Sight* sight = nullptr;   // the sight it walked with
    Particle result{};
    WalkStats stats;
    std::vector<Read> reads;
  };

  //! Several walkers at once, committed in launch order. Walker k runs against the structure
  //! as it is when it starts and records what it read; at its turn, if a particle attached
  //! since could have changed any answer it got, or the sight changed, it runs again, now
  //! against exactly the structure of a one-thread run. Walker k draws from its own stream, so
  //! the run again draws the same numbers, and the result is the one-thread result.
  void run_in_parallel(ModelShell& shell) {
    const std::size_t first = attached(cluster_), last = opt_.particles;
    const std::size_t window = 4 * static_cast<std::size_t>(opt_.threads);  // walkers ahead at most
    std::vector<Slot> slots(window);
    alignas(64) std::atomic<std::size_t> next{first};
    alignas(64) std::atomic<std::size_t> committed{first};
    alignas(64) std::atomic<bool> stop{false};
    std::mutex commit_mutex;
    std::exception_ptr error;

    // Commits finished walkers in order while the next one is done; one thread at a time.
    const auto commit = [&] {
      std::unique_lock<std::mutex> lock(commit_mutex, std::try_to_lock);
      if (!lock) return;
      try {
        for (std::size_t k = committed.load(); k < last && !stop.load(); k = committed.load()) {
          Slot& slot = slots[k % window];
          if (!slot.done.load(std::memory_order_acquire)) break;
          if (slot.failed || slot.sight != sight_ || !unchanged(slot.reads, slot.seen, k)) {
            ++stats_.replays;
            slot.stats = {};
            slot.result = walk(k, *sight_, slot.stats, nullptr);
          }
          add_stopping(slot.result);
          accumulate(stats_.walk, slot.stats);
          slot.done.store(false, std::memory_order_relaxed);
          committed.store(k + 1, std::memory_order_release);
          // Where the one-thread run stops too.
          if (!go_on(k, shell) || filled()) stop.store(true);
        }
      } catch (...) {
        error = std::current_exception();
        stop.store(true);
      }
    };

    const auto work = [&] {
      std::vector<Read> reads;
      for (;;) {
        const std::size_t k = next.fetch_add(1);
        if (k >= last) break;
        while (k >= committed.load(std::memory_order_acquire) + window && !stop.load()) {
          commit();
          std::this_thread::yield();
        }
        if (stop.load()) break;
        Slot& slot = slots[k % window];
        pause_.enter();
        slot.seen = committed.load(std::memory_order_acquire);
        slot.sight = sight_published_.load(std::memory_order_acquire);
        // The walk writes to this thread's own stats and reads, not to the shared slots.
        WalkStats stats;
        reads.clear();
        // A rare walk of millions of steps leaves a vector of hundreds of MB: let it go.
        if (reads.capacity() > kReadsKept) std::vector<Read>().swap(reads);
        try {
          slot.result = walk(k, *slot.sight, stats, &reads);
          slot.failed = false;
        } catch (...) {
          slot.failed = true;
        }
        pause_.leave();
        // Checked here against what is attached by now, while the reads are in this core's
        // cache: at its turn only the particles attached since remain to check.
        const std::size_t attached_now = committed.load(std::memory_order_acquire);
        if (!slot.failed && !unchanged(reads, slot.seen, attached_now)) slot.failed = true;
        slot.seen = attached_now;
        slot.stats = stats;
        std::swap(slot.reads, reads);
        slot.done.store(true, std::memory_order_release);
        commit();
      }
      while (committed.load() < last && !stop.load()) {
        commit();
        std::this_thread::yield();
      }
    };

    std::vector<std::thread> helpers;
    for (int t = 1; t < opt_.threads; ++t) helpers.emplace_back(work);
    work();
    for (std::thread& helper : helpers) helper.join();
    if (error) std::rethrow_exception(error);
  }

  //! Whether no particle attached by walkers [from, to) lies in a box of `reads` (an opening
  //! box only counts for a particle that opened a cell).
  bool unchanged(const std::vector<Read>& reads, std::size_t from, std::size_t to) const {
    for (std::size_t j = from; j < to; ++j) {
      const std::size_t id = cluster_.seed_count + j;
      const Vec3& p = position(static_cast<std::int32_t>(id));
      const bool opened = opened_[id] != 0;
      for (const Read& read : reads)
        if (in_box(p, read.min, read.max) || (opened && in_box(p, read.opening_min, read.opening_max))) return false;
    }
    return true;
  }

  bool drifting() const { return opt_.drift.squaredNorm() > 0.0; }
  bool turning() const { return radians_per_walker_ != 0.0; }

  //! Walker k's frame: the spawn and the drift turned by k times the rotation a walker (the
  //! same for any thread count: k is the number attached before it in every run).
  Eigen::Matrix3d frame(std::size_t k) const {
    Vec3 axis = Vec3::Zero();
    axis[static_cast<int>(opt_.rotate_axis)] = 1.0;
    return Eigen::AngleAxisd(static_cast<double>(k) * radians_per_walker_, axis).toRotationMatrix();
  }

  //! add() while walkers run on other threads: they stop while the grid's domain grows.
  void add_stopping(const Particle& p) {
    const double radius = std::max(sight_->cluster_radius, (p.position - cluster_.center).norm());
    if (index_.holds(p.position, 0.0) && index_.holds(cluster_.center, return_radius_for(radius))) {
      add(p);
      return;
    }
    pause_.while_stopped([&] {
      add(p);
      // The domain changed under the walkers in flight: a new sight sends them all round again.
      sights_.push_back(*sight_);
      sight_ = &sights_.back();
      sight_published_.store(sight_, std::memory_order_release);
    });
  }

  //! Walkers are put back on this sphere from outside; two spacings of margin keep a returned
  //! walker clear of every contact ball.
  double return_radius_for(double cluster_radius) const { return cluster_radius + 2.0 * contact_; }

  //! Whether growth asked to fill the mesh has: it stops there, complete.
  bool filled() const { return fill_ && stats_.filled >= opt_.fill; }

  void add(const Particle& p) {
    cluster_.particles.push_back(p);
    if (stats_.feed) stats_.feed->put(p);
    if (fill_) {
      fill_->add(p.position);
      stats_.filled = fill_->fraction();
    }
    const bool opened = index_.insert(static_cast<std::int32_t>(cluster_.particles.size() - 1));
    if (opt_.threads > 1) opened_.push_back(opened);
    const double r = (p.position - cluster_.center).norm();
    if (sight_ && r <= sight_->cluster_radius) return;
    sights_.push_back({r, return_radius_for(r)});
    sight_ = &sights_.back();
    index_.cover(cluster_.center, sight_->return_radius);
    sight_published_.store(sight_, std::memory_order_release);
  }

  //! Records, for a walker running ahead, what a look-up's answer depends on.
  static void read(std::vector<Read>* reads, const Probe& probe) {
    if (reads) reads->push_back({probe.reach_min, probe.reach_max, probe.opening_min, probe.opening_max});
  }

  //! Probes the index at x and records the answer for a walker running ahead, the only one
  //! that needs its reach.
  Probe probe(const Vec3& x, std::vector<Read>* reads) const {
    const Probe answer = index_.probe(x, reads ? Reach::set : Reach::skip);
    read(reads, answer);
    return answer;
  }

  //! Runs walker number k from launch to contact and returns the particle it becomes.
  Particle walk(std::size_t k, const Sight& sight, WalkStats& stats, std::vector<Read>* reads) {
    ++stats.walkers;
    Rng rng(opt_.rng_seed, k);
    const Vec3& center = cluster_.center;
    const double return_radius = sight.return_radius;
    const Eigen::Matrix3d turn = turning() ? frame(k) : Eigen::Matrix3d::Identity();
    const Vec3 drift = turning() ? Vec3(turn * opt_.drift) : opt_.drift;
    const Eigen::Matrix3d* turned = turning() ? &turn : nullptr;
    const auto start = [&] { return target_ ? launch_from_target(rng, sight, reads) : launch(rng, sight, reads, turned); };
    Vec3 x = start();
    // Bounds that turn a setup where nothing can stick into an error rather than a hang.
    constexpr std::uint64_t max_lost = 10'000'000, max_rejected = 10'000, max_relaunches = 100'000,
                            max_absorbed = 1'000'000;
    std::uint64_t lost = 0, rejected = 0, relaunches = 0, steps = 0, absorbed = 0;
    const auto relaunch = [&] {
      ++stats.relaunches;
      if (++relaunches == max_relaunches)
        throw GrowthError("walker " + std::to_string(k + 1) + " was started afresh " + std::to_string(max_relaunches) +
                          " times without reaching the structure: walkers start too far from it, or the drift "
                          "carries them away");
      x = start();
    };
    const auto back_to_target = [&] {
      ++stats.absorbed;
      if (++absorbed == max_absorbed)
        throw GrowthError("walkers leaving the target went back to it or far away " + std::to_string(max_absorbed) +
                          " times without reaching the structure: the target cannot reach it (an insulator between "
                          "them, or a target on the other side of the mesh)");
      x = start();
    };
    const double far_away = target_ ? target_->far_away(center, return_radius) : 0.0;
    // In a shell, steps reach at most its thickness, and half as far after each step refused at
    // its edge (down to the near step): a walker in a narrow part still moves.
    const double shell = constraint_ ? constraint_->shell() : 0.0;
    double reach = shell;
    const auto refused = [&] {
      ++stats.lost;
      if (++lost == max_lost)
        throw GrowthError("walker " + std::to_string(k + 1) + " had " + std::to_string(max_lost) +
                          " steps refused at the shell's edge: the shell is too thin to move in, or walkers start "
                          "in parts of it that the structure does not reach");
      reach = std::max(near_step_, 0.5 * reach);
    };
    for (;;) {
      if (reads) pause_.check();
      if (++steps % kStopCheckSteps == 0 && stop_ && stop_->load(std::memory_order_relaxed)) throw Stopped{};
      ++stats.steps;
      // A shell's parts need not meet (around letters far apart): a walker that has not
      // reached the structure in a million steps starts afresh.
      if (shell != 0.0 && steps % kShellRestartSteps == 0) {
        if (steps / kShellRestartSteps == kMaxShellRestarts)
          throw GrowthError("walker " + std::to_string(k + 1) + " walked " + std::to_string(steps) +
                            " steps in the shell without reaching the structure: parts of the shell do not meet it "
                            "(seed each, or use a thicker shell)");
        relaunch();
      }
      const Vec3 offset = x - center;
      const double r2 = offset.squaredNorm();
      // From a target, walkers walk on spheres clear of it and of the structure's sphere; one
      // back on the target, or far from both, leaves it again.
      const double to_target = target_ ? target_->distance(x) : 0.0;
      if (target_ && (to_target < target_->absorbs() || r2 > far_away * far_away)) {
        back_to_target();
        continue;
      }
      // Walkers put on the return sphere sit on it up to rounding: they count as inside. In a
      // shell, there is no return through free space: walkers far away walk on in the shell.
      if (shell == 0.0 && r2 > return_radius * return_radius * (1.0 + 1e-9)) {
        if (target_) {
          x += jump(rng, std::min(std::sqrt(r2) - sight.cluster_radius - contact_, to_target), drift);
          continue;
        }
        if (!drifting()) {
          const ReturnPoint back = return_to_sphere(offset, return_radius, rng, opt_.dimensions);
          if (back.returned) {
            ++stats.returns;
            x = center + back.offset;
          } else {
            relaunch();
          }
          continue;
        }
        // With drift there is no closed-form return: walk on, with the distance to the
        // bounding sphere as the free radius, and start afresh far away.
        const double kill = std::max(3.0 * return_radius, return_radius + 64.0 * contact_);
        if (r2 > kill * kill) {
          relaunch();
          continue;
        }
        x += jump(rng, std::sqrt(r2) - sight.cluster_radius - contact_, drift);
        continue;
      }

      if (constraint_ && constraint_->lost(x)) {
        ++stats.lost;
        if (++lost == max_lost)
          throw GrowthError("walker " + std::to_string(k + 1) + " left the growing side of the mesh " +
                            std::to_string(max_lost) + " times: walkers cannot reach the seeds");
        x = start();
        continue;
      }

      // Outside the sphere around every particle, its distance is a bound the index may not beat.
      double free = std::max(probe(x, reads).distance, std::sqrt(r2) - sight.cluster_radius) - contact_;
      // Near the target, a near step may cross it: the walker is back on it at the next.
      if (target_) free = std::min(free, to_target);
      if (free > near_step_) {
        if (shell == 0.0) {
          x += jump(rng, free, drift);
          continue;
        }
        const Vec3 next = x + jump(rng, std::min(free, reach), drift);
        if (constraint_->lost(next)) {
          refused();
          continue;
        }
        x = next;
        reach = shell;
        continue;
      }

      // Next to the structure: a short straight step, stopped at the first contact.
      ++stats.near_steps;
      const Vec3 step = near_step_ * (random_direction(rng, opt_.dimensions) + drift);
      double first = 2.0;
      std::int32_t touched = -1;
      const double search = contact_ + step.norm();
      read(reads, Probe{}.reaching(x, search));
      index_.for_each_within(x, search, [&](std::int32_t id, double) {
        const double t = contact_along(x, step, position(id), contact_);
        if (t >= 0.0 && t < first) {
          first = t;
          touched = id;
        }
      });
      if (touched < 0) {
        if (shell != 0.0 && constraint_->lost(x + step)) {
          refused();
          continue;
        }
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
                              std::to_string(k + 1) + ": it touches the structure only across the surface (seeds " +
                              "within a spacing of it, or, with the surface spawn, a structure that fills the " +
                              "mesh's skin: grow fewer particles or use `spawn` inside)");
          // In a shell, a walker can be caught between the structure and the shell's edge, where
          // every contact would put the particle outside the shell: it starts afresh.
          if (shell != 0.0) relaunch();
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
  Vec3 jump(Rng& rng, double free, const Vec3& drift) const {
    return free * drift_scale_ * (random_direction(rng, opt_.dimensions) + drift);
  }

  const Vec3& position(std::int32_t id) const {
    return cluster_.particles[static_cast<std::size_t>(id)].position;
  }

  //! A walker's start, in the frame `turn` if the spawn turns. Starts beyond the return sphere
  //! are fine: the walk's first step applies the return rule. A start within contact of the
  //! structure, or lost, is drawn again.
  Vec3 launch(Rng& rng, const Sight& sight, std::vector<Read>* reads, const Eigen::Matrix3d* turn) const {
    const Vec3& center = cluster_.center;
    const double R2 = sight.return_radius * sight.return_radius;
    constexpr int max_draws = 1'000'000;
    for (int draw = 0; draw < max_draws; ++draw) {
      Vec3 x = draw_start(rng, sight);
      if (turn) x = center + *turn * (x - center);
      if (constraint_ && constraint_->lost(x)) continue;
      if ((x - center).squaredNorm() >= R2) return x;
      if (probe(x, reads).distance >= contact_) return x;
    }
    throw GrowthError("no free start in " + std::to_string(max_draws) + " draws from the " +
                      std::string(to_string(opt_.spawn)) + " spawn" +
                      (constraint_ ? " on the growing side of the mesh" : ": the structure fills it"));
  }

  //! A start just off the target electrode (electrode.h), clear of the structure and on the
  //! growing side of the mesh; drawn again if not.
  Vec3 launch_from_target(Rng& rng, const Sight& sight, std::vector<Read>* reads) const {
    const Vec3& center = cluster_.center;
    const double R2 = sight.return_radius * sight.return_radius;
    constexpr int max_draws = 1'000'000;
    for (int draw = 0; draw < max_draws; ++draw) {
      const Vec3 x = target_->draw_start(rng);
      if (constraint_ && constraint_->lost(x)) continue;
      if ((x - center).squaredNorm() >= R2 || probe(x, reads).distance >= contact_) return x;
    }
    throw GrowthError("no free start by the target in " + std::to_string(max_draws) +
                      " draws: it lies on the wrong side of the mesh, or the structure covers it");
  }

  Vec3 draw_start(Rng& rng, const Sight& sight) const {
    if (constraint_) {
      switch (opt_.spawn) {
        case SpawnMode::inside: return constraint_->draw_inside(rng);
        case SpawnMode::radial: return constraint_->draw_radial(rng);
        case SpawnMode::surface: return constraint_->draw_near_surface(rng);
        case SpawnMode::sphere: {  // around the mesh and the structure
          const Vec3& c = constraint_->center();
          const double R = std::max(constraint_->radius(), (c - cluster_.center).norm() + sight.return_radius);
          return draw_spawn(opt_, c, R, rng);
        }
        default: break;
      }
    }
    return draw_spawn(opt_, cluster_.center, sight.return_radius, rng);
  }

  const DlaOptions& opt_;
  DlaStats& stats_;                   // the caller's, counted as walkers attach
  const MeshConstraint* constraint_;  // null: unconstrained
  const Electrode* target_;           // null: walkers come from the spawn
  const StopFlag* stop_;              // null: no stop but by `progress`
  const double contact_;      // centre distance at which a walker touches a particle
  const double near_step_;    // step length near the structure
  const double drift_scale_;  // keeps a drifted jump inside its free ball
  const double radians_per_walker_;  // Bourke's rotation of the spawn and the drift
  alignas(64) Cluster cluster_;  // written at every attachment: apart from what walkers read
  HugePageVector<std::uint8_t> opened_;  // per particle, with threads: whether it opened a cell
  std::unique_ptr<FillGauge> fill_;   // with DlaOptions::fill and a mesh: the volume covered
  alignas(64) Index index_;
  std::deque<Sight> sights_;                     // every sight so far: walkers may hold any
  const Sight* sight_ = nullptr;                // the current one
  std::atomic<const Sight*> sight_published_{nullptr};  // the current one, for worker threads
  Pause pause_;
};

}  // namespace detail

template <class Index>
Cluster grow_with(const DlaOptions& options, const ProgressFn& progress, const MeshConstraint* constraint,
                  const Cluster* partial, const StopFlag* stop, DlaStats* stats) {
  DlaStats own;
  return detail::Aggregation<Index>(options, constraint, partial, stop, stats ? *stats : own).run(progress);
}

}  // namespace dla
