// Space colonization: the kept closest nodes against a full rescan, node for node; the kill
// distance; determinism; the ends of growth; bad options.

#include "dla/models/colonization.h"
#include "dla/mesh/shapes.h"
#include "dla/look/strands.h"
#include "colonization_rescan.h"

#include "tree_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace dla;
using dla::testing::colonize_by_rescan;

namespace {

void expect_same_tree(const Cluster& a, const Cluster& b) {
  ASSERT_EQ(a.particles.size(), b.particles.size());
  ASSERT_EQ(a.seed_count, b.seed_count);
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    ASSERT_EQ(a.particles[i].position, b.particles[i].position) << "node " << i;
    ASSERT_EQ(a.particles[i].parent, b.particles[i].parent) << "node " << i;
    ASSERT_EQ(a.particles[i].seed, b.particles[i].seed) << "node " << i;
  }
}

}  // namespace

TEST(Colonization, KeptClosestNodesGiveTheFullRescansTree) {
  struct Case {
    const char* name;
    ColonizationOptions options;
    AttractorOptions attractors;
    std::vector<Vec3> roots;
    int copies = 1;  // of every attractor: ties between equally close nodes
  };
  std::vector<Case> cases;
  {
    Case c{"the write-up's first test: 100 in a sphere, one root", {}, {}, {Vec3(0, -20, 0)}};
    c.attractors.count = 100;
    c.attractors.radius = 20;
    cases.push_back(c);
  }
  {
    Case c{"three roots, finite influence", {}, {}, {Vec3(-15, 0, 0), Vec3(15, 0, 0), Vec3(0, 0, 15)}};
    c.attractors.count = 2000;
    c.attractors.radius = 25;
    c.options.influence = 6;
    c.options.kill_distance = 1.5;
    cases.push_back(c);
  }
  {
    Case c{"graded, with noise and tropism", {}, {}, {Vec3(0, 0, -30)}};
    c.attractors.count = 3000;
    c.attractors.radius = 30;
    c.attractors.falloff = 1.5;
    c.options.noise_amplitude = 0.4;
    c.options.noise_scale = 5;
    c.options.tropism = Vec3(0, 0, 0.2);
    c.options.rng_seed = 9;
    cases.push_back(c);
  }
  {
    Case c{"2D venation in a box, a node limit", {}, {}, {Vec3(0, -20, 0)}};
    c.options.dimensions = 2;
    c.options.max_nodes = 400;
    c.attractors.count = 1500;
    c.attractors.region = AttractorRegion::box;
    c.attractors.box_min = Vec3(-20, -20, 0);
    c.attractors.box_max = Vec3(20, 20, 0);
    cases.push_back(c);
  }
  {
    Case c{"unbounded among steeply graded attractors, each twice, two roots", {}, {}, {Vec3(0, 0, -25), Vec3(0, 0, 25)}};
    c.attractors.count = 1500;
    c.attractors.radius = 25;
    c.attractors.falloff = 3;
    c.copies = 2;
    cases.push_back(c);
  }
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    std::vector<Vec3> attractors;
    for (const Vec3& a : scatter_attractors(c.attractors, 5, c.options.dimensions)) attractors.insert(attractors.end(), c.copies, a);
    const Cluster kept = colonize(c.options, attractors, c.roots);
    ASSERT_GT(kept.particles.size(), c.roots.size() + 20) << "it grew";
    expect_same_tree(kept, colonize_by_rescan(c.options, attractors, c.roots));
    EXPECT_LE(kept.particles.size(), c.options.max_nodes);
    // One step a node, or as far as the noise moves it.
    const double noise = std::sqrt(3.0) * c.options.noise_amplitude;
    EXPECT_EQ(dla::testing::tree_fault(kept, {noise > 0 ? 0.0 : 1.0, 1.0 + noise, false}), "");
  }
}

