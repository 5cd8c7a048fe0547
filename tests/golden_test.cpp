// Golden runs: fixed options and seeds must give exactly these CSV bytes. Anything that changes
// a model (the index's bounds, the order of random draws, the arithmetic) or the run around it
// (the defaults a mesh gives, seed placement, the look the CSV carries) changes a checksum.
// When a change is meant to, update the value in a commit of its own that says why.

#include "dla/io/csv_writer.h"
#include "dla/models/dla.h"
#include "dla/core/hash.h"
#include "cli_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>

namespace dla {
namespace {

TEST(Golden, TwoThousandParticlesFromSeedOne) {
  testing::ScratchDir dir;
  DlaOptions options;
  options.particles = 2000;
  options.rng_seed = 1;
  write_csv(grow(options), dir / "golden.csv");
  EXPECT_EQ(fnv1a(testing::read_file(dir / "golden.csv")), 0x66074fd01f8d4580ULL);
}

//! The checksum of the CSV `dla3d ARGS -q --formats csv -o golden` writes.
std::uint64_t cli_checksum(const std::string& args) {
  testing::ScratchDir dir;
  const testing::CliRun run = testing::dla3d(dir, args + " -q --formats csv -o golden");
  EXPECT_EQ(run.exit_code, 0) << run.err;
  return fnv1a(testing::read_file(dir / "golden.csv"));
}

// Every model as the command line runs it, with the run's defaults and the look's radii.
TEST(Golden, EveryModelFromTheCommandLine) {
  EXPECT_EQ(cli_checksum("-n 2000 --rng-seed 1"), 0x70a10d1072c0a8e4ULL);
  EXPECT_EQ(cli_checksum("-n 1500 --rng-seed 2 --dimensions 2 --radius pipe --seed-at=-20,0,0 --seed-at 20,0,0"), 0x397ac0d77cfdc322ULL);
  EXPECT_EQ(cli_checksum("colonize -n 1500 --attractors 2000 --rng-seed 3 --noise 0.3,5"), 0xae2142ded7b3b5e9ULL);
  EXPECT_EQ(cli_checksum("eden -n 3000 --rng-seed 4"), 0x31b97f9fadc9fe45ULL);
  EXPECT_EQ(cli_checksum("eden -n 2000 --dimensions 3 --mode drop --mask B --rng-seed 5"), 0xaeb81844c469a688ULL);
  EXPECT_EQ(cli_checksum("drop -n 2000 --rng-seed 6 --dimensions 2"), 0x2fac262677afe2c6ULL);
  EXPECT_EQ(cli_checksum("ballistic -n 2000 --rng-seed 7"), 0x11a93258db23b599ULL);
  EXPECT_EQ(cli_checksum("aggregate -n 1000 --rng-seed 12"), 0x717958eab309a3ffULL);
  EXPECT_EQ(cli_checksum("aggregate --mode tuned --sizes lognormal --spread 1.3 -n 1000 --rng-seed 13"), 0x19d19d6500548cbcULL);
  EXPECT_EQ(cli_checksum("aggregate --mode rlca -n 500 --rng-seed 14"), 0x95967e28be9d114aULL);
  EXPECT_EQ(cli_checksum("aggregate --mode rlca --stick-probability 0.1 -n 500 --rng-seed 14"), 0xae2899417872c5daULL);
}

// With a mesh: the spacing, seeds, spawn and radii a mesh gives (an open box from tests/data).
TEST(Golden, ModelsInAMeshFromTheCommandLine) {
  const std::string box = std::string(TEST_DATA_DIR) + "/open_box.off";
  EXPECT_EQ(cli_checksum("--stl '" + box + "' -n 1500 --seeds 2 --rng-seed 8"), 0x404ce8e0173a22aeULL);
  EXPECT_EQ(cli_checksum("drop --stl '" + box + "' -n 1500 --rng-seed 9"), 0x327b21b8e0eeabc6ULL);
  EXPECT_EQ(cli_checksum("colonize --stl '" + box + "' --attractors-in mesh --roots 2 --roots-in mesh -n 800 "
                         "--attractors 1500 --rng-seed 10"), 0xed871c574c227ef8ULL);
}

// The main job, smaller: two trees in the scanned bust.
TEST(Golden, TheBust) {
  if (!std::filesystem::exists(BUST_OFF_PATH)) GTEST_SKIP() << "the bust needs libcgal-demo";
  EXPECT_EQ(cli_checksum("--stl '" BUST_OFF_PATH "' --seeds 2 -n 2000 --rng-seed 11"), 0xb5ea7a2434f951ccULL);
}

}  // namespace
}  // namespace dla
