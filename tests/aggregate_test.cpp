// The aggregate model (dla/models/aggregate.h): every mode's aggregate is one cluster of
// monomers that touch along its tree and overlap no more than asked, checked pair by pair by
// brute force; the tuned mode lands on its law; the same seed gives the same aggregate; bad
// input is refused in one line; the CLI writes a sphere list that reads back.

#include "cli_util.h"
#include "test_util.h"

#include "dla/models/aggregate.h"
#include "dla/run/run.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using dla::AggregateMode;
using dla::AggregateOptions;
using dla::Cluster;
using dla::MonomerSizes;
using dla::testing::ScratchDir;

//! The aggregate's invariants: one tree over every monomer, each monomer touching its parent
//! at (1 - overlap)(r_i + r_j), and no pair closer than that (brute force over every pair).
void expect_sound(const Cluster& aggregate, const AggregateOptions& o) {
  const auto& ps = aggregate.particles;
  ASSERT_EQ(ps.size(), o.monomers);
  ASSERT_EQ(aggregate.radii.size(), ps.size());
  EXPECT_TRUE(aggregate.complete);
  EXPECT_EQ(aggregate.seed_count, 1u);
  EXPECT_EQ(ps[0].parent, -1);
  const double keep = 1.0 - o.overlap;
  for (std::size_t i = 1; i < ps.size(); ++i) {
    const std::int32_t parent = ps[i].parent;
    ASSERT_GE(parent, 0) << "monomer " << i << " is not joined";  // one cluster: every one has a parent
    ASSERT_LT(static_cast<std::size_t>(parent), i);
    const auto pi = static_cast<std::size_t>(parent);
    const double touch = keep * (aggregate.radii[i] + aggregate.radii[pi]);
    EXPECT_NEAR((ps[i].position - ps[pi].position).norm(), touch, 1e-7 * touch) << "monomer " << i;
  }
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (std::size_t j = i + 1; j < ps.size(); ++j) {
      const double least = keep * (aggregate.radii[i] + aggregate.radii[j]);
      ASSERT_GE((ps[i].position - ps[j].position).norm(), least * (1.0 - 1e-7)) << "monomers " << i << " and " << j;
    }
}

AggregateOptions options(AggregateMode mode, std::size_t monomers) {
  AggregateOptions o;
  o.mode = mode;
  o.monomers = monomers;
  return o;
}

TEST(Aggregate, EveryModeGrowsOneSoundCluster) {
  for (const AggregateMode mode : {AggregateMode::dlca, AggregateMode::rlca, AggregateMode::ballistic, AggregateMode::tuned}) {
    SCOPED_TRACE(std::string(to_string(mode)));
    AggregateOptions o = options(mode, 300);
    if (mode != AggregateMode::tuned) o.volume_fraction = 0.05;
    if (mode == AggregateMode::rlca) o.stick_probability = 0.1;
    dla::AggregateStats stats;
    expect_sound(dla::aggregate(o, {}, nullptr, &stats), o);
    EXPECT_EQ(stats.joins.size(), o.monomers - 1);
  }
}

// rlca's reaction-limited limit has no box: clusters join at random contacts, and two large
// open ones, which rarely find room at one, along a line. 2,000 monomers on seed 107 take both
// ways (twice along a line), and every pair of monomers is checked.
TEST(Aggregate, ReactionLimitedClustersJoinWithoutABox) {
  AggregateOptions o = options(AggregateMode::rlca, 2000);
  o.rng_seed = 107;
  dla::AggregateStats stats;
  expect_sound(dla::aggregate(o, {}, nullptr, &stats), o);
  EXPECT_EQ(stats.box, 0.0);
  EXPECT_EQ(stats.moves, 0u);
  EXPECT_EQ(stats.joins.size(), o.monomers - 1);
  EXPECT_GE(stats.approaches, 1u);
  EXPECT_GT(stats.tries, stats.joins.size());
}

TEST(Aggregate, PolydisperseAndSinteredMonomersOverlapNoMoreThanAsked) {
  for (const AggregateMode mode : {AggregateMode::dlca, AggregateMode::rlca, AggregateMode::tuned}) {
    for (const MonomerSizes sizes : {MonomerSizes::lognormal, MonomerSizes::normal}) {
      SCOPED_TRACE(std::string(to_string(mode)) + " " + std::string(to_string(sizes)));
      AggregateOptions o = options(mode, 200);
      o.sizes = sizes;
      o.spread = sizes == MonomerSizes::lognormal ? 1.5 : 0.2;
      o.overlap = 0.2;
      const Cluster aggregate = dla::aggregate(o);
      expect_sound(aggregate, o);
      const auto [least, most] = std::minmax_element(aggregate.radii.begin(), aggregate.radii.end());
      EXPECT_LT(*least, 0.9 * o.monomer_radius);  // the radii spread
      EXPECT_GT(*most, 1.1 * o.monomer_radius);
    }
  }
}

