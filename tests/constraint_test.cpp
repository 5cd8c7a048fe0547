// Growth constrained by a mesh, checked with the brute-force references of mesh_util.h: every
// particle on the growing side, no branch through the surface, clipped branches ending at it,
// every seed growing, the same files for the same seed.

#include "dla/mesh/constraint.h"
#include "dla/models/fill.h"
#include "dla/models/growth.h"
#include "dla/mesh/mesh_repair.h"
#include "dla/mesh/shapes.h"
#include "mesh_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

namespace dla {
namespace {

struct Checked {
  std::size_t clipped = 0;  // branches shorter than the spacing
  std::vector<std::size_t> per_seed;
};

// Every branch against every triangle; every particle against the winding number by solid
// angles when `side` is inside or outside.
Checked expect_constrained(const Cluster& cluster, const MeshConstraint& constraint) {
  const TriangleMesh& mesh = constraint.mesh();
  const Side side = constraint.options().side;
  Checked checked;
  checked.per_seed.assign(cluster.seed_count, 0);
  for (std::size_t i = 0; i < cluster.particles.size(); ++i) {
    const Particle& p = cluster.particles[i];
    ++checked.per_seed[static_cast<std::size_t>(p.seed)];
    if (side != Side::both) {
      const double gwn = testing::generalized_winding_number(mesh, p.position);
      EXPECT_EQ(gwn > 0.5, side == Side::inside) << "particle " << i << " at " << p.position.transpose();
    }
    if (p.parent < 0) continue;
    const Vec3& parent = cluster.particles[static_cast<std::size_t>(p.parent)].position;
    const double t = testing::brute_first_hit(mesh, parent, p.position);
    EXPECT_LT(t, 0.0) << "branch " << i << " crosses the surface at t = " << t;
    const double length = (p.position - parent).norm();
    EXPECT_LE(length, cluster.spacing * (1 + 1e-9));
    if (length < cluster.spacing * (1 - 1e-9)) {
      ++checked.clipped;
      EXPECT_GE(length, 0.5 * cluster.spacing * (1 - 1e-9));
      EXPECT_LT(constraint.distance_to_surface(p.position), 1e-3 * cluster.spacing) << "a clipped branch short of the surface";
    }
  }
  return checked;
}

GrowthOptions options_for(const MeshConstraint& constraint, std::size_t particles, std::size_t seeds) {
  GrowthOptions o;
  o.particles = particles;
  o.spacing = constraint.spacing();
  o.spawn = SpawnMode::inside;
  o.seeds = constraint.place_seeds(seeds, o.rng_seed);
  return o;
}

TEST(Constraint, TwoSeedsGrowInsideTheBustWithoutCrossingIt) {
  DLA_NEED_BUST(path);
  const MeshConstraint constraint(read_mesh(path), {}, 0.2);
  EXPECT_TRUE(constraint.repair_report().closed);
  EXPECT_EQ(constraint.repair_report().holes_closed, 1u);
  const GrowthOptions o = options_for(constraint, 2500, 2);
  const Cluster cluster = grow(o, constraint);
  ASSERT_EQ(cluster.particles.size(), 2502u);
  const Checked checked = expect_constrained(cluster, constraint);
  EXPECT_EQ(checked.clipped, 0u);
  for (std::size_t count : checked.per_seed) EXPECT_GT(count, cluster.particles.size() / 5) << "a seed hardly grew";
  EXPECT_GT(cluster.stats.lost, 0u);
  EXPECT_EQ(grow(o, constraint).particles.back().position, cluster.particles.back().position) << "not deterministic";
}

TEST(Constraint, SameResultOnEveryThreadCount) {
  DLA_NEED_BUST(path);
  std::uint64_t replays = 0;
  for (ConstraintMode mode : {ConstraintMode::reject, ConstraintMode::clip}) {
    ConstraintOptions c;
    c.mode = mode;
    const MeshConstraint constraint(read_mesh(path), c, 0.5);
    GrowthOptions o = options_for(constraint, 3000, 2);
    const Cluster one = grow(o, constraint);
    o.threads = 2;
    const Cluster two = grow(o, constraint);
    ASSERT_EQ(two.particles.size(), one.particles.size());
    for (std::size_t i = 0; i < one.particles.size(); ++i)
      ASSERT_EQ(two.particles[i].position, one.particles[i].position) << to_string(mode) << ", particle " << i;
    EXPECT_EQ(two.stats.lost, one.stats.lost);
    EXPECT_EQ(two.stats.rejected, one.stats.rejected);
    EXPECT_EQ(two.stats.clipped, one.stats.clipped);
    replays += two.replays;
  }
  if (replays == 0) GTEST_SKIP() << "no walker ran alongside another: the threads never met";
}

TEST(Constraint, ClippedBranchesTouchTheBustButDoNotCross) {
  DLA_NEED_BUST(path);
  ConstraintOptions c;
  c.mode = ConstraintMode::clip;
  const MeshConstraint constraint(read_mesh(path), c, 1.0);
  const Cluster cluster = grow(options_for(constraint, 3000, 2), constraint);
  const Checked checked = expect_constrained(cluster, constraint);
  EXPECT_GT(checked.clipped, 0u);
  EXPECT_EQ(checked.clipped, cluster.stats.clipped);
}

TEST(Constraint, RejectedBranchesWalkOnInAThinVessel) {
  // A narrow tube: most walkers meet the wall before the structure, so many branches cross it.
  const MeshConstraint constraint(make_open_can(Vec3::Zero(), 3.0, 40.0, 24), {}, 1.0);
  EXPECT_EQ(constraint.repair_report().holes_closed, 1u);
  GrowthOptions o = options_for(constraint, 600, 1);
  o.seeds = {Vec3(0, 0, 20)};
  const Cluster cluster = grow(o, constraint);
  expect_constrained(cluster, constraint);
  EXPECT_GT(cluster.stats.rejected, 0u);
}

TEST(Constraint, RadialSpawnGrowsInATube) {
  ConstraintOptions c;
  c.mode = ConstraintMode::clip;
  const MeshConstraint constraint(make_open_can(Vec3::Zero(), 3.0, 40.0, 24), c, 1.0);
  GrowthOptions o = options_for(constraint, 600, 1);
  o.spawn = SpawnMode::radial;
  const Cluster cluster = grow(o, constraint);
  EXPECT_GT(expect_constrained(cluster, constraint).clipped, 0u);
}

TEST(Constraint, SurfaceSpawnStartsHalfASpacingOffTheSurfaceOnTheGrowingSide) {
  for (const Side side : {Side::inside, Side::outside}) {
    SCOPED_TRACE(std::string(to_string(side)));
    ConstraintOptions c;
    c.side = side;
    const MeshConstraint constraint(make_sphere(Vec3::Zero(), 6.0), c, 0.5);
    Rng rng(7, 0);
    for (int i = 0; i < 500; ++i) {
      const Vec3 p = constraint.draw_near_surface(rng);
      EXPECT_EQ(testing::generalized_winding_number(constraint.mesh(), p) > 0.5, side == Side::inside);
      // Half a spacing from the triangle it was drawn on; a neighbour can be nearer inside.
      const double d = constraint.distance_to_surface(p);
      EXPECT_LE(d, 0.25 + 1e-9);
      EXPECT_GE(d, side == Side::inside ? 0.2 : 0.25 - 1e-9);
    }
    GrowthOptions o;
    o.particles = 800;
    o.spacing = 0.5;
    o.spawn = SpawnMode::surface;
    o.seeds = constraint.place_seeds(1, o.rng_seed);
    expect_constrained(grow(o, constraint), constraint);
  }
}

// Once the structure covers the skin, walkers find no free start there, or start trapped
// against it across the surface: a clear error in seconds, not a run that crawls on for ever
// (a walker refused up to a million times in a row, as before, kept the bust's run going for
// minutes).
TEST(Constraint, SurfaceSpawnThatFillsTheSkinEndsWithAnError) {
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 4.0), {}, 0.5);
  GrowthOptions o;
  o.particles = 100000;  // a sphere of 16 spacings across holds nothing like it
  o.spacing = 0.5;
  o.spawn = SpawnMode::surface;
  o.seeds = {Vec3::Zero()};
  EXPECT_THROW(grow(o, constraint), GrowthError);
}

