// Growth end to end: the invariants of the grown tree under every option that changes the
// walk, determinism, the fractal dimension, and that bad options are refused.

#include "dla/core/analysis.h"
#include "dla/core/particle_feed.h"
#include "dla/models/dla.h"
#include "tree_check.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include <thread>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <vector>

namespace dla {
namespace {

// The counts asked for, and a tree (tree_check.h) whose particles are a spacing apart.
void expect_valid_tree(const Cluster& c, const DlaOptions& o) {
  ASSERT_EQ(c.particles.size(), o.seeds.size() + o.particles);
  ASSERT_EQ(c.seed_count, o.seeds.size());
  EXPECT_EQ(testing::tree_fault(c), "");
}

double mean_z(const Cluster& c) {
  double sum = 0.0;
  for (const Particle& p : c.particles) sum += p.position.z();
  return sum / static_cast<double>(c.particles.size());
}

DlaOptions small(std::size_t n = 3000) {
  DlaOptions o;
  o.particles = n;
  return o;
}

TEST(Growth, TreeInvariantsDefault) {
  const DlaOptions o = small();
  expect_valid_tree(grow(o), o);
}

TEST(Growth, TreeInvariantsPlanar) {
  DlaOptions o = small();
  o.dimensions = 2;
  expect_valid_tree(grow(o), o);
}

TEST(Growth, TreeInvariantsLowStickinessAndShortSteps) {
  DlaOptions o = small(2000);
  o.stickiness = 0.2;
  o.min_step = 0.2;
  o.spacing = 2.5;
  DlaStats stats;
  const Cluster c = grow(o, {}, nullptr, &stats);
  expect_valid_tree(c, o);
  EXPECT_GT(stats.walk.contacts, 2 * stats.walk.walkers) << "refused contacts must happen";
}

TEST(Growth, TreeInvariantsEveryIndex) {
  for (IndexKind kind : {IndexKind::kdtree, IndexKind::brute}) {
    DlaOptions o = small(800);
    o.index = kind;
    expect_valid_tree(grow(o), o);
  }
}

TEST(Growth, DiskSpawnGrowsTowardsTheDisk) {
  DlaOptions o = small();
  o.spawn = SpawnMode::disk;
  o.spawn_axis = Axis::z;
  const Cluster c = grow(o);
  expect_valid_tree(c, o);
  EXPECT_GT(mean_z(c), 0.3 * radius_of_gyration(c));
}

TEST(Growth, DriftBiasesGrowthAgainstIt) {
  // Walkers falling along -z land on the top of the structure, which grows up towards them.
  DlaOptions o = small();
  o.drift = Vec3(0, 0, -0.5);
  const Cluster c = grow(o);
  expect_valid_tree(c, o);
  EXPECT_GT(mean_z(c), 0.3 * radius_of_gyration(c));
}

TEST(Growth, BoxSpawn) {
  DlaOptions o = small(1500);
  o.spawn = SpawnMode::box;
  expect_valid_tree(grow(o), o);
  o.spawn_box = Box{Vec3(-20, -20, -20), Vec3(20, 20, 20)};
  expect_valid_tree(grow(o), o);
}

TEST(Growth, SeveralSeedsAllGrow) {
  DlaOptions o = small(3000);
  o.seeds = {Vec3(-30, 0, 0), Vec3(30, 0, 0), Vec3(0, 40, 0)};
  const Cluster c = grow(o);
  expect_valid_tree(c, o);
  std::vector<int> per_seed(3, 0);
  for (const Particle& p : c.particles) ++per_seed[static_cast<std::size_t>(p.seed)];
  for (int count : per_seed) EXPECT_GT(count, 100);
  EXPECT_NEAR(c.center.x(), 0.0, 1e-12);
  EXPECT_NEAR(c.center.y(), 40.0 / 3, 1e-12);
}

TEST(Growth, SameSeedSameStructureOtherSeedOther) {
  DlaOptions o = small(2000);
  o.rng_seed = 42;
  const Cluster a = grow(o), b = grow(o);
  ASSERT_EQ(a.particles.size(), b.particles.size());
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    ASSERT_EQ(std::memcmp(a.particles[i].position.data(), b.particles[i].position.data(), 3 * sizeof(double)), 0);
    ASSERT_EQ(a.particles[i].parent, b.particles[i].parent);
  }
  o.rng_seed = 43;
  const Cluster other = grow(o);
  EXPECT_NE(other.particles.back().position, a.particles.back().position);
}

// The callback is called as growth begins and at its end (and in between as time goes by);
// when it says stop, growth stops there, and it is not called again.
TEST(Growth, ProgressSeesTheEndAndCanStopGrowth) {
  DlaOptions o = small(5000);
  std::size_t calls = 0, seen = 0;
  const Cluster whole = grow(o, [&](const Cluster& so_far) {
    ++calls;
    seen = attached(so_far);
    return true;
  });
  EXPECT_TRUE(whole.complete);
  EXPECT_GE(calls, 2u);
  EXPECT_EQ(seen, o.particles) << "the last call sees the whole structure";

  calls = 0;
  const Cluster stopped = grow(o, [&](const Cluster& so_far) {
    ++calls;
    seen = attached(so_far);
    return false;
  });
  EXPECT_FALSE(stopped.complete);
  EXPECT_EQ(calls, 1u);
  EXPECT_EQ(attached(stopped), seen);
  EXPECT_LT(attached(stopped), o.particles);
}

//! Stopped short, by a smaller count and by the progress callback at once, a run grown on
//! with `o` is the run grown whole on one thread, particle for particle and walk for walk.
void expect_resumed_runs_are_whole(const DlaOptions& o, std::size_t stop_at) {
  DlaOptions one_thread = o;
  one_thread.threads = 1;
  DlaStats whole_stats;
  const Cluster whole = grow(one_thread, {}, nullptr, &whole_stats);
  const auto expect_whole = [&](const Cluster& part, DlaStats stats) {
    const Cluster resumed = resume(o, part, {}, nullptr, &stats);
    EXPECT_TRUE(resumed.complete);
    ASSERT_EQ(resumed.particles.size(), whole.particles.size());
    for (std::size_t i = 0; i < whole.particles.size(); ++i) {
      ASSERT_EQ(resumed.particles[i].position, whole.particles[i].position) << i;
      ASSERT_EQ(resumed.particles[i].parent, whole.particles[i].parent) << i;
    }
    EXPECT_EQ(stats.walk.steps, whole_stats.walk.steps);
    EXPECT_EQ(stats.walk.walkers, whole_stats.walk.walkers);
  };
  DlaOptions shorter = o;
  shorter.particles = stop_at;
  DlaStats stats;
  const Cluster part = grow(shorter, {}, nullptr, &stats);
  ASSERT_EQ(attached(part), stop_at);
  expect_whole(part, stats);
  // As a program stops it, with walkers running ahead on other threads.
  const Cluster stopped = grow(o, [](const Cluster&) { return false; }, nullptr, &stats);
  ASSERT_FALSE(stopped.complete);
  expect_whole(stopped, stats);
}

TEST(Growth, ResumedGrowthIsTheUninterruptedOne) {
  DlaOptions o = small(3000);
  o.seeds = {Vec3(-6, 0, 0), Vec3(6, 0, 0)};
  expect_resumed_runs_are_whole(o, 1280);

  DlaOptions shorter = o;
  shorter.particles = 1280;
  Cluster foreign = grow(shorter);
  foreign.particles[1].position.x() += 1.0;  // a seed that is not the options'
  EXPECT_THROW(resume(o, foreign), InvalidInput);
}

TEST(ParticleFeed, HandsOverEveryParticleInOrderUntilItCloses) {
  const auto particle = [](std::size_t i) { return Particle{Vec3(static_cast<double>(i), 0, 0), static_cast<std::int32_t>(i) - 1, 0}; };
  // No one takes: the room fills, the feed closes and takes no more, and keeps the first.
  ParticleFeed full(1024);
  for (std::size_t i = 0; i < 1500; ++i) full.put(particle(i));
  ASSERT_TRUE(full.closed());
  ASSERT_EQ(full.put_count(), 1024u);
  for (std::size_t k = 0; k < 1024; ++k) ASSERT_EQ(full.at(k).parent, static_cast<std::int32_t>(k) - 1);
  full.taken(1024);
  full.put(particle(1500));
  EXPECT_EQ(full.put_count(), 1024u) << "closed for good";

  // A room that is not a power of two gets the next one: every particle keeps its place.
  ParticleFeed odd(1000);
  for (std::size_t i = 0; i < 1500; ++i) odd.put(particle(i));
  ASSERT_TRUE(odd.closed());
  ASSERT_EQ(odd.put_count(), 1024u);
  for (std::size_t k = 0; k < 1024; ++k) ASSERT_EQ(odd.at(k).parent, static_cast<std::int32_t>(k) - 1) << k;
  // A room beyond every power of two is refused, not a loop that never ends.
  EXPECT_THROW(ParticleFeed{std::numeric_limits<std::size_t>::max()}, std::length_error);

  // A taker on another thread gets every particle in order, up to where the feed closed if it
  // fell a room behind.
  ParticleFeed feed(1024);
  constexpr std::size_t kCount = 200000;
  std::vector<Particle> got;
  std::atomic<bool> done{false};
  std::thread taker([&] {
    std::size_t k = 0;
    for (;;) {
      const bool last = done.load();
      for (const std::size_t put = feed.put_count(); k < put; ++k) got.push_back(feed.at(k));
      feed.taken(k);
      if (last) return;
    }
  });
  for (std::size_t i = 0; i < kCount; ++i) feed.put(particle(i));
  done = true;
  taker.join();
  ASSERT_EQ(got.size(), feed.closed() ? feed.put_count() : kCount);
  ASSERT_GE(got.size(), 1024u);
  for (std::size_t k = 0; k < got.size(); ++k) ASSERT_EQ(got[k].position.x(), static_cast<double>(k)) << k;
}

TEST(ParticleFeed, GrowthFeedsEveryParticleAsItAttaches) {
  DlaOptions o = small(2000);
  o.seeds = {Vec3(-6, 0, 0), Vec3(6, 0, 0)};
  for (const int threads : {1, 2}) {
    o.threads = threads;
    ParticleFeed feed(4096);
    DlaStats stats;
    stats.feed = &feed;
    const Cluster c = grow(o, {}, nullptr, &stats);
    ASSERT_EQ(feed.put_count(), c.particles.size()) << threads << " threads";
    for (std::size_t k = 0; k < c.particles.size(); ++k) {
      ASSERT_EQ(feed.at(k).position, c.particles[k].position) << k;
      ASSERT_EQ(feed.at(k).parent, c.particles[k].parent) << k;
    }
  }
}

// Walkers on several threads commit in launch order and run again when a particle attached
// meanwhile could have changed their path: every thread count gives the one-thread result.
void expect_same_for_every_thread_count(DlaOptions o) {
  o.threads = 1;
  DlaStats one_stats;
  const Cluster one = grow(o, {}, nullptr, &one_stats);
  const WalkStats& walk = one_stats.walk;
  std::uint64_t replays = 0;
  for (int threads : {2, 3, 4}) {
    o.threads = threads;
    DlaStats stats;
    const Cluster many = grow(o, {}, nullptr, &stats);
    ASSERT_EQ(many.particles.size(), one.particles.size());
    for (std::size_t i = 0; i < one.particles.size(); ++i) {
      ASSERT_EQ(many.particles[i].position, one.particles[i].position) << threads << " threads, particle " << i;
      ASSERT_EQ(many.particles[i].parent, one.particles[i].parent) << threads << " threads, particle " << i;
    }
    EXPECT_EQ(stats.walk.steps, walk.steps);
    EXPECT_EQ(stats.walk.near_steps, walk.near_steps);
    EXPECT_EQ(stats.walk.returns, walk.returns);
    EXPECT_EQ(stats.walk.relaunches, walk.relaunches);
    EXPECT_EQ(stats.walk.contacts, walk.contacts);
    replays += stats.replays;
  }
  // Whether walkers overlap is up to the scheduler: on a machine too busy to run two at once
  // nothing was run again, and only the plain path was tested.
  if (replays == 0) GTEST_SKIP() << "no walker ran alongside another: the threads never met";
}

TEST(Threads, SameResultForEveryCount3D) { expect_same_for_every_thread_count(small(20000)); }

TEST(Threads, SameResultForEveryCount2D) {
  DlaOptions o = small(8000);
  o.dimensions = 2;
  expect_same_for_every_thread_count(o);
}

TEST(Threads, SameResultWithDriftStickinessAndSeveralSeeds) {
  DlaOptions o = small(6000);
  o.drift = Vec3(0.0, 0.0, -0.3);
  o.stickiness = 0.4;
  o.seeds = {Vec3(-10, 0, 0), Vec3(10, 0, 0), Vec3(0, 12, 0)};
  expect_same_for_every_thread_count(o);
}

TEST(Threads, SameResultWithSeedsFarApart) {
  // Walkers start 150 spacings and more from either tree, beyond the node map's reach (64):
  // the far map bounds most of their steps (its opening boxes are checked one by one in
  // index_test.cpp), and the result must still not depend on the thread count.
  DlaOptions o = small(3000);
  o.seeds = {Vec3(-150, 0, 0), Vec3(150, 0, 0)};
  expect_same_for_every_thread_count(o);
}

TEST(Threads, StoppedAndResumedGrowthIsTheOneThreadRun) {
  for (const int threads : {1, 2, 3, 4}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    DlaOptions o = small(4000);
    o.threads = threads;
    expect_resumed_runs_are_whole(o, 1536);
  }
}

// Growth that cannot go on fails on any thread count as on one: the same message, after the
// same particles.
TEST(Threads, ErrorsAreTheOneThreadErrors) {
  const auto failure = [](int threads) {
    DlaOptions o = small(1000);
    o.spawn = SpawnMode::box;
    o.spawn_box = Box{Vec3(-2, -2, -2), Vec3(2, 2, 2)};  // the structure fills it after a few dozen
    o.threads = threads;
    try {
      grow(o);
    } catch (const PartialGrowth& e) {
      return std::make_pair(std::string(e.what()), e.partial());
    }
    ADD_FAILURE() << threads << " threads: the box held 1000 particles";
    return std::make_pair(std::string(), Cluster{});
  };
  const auto [one_message, one_part] = failure(1);
  ASSERT_FALSE(one_message.empty());
  for (const int threads : {2, 3, 4}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    const auto [message, part] = failure(threads);
    EXPECT_EQ(message, one_message);
    ASSERT_EQ(part.particles.size(), one_part.particles.size());
    for (std::size_t i = 0; i < part.particles.size(); ++i) {
      ASSERT_EQ(part.particles[i].position, one_part.particles[i].position) << i;
      ASSERT_EQ(part.particles[i].parent, one_part.particles[i].parent) << i;
    }
  }
}

TEST(Growth, RotationTurnsTheDriftAndSoTheGrowth) {
  // Walkers drifting along +x build towards -x. Turned about z by 180 degrees per 1000
  // particles, the drift sweeps half a turn over the first 1000 and the second half over the
  // next: growth leans to -y (the mean of -(cos t, sin t) over the half turn), then back
  // towards +y. Without rotation all of it leans to -x alone.
  DlaOptions o = small(2000);
  o.dimensions = 2;
  o.drift = Vec3(0.5, 0.0, 0.0);
  const auto lean = [](const Cluster& c, std::size_t from, std::size_t to) {
    Vec3 sum = Vec3::Zero();
    for (std::size_t i = c.seed_count + from; i < c.seed_count + to; ++i) sum += c.particles[i].position;
    return Vec3(sum / static_cast<double>(to - from));
  };
  const Cluster straight = grow(o);
  o.rotate_degrees = 180.0;
  const Cluster turned = grow(o);
  expect_valid_tree(turned, o);
  const Vec3 first = lean(turned, 0, 1000), second = lean(turned, 1000, 2000);
  EXPECT_LT(first.y(), -0.2 * radius_of_gyration(turned)) << first.transpose();
  EXPECT_GT(second.y() - first.y(), 0.2 * radius_of_gyration(turned)) << second.transpose();
  EXPECT_LT(std::abs(lean(straight, 0, 2000).y()), 0.2 * radius_of_gyration(straight));
  EXPECT_LT(lean(straight, 0, 2000).x(), -0.3 * radius_of_gyration(straight));
  // The frame turns with the walker's number, so threads give the same structure.
  expect_same_for_every_thread_count(o);
}

TEST(Growth, FilledSpawnBoxIsAnErrorNotAHang) {
  DlaOptions o = small(10);
  o.spawn = SpawnMode::box;
  o.spawn_box = Box{Vec3(-0.5, -0.5, -0.5), Vec3(0.5, 0.5, 0.5)};
  EXPECT_THROW(grow(o), GrowthError);
}

// Radius of gyration against n over the growth history: 3D off-lattice DLA has D close to 2.5
// (Tolman & Meakin 1989: 2.495), 2D close to 1.71. The bands allow for one cluster's noise.
TEST(Growth, FractalDimension3D) {
  DlaOptions o = small(20000);
  const FractalFit fit = fractal_dimension_by_gyration(grow(o), 200);
  EXPECT_GE(fit.dimension, 2.3);
  EXPECT_LE(fit.dimension, 2.7);
}

TEST(Growth, FractalDimension2D) {
  DlaOptions o = small(10000);
  o.dimensions = 2;
  const FractalFit fit = fractal_dimension_by_gyration(grow(o), 200);
  EXPECT_GE(fit.dimension, 1.55);
  EXPECT_LE(fit.dimension, 1.87);
}

TEST(Growth, NoTwoParticlesCloserThanTheSpacing) {
  DlaOptions o = small(20000);
  o.spacing = 0.7;
  const Cluster c = grow(o);
  // Every pair within two spacings, found through a hash of cells one spacing wide.
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells;
  const auto key = [&](const Vec3& p, int dx, int dy, int dz) {
    const auto q = [&](double v, int d) { return static_cast<std::int64_t>(std::floor(v / o.spacing)) + d + (1 << 20); };
    return (q(p.x(), dx) << 42) | (q(p.y(), dy) << 21) | q(p.z(), dz);
  };
  for (std::size_t i = 0; i < c.particles.size(); ++i) cells[key(c.particles[i].position, 0, 0, 0)].push_back(i);
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.particles.size(); ++i)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find(key(c.particles[i].position, dx, dy, dz));
          if (it == cells.end()) continue;
          for (std::size_t j : it->second)
            if (j != i) closest = std::min(closest, (c.particles[i].position - c.particles[j].position).norm());
        }
  EXPECT_GE(closest, 0.999 * o.spacing);
}

