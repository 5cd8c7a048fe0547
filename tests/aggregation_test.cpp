// Random-drop ballistic aggregation (drop.h) and ballistic aggregation (ballistic.h), and the
// grid's exact nearest look-up and distance bound they stand on: against brute force, the
// trees' invariants, the drops' counts, and ballistic clusters' uniform density.

#include "dla/core/analysis.h"
#include "dla/index/grid_index.h"
#include "dla/models/ballistic.h"
#include "dla/models/drop.h"
#include "tree_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using dla::Vec3;

//! A tree (tree_check.h) whose particles are a spacing apart.
void expect_tree(const dla::Cluster& c) { EXPECT_EQ(dla::testing::tree_fault(c), ""); }

//! Clouds to look up in: uniform, in tight clumps far apart, and along a line.
std::vector<dla::Particle> cloud(int kind, int dimensions, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<dla::Particle> points;
  for (int i = 0; i < 3000; ++i) {
    Vec3 p;
    if (kind == 0) p = Vec3(u(rng), u(rng), u(rng)) * 60.0;
    else if (kind == 1) p = Vec3(i % 3 == 0 ? 300.0 : -200.0, i % 3 == 1 ? 150.0 : 0.0, 0.0) + Vec3(u(rng), u(rng), u(rng)) * 5.0;
    else p = Vec3(i * 0.7, 0.0, 0.0);
    if (dimensions == 2) p.z() = 0.0;
    points.push_back({p, -1, 0});
  }
  return points;
}

TEST(GridNearest, IsTheBruteForceAnswerNearAndFar) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const int dimensions : {2, 3})
    for (const bool maps : {true, false})
      for (int kind = 0; kind < 3; ++kind) {
        const std::vector<dla::Particle> points = cloud(kind, dimensions, rng);
        dla::GridIndex grid(points, 1.0, dimensions, maps);
        dla::BruteForceIndex brute(points, 1.0, dimensions);
        for (std::size_t i = 0; i < points.size(); ++i) {
          grid.insert(static_cast<std::int32_t>(i));
          brute.insert(static_cast<std::int32_t>(i));
          if (i % 300 != 0) continue;
          // Queries from within a spacing of the cloud to thousands of spacings off it.
          for (const double scale : {1.0, 10.0, 100.0, 1000.0, 5000.0})
            for (int q = 0; q < 20; ++q) {
              Vec3 x = points[i].position + Vec3(u(rng), u(rng), u(rng)) * scale;
              if (dimensions == 2) x.z() = 0.0;
              const dla::Probe exact = brute.nearest(x), fast = grid.nearest(x);
              ASSERT_EQ(fast.nearest, exact.nearest) << "dimensions " << dimensions << " kind " << kind << " scale " << scale;
              ASSERT_DOUBLE_EQ(fast.distance, exact.distance);
              ASSERT_LE(grid.bound(x), exact.distance * (1.0 + 1e-12)) << "maps " << maps << " scale " << scale;
            }
        }
      }
}

TEST(Drop, AttachesToTheExactlyClosestParticle) {
  // The grid's nearest and brute force grow the same structure, particle for particle: every
  // drop joined its exactly closest particle. Uniform, biased and fixed-zone drops.
  for (const int dimensions : {2, 3})
    for (const char* bias : {"uniform", "circle", "same:4", "offset:6,2.5"})
      for (const double zone : {0.0, 40.0}) {
        dla::DropOptions o;
        o.particles = 1500;
        o.dimensions = dimensions;
        o.bias = dla::parse_drop_bias(bias);
        o.zone_radius = zone;
        o.seeds = {Vec3::Zero(), Vec3(12.0, 0.0, 0.0)};
        SCOPED_TRACE(std::string(bias) + " in " + std::to_string(dimensions) + "D, zone " + std::to_string(zone));
        dla::validate(o);
        dla::DropStats fast_stats, exact_stats;
        const dla::Cluster fast = dla::drop_with<dla::GridIndex>(o, nullptr, {}, nullptr, &fast_stats);
        const dla::Cluster exact = dla::drop_with<dla::BruteForceIndex>(o, nullptr, {}, nullptr, &exact_stats);
        // Drops on a fixed circle fill it: growth then ends early.
        if (o.bias.pattern != dla::DropPattern::circle || zone == 0.0) {
          ASSERT_EQ(fast.particles.size(), o.seeds.size() + o.particles);
        }
        ASSERT_EQ(fast.particles.size(), exact.particles.size());
        for (std::size_t i = 0; i < fast.particles.size(); ++i) {
          ASSERT_EQ(fast.particles[i].parent, exact.particles[i].parent) << i;
          ASSERT_EQ(fast.particles[i].position, exact.particles[i].position) << i;
        }
        expect_tree(fast);
        // Every drop attached a particle or was counted as rejected.
        EXPECT_EQ(fast_stats.drops, dla::attached(fast) + fast_stats.on_structure);
        EXPECT_EQ(fast_stats.drops, exact_stats.drops);
      }
}

TEST(Drop, CountsRejectedDropsAndEndsWhenTheZoneIsFull) {
  dla::DropOptions o;
  o.particles = 100000;
  o.dimensions = 2;
  o.zone_radius = 6.0;  // room for a hundred or so particles
  dla::DropStats stats;
  const dla::Cluster c = dla::drop(o, nullptr, {}, nullptr, &stats);
  EXPECT_TRUE(stats.zone_full);
  EXPECT_TRUE(c.complete);
  EXPECT_LT(dla::attached(c), 200u);
  EXPECT_GT(dla::attached(c), 20u);
  EXPECT_EQ(stats.drops, dla::attached(c) + stats.on_structure);
  EXPECT_GE(stats.on_structure, dla::kMaxFailedDrops);
  expect_tree(c);
  for (const dla::Particle& p : c.particles) EXPECT_LE(p.position.norm(), 6.0 + 1e-9);
}

