// Every index against brute force: probes never overshoot the nearest distance and are exact
// when they name a particle; radius visits find exactly the particles within the radius.

#include "dla/core/huge_pages.h"
#include "dla/index/grid_index.h"
#include "dla/index/kdtree_index.h"
#include "dla/core/random.h"
#include "dla/index/spatial_index.h"
#include "index/gap_rows.h"  // libdla/: the gap update's row test

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

namespace dla {
namespace {

// Points in clumps plus a spread, like a growing structure, inserted as they come; spread
// grows so the grid has to enlarge its domain on the way.
std::vector<Particle> points(int dimensions, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Particle> ps;
  for (std::size_t i = 0; i < count; ++i) {
    const double scale = 2.0 + 0.2 * static_cast<double>(i);
    Vec3 p = scale * random_direction(rng, dimensions) * rng.uniform();
    if (i > 0 && rng.uniform() < 0.5)
      p = ps[static_cast<std::size_t>(rng() % i)].position + 1.0 * random_direction(rng, dimensions);
    ps.push_back({p, -1, 0});
  }
  return ps;
}

template <class Index>
void check_against_brute_force(int dimensions) {
  std::vector<Particle> store;
  Index index(store, 1.0, dimensions);
  BruteForceIndex brute(store, 1.0, dimensions);
  const std::vector<Particle> all = points(dimensions, 3000, 7);
  Rng rng(11);
  for (std::size_t i = 0; i < all.size(); ++i) {
    store.push_back(all[i]);
    index.insert(static_cast<std::int32_t>(i));
    brute.insert(static_cast<std::int32_t>(i));
    if (i % 100 != 99) continue;
    double reach = 0.0;
    for (const Particle& p : store) reach = std::max(reach, p.position.norm());
    index.cover(Vec3::Zero(), reach + 2.0);
    for (int q = 0; q < 200; ++q) {
      Vec3 x = (reach + 2.0) * random_direction(rng, dimensions) * std::cbrt(rng.uniform());
      if (q % 2) x = store[rng() % store.size()].position + 3.0 * rng.uniform() * random_direction(rng, dimensions);
      const Probe expected = brute.probe(x);
      const Probe got = index.probe(x);
      ASSERT_LE(got.distance, expected.distance * (1 + 1e-12)) << "bound above the true distance";
      if (got.nearest >= 0) {
        EXPECT_NEAR(got.distance, expected.distance, 1e-12);
        EXPECT_NEAR((store[static_cast<std::size_t>(got.nearest)].position - x).norm(),
                    expected.distance, 1e-12);
      }
      // Within two spacings the exact nearest must come back (the walk relies on it).
      if (expected.distance < 2.0) {
        EXPECT_EQ(got.nearest, expected.nearest);
      }
      // Skipping the reach (one thread) leaves the answer as it is.
      const Probe unreached = index.probe(x, Reach::skip);
      ASSERT_EQ(unreached.nearest, got.nearest);
      ASSERT_EQ(unreached.distance, got.distance);
      const double radius = 0.5 + 2.5 * rng.uniform();
      std::set<std::int32_t> want, have;
      brute.for_each_within(x, radius, [&](std::int32_t id, double) { want.insert(id); });
      index.for_each_within(x, radius, [&](std::int32_t id, double d2) {
        EXPECT_NEAR(d2, (store[static_cast<std::size_t>(id)].position - x).squaredNorm(), 1e-9);
        have.insert(id);
      });
      ASSERT_EQ(want, have) << "radius " << radius;
    }
  }
}

}  // namespace
}  // namespace dla

TEST(GridIndex, MatchesBruteForce3D) { dla::check_against_brute_force<dla::GridIndex>(3); }
TEST(GridIndex, MatchesBruteForce2D) { dla::check_against_brute_force<dla::GridIndex>(2); }
TEST(KdTreeIndex, MatchesBruteForce3D) { dla::check_against_brute_force<dla::KdTreeIndex>(3); }
TEST(KdTreeIndex, MatchesBruteForce2D) { dla::check_against_brute_force<dla::KdTreeIndex>(2); }