TEST(Colonization, AttractorsDieExactlyAtTheKillDistance) {
  ColonizationOptions o;
  o.kill_distance = 2.0;
  // On the kill distance from the root: dead before anything grows.
  EXPECT_EQ(colonize(o, {Vec3(2, 0, 0)}, {Vec3::Zero()}).particles.size(), 1u);
  // Just beyond it: one step towards it, then it dies.
  const Cluster one = colonize(o, {Vec3(2.000001, 0, 0)}, {Vec3::Zero()});
  ASSERT_EQ(one.particles.size(), 2u);
  EXPECT_NEAR((one.particles[1].position - Vec3(1, 0, 0)).norm(), 0.0, 1e-12);
  // Along a line: an attractor m steps plus the kill distance away dies after exactly m steps,
  // one a hair farther after m + 1.
  for (const double kill : {1.0, 1.5, 2.5, 4.0}) {
    o.kill_distance = kill;
    for (const int m : {1, 3, 7}) {
      EXPECT_EQ(colonize(o, {Vec3(kill + m, 0, 0)}, {Vec3::Zero()}).particles.size(), static_cast<std::size_t>(m + 1))
          << kill << " " << m;
      EXPECT_EQ(colonize(o, {Vec3(kill + m + 1e-6, 0, 0)}, {Vec3::Zero()}).particles.size(), static_cast<std::size_t>(m + 2))
          << kill << " " << m;
    }
  }
}

TEST(Colonization, TheSameInputsGiveTheSameTreeAndTheNoiseSeedMatters) {
  ColonizationOptions o;
  o.noise_amplitude = 0.5;
  AttractorOptions a;
  a.count = 2000;
  a.radius = 20;
  const std::vector<Vec3> attractors = scatter_attractors(a, 1, 3);
  EXPECT_EQ(attractors, scatter_attractors(a, 1, 3));
  EXPECT_NE(attractors, scatter_attractors(a, 2, 3));
  const Cluster first = colonize(o, attractors, {Vec3::Zero()});
  expect_same_tree(first, colonize(o, attractors, {Vec3::Zero()}));
  o.rng_seed = 2;
  const Cluster other = colonize(o, attractors, {Vec3::Zero()});
  EXPECT_NE(first.particles.back().position, other.particles.back().position);
}

TEST(Colonization, GrowthEndsWhenItStallsOrMeetsALimit) {
  ColonizationOptions o;
  // Two attractors pulling a root in opposite directions: the directions cancel, nothing grows.
  EXPECT_EQ(colonize(o, {Vec3(5, 0, 0), Vec3(-5, 0, 0)}, {Vec3::Zero()}).particles.size(), 1u);
  // Out of reach of a finite influence: nothing grows.
  o.influence = 3;
  EXPECT_EQ(colonize(o, {Vec3(5, 0, 0)}, {Vec3::Zero()}).particles.size(), 1u);
  o.influence = std::numeric_limits<double>::infinity();
  AttractorOptions a;
  a.count = 3000;
  a.radius = 25;
  const std::vector<Vec3> attractors = scatter_attractors(a, 4, 3);
  o.max_iterations = 3;
  const Cluster three = colonize(o, attractors, {Vec3::Zero()});
  std::vector<int> depth(three.particles.size(), 0);
  for (std::size_t i = 1; i < three.particles.size(); ++i)
    depth[i] = depth[static_cast<std::size_t>(three.particles[i].parent)] + 1;
  EXPECT_EQ(*std::max_element(depth.begin(), depth.end()), 3) << "one step an iteration";
  o.max_iterations = 1000000;
  o.max_nodes = 50;
  EXPECT_EQ(colonize(o, attractors, {Vec3::Zero()}).particles.size(), 50u);
  // A progress callback that says stop as growth begins: the roots, marked incomplete; one
  // that lets it go on sees the whole tree last.
  o.max_nodes = 100000;
  int calls = 0;
  const Cluster stopped = colonize(o, attractors, {Vec3::Zero()}, [&](const Cluster&) { return ++calls < 1; });
  EXPECT_FALSE(stopped.complete);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(stopped.particles.size(), 1u);
  std::size_t seen = 0;
  const Cluster whole = colonize(o, attractors, {Vec3::Zero()}, [&](const Cluster& so_far) {
    seen = so_far.particles.size();
    return true;
  });
  EXPECT_TRUE(whole.complete);
  EXPECT_EQ(seen, whole.particles.size());
}

TEST(Colonization, PushKeepsEveryNodeOutOfTheCollisionObject) {
  const CollisionObject ball(make_sphere(Vec3::Zero(), 8.0, 24, 48), 1.0, CollisionMode::push);
  ColonizationOptions o;
  o.collide = &ball;
  AttractorOptions a;
  a.count = 3000;
  a.radius = 25;
  std::vector<Vec3> attractors;
  for (const Vec3& p : scatter_attractors(a, 6, 3))
    if (ball.signed_distance(p) > 2.0) attractors.push_back(p);  // none the tree cannot reach
  const Cluster tree = colonize(o, attractors, {Vec3(0, -24, 0)});
  ASSERT_GT(tree.particles.size(), 500u);
  std::size_t on_surface = 0;
  for (const Particle& node : tree.particles) {
    const double d = ball.signed_distance(node.position);
    ASSERT_GE(d, -1e-9) << "a node inside the object";
    on_surface += d < 1e-9;
  }
  EXPECT_GT(on_surface, 10u) << "growth met the object and went around it";
  // The kept closest nodes and the rescan agree with a collision too.
  expect_same_tree(tree, colonize_by_rescan(o, attractors, {Vec3(0, -24, 0)}));
}