TEST(Drop, StickinessRefusesAndStillKeepsTheSpacing) {
  dla::DropOptions o;
  o.particles = 2000;
  o.stickiness = 0.2;
  dla::DropStats stats;
  const dla::Cluster c = dla::drop(o, nullptr, {}, nullptr, &stats);
  EXPECT_GT(stats.refused, 2000u);  // about four refusals a particle
  expect_tree(c);
  // The same seed, the same structure; another seed, another.
  EXPECT_EQ(dla::drop(o).particles.back().position, c.particles.back().position);
  o.rng_seed = 2;
  EXPECT_NE(dla::drop(o).particles.back().position, c.particles.back().position);
}

TEST(Drop, BoxZonesKeepTheirDropsInTheBox) {
  dla::DropOptions o;
  o.particles = 800;
  o.zone = dla::DropZone::box;
  o.zone_box = dla::Box{Vec3(-10.0, -10.0, -10.0), Vec3(30.0, 10.0, 10.0)};
  const dla::Cluster c = dla::drop(o);
  expect_tree(c);
  // Drops in the box pull the structure towards +x.
  double mean_x = 0.0;
  for (const dla::Particle& p : c.particles) mean_x += p.position.x() / static_cast<double>(c.particles.size());
  EXPECT_GT(mean_x, 2.0);
  o.bias = dla::parse_drop_bias("circle");  // on the box's faces
  expect_tree(dla::drop(o));
}

TEST(Drop, RejectsOptionsThatCannotWork) {
  const auto invalid = [](auto change) {
    dla::DropOptions o;
    change(o);
    EXPECT_THROW(dla::drop(o), dla::InvalidInput);
  };
  invalid([](dla::DropOptions& o) { o.zone_radius = 0.5; });
  invalid([](dla::DropOptions& o) { o.zone_margin = 0.1; });
  invalid([](dla::DropOptions& o) { o.zone = dla::DropZone::mesh; });
  invalid([](dla::DropOptions& o) { o.zone_box = dla::Box{Vec3::Zero(), Vec3::Ones()}; });
  invalid([](dla::DropOptions& o) { o.bias = {dla::DropPattern::offset, 3, 0.0}; });
  invalid([](dla::DropOptions& o) { o.stickiness = 0.0; });
  invalid([](dla::DropOptions& o) { o.seeds = {Vec3::Zero(), Vec3(0.5, 0.0, 0.0)}; });
  for (const char* word : {"same:0", "same:1.5", "offset:3", "offset:x,1", "rain", "same:", "circle:2"})
    EXPECT_THROW(dla::parse_drop_bias(word), dla::InvalidInput) << word;
  EXPECT_EQ(dla::to_string(dla::parse_drop_bias("offset:12,2.5")), "offset:12,2.5");
}

TEST(Ballistic, FirstContactsAreTheBruteForceOnes) {
  // The grid's bounds and brute force's exact distances trace the lines differently, but the
  // first contact along each is solved from the line's start: the same structure.
  for (const int dimensions : {2, 3})
    for (const bool deposit : {false, true}) {
      dla::BallisticOptions o;
      o.particles = 1500;
      o.dimensions = dimensions;
      if (deposit) o.direction = Vec3(0.3, -1.0, 0.0);
      o.seeds = {Vec3::Zero(), Vec3(6.0, 0.0, 0.0)};
      SCOPED_TRACE(std::to_string(dimensions) + "D, deposition " + std::to_string(deposit));
      dla::validate(o);
      dla::BallisticStats stats;
      const dla::Cluster fast = dla::ballistic_with<dla::GridIndex>(o, {}, nullptr, &stats);
      const dla::Cluster exact = dla::ballistic_with<dla::BruteForceIndex>(o);
      ASSERT_EQ(fast.particles.size(), exact.particles.size());
      for (std::size_t i = 0; i < fast.particles.size(); ++i) {
        ASSERT_EQ(fast.particles[i].parent, exact.particles[i].parent) << i;
        ASSERT_EQ(fast.particles[i].position, exact.particles[i].position) << i;
      }
      expect_tree(fast);
      EXPECT_EQ(stats.launched, o.particles + stats.missed);
      if (deposit) {
        // Particles falling along -y land on top: the structure grows up, against the flow.
        double mean_y = 0.0;
        for (const dla::Particle& p : fast.particles) mean_y += p.position.y() / static_cast<double>(fast.particles.size());
        EXPECT_GT(mean_y, 5.0);
      }
    }
}

TEST(Ballistic, ClustersAreCompactNotFractal) {
  // Ballistic aggregates fill space at a uniform density (Ramanlal and Sander 1985, the paper's
  // reference for "not fractal"): D from the radius of gyration against n is the space's
  // dimension, within 0.1 (off-lattice 2D: 1.97-2.0 at 3,000-30,000 particles).
  for (const int dimensions : {2, 3}) {
    dla::BallisticOptions o;
    o.particles = dimensions == 2 ? 30000 : 20000;
    o.dimensions = dimensions;
    const dla::Cluster c = dla::ballistic(o);
    const dla::FractalFit fit = dla::fractal_dimension_by_gyration(c);
    EXPECT_NEAR(fit.dimension, dimensions, 0.1) << dimensions << "D";
  }
}

}  // namespace