// A plane cluster of 10^8 particles reaches about 40,000 spacings from its seed: the grid holds
// clumps 60,000 spacings either side of the centre, and answers there as brute force does.
TEST(GridIndex, HoldsAPlaneStructureOfTenToTheEightsReach) {
  std::vector<dla::Particle> store;
  dla::GridIndex index(store, 1.0, 2);
  dla::BruteForceIndex brute(store, 1.0, 2);
  dla::Rng rng(3);
  const std::array<dla::Vec3, 3> clumps{dla::Vec3(60000, 0, 0), dla::Vec3(-60000, 1000, 0), dla::Vec3(0, -59000, 0)};
  // As DLA does: the domain about the seeds' centre, then the particles, which grow it.
  index.cover(dla::Vec3::Zero(), 100.0);
  for (int i = 0; i < 300; ++i) {
    store.push_back({clumps[i % 3] + 6.0 * rng.uniform() * dla::random_direction(rng, 2), -1, 0});
    ASSERT_NO_THROW(index.insert(i)) << "particle " << i;
    brute.insert(i);
  }
  for (int q = 0; q < 600; ++q) {
    const dla::Vec3 x = clumps[q % 3] + 12.0 * rng.uniform() * dla::random_direction(rng, 2);
    const dla::Probe expected = brute.probe(x), got = index.probe(x);
    ASSERT_LE(got.distance, expected.distance * (1 + 1e-12));
    if (expected.distance < 2.0) {
      ASSERT_EQ(got.nearest, expected.nearest);
    }
    if (got.nearest >= 0) {
      ASSERT_NEAR(got.distance, expected.distance, 1e-9);
    }
  }
}

// The gap update tests a block's row of 8 cells in floats first (detail::may_lower_gaps): every
// cell the exact test in double lowers must be flagged, at random and a rounding below the gap,
// and a cell clearly beyond its gap must not be.
TEST(GridIndex, GapUpdateFlagsEveryCellTheExactTestLowers) {
  dla::Rng rng(5);
  constexpr double reach2 = 128.0 * 128.0;  // the gap map's reach, in gap units squared
  int lowered = 0, edges = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    std::array<std::uint8_t, 8> row;
    std::array<double, 8> along;
    std::array<float, 8> along_floats;
    const double yz2 = trial % 4 == 0 ? 0.0 : reach2 * rng.uniform() * rng.uniform();
    for (int i = 0; i < 8; ++i) {
      row[i] = static_cast<std::uint8_t>(rng() % 129);
      const double gap2 = static_cast<double>(row[i]) * row[i];
      along[i] = reach2 * rng.uniform();
      if (rng() % 2 && gap2 > yz2) {  // within a few roundings of the gap, either side
        along[i] = gap2 - yz2;
        for (int k = static_cast<int>(rng() % 7) - 3; k != 0; k += k > 0 ? -1 : 1)
          along[i] = std::nextafter(along[i], k > 0 ? reach2 : 0.0);
        ++edges;
      }
      along_floats[i] = static_cast<float>(along[i]);
    }
    const unsigned bits = dla::detail::may_lower_gaps(row.data(), static_cast<float>(yz2), along_floats.data());
    for (int i = 0; i < 8; ++i) {
      const double d2 = yz2 + along[i], gap2 = static_cast<double>(row[i]) * row[i];
      const bool flagged = (bits >> i) & 1u;
      if (d2 < gap2) {
        ASSERT_TRUE(flagged) << "gap " << int{row[i]} << ", distance² " << d2;
        ++lowered;
      }
      if (d2 > gap2 * 1.00001) {
        ASSERT_FALSE(flagged) << "gap " << int{row[i]} << ", distance² " << d2;
      }
    }
  }
  EXPECT_GT(lowered, 10000);
  EXPECT_GT(edges, 10000);
}