TEST(Growth, MassRadiusDimension3D) {
  const FractalFit fit = fractal_dimension_by_mass_radius(grow(small(20000)));
  EXPECT_GE(fit.dimension, 2.3);
  EXPECT_LE(fit.dimension, 2.7);
}

// The ensemble figures of Tolman and Meakin, Phys. Rev. A 40, 428 (1989): D = 2.495 in 3D and
// 1.715 in 2D for off-lattice hard-sphere DLA, from the radius of gyration. Twenty clusters of
// 10^5 each (the standard error of the mean is about 0.01 in 3D), about 40 s, so only in the
// full tier (ctest -L full sets DLA_FULL_TESTS). The fit takes the last decade of the growth history: the local slope
// of log R_g against log n still falls at n = 10^3 (on the same ten 3D clusters, 2.550 from
// n = 10^3 and 2.513 from 10^4; docs/dla.md).
void expect_ensemble_dimension(int dimensions, double expected, double tolerance, std::size_t particles = 100000,
                               int clusters = 20) {
  if (!std::getenv("DLA_FULL_TESTS")) GTEST_SKIP() << "in the full tier: ctest -L full";
  double sum_gyration = 0.0, sum_mass = 0.0;
  for (int i = 0; i < clusters; ++i) {
    DlaOptions o = small(particles);
    o.dimensions = dimensions;
    o.threads = 2;  // the same clusters as on one thread
    o.rng_seed = 1000 + static_cast<std::uint64_t>(i);
    const Cluster c = grow(o);
    sum_gyration += fractal_dimension_by_gyration(c).dimension;  // the last decade
    sum_mass += fractal_dimension_by_mass_radius(c).dimension;
  }
  std::printf("%dD ensemble of %d clusters of %zu: D by gyration %.3f, by mass-radius %.3f\n", dimensions, clusters,
              particles, sum_gyration / clusters, sum_mass / clusters);
  EXPECT_NEAR(sum_gyration / clusters, expected, tolerance);
  // Mass within r of the seed converges to D more slowly (10^5 particles span only about a
  // decade of r): measured 2.43 and 1.70 here, so a looser band.
  EXPECT_NEAR(sum_mass / clusters, expected, 0.1);
}