TEST(Colonization, StickHoldsEveryNewNodeOnTheSurface) {
  const CollisionObject ball(make_sphere(Vec3::Zero(), 10.0, 24, 48), 1.0, CollisionMode::stick);
  ColonizationOptions o;
  o.collide = &ball;
  AttractorOptions a;
  a.count = 2000;
  a.radius = 14;
  const Cluster tree = colonize(o, scatter_attractors(a, 8, 3), {Vec3(0, -10, 0)});
  ASSERT_GT(tree.particles.size(), 100u);
  std::vector<double> lengths;
  for (std::size_t i = tree.seed_count; i < tree.particles.size(); ++i) {
    ASSERT_LE(std::abs(ball.signed_distance(tree.particles[i].position)), 1e-9) << "node " << i;
    const Vec3& parent = tree.particles[static_cast<std::size_t>(tree.particles[i].parent)].position;
    lengths.push_back((tree.particles[i].position - parent).norm());
    ASSERT_GE(lengths.back(), 0.1) << "a branch of almost no length";
  }
  // Attractors inside the ball pull into it: the steps still go a whole step over the surface.
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  EXPECT_GT(lengths[lengths.size() / 2], 0.9);
  ColonizationOptions flat = o;
  flat.dimensions = 2;
  EXPECT_THROW(colonize(flat, {Vec3(5, 0, 0)}, {Vec3::Zero()}), InvalidInput);
  EXPECT_EQ(parse_word<CollisionMode>("stick"), CollisionMode::stick);
  EXPECT_THROW(parse_word<CollisionMode>("bounce"), InvalidInput);
}

TEST(Colonization, AVesselHoldsTheGrowthAndItsBranches) {
  // Attractors in a box vessel, and a tropism up that presses growth on its top wall.
  const Vec3 lo(-6, -6, -6), hi(6, 6, 6);
  const MeshConstraint vessel(make_box(lo, hi), {Side::inside, ConstraintMode::reject}, 1.0);
  ColonizationOptions o;
  o.vessel = &vessel;
  o.tropism = Vec3(0, 1.5, 0);
  AttractorOptions a;
  a.count = 3000;
  a.region = AttractorRegion::mesh;
  const std::vector<Vec3> attractors = scatter_attractors(a, 4, 3, &vessel);
  const std::vector<Vec3> root{Vec3(0, -5, 0)};
  const auto inside = [&](const Vec3& p) { return (p.array() > lo.array()).all() && (p.array() < hi.array()).all(); };
  ColonizationOptions free = o;
  free.vessel = nullptr;
  const Cluster unbounded = colonize(free, attractors, root);
  EXPECT_TRUE(std::any_of(unbounded.particles.begin(), unbounded.particles.end(),
                          [&](const Particle& node) { return !inside(node.position); }))
      << "without the vessel, the tropism takes growth through the wall";
  const Cluster tree = colonize(o, attractors, root);
  ASSERT_GT(tree.particles.size(), 500u);
  for (const Particle& node : tree.particles)  // and so its branch: the box is convex
    ASSERT_TRUE(inside(node.position)) << node.position.transpose();
  expect_same_tree(tree, colonize_by_rescan(o, attractors, root));
  // Clipped steps end short of the wall instead.
  const MeshConstraint clipping(make_box(lo, hi), {Side::inside, ConstraintMode::clip}, 1.0);
  o.vessel = &clipping;
  for (const Particle& node : colonize(o, attractors, root).particles) ASSERT_TRUE(inside(node.position));
  EXPECT_THROW(colonize(o, attractors, {Vec3(0, -9, 0)}), InvalidInput) << "a root outside the vessel";
}

