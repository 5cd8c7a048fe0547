// The attractors' index of space colonization against brute force: after every batch of new
// nodes, each attractor's node and life are what comparing it with every node in order gives,
// and every change was reported once, from the right node to the right one.

#include "dla/index/attractor_tree.h"
#include "dla/core/random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace dla {
namespace {

struct Cloud {
  std::string name;
  std::vector<Vec3> points;
};

// Clouds that stress the Morton order and its splits: uniform, graded, flat, on a line, with
// many copies of a few points, and far from the origin.
std::vector<Cloud> clouds() {
  Rng rng(7);
  std::vector<Cloud> all;
  const auto ball = [&](std::size_t count, double radius, double grading, int dimensions, const Vec3& center) {
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < count; ++i)
      points.push_back(center + radius * std::pow(rng.uniform(), grading) * random_direction(rng, dimensions));
    return points;
  };
  all.push_back({"uniform", ball(3000, 20, 1.0 / 3, 3, Vec3::Zero())});
  all.push_back({"graded", ball(3000, 20, 2.0, 3, Vec3::Zero())});
  all.push_back({"flat", ball(2000, 20, 0.5, 2, Vec3::Zero())});
  std::vector<Vec3> line;
  for (int i = 0; i < 500; ++i) line.push_back(Vec3(0.1 * i, 0, 0));
  all.push_back({"a line", line});
  std::vector<Vec3> copies;
  const std::vector<Vec3> few = ball(7, 10, 0.5, 3, Vec3::Zero());
  for (int i = 0; i < 700; ++i) copies.push_back(few[static_cast<std::size_t>(i) % few.size()]);
  all.push_back({"copies of seven points", copies});
  all.push_back({"far from the origin", ball(2000, 20, 1.0 / 3, 3, Vec3(1e7, -3e6, 5e5))});
  all.push_back({"one", {Vec3(1, 2, 3)}});
  return all;
}

TEST(AttractorTree, EveryAttractorKnowsItsClosestNodeAsBruteForceDoes) {
  for (const Cloud& cloud : clouds()) {
    for (const double reach : {8.0, std::numeric_limits<double>::infinity()}) {
      SCOPED_TRACE(cloud.name + ", reach " + std::to_string(reach));
      const double kill2 = 2.0 * 2.0, reach2 = reach * reach;
      AttractorTree tree(cloud.points, reach2, kill2);
      ASSERT_EQ(tree.size(), cloud.points.size());
      // Brute force, on the tree's own order: node, squared distance, life.
      std::vector<std::int32_t> node(tree.size(), AttractorTree::kNone);
      std::vector<double> distance2(tree.size(), reach2);
      std::vector<bool> alive(tree.size(), true);
      std::vector<std::int32_t> reported(tree.size(), AttractorTree::kNone);
      std::vector<Vec3> nodes;
      Rng rng(11);
      Vec3 center = Vec3::Zero();
      for (const Vec3& p : cloud.points) center += p / static_cast<double>(cloud.points.size());
      for (int batch = 0; batch < 40; ++batch) {
        // Batches of 1 to 40 nodes, around the cloud and now and then on an attractor.
        std::vector<Vec3> added;
        const std::size_t count = 1 + rng() % 40;
        for (std::size_t i = 0; i < count; ++i) {
          Vec3 p = center + 25.0 * rng.uniform() * random_direction(rng, 3);
          if (rng.uniform() < 0.2) p = tree.position(rng() % tree.size());
          added.push_back(p);
        }
        const auto first = static_cast<std::int32_t>(nodes.size());
        for (std::size_t i = 0; i < added.size(); ++i) {
          const auto v = static_cast<std::int32_t>(nodes.size() + i);
          for (std::size_t a = 0; a < tree.size(); ++a) {
            if (!alive[a]) continue;
            const double d2 = (tree.position(a) - added[i]).squaredNorm();
            if (d2 <= kill2) {
              alive[a] = false;
            } else if (d2 < distance2[a]) {
              node[a] = v;
              distance2[a] = d2;
            }
          }
        }
        nodes.insert(nodes.end(), added.begin(), added.end());
        tree.add_nodes(first, added, [&](std::size_t a, std::int32_t from, std::int32_t to) {
          ASSERT_EQ(from, reported[a]) << "attractor " << a << " moves from the node it was at";
          ASSERT_NE(from, AttractorTree::kDied) << "attractor " << a << " died twice";
          ASSERT_TRUE(to == AttractorTree::kDied || (to >= first && to < static_cast<std::int32_t>(nodes.size())));
          reported[a] = to;
        });
        std::size_t live = 0;
        for (std::size_t a = 0; a < tree.size(); ++a) {
          ASSERT_EQ(tree.alive(a), alive[a]) << "attractor " << a << ", batch " << batch;
          live += alive[a];
          if (!alive[a]) continue;
          ASSERT_EQ(tree.closest(a), node[a]) << "attractor " << a << ", batch " << batch;
          ASSERT_EQ(reported[a], node[a]) << "attractor " << a << ", batch " << batch;
        }
        ASSERT_EQ(tree.live(), live);
      }
    }
  }
}

TEST(AttractorTree, KeepsEveryPointOnceAndKillsOnTheKillDistance) {
  std::vector<Vec3> points;
  for (int i = 0; i < 100; ++i) points.push_back(Vec3(i, 0.5 * i, -i));
  const AttractorTree tree(points, 100.0, 4.0);
  std::vector<Vec3> kept;
  for (std::size_t a = 0; a < tree.size(); ++a) kept.push_back(tree.position(a));
  const auto by_x = [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); };
  std::sort(kept.begin(), kept.end(), by_x);
  EXPECT_EQ(kept, points) << "the same points, in another order";

  // A reach equal to the kill distance: an attractor exactly on it dies, it is not pulled.
  AttractorTree edge({Vec3(2, 0, 0), Vec3(2.5, 0, 0)}, 4.0, 4.0);
  std::vector<std::int32_t> to(2, AttractorTree::kNone);
  edge.add_nodes(0, {Vec3::Zero()}, [&](std::size_t a, std::int32_t, std::int32_t node) { to[a] = node; });
  EXPECT_EQ(edge.live(), 1u);
  for (std::size_t a = 0; a < 2; ++a)
    EXPECT_EQ(to[a], edge.position(a).x() == 2.0 ? AttractorTree::kDied : AttractorTree::kNone);

  AttractorTree empty({}, 100.0, 4.0);
  empty.add_nodes(0, {Vec3::Zero()}, [](std::size_t, std::int32_t, std::int32_t) { FAIL() << "nothing to move"; });
  EXPECT_EQ(empty.live(), 0u);
}

}  // namespace
}  // namespace dla