TEST(Slow, EnsembleDimension3D) { expect_ensemble_dimension(3, 2.50, 0.03); }
TEST(Slow, EnsembleDimension2D) { expect_ensemble_dimension(2, 1.71, 0.02); }
// The plane's walk at the sizes researchers grow (Menshutin and Shchur, Phys. Rev. E 73,
// 011407, 2006: 1.71): ten clusters of 10^6, about 50 s on two threads.
TEST(Slow, EnsembleDimension2DAtAMillion) { expect_ensemble_dimension(2, 1.71, 0.02, 1000000, 10); }

// A stop request reaches walkers inside their walk, on one thread and on two: set while
// growth goes on, it ends the walk under way before its particle attaches.
TEST(Growth, AStopFlagEndsGrowthInsideAWalk) {
  for (const int threads : {1, 2}) {
    DlaOptions o;
    o.particles = 100000;
    o.stickiness = 1e-4;  // a walk takes thousands of contacts: far more steps than between looks at the flag
    o.threads = threads;
    StopFlag stop{false};
    // The first progress call sets the flag and lets growth go on: only the flag can stop it.
    std::size_t when_set = 0;
    const ProgressFn set_the_flag = [&](const Cluster& so_far) {
      if (!stop.load()) when_set = attached(so_far), stop.store(true);
      return true;
    };
    const Cluster part = grow(o, set_the_flag, &stop);
    EXPECT_FALSE(part.complete);
    // One thread: the walk under way when the flag was set ends inside it, unattached. Two: the
    // walk being committed then may attach.
    if (threads == 1) EXPECT_EQ(attached(part), when_set) << "the flag waited for the walk to end";
    else EXPECT_LE(attached(part), when_set + 1) << "the flag waited for walks to end";
    // What grew is a prefix of the whole run: it resumes to the same structure.
    o.particles = attached(part) + 20;
    const Cluster whole = grow(o), resumed = resume(o, part);
    ASSERT_EQ(whole.particles.size(), resumed.particles.size());
    for (std::size_t i = 0; i < whole.particles.size(); ++i)
      ASSERT_EQ(whole.particles[i].position, resumed.particles[i].position) << i;
  }
}