TEST(Colonization, AttractorsInAMeshAndOnItsSurface) {
  const MeshConstraint ball(make_sphere(Vec3(1, 2, 3), 10.0, 32, 64), {}, 0.5);
  AttractorOptions a;
  a.count = 2000;
  a.region = AttractorRegion::mesh;
  const std::vector<Vec3> inside = scatter_attractors(a, 3, 3, &ball);
  ASSERT_EQ(inside.size(), a.count);
  double mean_radius = 0;
  for (const Vec3& p : inside) {
    ASSERT_LE((p - Vec3(1, 2, 3)).norm(), 10.0) << "in the ball";
    mean_radius += (p - Vec3(1, 2, 3)).norm() / static_cast<double>(inside.size());
  }
  EXPECT_NEAR(mean_radius, 0.75 * 10.0, 0.25) << "uniform in the volume: the mean radius is 3R/4";
  a.region = AttractorRegion::surface;
  for (const Vec3& p : scatter_attractors(a, 3, 3, &ball)) {
    // Half a spacing off a triangle, so a little less near the edges of a neighbour.
    ASSERT_LE(ball.distance_to_surface(p), 0.25 + 1e-9);
    ASSERT_GE(ball.distance_to_surface(p), 0.2);
    ASSERT_LT((p - Vec3(1, 2, 3)).norm(), 10.0);
  }
  EXPECT_EQ(scatter_attractors(a, 3, 3, &ball), scatter_attractors(a, 3, 3, &ball));
  EXPECT_THROW(scatter_attractors(a, 3, 3), InvalidInput) << "no mesh";
  EXPECT_THROW(scatter_attractors(a, 3, 2, &ball), InvalidInput) << "2D";
  EXPECT_EQ(parse_word<AttractorRegion>("surface"), AttractorRegion::surface);
}

TEST(Colonization, ASampleOfAttractorsIsASubsetOfTheRightSize) {
  AttractorOptions a;
  a.count = 1000;
  const std::vector<Vec3> all = scatter_attractors(a, 2, 3);
  const std::vector<Vec3> some = sample_attractors(all, 300, 7);
  ASSERT_EQ(some.size(), 300u);
  std::size_t at = 0;  // in the file's order, without repeats
  for (const Vec3& p : some) {
    while (at < all.size() && all[at] != p) ++at;
    ASSERT_LT(at++, all.size()) << "a point not in the file, or out of order";
  }
  EXPECT_EQ(some, sample_attractors(all, 300, 7));
  EXPECT_NE(some, sample_attractors(all, 300, 8));
  EXPECT_EQ(sample_attractors(all, 1000, 7), all);
  EXPECT_THROW(sample_attractors(all, 1001, 7), InvalidInput);
}

TEST(Colonization, BadOptionsGetOneLine) {
  const std::vector<Vec3> attractors{Vec3(5, 0, 0)};
  const std::vector<Vec3> root{Vec3::Zero()};
  const auto refuses = [&](auto&& change) {
    ColonizationOptions o;
    change(o);
    EXPECT_THROW(colonize(o, attractors, root), InvalidInput);
  };
  refuses([](ColonizationOptions& o) { o.kill_distance = 0.5; });
  refuses([](ColonizationOptions& o) { o.kill_distance = std::nan(""); });
  refuses([](ColonizationOptions& o) { o.influence = 1.5; });
  refuses([](ColonizationOptions& o) { o.spacing = 0; });
  refuses([](ColonizationOptions& o) { o.max_nodes = 0; });
  refuses([](ColonizationOptions& o) { o.max_iterations = 0; });
  refuses([](ColonizationOptions& o) { o.noise_amplitude = -1; });
  refuses([](ColonizationOptions& o) { o.noise_scale = 0; });
  refuses([](ColonizationOptions& o) { o.tropism = Vec3(0, 0, std::numeric_limits<double>::infinity()); });
  refuses([](ColonizationOptions& o) { o.dimensions = 4; });
  EXPECT_THROW(colonize({}, attractors, {}), InvalidInput) << "no root";
  EXPECT_THROW(colonize({}, {Vec3(std::nan(""), 0, 0)}, root), InvalidInput);
  AttractorOptions a;
  a.count = 0;
  EXPECT_THROW(scatter_attractors(a, 1, 3), InvalidInput);
  a.count = 10;
  a.falloff = -1;
  EXPECT_THROW(scatter_attractors(a, 1, 3), InvalidInput);
  a.falloff = 0;
  a.region = AttractorRegion::box;
  a.box_max = a.box_min;
  EXPECT_THROW(scatter_attractors(a, 1, 3), InvalidInput);
  EXPECT_EQ(parse_word<AttractorRegion>("box"), AttractorRegion::box);
  EXPECT_THROW(parse_word<AttractorRegion>("cube"), InvalidInput);
}
