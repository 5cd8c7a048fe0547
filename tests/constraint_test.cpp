// Growth constrained by a mesh, checked with the brute-force references of mesh_util.h: every
// particle on the growing side, no branch through the surface, clipped branches ending at it,
// every seed growing, the same files for the same seed.

#include "dla/mesh/constraint.h"
#include "dla/models/colonization.h"
#include "dla/models/fill.h"
#include "dla/models/dla.h"
#include "dla/mesh/mesh_repair.h"
#include "dla/mesh/shapes.h"
#include "mesh_util.h"
#include "test_util.h"

#include "tree_check.h"

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
  // Rejecting, a branch is a spacing long and no particle nearer another; clipping, a branch
  // may be clipped at the surface to half of one or more.
  const bool clipping = constraint.options().mode == ConstraintMode::clip;
  EXPECT_EQ(testing::tree_fault(cluster, {clipping ? 0.5 : 1.0, 1.0, !clipping}), "");
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
    if ((p.position - parent).norm() < cluster.spacing * (1 - 1e-9)) {
      ++checked.clipped;
      EXPECT_LT(constraint.distance_to_surface(p.position), 1e-3 * cluster.spacing) << "a clipped branch short of the surface";
    }
  }
  return checked;
}

DlaOptions options_for(const MeshConstraint& constraint, std::size_t particles, std::size_t seeds) {
  DlaOptions o;
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
  const DlaOptions o = options_for(constraint, 2500, 2);
  DlaStats stats;
  const Cluster cluster = grow(o, constraint, {}, nullptr, &stats);
  ASSERT_EQ(cluster.particles.size(), 2502u);
  const Checked checked = expect_constrained(cluster, constraint);
  EXPECT_EQ(checked.clipped, 0u);
  for (std::size_t count : checked.per_seed) EXPECT_GT(count, cluster.particles.size() / 5) << "a seed hardly grew";
  EXPECT_GT(stats.walk.lost, 0u);
  EXPECT_EQ(grow(o, constraint).particles.back().position, cluster.particles.back().position) << "not deterministic";
}

TEST(Constraint, SameResultOnEveryThreadCount) {
  DLA_NEED_BUST(path);
  std::uint64_t replays = 0;
  for (ConstraintMode mode : {ConstraintMode::reject, ConstraintMode::clip}) {
    ConstraintOptions c;
    c.mode = mode;
    const MeshConstraint constraint(read_mesh(path), c, 0.5);
    DlaOptions o = options_for(constraint, 3000, 2);
    DlaStats one_stats, two_stats;
    const Cluster one = grow(o, constraint, {}, nullptr, &one_stats);
    o.threads = 2;
    const Cluster two = grow(o, constraint, {}, nullptr, &two_stats);
    ASSERT_EQ(two.particles.size(), one.particles.size());
    for (std::size_t i = 0; i < one.particles.size(); ++i)
      ASSERT_EQ(two.particles[i].position, one.particles[i].position) << to_string(mode) << ", particle " << i;
    EXPECT_EQ(two_stats.walk.lost, one_stats.walk.lost);
    EXPECT_EQ(two_stats.walk.rejected, one_stats.walk.rejected);
    EXPECT_EQ(two_stats.walk.clipped, one_stats.walk.clipped);
    replays += two_stats.replays;
  }
  if (replays == 0) GTEST_SKIP() << "no walker ran alongside another: the threads never met";
}

TEST(Constraint, ClippedBranchesTouchTheBustButDoNotCross) {
  DLA_NEED_BUST(path);
  ConstraintOptions c;
  c.mode = ConstraintMode::clip;
  const MeshConstraint constraint(read_mesh(path), c, 1.0);
  DlaStats stats;
  const Cluster cluster = grow(options_for(constraint, 3000, 2), constraint, {}, nullptr, &stats);
  const Checked checked = expect_constrained(cluster, constraint);
  EXPECT_GT(checked.clipped, 0u);
  EXPECT_EQ(checked.clipped, stats.walk.clipped);
}

TEST(Constraint, RejectedBranchesWalkOnInAThinVessel) {
  // A narrow tube: most walkers meet the wall before the structure, so many branches cross it.
  const MeshConstraint constraint(make_open_can(Vec3::Zero(), 3.0, 40.0, 24), {}, 1.0);
  EXPECT_EQ(constraint.repair_report().holes_closed, 1u);
  DlaOptions o = options_for(constraint, 600, 1);
  o.seeds = {Vec3(0, 0, 20)};
  DlaStats stats;
  const Cluster cluster = grow(o, constraint, {}, nullptr, &stats);
  expect_constrained(cluster, constraint);
  EXPECT_GT(stats.walk.rejected, 0u);
}

