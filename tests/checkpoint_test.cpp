// Checkpoints read back exactly what was written, refuse damaged files, and a run resumed from
// one ends as the uninterrupted run does, with a constraint mesh too.

#include "dla/io/checkpoint.h"
#include "dla/models/dla.h"
#include "dla/mesh/shapes.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <fstream>

namespace dla {
namespace {

using testing::ScratchDir;

TEST(Checkpoint, ReadsBackWhatWasWritten) {
  ScratchDir dir;
  DlaOptions o;
  o.particles = 700;
  DlaStats stats;
  const Cluster grown = grow(o, {}, nullptr, &stats);
  Checkpoint saved{{"-n", "700", "--seed-at", "1,2,3", "a word with spaces"}, 0x1234, grown, stats.walk};
  write_checkpoint(saved, dir / "run.ck");
  const Checkpoint back = read_checkpoint(dir / "run.ck");
  EXPECT_EQ(back.command, saved.command);
  EXPECT_EQ(back.input_hash, saved.input_hash);
  ASSERT_EQ(back.cluster.particles.size(), saved.cluster.particles.size());
  for (std::size_t i = 0; i < saved.cluster.particles.size(); ++i) {
    EXPECT_EQ(back.cluster.particles[i].position, saved.cluster.particles[i].position);
    EXPECT_EQ(back.cluster.particles[i].parent, saved.cluster.particles[i].parent);
  }
  EXPECT_GT(saved.walk.steps, 0u);
  EXPECT_EQ(back.walk.steps, saved.walk.steps);
  EXPECT_EQ(back.walk.clipped, saved.walk.clipped);
  EXPECT_EQ(back.cluster.seed_count, 1u);
  EXPECT_FALSE(back.cluster.complete);
}

TEST(Checkpoint, DamagedOrForeignFilesAreClearErrors) {
  ScratchDir dir;
  DlaOptions o;
  o.particles = 300;
  write_checkpoint({{"-n", "300"}, 0, grow(o), {}}, dir / "run.ck");
  const std::string bytes = testing::read_file(dir / "run.ck");
  const auto expect_refused = [&](const std::string& content, const char* says) {
    std::ofstream(dir / "bad.ck", std::ios::binary) << content;
    try {
      read_checkpoint(dir / "bad.ck");
      ADD_FAILURE() << "accepted: " << says;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  expect_refused(bytes.substr(0, bytes.size() / 2), "cut short or damaged");
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 1;
  expect_refused(flipped, "cut short or damaged");
  expect_refused("solid not a checkpoint", "is not a dla3d checkpoint");
  expect_refused("", "is not a dla3d checkpoint");
  EXPECT_THROW(read_checkpoint(dir / "missing.ck"), IOError);
}

TEST(Checkpoint, ResumedConstrainedGrowthIsTheUninterruptedOne) {
  const MeshConstraint tube(make_open_can(Vec3::Zero(), 4.0, 30.0, 24), {}, 1.0);
  DlaOptions o;
  o.particles = 900;
  o.spawn = SpawnMode::inside;
  o.seeds = tube.place_seeds(2, o.rng_seed);
  DlaStats whole_stats, stats;
  const Cluster whole = grow(o, tube, {}, nullptr, &whole_stats);
  DlaOptions shorter = o;
  shorter.particles = 512;
  const Cluster part = grow(shorter, tube, {}, nullptr, &stats);
  const Cluster resumed = resume(o, tube, part, {}, nullptr, &stats);
  ASSERT_EQ(resumed.particles.size(), whole.particles.size());
  for (std::size_t i = 0; i < whole.particles.size(); ++i)
    ASSERT_EQ(resumed.particles[i].position, whole.particles[i].position) << i;
  EXPECT_GT(whole_stats.walk.rejected, 0u);
  EXPECT_EQ(stats.walk.rejected, whole_stats.walk.rejected);
}

}  // namespace
}  // namespace dla