// The grid's large arrays: from 2 MiB on, a mapping of their own on a 2 MiB boundary, counted
// while held; below that, the heap. Growing through both keeps every value.
TEST(HugePageAllocator, LargeArraysStartOnAHugePageAndKeepTheirValues) {
  const std::size_t before = dla::huge_page_bytes();
  {
    dla::HugePageVector<std::uint32_t> values;
    for (std::uint32_t i = 0; i < 3'000'000; ++i) {
      values.push_back(i * 2654435761u);
      if (values.size() != values.capacity()) continue;  // full: the next push reallocates
      const std::size_t bytes = values.capacity() * sizeof(std::uint32_t);
      if (bytes >= dla::kHugePageBytes) {
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(values.data()) % dla::kHugePageBytes, 0u) << bytes << " bytes";
        EXPECT_EQ(dla::huge_page_bytes(), before + bytes);  // capacities double: whole pages
      } else {
        EXPECT_EQ(dla::huge_page_bytes(), before) << bytes << " bytes";
      }
    }
    for (std::uint32_t i = 0; i < values.size(); ++i) ASSERT_EQ(values[i], i * 2654435761u) << i;
    const dla::HugePageVector<std::uint32_t> copy = values;
    EXPECT_EQ(copy, values);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(copy.data()) % dla::kHugePageBytes, 0u);
  }
  EXPECT_EQ(dla::huge_page_bytes(), before) << "every mapping given back";
}

TEST(GridIndex, EmptyIndexKnowsNothing) {
  std::vector<dla::Particle> store;
  dla::GridIndex grid(store, 1.0, 3);
  EXPECT_EQ(grid.probe(dla::Vec3(1, 2, 3)).nearest, -1);
  grid.cover(dla::Vec3::Zero(), 10.0);
  const dla::Probe probe = grid.probe(dla::Vec3(1, 2, 3));
  EXPECT_EQ(probe.nearest, -1);
  EXPECT_GT(probe.distance, 1.0);
}

TEST(GridIndex, FarQueriesGetLargeBounds) {
  // A bound that stays tiny far away would make every walk crawl. The coarsest clear level's
  // cell size S bounds the distance, and the next level is not clear, so the particle is
  // within 4 sqrt(3) S < 8 S: the bound is at least an eighth of the true distance.
  std::vector<dla::Particle> store{{dla::Vec3::Zero(), -1, 0}};
  dla::GridIndex grid(store, 1.0, 3);
  grid.insert(0);
  grid.cover(dla::Vec3::Zero(), 200.0);
  for (double r : {30.0, 77.0, 150.0, 190.0}) {
    EXPECT_GE(grid.probe(dla::Vec3(r, 0, 0)).distance, r / 8) << r;
    EXPECT_GE(grid.probe(dla::Vec3(0.6 * r, -0.8 * r, 0)).distance, r / 8) << r;
  }
}

namespace {

// Probes at a uniform distance r in [from, from + span) from a lone particle, in 3D and 2D,
// with the domain covering `covers` in turn (the larger makes it double): every bound at most
// r and at least least(r), and on average at least `mean` of r.
template <class Least>
void expect_tight_bounds(double from, double span, std::initializer_list<double> covers, Least least,
                         double mean, std::initializer_list<int> dimensions_list = {3, 2}) {
  for (int dimensions : dimensions_list) {
    std::vector<dla::Particle> store{{dla::Vec3::Zero(), -1, 0}};
    dla::GridIndex grid(store, 1.0, dimensions);
    grid.insert(0);
    for (double cover : covers) {
      grid.cover(dla::Vec3::Zero(), cover);
      dla::Rng rng(3);
      double ratio_sum = 0.0;
      constexpr int probes = 400;
      for (int i = 0; i < probes; ++i) {
        const double r = from + span * rng.uniform();
        const double bound = grid.probe(r * dla::random_direction(rng, dimensions)).distance;
        ASSERT_LE(bound, r * (1 + 1e-12)) << dimensions << "D, r " << r;
        ASSERT_GE(bound, least(r)) << dimensions << "D, r " << r;
        ratio_sum += bound / r;
      }
      EXPECT_GE(ratio_sum / probes, mean) << dimensions << "D, cover " << cover;
    }
  }
}

}  // namespace