TEST(Constraint, RadialSpawnGrowsInATube) {
  ConstraintOptions c;
  c.mode = ConstraintMode::clip;
  const MeshConstraint constraint(make_open_can(Vec3::Zero(), 3.0, 40.0, 24), c, 1.0);
  DlaOptions o = options_for(constraint, 600, 1);
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
    DlaOptions o;
    o.particles = 800;
    o.spacing = 0.5;
    o.spawn = SpawnMode::surface;
    o.seeds = constraint.place_seeds(1, o.rng_seed);
    expect_constrained(grow(o, constraint), constraint);
  }
}

// Starts off triangles whose offset crosses the surface (where the mesh crosses itself, or is
// thinner than a spacing) are tested one by one; the rest by one test per triangle. Either way
// every start lies on the growing side.
TEST(Constraint, SurfaceSpawnOnCrossingAndThinPartsStartsOnTheGrowingSide) {
  TriangleMesh two_spheres = make_sphere(Vec3::Zero(), 2.0, 12, 24);
  append(two_spheres, make_sphere(Vec3(2.5, 0.3, 0.2), 2.0, 12, 24));
  for (const TriangleMesh& mesh : {two_spheres, make_box(Vec3::Zero(), Vec3(4, 4, 0.3))})
    for (const Side side : {Side::inside, Side::outside}) {
      SCOPED_TRACE(std::string(to_string(side)));
      ConstraintOptions c;
      c.side = side;
      const MeshConstraint constraint(mesh, c, 0.5);
      Rng rng(8, 0);
      for (int i = 0; i < 400; ++i) {
        const Vec3 p = constraint.draw_near_surface(rng);
        ASSERT_EQ(testing::generalized_winding_number(constraint.mesh(), p) > 0.5, side == Side::inside) << p.transpose();
      }
    }
}

// Once the structure covers the skin, walkers find no free start there, or start trapped
// against it across the surface: a clear error in seconds, not a run that crawls on for ever
// (a walker refused up to a million times in a row, as before, kept the bust's run going for
// minutes).
TEST(Constraint, SurfaceSpawnThatFillsTheSkinEndsWithAnError) {
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 4.0), {}, 0.5);
  DlaOptions o;
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
  DlaOptions o;
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
  DlaOptions o;
  o.particles = 2000;
  o.spacing = 0.5;
  o.seeds = {Vec3(0, 0, 20)};
  DlaStats stats;
  const Cluster cluster = grow(o, constraint, {}, nullptr, &stats);
  expect_constrained(cluster, constraint);
  std::size_t in_can = 0;
  for (const Particle& p : cluster.particles) in_can += p.position.z() < 19.0 && p.position.head<2>().norm() < 10.0;
  EXPECT_GT(in_can, 0u) << "nothing grew down into the can";
  EXPECT_GT(stats.walk.rejected, 0u);
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
  DlaOptions o = options_for(constraint, 100000, 1);
  o.fill = 0.6;
  o.fill_distance = 3.0;
  DlaStats stats;
  const Cluster c = grow(o, constraint, {}, nullptr, &stats);
  EXPECT_TRUE(c.complete);
  EXPECT_LT(attached(c), o.particles);
  EXPECT_GE(stats.filled, 0.6);
  // The particle before the last had not covered it: growth stopped at the first that did.
  FillGauge gauge(constraint, 1.5);
  for (std::size_t i = 0; i + 1 < c.particles.size(); ++i) gauge.add(c.particles[i].position);
  EXPECT_LT(gauge.fraction(), 0.6);
  gauge.add(c.particles.back().position);
  EXPECT_EQ(gauge.fraction(), stats.filled);
  EXPECT_NEAR(stats.filled, sampled_fill(constraint, c.particles, 1.5), 0.03);
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
    DlaOptions o = options_for(constraint, 1500, 1);
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

namespace {

//! A sphere of radius 8 painted red above z = 4 and white below, through a PLY file's text as
//! Blender writes it.
TriangleMesh painted_sphere() {
  TriangleMesh sphere = make_sphere(Vec3::Zero(), 8.0);
  for (const Vec3& v : sphere.vertices) sphere.colors.push_back(v.z() > 4.0 ? Vec3(1, 0, 0) : Vec3(1, 1, 1));
  return parse_mesh(testing::painted_ply(sphere), "ply", "painted.ply");
}

//! Fails unless some point lies within `reach` of p.
void expect_near_one(const std::vector<Vec3>& points, const Vec3& p, double reach) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Vec3& q : points) nearest = std::min(nearest, (q - p).norm());
  EXPECT_LE(nearest, reach) << "nothing near " << p.transpose();
}

}  // namespace