// Growth that cannot go on throws PartialGrowth with what grew before: here the spawn box
// fills up after a few dozen particles.
TEST(Growth, AFailurePartWayKeepsWhatGrew) {
  DlaOptions o;
  o.particles = 1000;
  o.spawn = SpawnMode::box;
  o.spawn_box = Box{Vec3(-2, -2, -2), Vec3(2, 2, 2)};
  try {
    grow(o);
    FAIL() << "the box cannot hold 1000 particles";
  } catch (const PartialGrowth& e) {
    EXPECT_NE(std::string(e.what()).find("the structure fills it"), std::string::npos) << e.what();
    const Cluster& part = e.partial();
    EXPECT_FALSE(part.complete);
    EXPECT_GT(attached(part), 20u);
    for (std::size_t i = part.seed_count; i < part.particles.size(); ++i) {
      const Particle& p = part.particles[i];
      ASSERT_TRUE(p.parent >= 0 && static_cast<std::size_t>(p.parent) < i);
      EXPECT_NEAR((p.position - part.particles[static_cast<std::size_t>(p.parent)].position).norm(), 1.0, 1e-9);
    }
  }
  // A drift that carries every walker away from the disk they start on: an error, not a hang.
  DlaOptions away;
  away.particles = 10;
  away.spawn = SpawnMode::disk;
  away.spawn_axis = Axis::y;
  away.drift = Vec3(0, 0.9, 0);
  EXPECT_THROW(grow(away), PartialGrowth);
}