TEST(GridIndex, MidRangeBoundsAreTight) {
  // Between half a cell and the gap map's reach (2 to 16 spacings with cells of 4), the bound is
  // at least the distance less the diagonal of a cell (4 sqrt(3) spacings) and one gap unit
  // (1/8 spacing); on average within a fifth of it (the pyramid alone gave about half). That
  // is what keeps walks short. It must survive the domain doubling, which moves blocks of gaps
  // instead of recomputing them.
  expect_tight_bounds(2.5, 11.0, {10.0, 600.0}, [](double r) { return r - 4.0 * std::sqrt(3.0) - 0.125; }, 0.78);
}

TEST(GridIndex, FarBoundsAreTight) {
  // Beyond the gap map's reach (16 spacings) the node map bounds the distance within the
  // diagonal of a cell and the corners' offsets: on average within a seventh of it at 18-58
  // spacings (the pyramid alone gave about half). It must survive the domain doubling, which
  // makes the node map again.
  expect_tight_bounds(18.0, 40.0, {70.0, 600.0}, [](double r) { return r / 2; }, 0.8);
}

TEST(GridIndex, BeyondTheNodeMapTheFarMapBounds) {
  // Beyond the node map's reach (64 spacings) only the pyramid bounded the distance, at about
  // half of it (docs/spatial-index.md). The far map counts whole blocks (32
  // spacings) to the nearest block holding a particle, up to 8: where it is below that cap its
  // bound is within two block diagonals of the distance, and it must survive the domain
  // doubling, which makes the map again.
  expect_tight_bounds(100.0, 150.0, {300.0, 1200.0},
                      [](double r) { return std::max(r / 8, r - 64.0 * std::sqrt(3.0)); }, 0.7);
}

TEST(GridIndex, InThePlaneTheNodeMapReachesTwiceAsFar) {
  // A node costs a square in the plane, not a cube: occupied cells lower the nodes within 31
  // cells (124 spacings), not 16. At 70-120 spacings the node map, not the far map's whole
  // blocks, bounds the distance: within a cell's diagonal, a node cell's and a node unit.
  expect_tight_bounds(70.0, 50.0, {130.0, 600.0}, [](double r) { return r - 20.0 * std::sqrt(2.0) - 0.5; },
                      0.9, {2});
}

TEST(GridIndex, BeyondTheFarMapsCapThePyramidBounds) {
  // Beyond the node map the far map answers alone where it is between 0 and its cap; the
  // pyramid is read only where it says 0 or is at its cap (8 blocks, 256 spacings). At the cap
  // the far map says only that much, and the pyramid must still give its half or so of the
  // distance: the far map alone gives about a third at 500-1000.
  expect_tight_bounds(500.0, 500.0, {1200.0}, [](double r) { return r / 8; }, 0.5);
}

namespace {

// Whether inserting a particle at p, which opened a cell or not, may change what a probe
// answered before: only inside its reach box, or inside its opening box if a cell opened.
bool may_change(const dla::Probe& before, const dla::Vec3& p, bool opened) {
  return dla::in_box(p, before.reach_min, before.reach_max) ||
         (opened && dla::in_box(p, before.opening_min, before.opening_max));
}

bool same_answer(const dla::Probe& a, const dla::Probe& b) {
  return a.nearest == b.nearest && a.distance == b.distance;
}

}  // namespace