TEST(Constraint, PaintedSeedsCoverThePaintAndNothingElse) {
  const TriangleMesh sphere = painted_sphere();
  ASSERT_EQ(sphere.colors.size(), sphere.vertices.size());
  const MeshConstraint constraint(sphere, {}, 0.5);
  Paint red;
  red.color = Vec3(1, 0, 0);
  red.tolerance = 0.3;
  const std::vector<Vec3> seeds = constraint.sample_surface(5, &red);
  ASSERT_GT(seeds.size(), 50u);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    // Half a spacing inside, over the paint: the colour blended at the closest point of the
    // surface (by brute force) is within the tolerance, give or take the step to that point.
    const testing::SampledClosest closest = testing::sampled_closest(constraint.mesh(), seeds[i]);
    ASSERT_LE(closest.distance, 0.26) << i;  // the sampling's own error is about 0.01
    ASSERT_LE((closest.color - red.color).cwiseAbs().maxCoeff(), red.tolerance + 0.05) << i << ": " << seeds[i].transpose();
    ASSERT_TRUE(constraint.inside_test().contains(seeds[i])) << i;
    for (std::size_t j = 0; j < i; ++j) ASSERT_GE((seeds[j] - seeds[i]).norm(), 0.5) << j << ", " << i;
  }
  // Every part of the paint has a seed near it: the cap above z = 5, sampled.
  Rng rng(11, 0);
  for (int k = 0; k < 300; ++k) {
    const double z = 5.0 + 3.0 * rng.uniform(), phi = 2 * 3.14159265358979 * rng.uniform();
    const double r = std::sqrt(64.0 - z * z);
    expect_near_one(seeds, Vec3(r * std::cos(phi), r * std::sin(phi), z), 1.0);
  }
  EXPECT_EQ(constraint.sample_surface(5, &red), seeds);
  // K far apart: among the cover, the first at its middle, the top of the cap.
  const std::vector<Vec3> three = farthest_apart(seeds, 3);
  ASSERT_EQ(three.size(), 3u);
  EXPECT_GT(three[0].z(), 7.0);
  for (const Vec3& s : three) EXPECT_NE(std::find(seeds.begin(), seeds.end(), s), seeds.end());
  EXPECT_GT((three[1] - three[2]).norm(), 6.0);
  EXPECT_THROW(farthest_apart(seeds, seeds.size() + 1), InvalidInput);
  // A colour the mesh does not carry, and a mesh without colours, are errors that say so.
  Paint blue = red;
  blue.color = Vec3(0, 0, 1);
  try {
    constraint.sample_surface(5, &blue);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("#ffffff on"), std::string::npos) << e.what();
  }
  EXPECT_THROW(MeshConstraint(make_sphere(Vec3::Zero(), 8.0), {}, 0.5).sample_surface(5, &red), InvalidInput);
}