TEST(Options, BadValuesAreRefusedWithAClearMessage) {
  const auto message = [](auto change) {
    DlaOptions o;
    change(o);
    try {
      validate(o);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message([](DlaOptions& o) { o.stickiness = 1.7; }), "`stickiness` 1.7 is not in [0.0001, 1]");
  EXPECT_EQ(message([](DlaOptions& o) { o.stickiness = 0; }), "`stickiness` 0 is not in [0.0001, 1]");
  EXPECT_EQ(message([](DlaOptions& o) { o.spacing = -1; }), "spacing -1 is not in [1e-25, 1e+25]");
  EXPECT_EQ(message([](DlaOptions& o) { o.spacing = NAN; }), "spacing nan is not in [1e-25, 1e+25]");
  EXPECT_EQ(message([](DlaOptions& o) { o.dimensions = 4; }), "dimensions 4 is not 2 or 3");
  EXPECT_EQ(message([](DlaOptions& o) { o.seeds.clear(); }), "there is no seed");
  EXPECT_EQ(message([](DlaOptions& o) { o.seeds.push_back(Vec3(0.5, 0, 0)); }),
            "seeds 1 and 2 are closer than the spacing 1");
  EXPECT_EQ(message([](DlaOptions& o) { o.dimensions = 2, o.seeds = {Vec3(0, 0, 1)}; }),
            "seed 1 has z = 1 but growth in 2 dimensions is in the plane z = 0");
  EXPECT_EQ(message([](DlaOptions& o) { o.drift = Vec3(0, 0, 1); }), "drift length 1 is not below 1");
  EXPECT_EQ(message([](DlaOptions& o) { o.min_step = 2; }), "`min_step` 2 is not in [0.01, 1]");
  EXPECT_EQ(message([](DlaOptions& o) { o.spawn_box = Box{Vec3(1, 0, 0), Vec3(0, 1, 1)}; }),
            "spawn box is empty: its min corner is not below its max corner");
  EXPECT_EQ(message([](DlaOptions& o) { o.dimensions = 2, o.spawn = SpawnMode::disk; }),
            "the disk spawn axis must be x or y in 2 dimensions");
  EXPECT_EQ(message([](DlaOptions& o) { o.threads = 0; }), "`threads` 0 is not in [1, 256]");
  EXPECT_EQ(message([](DlaOptions& o) { o.dimensions = 2, o.rotate_degrees = 10, o.rotate_axis = Axis::y; }),
            "growth in 2 dimensions turns about z, not y");
  EXPECT_EQ(message([](DlaOptions& o) { o.rotate_degrees = NAN; }),
            "rotation, in degrees per 1000 particles, nan is not in [-36000, 36000]");
  // Where the walk's arithmetic breaks down or a walker would practically never stick.
  EXPECT_EQ(message([](DlaOptions& o) { o.spacing = 1e300; }), "spacing 1e+300 is not in [1e-25, 1e+25]");
  EXPECT_EQ(message([](DlaOptions& o) { o.spacing = 1e-300; }), "spacing 1e-300 is not in [1e-25, 1e+25]");
  EXPECT_EQ(message([](DlaOptions& o) { o.stickiness = 1e-9; }), "`stickiness` 1e-09 is not in [0.0001, 1]");
  EXPECT_EQ(message([](DlaOptions& o) { o.min_step = 1e-300; }), "`min_step` 1e-300 is not in [0.01, 1]");
  EXPECT_EQ(message([](DlaOptions& o) { o.disk_radius = INFINITY; }), "`disk_radius` inf is not in (0, 1000]");
  EXPECT_EQ(message([](DlaOptions& o) { o.seeds = {Vec3(1e12, 0, 0)}; }),
            "seed 1 lies more than 1e+09 spacings from the origin, beyond what double precision resolves");
  EXPECT_EQ(message([](DlaOptions& o) { o.seeds = {Vec3(0, NAN, 0)}; }), "seed 1 is not finite");
  EXPECT_EQ(message([](DlaOptions& o) { o.spawn = SpawnMode::box, o.spawn_box = Box{Vec3(0, 0, 0), Vec3(1e10, 1, 1)}; }),
            "spawn box's max corner lies more than 1e+09 spacings from the origin, beyond what double precision "
            "resolves");
  EXPECT_EQ(message([](DlaOptions& o) { o.threads = 2, o.index = IndexKind::kdtree; }),
            "threads above 1 need the grid index, not kdtree");
  EXPECT_EQ(message([](DlaOptions&) {}), "accepted");
  EXPECT_THROW(parse_word<SpawnMode>("cube"), InvalidInput);
  EXPECT_EQ(parse_word<SpawnMode>("disk"), SpawnMode::disk);
  EXPECT_EQ(parse_word<IndexKind>(to_string(IndexKind::kdtree)), IndexKind::kdtree);
}

}  // namespace
}  // namespace dla

