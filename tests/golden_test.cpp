// A golden run: 2,000 particles from seed 1 must give exactly these CSV bytes. Anything that
// changes the walk (the index's bounds, the order of random draws, the arithmetic) changes the
// checksum. When a change is meant to, update the value in a commit of its own that says why.

#include "dla/io/csv_writer.h"
#include "dla/models/growth.h"
#include "dla/core/hash.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace dla {
namespace {

TEST(Golden, TwoThousandParticlesFromSeedOne) {
  testing::ScratchDir dir;
  GrowthOptions options;
  options.particles = 2000;
  options.rng_seed = 1;
  write_csv(grow(options), dir / "golden.csv");
  EXPECT_EQ(fnv1a(testing::read_file(dir / "golden.csv")), 0x66074fd01f8d4580ULL);
}

}  // namespace
}  // namespace dla