TEST(Constraint, PaintedAttractorsLieOverThePaintAndFillIt) {
  const MeshConstraint constraint(painted_sphere(), {}, 0.5);
  AttractorOptions options;
  options.count = 2000;
  options.region = AttractorRegion::surface;
  options.paint = parse_paint("red", "attractor_paint");
  const std::vector<Vec3> points = scatter_attractors(options, 7, 3, &constraint);
  ASSERT_EQ(points.size(), 2000u);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const testing::SampledClosest closest = testing::sampled_closest(constraint.mesh(), points[i]);
    ASSERT_LE(closest.distance, 0.26) << i;
    ASSERT_LE((closest.color - Vec3(1, 0, 0)).cwiseAbs().maxCoeff(), 0.35) << i << ": " << points[i].transpose();
    ASSERT_TRUE(constraint.inside_test().contains(points[i])) << i;
  }
  // Uniform by area over the paint: the share above z = 6 is the painted area's share there
  // (half a spacing in: z = 6 · 8 / 7.75 on the surface), found by quadrature over every
  // triangle, blend and all.
  const TriangleMesh& mesh = constraint.mesh();
  const double z_high = 6.0 * 8.0 / 7.75;
  double painted = 0.0, painted_high = 0.0;
  constexpr int steps = 24;
  for (const auto& tri : mesh.triangles) {
    const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    const double cell = 0.5 * (b - a).cross(c - a).norm() / (steps * steps);
    for (int i = 0; i < steps; ++i)
      for (int j = 0; i + j < steps; ++j)
        for (const int flip : {0, 1}) {
          if (flip && i + j + 1 >= steps) continue;
          // The centroid of each small triangle of the subdivision.
          const double u = (i + (flip ? 2.0 : 1.0) / 3.0) / steps, v = (j + (flip ? 2.0 : 1.0) / 3.0) / steps;
          const Vec3 color = (1 - u - v) * mesh.colors[tri[0]] + u * mesh.colors[tri[1]] + v * mesh.colors[tri[2]];
          if ((color - Vec3(1, 0, 0)).cwiseAbs().maxCoeff() > 0.3) continue;
          painted += cell;
          if ((a + u * (b - a) + v * (c - a)).z() > z_high) painted_high += cell;
        }
  }
  const auto high = std::count_if(points.begin(), points.end(), [](const Vec3& p) { return p.z() > 6.0; });
  EXPECT_NEAR(static_cast<double>(high) / points.size(), painted_high / painted, 0.035);  // 3 sd of 2000 draws
  EXPECT_EQ(scatter_attractors(options, 7, 3, &constraint), points);
  // Paint is for the surface alone, and a colour the mesh lacks is an error naming the option.
  options.region = AttractorRegion::mesh;
  EXPECT_THROW(scatter_attractors(options, 7, 3, &constraint), InvalidInput);
  options.region = AttractorRegion::surface;
  options.paint = parse_paint("blue", "attractor_paint");
  try {
    scatter_attractors(options, 7, 3, &constraint);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("attractor_paint"), std::string::npos) << e.what();
  }
  EXPECT_EQ(to_string(parse_paint("ff8000,0.25", "attractor_paint")), "ff8000,0.25");
}

TEST(Constraint, PaintedSeedsOnAPatchOfTheBust) {
  DLA_NEED_BUST(path);
  TriangleMesh bust = read_mesh(path);
  // A patch of radius 5 about the top of the head, in Blender's red, the rest grey.
  const Vec3 top = *std::max_element(bust.vertices.begin(), bust.vertices.end(),
                                     [](const Vec3& a, const Vec3& b) { return a.z() < b.z(); });
  constexpr double radius = 5.0;
  double longest_edge = 0.0;
  for (const auto& t : bust.triangles)
    for (int k = 0; k < 3; ++k)
      longest_edge = std::max(longest_edge, (bust.vertices[t[k]] - bust.vertices[t[(k + 1) % 3]]).norm());
  for (const Vec3& v : bust.vertices)
    bust.colors.push_back((v - top).norm() < radius ? Vec3(0.8, 0.05, 0.05) : Vec3(0.6, 0.6, 0.6));
  const MeshConstraint constraint(bust, {}, 0.4);
  Paint paint;
  paint.color = Vec3(0.8, 0.05, 0.05);
  const std::vector<Vec3> seeds = constraint.sample_surface(3, &paint);
  // The patch is some 80 units² (a cap of the head): a seed for every spacing² or so.
  EXPECT_GT(seeds.size(), 150u);
  for (const Vec3& s : seeds) {
    ASSERT_LE((s - top).norm(), radius + longest_edge + 0.2) << s.transpose();
    ASSERT_LE(constraint.distance_to_surface(s), 0.2 + 1e-9);
  }
  // Each painted vertex well inside the patch has a seed near it.
  for (const Vec3& v : bust.vertices)
    if ((v - top).norm() < radius - 1.0) expect_near_one(seeds, v, 1.0);
}