TEST(Constraint, GrowsInsideATestMeshWithAHole) {
  const MeshConstraint constraint(read_mesh(TEST_DATA_DIR "/open_box.off"), {}, 0.5);
  EXPECT_EQ(constraint.repair_report().holes_closed, 1u);
  const Cluster cluster = grow(options_for(constraint, 1500, 3), constraint);
  const Checked checked = expect_constrained(cluster, constraint);
  EXPECT_EQ(checked.per_seed.size(), 3u);
}

TEST(Constraint, GrowsAroundAnObjectOutside) {
  ConstraintOptions c;
  c.side = Side::outside;
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 6.0), c, 0.5);
  GrowthOptions o;
  o.particles = 1500;
  o.spacing = 0.5;
  o.seeds = constraint.place_seeds(2, o.rng_seed);
  for (const Vec3& s : o.seeds) EXPECT_NEAR(s.norm(), 7.0, 0.05);  // two spacings off the surface
  expect_constrained(grow(o, constraint), constraint);
}

TEST(Constraint, OpenCanOfBourkesFigure4) {
  // Side both: the can is a wall, not a vessel; walkers come from a sphere about its centre.
  ConstraintOptions c;
  c.side = Side::both;
  const MeshConstraint constraint(make_open_can(Vec3::Zero(), 10.0, 20.0), c, 0.5);
  EXPECT_EQ(constraint.repair_report().holes_closed, 0u);
  EXPECT_FALSE(constraint.repair_report().closed);
  GrowthOptions o;
  o.particles = 2000;
  o.spacing = 0.5;
  o.seeds = {Vec3(0, 0, 20)};
  const Cluster cluster = grow(o, constraint);
  expect_constrained(cluster, constraint);
  std::size_t in_can = 0;
  for (const Particle& p : cluster.particles) in_can += p.position.z() < 19.0 && p.position.head<2>().norm() < 10.0;
  EXPECT_GT(in_can, 0u) << "nothing grew down into the can";
  EXPECT_GT(cluster.stats.rejected, 0u);
}