namespace dla {
namespace {

// The tree checker every test uses (tree_check.h) finds each fault it is there for.
TEST(TreeCheck, FindsEachFault) {
  Cluster good;
  good.seed_count = 1;
  good.particles = {{Vec3(0, 0, 0), -1, 0}, {Vec3(1, 0, 0), 0, 0}, {Vec3(2, 0, 0), 1, 0}};
  ASSERT_EQ(testing::tree_fault(good), "");
  const auto fault = [&](auto&& spoil, testing::TreeRules rules = {}) {
    Cluster bad = good;
    spoil(bad);
    return testing::tree_fault(bad, rules);
  };
  EXPECT_NE(fault([](Cluster& c) { c.particles[2].parent = 2; }), "");        // not before it
  EXPECT_NE(fault([](Cluster& c) { c.particles[1].seed = 1; }), "");          // another tree
  EXPECT_NE(fault([](Cluster& c) { c.particles[0].parent = 0; }), "");        // a seed with a parent
  EXPECT_NE(fault([](Cluster& c) { c.particles[2].position.x() = 2.5; }), "");  // too long
  EXPECT_NE(fault([](Cluster& c) { c.particles[2].position.x() = NAN; }), "");
  EXPECT_NE(fault([](Cluster& c) { c.dimensions = 2, c.particles[2].position.z() = 1e-9; }), "");
  // Too close to particle 0, though a spacing from its parent.
  const auto bent = [](Cluster& c) { c.particles[2].position = Vec3(1 - std::sqrt(0.75), 0.5, 0); };
  EXPECT_NE(fault(bent), "");
  EXPECT_EQ(fault(bent, {1.0, 1.0, false}), "");
  EXPECT_EQ(fault([](Cluster& c) { c.particles[2].position.x() = 1.5; }, {0.5, 1.0, false}), "");  // clipped
}

}  // namespace
}  // namespace dla