TEST(Constraint, IntersectionSeedsFollowWhereAnotherMeshEnters) {
  const MeshConstraint ball(make_sphere(Vec3::Zero(), 10.0), {}, 0.5);
  const auto expect_on_both = [&](const std::vector<Vec3>& seeds, const TriangleMesh& other) {
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      ASSERT_TRUE(ball.inside_test().contains(seeds[i])) << i;
      ASSERT_LE(ball.distance_to_surface(seeds[i]), 0.25 + 1e-9) << i;
      double to_other = std::numeric_limits<double>::infinity();
      for (const auto& t : other.triangles)
        to_other = std::min(to_other, distance_to_triangle(seeds[i], other.vertices[t[0]], other.vertices[t[1]],
                                                           other.vertices[t[2]]));
      ASSERT_LE(to_other, 0.25 + 1e-9) << i;
      for (std::size_t j = 0; j < i; ++j) ASSERT_GE((seeds[j] - seeds[i]).norm(), 0.5) << j << ", " << i;
    }
  };
  // A rod (a can, closed at its base inside the ball, open outside) enters through a circle.
  const TriangleMesh rod = make_open_can(Vec3(0, 0, 5), 2.0, 10.0, 32);
  const std::vector<Vec3> ring = ball.sample_intersection({rod}, 7);
  expect_on_both(ring, rod);
  for (int k = 0; k < 64; ++k) {
    const double phi = 2 * 3.14159265358979 * k / 64;
    expect_near_one(ring, Vec3(2 * std::cos(phi), 2 * std::sin(phi), std::sqrt(96.0)), 1.0);
  }
  EXPECT_EQ(ball.sample_intersection({rod}, 7), ring);
  // Two open squares crossing each other (one self-intersecting mesh) cut two great circles.
  TriangleMesh cross;
  cross.vertices = {{0, -15, -15}, {0, 15, -15}, {0, 15, 15}, {0, -15, 15},
                    {-15, 0, -15}, {15, 0, -15}, {15, 0, 15}, {-15, 0, 15}};
  cross.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const std::vector<Vec3> circles = ball.sample_intersection({cross}, 7);
  expect_on_both(circles, cross);
  for (int k = 0; k < 128; ++k) {
    const double phi = 2 * 3.14159265358979 * k / 128, c = 10 * std::cos(phi), s = 10 * std::sin(phi);
    expect_near_one(circles, Vec3(0, c, s), 1.0);
    expect_near_one(circles, Vec3(c, 0, s), 1.0);
  }
  // A box's face lying in a face of the room: a patch, seeded over.
  const MeshConstraint room(make_box(Vec3::Zero(), Vec3(10, 10, 10)), {}, 0.5);
  const std::vector<Vec3> patch = room.sample_intersection({make_box(Vec3(2, 2, -1), Vec3(4, 4, 0))}, 7);
  for (const Vec3& s : patch) {
    ASSERT_NEAR(s.z(), 0.25, 1e-9);
    ASSERT_TRUE(s.x() >= 2 - 1e-9 && s.x() <= 4 + 1e-9 && s.y() >= 2 - 1e-9 && s.y() <= 4 + 1e-9) << s.transpose();
  }
  for (double x = 2.25; x < 4; x += 0.5)
    for (double y = 2.25; y < 4; y += 0.5) expect_near_one(patch, Vec3(x, y, 0.25), 0.75);
  // Meshes that do not meet the surface, and a wall without a growing side, are errors.
  EXPECT_THROW(ball.sample_intersection({make_sphere(Vec3::Zero(), 3.0)}, 7), InvalidInput);
  ConstraintOptions wall;
  wall.side = Side::both;
  EXPECT_THROW(MeshConstraint(make_sphere(Vec3::Zero(), 10.0), wall, 0.5).sample_intersection({rod}, 7), InvalidInput);
}

TEST(Constraint, ShellBandMatchesBruteForceDistances) {
  const TriangleMesh sphere = make_sphere(Vec3::Zero(), 8.0);
  ConstraintOptions outside;
  outside.side = Side::outside;
  const MeshConstraint constraint(sphere, outside, 0.5);
  const ShellBand band(constraint.mesh(), constraint.inside_test(), Layer::outside, 1.5, 0.25);
  const double slack = 0.5 * std::sqrt(3.0) * band.cell_size();  // a voxel's half-diagonal
  Rng rng(5, 0);
  int held = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p(-11 + 22 * rng.uniform(), -11 + 22 * rng.uniform(), -11 + 22 * rng.uniform());
    const double d = testing::brute_distance(constraint.mesh(), p);
    const bool out = testing::generalized_winding_number(constraint.mesh(), p) < 0.5;
    if (band.holds(p)) {
      ++held;
      ASSERT_LE(d, 1.5 + slack) << p.transpose();
      ASSERT_TRUE(out || d <= slack) << p.transpose();
    } else if (d <= 1.5 - slack && out && d > slack) {
      ADD_FAILURE() << "in the layer but not held: " << p.transpose();
    }
  }
  EXPECT_GT(held, 100);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = band.draw(rng);
    ASSERT_TRUE(band.holds(p));
  }
}