//! The fraction of the mesh's volume within `distance` of a particle, by Monte Carlo: points
//! uniform in the box, inside by the exact winding number, near by a scan of every particle.
double sampled_fill(const MeshConstraint& constraint, const std::vector<Particle>& particles, double distance) {
  Rng rng(99);
  const Box& box = constraint.box();
  std::size_t inside = 0, near = 0;
  for (int i = 0; i < 40000; ++i) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box.min[a] + rng.uniform() * (box.max[a] - box.min[a]);
    if (!constraint.inside_test().contains(p)) continue;
    ++inside;
    for (const Particle& q : particles)
      if ((q.position - p).squaredNorm() <= distance * distance) {
        ++near;
        break;
      }
  }
  return static_cast<double>(near) / static_cast<double>(inside);
}

TEST(Constraint, FillGaugeMatchesASampledFraction) {
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 10.0), {}, 0.5);
  Rng rng(5);
  std::vector<Particle> particles;
  FillGauge gauge(constraint, 1.5);
  for (int i = 0; i < 120; ++i) {
    const Vec3 p = 9.0 * random_direction(rng, 3) * std::cbrt(rng.uniform());
    particles.push_back({p, -1, 0});
    gauge.add(p);
    if (i % 40 == 39) {
      EXPECT_NEAR(gauge.fraction(), sampled_fill(constraint, particles, 1.5), 0.02) << i + 1;
    }
  }
}

TEST(Constraint, FillStopsGrowthOnceTheVolumeIsCovered) {
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 8.0), {}, 0.5);
  GrowthOptions o = options_for(constraint, 100000, 1);
  o.fill = 0.6;
  o.fill_distance = 3.0;
  const Cluster c = grow(o, constraint);
  EXPECT_TRUE(c.complete);
  EXPECT_LT(attached(c), o.particles);
  EXPECT_GE(c.filled, 0.6);
  // The particle before the last had not covered it: growth stopped at the first that did.
  FillGauge gauge(constraint, 1.5);
  for (std::size_t i = 0; i + 1 < c.particles.size(); ++i) gauge.add(c.particles[i].position);
  EXPECT_LT(gauge.fraction(), 0.6);
  gauge.add(c.particles.back().position);
  EXPECT_EQ(gauge.fraction(), c.filled);
  EXPECT_NEAR(c.filled, sampled_fill(constraint, c.particles, 1.5), 0.03);
  // Threads stop at the same particle.
  o.threads = 2;
  const Cluster two = grow(o, constraint);
  ASSERT_EQ(two.particles.size(), c.particles.size());
  EXPECT_EQ(two.particles.back().position, c.particles.back().position);
  // Without a mesh, or outside one, there is no volume to fill.
  EXPECT_THROW(grow(o), InvalidInput);
  ConstraintOptions outside;
  outside.side = Side::outside;
  o.seeds = {Vec3(12, 0, 0)};
  o.spawn = SpawnMode::sphere;
  EXPECT_THROW(grow(o, MeshConstraint(make_sphere(Vec3::Zero(), 8.0), outside, 0.5)), InvalidInput);
}