TEST(Aggregate, TheSameSeedGivesTheSameAggregate) {
  for (const AggregateMode mode : {AggregateMode::dlca, AggregateMode::rlca, AggregateMode::tuned}) {
    AggregateOptions o = options(mode, 150);
    const Cluster a = dla::aggregate(o), b = dla::aggregate(o);
    ASSERT_EQ(a.particles.size(), b.particles.size());
    for (std::size_t i = 0; i < a.particles.size(); ++i) {
      EXPECT_EQ(a.particles[i].position, b.particles[i].position);
      EXPECT_EQ(a.particles[i].parent, b.particles[i].parent);
    }
    o.rng_seed = 2;
    EXPECT_NE(dla::aggregate(o).particles.back().position, a.particles.back().position);
  }
}

// The box's threads split the contact test of clusters of 512 monomers or more: 3,000 monomers
// grow such clusters, and two threads must give the aggregate one does, monomer for monomer.
TEST(Aggregate, TheSameAggregateOnAnyThreadCount) {
  for (const AggregateMode mode : {AggregateMode::dlca, AggregateMode::ballistic}) {
    SCOPED_TRACE(std::string(to_string(mode)));
    AggregateOptions o = options(mode, 3000);
    o.volume_fraction = 0.03;
    dla::AggregateStats one_stats, two_stats;
    const Cluster one = dla::aggregate(o, {}, nullptr, &one_stats);
    o.threads = 2;
    const Cluster two = dla::aggregate(o, {}, nullptr, &two_stats);
    EXPECT_EQ(one_stats.moves, two_stats.moves);
    ASSERT_EQ(one.particles.size(), two.particles.size());
    for (std::size_t i = 0; i < one.particles.size(); ++i) {
      ASSERT_EQ(one.particles[i].position, two.particles[i].position) << "monomer " << i;
      ASSERT_EQ(one.particles[i].parent, two.particles[i].parent) << "monomer " << i;
    }
  }
}

TEST(Aggregate, TunedClustersLieOnTheirLaw) {
  // Every join of whole pieces places its clusters so that N = kf (Rg/a)^df holds exactly.
  // 2.5 and 1 leaves two pieces no room to interlock: that aggregate grows a monomer at a time.
  for (const auto& [df, kf] : {std::pair{1.5, 1.0}, std::pair{1.8, 1.3}, std::pair{2.2, 1.5}, std::pair{2.5, 1.0}}) {
    SCOPED_TRACE("df " + std::to_string(df) + " kf " + std::to_string(kf));
    AggregateOptions o = options(AggregateMode::tuned, 512);
    o.df = df;
    o.kf = kf;
    dla::AggregateStats stats;
    const Cluster aggregate = dla::aggregate(o, {}, nullptr, &stats);
    expect_sound(aggregate, o);
    const double rg = dla::radius_of_gyration(aggregate) / o.monomer_radius;
    EXPECT_NEAR(kf * std::pow(rg, df), 512.0, 512.0 * (df < 2.5 ? 1e-6 : 2.5e-3));
    if (df < 2.5) {  // the clusters its joins made lie on the law too
      const dla::FractalLaw fit = dla::fit_joins(stats, 32.0);
      EXPECT_NEAR(fit.dimension, df, 1e-6);
      EXPECT_NEAR(fit.prefactor, kf, 1e-5);
    }
  }
}

TEST(Aggregate, TheFractalFitRecoversAKnownLaw) {
  std::vector<std::pair<double, double>> clusters;
  for (double rg = 2.0; rg < 100.0; rg *= 1.5) clusters.emplace_back(1.3 * std::pow(rg, 1.78), rg);
  const dla::FractalLaw fit = dla::fit_fractal_law(clusters);
  EXPECT_NEAR(fit.dimension, 1.78, 1e-12);
  EXPECT_NEAR(fit.prefactor, 1.3, 1e-12);
}

TEST(Aggregate, StoppedItReturnsTheLargestClusterSoFar) {
  AggregateOptions o = options(AggregateMode::dlca, 400);
  int calls = 0;
  const Cluster part = dla::aggregate(o, [&](const Cluster&) { return ++calls < 2; });
  EXPECT_FALSE(part.complete);
  EXPECT_LT(part.particles.size(), o.monomers);
  for (std::size_t i = 1; i < part.particles.size(); ++i) EXPECT_GE(part.particles[i].parent, 0);
}