TEST(GridIndex, FarProbesChangeOnlyThroughTheirBoxes) {
  // Far from a lone particle the answer comes from the far map or the pyramid, each with an
  // opening box of its own, which the test below seldom probes. Each trial puts one particle
  // just outside the probe's boxes, where it must change nothing, or within 300 spacings,
  // where it mostly does. (A pyramid box one ring too small fails here, not there.)
  for (int dimensions : {3, 2}) {
    dla::Rng rng(29);
    int outside = 0, changed = 0;
    for (int trial = 0; trial < 40; ++trial) {
      std::vector<dla::Particle> store{{dla::Vec3::Zero(), -1, 0}};
      dla::GridIndex grid(store, 1.0, dimensions);
      grid.insert(0);
      grid.cover(dla::Vec3::Zero(), 1000.0);
      const dla::Vec3 x = (350.0 + 250.0 * rng.uniform()) * dla::random_direction(rng, dimensions);
      const dla::Probe before = grid.probe(x);
      dla::Vec3 p = x + (150.0 + 150.0 * rng.uniform()) * dla::random_direction(rng, dimensions);
      if (trial % 2 == 0) {  // beyond a face of the boxes, level with x
        const int axis = static_cast<int>(rng() % static_cast<std::uint64_t>(dimensions));
        const double beyond = 1.0 + 40.0 * rng.uniform();
        p = x;
        p[axis] = rng() % 2 ? std::max(before.reach_max[axis], before.opening_max[axis]) + beyond
                            : std::min(before.reach_min[axis], before.opening_min[axis]) - beyond;
      }
      store.push_back({p, 0, 0});
      const bool opened = grid.insert(1);
      const dla::Probe after = grid.probe(x);
      const bool same = same_answer(after, before);
      if (!may_change(before, p, opened)) {
        ++outside;
        ASSERT_TRUE(same) << dimensions << "D, trial " << trial << ": " << before.distance << " became "
                          << after.distance;
      }
      changed += !same;
    }
    EXPECT_GE(outside, 20) << dimensions << "D";
    EXPECT_GT(changed, 10) << dimensions << "D: the particles hardly changed a probe";
  }
}

TEST(GridIndex, AParticleOutsideAProbesReachChangesNothing) {
  // What lets walkers run ahead on other threads (dla.h): a probe's answer stays the same
  // when a particle is inserted outside its reach box, and outside its opening box unless it
  // opens a cell; a particle inside them may change it.
  for (int dimensions : {3, 2}) {
    std::vector<dla::Particle> store;
    const std::vector<dla::Particle> all = dla::points(dimensions, 2500, 5);
    dla::GridIndex grid(store, 1.0, dimensions);
    grid.reserve(all.size());
    dla::Rng rng(17);
    std::size_t outside = 0, changed = 0, opening_only = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
      const double reach = 30.0 + 0.2 * static_cast<double>(i);
      grid.cover(dla::Vec3::Zero(), reach);
      // Probes near particle i, near others and anywhere, before it goes in; the same after.
      std::vector<dla::Vec3> xs;
      std::vector<dla::Probe> before;
      for (int q = 0; q < 9; ++q) {
        dla::Vec3 x = reach * dla::random_direction(rng, dimensions) * rng.uniform();
        if (q % 2 && i > 0) x = store[rng() % i].position + 4.0 * rng.uniform() * dla::random_direction(rng, dimensions);
        if (q % 3 == 0) x = all[i].position + 12.0 * rng.uniform() * dla::random_direction(rng, dimensions);
        xs.push_back(x);
        before.push_back(grid.probe(x));
      }
      if (!grid.holds(all[i].position, 0.0)) {  // a new layout: every walker runs again anyway
        store.push_back(all[i]);
        grid.insert(static_cast<std::int32_t>(i));
        continue;
      }
      store.push_back(all[i]);
      const bool opened = grid.insert(static_cast<std::int32_t>(i));
      const dla::Vec3& p = all[i].position;
      for (std::size_t q = 0; q < xs.size(); ++q) {
        const dla::Probe after = grid.probe(xs[q]);
        const bool in_reach = may_change(before[q], p, opened);
        const bool same = same_answer(after, before[q]);
        if (!in_reach && dla::in_box(p, before[q].opening_min, before[q].opening_max)) ++opening_only;
        if (!in_reach) {
          ++outside;
          ASSERT_TRUE(same) << dimensions << "D, particle " << i << " outside the reach changed a probe";
        } else if (!same) {
          ++changed;
        }
      }
    }
    EXPECT_GT(outside, 1000u) << "reaches so wide that no particle falls outside them prove nothing";
    EXPECT_GT(changed, 500u) << "insertions hardly changed a probe: a wrong reach would go unseen";
    EXPECT_GT(opening_only, 20u) << dimensions << "D: no particle fell in an opening box without opening a cell";
  }
}