TEST(Constraint, SurfaceSamplesLineTheGrowingSideASpacingApart) {
  const TriangleMesh sphere = make_sphere(Vec3::Zero(), 8.0);
  for (const Side side : {Side::inside, Side::outside}) {
    ConstraintOptions c;
    c.side = side;
    const MeshConstraint constraint(sphere, c, 0.5);
    const std::vector<Vec3> seeds = constraint.sample_surface(3);
    SCOPED_TRACE(std::string(to_string(side)));
    // A spacing apart, seeds cover a spacing² or a little more each: 804 units² of sphere.
    const double per_spacing2 = static_cast<double>(seeds.size()) * 0.25 / (4.0 * 3.14159265 * 64.0);
    EXPECT_GT(per_spacing2, 0.4);
    EXPECT_LT(per_spacing2, 1.2);
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      ASSERT_EQ(constraint.inside_test().contains(seeds[i]), side == Side::inside) << i;
      const double d = constraint.distance_to_surface(seeds[i]);
      ASSERT_GT(d, 0.0) << i;
      ASSERT_LE(d, 0.25 * (1.0 + 1e-9)) << i;  // half a spacing off, or nearer another triangle
      for (std::size_t j = 0; j < i; ++j) ASSERT_GE((seeds[j] - seeds[i]).norm(), 0.5) << j << ", " << i;
    }
    EXPECT_EQ(constraint.sample_surface(3), seeds);
    // The surface as the start: every seed is a root, and growth inside stays inside.
    GrowthOptions o = options_for(constraint, 1500, 1);
    o.seeds = seeds;
    if (side == Side::outside) o.spawn = SpawnMode::sphere;
    const Cluster grown = grow(o, constraint);
    EXPECT_EQ(grown.seed_count, seeds.size());
    for (const Particle& p : grown.particles) ASSERT_EQ(constraint.inside_test().contains(p.position), side == Side::inside);
  }
  ConstraintOptions wall;
  wall.side = Side::both;
  EXPECT_THROW(MeshConstraint(sphere, wall, 0.5).sample_surface(1), InvalidInput);
  EXPECT_THROW(MeshConstraint(sphere, {}, 0.01).sample_surface(1), InvalidInput);  // 8 million spacings²
}

TEST(Constraint, BadSetupsAreClearErrors) {
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 5.0), {}, 1.0);
  GrowthOptions o;
  o.seeds = {Vec3(9, 0, 0)};
  EXPECT_THROW(grow(o, constraint), InvalidInput);  // a seed outside
  o.seeds = {Vec3::Zero()};
  o.spacing = 0.5;
  EXPECT_THROW(grow(o, constraint), InvalidInput);  // not the constraint's spacing
  o.spacing = 1.0;
  o.spawn = SpawnMode::sphere;
  EXPECT_THROW(grow(o, constraint), GrowthError);  // every start outside: no free start
  o.spawn = SpawnMode::inside;
  EXPECT_THROW(grow(o), InvalidInput);  // inside without a mesh
  o.spawn = SpawnMode::surface;
  EXPECT_THROW(grow(o), InvalidInput);  // surface without a mesh
  ConstraintOptions wall;
  wall.side = Side::both;
  EXPECT_THROW(grow(o, MeshConstraint(make_open_can(Vec3::Zero(), 5.0, 10.0), wall, 1.0)), InvalidInput);
  EXPECT_THROW(constraint.place_seeds(1000, 1), InvalidInput);  // too many to fit
}

}  // namespace
}  // namespace dla