//! The message validate() throws for `o`, or "" when it takes them.
std::string refusal(const AggregateOptions& o) {
  try {
    dla::validate(o);
  } catch (const dla::InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(Aggregate, BadInputIsRefusedInOneLineNamingTheOption) {
  AggregateOptions o = options(AggregateMode::tuned, 1000);
  o.df = 3.5;
  EXPECT_EQ(refusal(o), "`df` 3.5 is not in [1, 3]");
  o.df = 1.8;
  o.kf = 0.0;
  EXPECT_EQ(refusal(o), "`kf` 0 is not in (0, 10]");
  o.kf = 10.0;
  o.df = 3.0;  // 1,000 monomers within R_g 4.6 a: denser than spheres pack
  EXPECT_NE(refusal(o).find("denser than spheres pack"), std::string::npos) << refusal(o);
  o.df = 2.5;
  o.kf = 2.5;  // possible for 1,000 monomers, not for their first clusters: refused as it grows
  try {
    dla::aggregate(o);
    ADD_FAILURE() << "df 2.5 and kf 2.5 grew";
  } catch (const dla::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("not the law's"), std::string::npos) << e.what();
  }
  o.df = 1.0;
  o.kf = 0.1;  // R_g 10,000 a: beyond a straight chain
  EXPECT_NE(refusal(o).find("beyond a straight chain"), std::string::npos) << refusal(o);
  o = options(AggregateMode::dlca, 1000);
  o.volume_fraction = 0.64;
  EXPECT_EQ(refusal(o), "`volume_fraction` 0.64 is not in [0.0001, 0.3]");
  o = options(AggregateMode::dlca, 1000);
  o.sizes = MonomerSizes::lognormal;
  o.spread = 0.5;
  EXPECT_NE(refusal(o).find("`spread` 0.5 is below 1"), std::string::npos);
  o.spread = -1.0;
  EXPECT_EQ(refusal(o), "`spread` -1 is not in [0, 2]");
  o = options(AggregateMode::dlca, 1000);
  o.df = 2.0;
  EXPECT_EQ(refusal(o), "`df` and `kf` are for `mode` tuned");
  o = options(AggregateMode::rlca, 1000);
  o.volume_fraction = 0.05;  // the reaction-limited limit has no box
  EXPECT_NE(refusal(o).find("are for the box"), std::string::npos) << refusal(o);
  o.stick_probability = 0.1;
  EXPECT_EQ(refusal(o), "");
  for (const std::string& message : {refusal(o)}) EXPECT_EQ(message.find('\n'), std::string::npos);
}

TEST(Aggregate, TheCliWritesASphereListThatReadsBack) {
  ScratchDir dir;
  const dla::testing::CliRun run =
      dla::testing::dla3d(dir, "aggregate -n 120 --mode tuned --df 1.9 --kf 1.2 --monomer-radius 15 -o soot --formats spheres,json,pov");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream in(dir / "soot_spheres.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "x,y,z,r");
  std::vector<std::array<double, 4>> spheres;
  for (std::string line; std::getline(in, line);) {
    std::array<double, 4> row{};
    std::istringstream fields(line);
    char comma = 0;
    fields >> row[0] >> comma >> row[1] >> comma >> row[2] >> comma >> row[3];
    ASSERT_FALSE(fields.fail()) << line;
    spheres.push_back(row);
  }
  ASSERT_EQ(spheres.size(), 120u);
  for (const auto& s : spheres) EXPECT_EQ(s[3], 15.0);
  // No two spheres overlap, and the list's R_g is the law's (N = kf (Rg/a)^df).
  dla::Vec3 centre = dla::Vec3::Zero();
  for (const auto& s : spheres) centre += dla::Vec3(s[0], s[1], s[2]);
  centre /= 120.0;
  double sum2 = 0.0;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const dla::Vec3 p(spheres[i][0], spheres[i][1], spheres[i][2]);
    sum2 += (p - centre).squaredNorm();
    for (std::size_t j = i + 1; j < spheres.size(); ++j)
      ASSERT_GE((p - dla::Vec3(spheres[j][0], spheres[j][1], spheres[j][2])).norm(), 30.0 * (1.0 - 1e-7));
  }
  const double rg = std::sqrt(sum2 / 120.0) / 15.0;
  EXPECT_NEAR(1.2 * std::pow(rg, 1.9), 120.0, 120.0 * 1e-6);
  const std::string record = dla::testing::read_file(dir / "soot.json");
  EXPECT_NE(record.find("\"model\": \"aggregate\""), std::string::npos);
  EXPECT_NE(record.find("\"fractal_dimension\""), std::string::npos);
  EXPECT_NE(record.find("\"mode\": \"tuned\""), std::string::npos);
  // POV-Ray draws a sphere of each monomer's own radius.
  const std::string scene = dla::testing::read_file(dir / "soot.inc");
  EXPECT_NE(scene.find("sphere {"), std::string::npos);
  EXPECT_EQ(scene.find("sphere_sweep"), std::string::npos);
}

TEST(Aggregate, TheCliRefusesInOneLine) {
  ScratchDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {"aggregate --df 0.5 --mode tuned", "--df 0.5 is not in [1, 3]"},
      {"aggregate -n 0", "--monomers 0 is not in [1, 1e+08]"},
      {"aggregate --volume-fraction 0.7", "--volume-fraction 0.7 is not in [0.0001, 0.3]"},
      {"aggregate --kf -1 --mode tuned", "--kf -1 is not in (0, 10]"},
      {"aggregate --sizes lognormal --spread 0.5", "--spread 0.5 is below 1"},
      {"aggregate --mode tuned -n 1000 --df 2.5 --kf 2.5", "not the law's"},
      {"aggregate --mode rlca --volume-fraction 0.05", "--volume-fraction and --mobility-exponent are for the box"},
      {"-n 10 --radius particle", "--radius particle draws each particle's own radius"},
  };
  for (const auto& [args, message] : cases) {
    SCOPED_TRACE(args);
    const dla::testing::CliRun run = dla::testing::dla3d(dir, args);
    EXPECT_NE(run.exit_code, 0);
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
  }
}

}  // namespace

