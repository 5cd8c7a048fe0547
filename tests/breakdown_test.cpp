// The breakdown model (breakdown.h): DLA at eta 1, a tree whatever eta, the same structure on
// any thread count, sparser with eta, a strike that ends growth at the target, insulators that
// hold, and one line for every option that cannot work.

#include "tree_check.h"

#include "dla/core/analysis.h"
#include "dla/models/breakdown.h"
#include "dla/models/dla.h"
#include "dla/mesh/shapes.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>

namespace dla {
namespace {

DlaOptions walk_of(std::size_t particles, std::uint64_t seed = 3, int dimensions = 3) {
  DlaOptions walk;
  walk.particles = particles;
  walk.rng_seed = seed;
  walk.dimensions = dimensions;
  return walk;
}

bool same_particles(const Cluster& a, const Cluster& b) {
  if (a.particles.size() != b.particles.size()) return false;
  for (std::size_t i = 0; i < a.particles.size(); ++i)
    if (a.particles[i].position != b.particles[i].position || a.particles[i].parent != b.particles[i].parent) return false;
  return true;
}

TEST(Breakdown, AtEtaOneWithOneWalkerItIsDla) {
  const DlaOptions walk = walk_of(1500);
  const Cluster dla = grow(walk);
  const Cluster discharge = breakdown(walk, BreakdownOptions{}, nullptr);
  EXPECT_TRUE(same_particles(dla, discharge));
  EXPECT_EQ(discharge.strike, -1);
}

TEST(Breakdown, GrowsATreeOfSpacedParticlesForEveryEta) {
  for (const double eta : {0.0, 0.5, 2.0, 3.5})
    for (const int dimensions : {2, 3}) {
      BreakdownOptions o;
      o.eta = eta;
      BreakdownStats stats;
      const Cluster c = breakdown(walk_of(400, 5, dimensions), o, nullptr, {}, nullptr, &stats);
      SCOPED_TRACE("eta " + std::to_string(eta) + ", " + std::to_string(dimensions) + "D");
      EXPECT_EQ(testing::tree_fault(c), "");
      EXPECT_EQ(attached(c), 400u);
      EXPECT_TRUE(c.complete);
      // At least the walkers a particle asks for; past eta 1, more where no site had weight.
      EXPECT_GE(stats.walk.walkers, 400u * kDefaultBreakdownWalkers);
    }
}

TEST(Breakdown, TheSameStructureOnAnyThreadCount) {
  BreakdownOptions o;
  o.eta = 2.5;
  DlaOptions walk = walk_of(600, 9);
  const Cluster one = breakdown(walk, o, nullptr);
  walk.threads = 3;
  EXPECT_TRUE(same_particles(one, breakdown(walk, o, nullptr)));
}

TEST(Breakdown, HigherEtaGrowsSparserChannels) {
  // The same count spreads farther, and fills space less, as eta rises (docs/breakdown.md
  // has the ensembles; one seeded run each here, far apart in eta).
  const std::size_t n = 4000;
  BreakdownOptions low, high;
  low.eta = 0.0;
  high.eta = 3.0;
  const Cluster compact = breakdown(walk_of(n, 11), low, nullptr);
  const Cluster dla = grow(walk_of(n, 11));
  const Cluster sparse = breakdown(walk_of(n, 11), high, nullptr);
  EXPECT_LT(radius_of_gyration(compact), radius_of_gyration(dla));
  EXPECT_LT(1.3 * radius_of_gyration(dla), radius_of_gyration(sparse));
}

TEST(Breakdown, AStrikeEndsGrowthAtTheTarget) {
  for (const int dimensions : {2, 3})
    for (const TargetKind kind : {TargetKind::point, TargetKind::plane}) {
      BreakdownOptions o;
      o.eta = 2.0;
      o.target.kind = kind;
      o.target.point = Vec3(0.0, -25.0, 0.0);
      o.target.axis = Axis::y;
      o.target.at = -25.0;
      SCOPED_TRACE(std::string(to_string(kind)) + ", " + std::to_string(dimensions) + "D");
      const Cluster c = breakdown(walk_of(20000, 4, dimensions), o, nullptr);
      EXPECT_EQ(testing::tree_fault(c), "");
      ASSERT_GE(c.strike, 0);
      EXPECT_EQ(static_cast<std::size_t>(c.strike), c.particles.size() - 1);  // it ended there
      EXPECT_LT(attached(c), 20000u);
      const Vec3& tip = c.particles[static_cast<std::size_t>(c.strike)].position;
      const double to_target = kind == TargetKind::point ? (tip - o.target.point).norm() - 0.5 : tip.y() + 25.0;
      EXPECT_LE(to_target, 1.0);
      // Every particle before the strike stayed clear of it: it is the first to come near.
      for (std::size_t i = 0; i + 1 < c.particles.size(); ++i) {
        const Vec3& p = c.particles[i].position;
        EXPECT_GT(kind == TargetKind::point ? (p - o.target.point).norm() - 0.5 : p.y() + 25.0, 1.0) << i;
      }
    }
}

TEST(Breakdown, GoesOnPastTheStrikeWhenAsked) {
  BreakdownOptions o;
  o.eta = 2.0;
  o.target.kind = TargetKind::point;
  o.target.point = Vec3(12.0, 0.0, 0.0);
  o.stop_at_strike = false;
  const Cluster c = breakdown(walk_of(600, 2, 2), o, nullptr);
  EXPECT_EQ(attached(c), 600u);
  EXPECT_GE(c.strike, 0);
  EXPECT_LT(static_cast<std::size_t>(c.strike), c.particles.size() - 1);
}

TEST(Breakdown, AnInsulatorHoldsTheDischargeOnItsSide) {
  // Growth inside a ball it cannot leave, towards a plane beyond the ball's wall.
  const TriangleMesh ball = make_sphere(Vec3::Zero(), 15.0);
  const MeshConstraint inside(ball, ConstraintOptions{}, 1.0);
  BreakdownOptions o;
  o.eta = 2.0;
  o.target.kind = TargetKind::plane;
  o.target.axis = Axis::y;
  o.target.at = -30.0;
  DlaOptions walk = walk_of(300);
  walk.spawn = SpawnMode::inside;
  // Walkers leave the plane outside the ball and never reach in: one line, not a hang.
  try {
    breakdown(walk, o, &inside);
    FAIL() << "growth went on with a target the walkers cannot leave";
  } catch (const PartialGrowth& e) {
    EXPECT_NE(std::string(e.what()).find("target"), std::string::npos) << e.what();
  }
  // Outside the ball, from above it, the discharge runs around it.
  const MeshConstraint outside(ball, ConstraintOptions{Side::outside}, 1.0);
  walk.spawn = SpawnMode::sphere;
  walk.seeds = {Vec3(0.0, 25.0, 0.0)};
  walk.particles = 3000;
  o.target.at = -25.0;
  const Cluster c = breakdown(walk, o, &outside);
  EXPECT_EQ(testing::tree_fault(c), "");
  for (const Particle& p : c.particles) EXPECT_GT(p.position.norm(), 15.0);
}

TEST(Breakdown, RefusesWhatCannotWorkInOneLine) {
  const auto refusal = [](BreakdownOptions o, DlaOptions walk = walk_of(10)) {
    try {
      breakdown(walk, o, nullptr);
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  BreakdownOptions o;
  o.eta = 11.0;
  EXPECT_NE(refusal(o).find("`eta`"), std::string::npos);
  o.eta = std::nan("");
  EXPECT_NE(refusal(o).find("`eta`"), std::string::npos);
  o.eta = 2.0;
  o.walkers = 5000;
  EXPECT_NE(refusal(o).find("`walkers`"), std::string::npos);
  o.walkers = 0;
  o.target.kind = TargetKind::point;
  o.target.point = Vec3(0.5, 0.0, 0.0);
  EXPECT_NE(refusal(o).find("electrodes must be apart"), std::string::npos);
  o.target.kind = TargetKind::plane;
  o.target.axis = Axis::z;
  EXPECT_NE(refusal(o, walk_of(10, 1, 2)).find("growth plane"), std::string::npos);
  o.target.axis = Axis::x;
  o.target.at = 0.3;
  EXPECT_NE(refusal(o).find("touches the target"), std::string::npos);
  BreakdownOptions negative;
  negative.eta = -1.0;
  for (const std::string& line : {refusal(o), refusal(negative)})
    EXPECT_EQ(line.find('\n'), std::string::npos) << line;
}

TEST(Breakdown, StopsWhenAskedAndKeepsWhatGrew) {
  std::atomic<bool> stop{false};
  BreakdownOptions o;
  o.eta = 2.0;
  std::size_t calls = 0;
  const Cluster c = breakdown(walk_of(200000), o, nullptr, [&](const Cluster& so_far) {
    if (++calls == 2) stop.store(true);
    return so_far.particles.size() < 200000;
  }, &stop);
  EXPECT_FALSE(c.complete);
  EXPECT_EQ(testing::tree_fault(c), "");
  EXPECT_LT(attached(c), 200000u);
}

}  // namespace
}  // namespace dla