TEST(Constraint, ShellKeepsGrowthOverTheSurface) {
  const TriangleMesh sphere = make_sphere(Vec3::Zero(), 8.0);
  for (const Side side : {Side::outside, Side::inside}) {
    SCOPED_TRACE(std::string(to_string(side)));
    ConstraintOptions c;
    c.side = side;
    c.shell = 3.0;
    const MeshConstraint constraint(sphere, c, 0.5);
    EXPECT_DOUBLE_EQ(constraint.shell(), 1.5);
    DlaOptions o;
    o.particles = 1500;
    o.spacing = 0.5;
    o.spawn = SpawnMode::inside;  // uniform in the shell
    o.seeds = constraint.place_seeds(1, o.rng_seed);
    const Cluster grown = grow(o, constraint);
    expect_constrained(grown, constraint);
    for (const Particle& p : grown.particles)
      ASSERT_LE(constraint.distance_to_surface(p.position), 1.5 + 1e-9) << p.position.transpose();
    // Over the surface, not a lump: the structure spans much of the sphere.
    EXPECT_GT(radius_of_gyration(grown), 4.0);
    o.threads = 2;
    const Cluster two = grow(o, constraint);
    ASSERT_EQ(two.particles.size(), grown.particles.size());
    for (std::size_t i = 0; i < grown.particles.size(); ++i)
      ASSERT_EQ(two.particles[i].position, grown.particles[i].position) << "particle " << i;
  }
  // An open sheet, grown over on both sides.
  TriangleMesh sheet;
  sheet.vertices = {{-10, -10, 0}, {10, -10, 0}, {10, 10, 0}, {-10, 10, 0}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  ConstraintOptions on;
  on.side = Side::surface;
  const MeshConstraint leaf(sheet, on, 0.5);
  EXPECT_DOUBLE_EQ(leaf.shell(), 1.5);  // three spacings by default
  DlaOptions o;
  o.particles = 1500;
  o.spacing = 0.5;
  o.spawn = SpawnMode::inside;
  o.seeds = {Vec3(-5, 0, 0.25), Vec3(5, 0, -0.25)};  // one on each side: branches cannot cross the sheet
  const Cluster frosted = grow(o, leaf);
  expect_constrained(frosted, leaf);  // no branch meets the sheet
  int above = 0, below = 0;
  for (const Particle& p : frosted.particles) {
    ASSERT_LE(testing::brute_distance(sheet, p.position), 1.5 + 1e-9) << p.position.transpose();
    above += p.position.z() > 0.25;
    below += p.position.z() < -0.25;
  }
  EXPECT_GT(above, 100);
  EXPECT_GT(below, 100);
  // Seeds placed on a surface that grows on both sides go to either side.
  int up = 0;
  for (const Vec3& seed : leaf.place_seeds(20, 3)) up += seed.z() > 0.0;
  EXPECT_GT(up, 2);
  EXPECT_LT(up, 18);
}

TEST(Constraint, FrostOverTheBust) {
  DLA_NEED_BUST(path);
  ConstraintOptions c;
  c.side = Side::outside;
  c.shell = 3.0;
  const MeshConstraint constraint(read_mesh(path), c, 0.4);
  DlaOptions o;
  o.particles = 2000;
  o.spacing = 0.4;
  o.spawn = SpawnMode::inside;
  o.seeds = constraint.place_seeds(1, o.rng_seed);
  const Cluster frost = grow(o, constraint);
  for (const Particle& p : frost.particles) {
    ASSERT_LE(constraint.distance_to_surface(p.position), 1.2 + 1e-9) << p.position.transpose();
    ASSERT_FALSE(constraint.inside_test().contains(p.position)) << p.position.transpose();
  }
  EXPECT_GT(radius_of_gyration(frost), 5.0);
}

TEST(Constraint, BadSetupsAreClearErrors) {
  const MeshConstraint constraint(make_sphere(Vec3::Zero(), 5.0), {}, 1.0);
  DlaOptions o;
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
  ConstraintOptions thin;
  thin.shell = 0.5;
  EXPECT_THROW(MeshConstraint(make_sphere(Vec3::Zero(), 5.0), thin, 1.0), InvalidInput);
  thin.shell = 2.0;
  DlaOptions filling;
  filling.spacing = 1.0;
  filling.fill = 0.5;
  filling.spawn = SpawnMode::inside;
  const MeshConstraint lined(make_sphere(Vec3::Zero(), 5.0), thin, 1.0);
  filling.seeds = lined.place_seeds(1, 1);
  EXPECT_THROW(grow(filling, lined), InvalidInput);  // --fill in a shell
}

}  // namespace
}  // namespace dla