namespace {

//! The fractal law fitted over the clusters of `runs` aggregates of `monomers` grown as `o` asks.
dla::FractalLaw ensemble_law(AggregateOptions o, int runs) {
  dla::AggregateStats pooled;
  for (int run = 0; run < runs; ++run) {
    o.rng_seed = 100 + static_cast<std::uint64_t>(run);
    dla::AggregateStats stats;
    dla::aggregate(o, {}, nullptr, &stats);
    pooled.crowded = stats.crowded;
    pooled.joins.insert(pooled.joins.end(), stats.joins.begin(), stats.joins.end());
  }
  return dla::fit_joins(pooled);
}

// The dimensions of the literature, on ensembles: in the full tier only (ctest -L full sets
// DLA_FULL_TESTS). DLCA's is 1.75-1.8 (Sorensen, Aerosol Sci. Technol. 35, 648, 2001: 1.75).
// The record's fit of log N on log R_g reads a few hundredths low, as a least-squares fit does
// when its abscissa scatters: one run of 3,000 reads 1.65 to 1.83, and four pools of twelve
// read 1.69 to 1.73, these seeds 1.69. RLCA's reaction-limited limit, where clusters join as
// often as the bonds they offer, is 2.0-2.1 in the literature (docs/aggregate.md); the same fit
// reads 2.00 to 2.06 on four pools of twelve, these seeds 2.04.
TEST(Slow, AggregatesHaveTheirDimensions) {
  if (!std::getenv("DLA_FULL_TESTS")) GTEST_SKIP() << "in the full tier: ctest -L full";
  AggregateOptions o = options(AggregateMode::dlca, 3000);
  const dla::FractalLaw dlca = ensemble_law(o, 12);
  EXPECT_NEAR(dlca.dimension, 1.74, 0.08);
  EXPECT_NEAR(dlca.prefactor, 1.5, 0.25);
  o.mode = AggregateMode::rlca;
  const dla::FractalLaw rlca = ensemble_law(o, 12);
  std::printf("12 aggregates of 3000: dlca D_f %.3f k_f %.3f, rlca D_f %.3f k_f %.3f\n", dlca.dimension,
              dlca.prefactor, rlca.dimension, rlca.prefactor);
  EXPECT_NEAR(rlca.dimension, 2.03, 0.07);
  EXPECT_NEAR(rlca.prefactor, 1.15, 0.2);
}

// Every pair of D_f from 1.5 to 2.5 and k_f from 1 to 2.5 lands on its law, but one the first
// clusters cannot pack, which is refused.
TEST(Slow, TunedAggregatesHitTheirTargetsFromOnePointFiveToTwoPointFive) {
  if (!std::getenv("DLA_FULL_TESTS")) GTEST_SKIP() << "in the full tier: ctest -L full";
  for (const double df : {1.5, 1.8, 2.1, 2.5})
    for (const double kf : {1.0, 1.5, 2.5}) {
      SCOPED_TRACE("df " + std::to_string(df) + " kf " + std::to_string(kf));
      AggregateOptions o = options(AggregateMode::tuned, 1000);
      o.df = df;
      o.kf = kf;
      if (df == 2.5 && kf == 2.5) {
        EXPECT_THROW(dla::aggregate(o), dla::InvalidInput);
        continue;
      }
      const Cluster aggregate = dla::aggregate(o);
      expect_sound(aggregate, o);
      // Joins of pieces land on the law exactly; monomers joined one at a time, within 0.1% of R_g.
      EXPECT_NEAR(kf * std::pow(dla::radius_of_gyration(aggregate) / o.monomer_radius, df), 1000.0, 1000.0 * 2.5e-3);
    }
}

}  // namespace
