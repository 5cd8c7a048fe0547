// Strands cover every branch exactly once and run from a start to a tip.

#include "dla/models/dla.h"
#include "dla/look/strands.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>

namespace dla {
namespace {

TEST(Strands, CoverEveryBranchOnceFromStartToTip) {
  DlaOptions o;
  o.particles = 3000;
  o.seeds = {Vec3(-20, 0, 0), Vec3(20, 0, 0)};
  const Cluster c = grow(o);
  const std::vector<Strand> strands = decompose_strands(c);
  std::vector<int> children(c.particles.size(), 0);
  for (const Particle& p : c.particles)
    if (p.parent >= 0) ++children[static_cast<std::size_t>(p.parent)];

  std::set<std::pair<int, int>> edges;
  std::size_t tips = 0;
  for (const Strand& s : strands) {
    ASSERT_GE(s.size(), 2u);
    for (std::size_t i = 1; i < s.size(); ++i) {
      ASSERT_EQ(c.particles[static_cast<std::size_t>(s[i])].parent, s[i - 1]) << "not a chain";
      ASSERT_TRUE(edges.insert({s[i - 1], s[i]}).second) << "a branch in two strands";
      if (i + 1 < s.size()) {
        ASSERT_GE(children[static_cast<std::size_t>(s[i])], 1);
      }
    }
    ASSERT_EQ(children[static_cast<std::size_t>(s.back())], 0) << "a strand ends at a tip";
    ++tips;
  }
  EXPECT_EQ(edges.size(), c.particles.size() - c.seed_count) << "every branch is drawn";
  std::size_t leaves = 0;
  for (int n : children) leaves += n == 0;
  EXPECT_EQ(tips, leaves) << "one strand per tip";
  EXPECT_EQ(count_strands(c), strands.size());
}

// What the POV-Ray writer relies on to format ranges on several threads.
TEST(Strands, RangesOfTipsGiveTheWholeSequenceInOrder) {
  DlaOptions o;
  o.particles = 2000;
  const Cluster c = grow(o);
  const std::vector<bool> tips = tip_flags(c);
  const std::vector<bool> continues = continuing_children(c, subtree_sizes(c));
  const auto is_tip = [&](std::size_t i) { return static_cast<bool>(tips[i]); };
  const auto goes_on = [&](std::size_t i) { return static_cast<bool>(continues[i]); };
  const std::size_t n = c.particles.size();
  for (const std::size_t parts : {1u, 3u, 7u}) {
    std::vector<Strand> joined;
    for (std::size_t part = 0; part < parts; ++part)
      for_each_strand_in(c, n * part / parts, n * (part + 1) / parts, is_tip, goes_on,
                         [&](const Strand& s) { joined.push_back(s); });
    EXPECT_EQ(joined, decompose_strands(c)) << parts << " parts";
  }
}

TEST(Strands, LoneSeedIsAStrandOfOne) {
  Cluster c;
  c.particles = {{Vec3::Zero(), -1, 0}};
  c.seed_count = 1;
  const std::vector<Strand> strands = decompose_strands(c);
  ASSERT_EQ(strands.size(), 1u);
  EXPECT_EQ(strands[0], Strand{0});
  EXPECT_EQ(count_strands(c), 1u);
}

}  // namespace
}  // namespace dla
