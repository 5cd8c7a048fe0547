#pragma once
// Space colonization as the Hyphae write-up states it: every iteration, every live attractor
// scans every node for its closest. The oracle the kept closest nodes of colonize() are tested
// against, node for node (tests/colonization_test.cpp), and the baseline they are measured
// against (bench/colonization_bench.cpp).

#include "dla/models/colonization.h"

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace dla::testing {

inline Cluster colonize_by_rescan(const ColonizationOptions& o, const std::vector<Vec3>& attractors,
                                  const std::vector<Vec3>& roots) {
  validate(o);
  Cluster tree = detail::seeded(roots, o.spacing, o.dimensions);
  const double kill2 = detail::kill_distance2(o), reach2 = detail::reach2(o);
  std::vector<bool> alive(attractors.size(), true);
  const auto kill_near = [&](std::size_t first_node) {
    for (std::size_t a = 0; a < attractors.size(); ++a)
      for (std::size_t v = first_node; v < tree.particles.size() && alive[a]; ++v)
        if ((attractors[a] - tree.particles[v].position).squaredNorm() <= kill2) alive[a] = false;
  };
  kill_near(0);
  const detail::LatticeNoise noise(o.rng_seed);
  std::vector<std::int32_t> last_child(roots.size(), -1);
  for (std::size_t iteration = 0; iteration < o.max_iterations && tree.particles.size() < o.max_nodes; ++iteration) {
    std::vector<std::array<std::int64_t, 3>> sums(tree.particles.size(), {0, 0, 0});
    std::vector<int> pulls(tree.particles.size(), 0);
    bool any = false;
    for (std::size_t a = 0; a < attractors.size(); ++a) {
      if (!alive[a]) continue;
      any = true;
      double best = reach2;
      std::int32_t closest = -1;
      for (std::size_t v = 0; v < tree.particles.size(); ++v) {
        const double d2 = (attractors[a] - tree.particles[v].position).squaredNorm();
        if (d2 < best) best = d2, closest = static_cast<std::int32_t>(v);
      }
      if (closest < 0) continue;
      const auto d = detail::fixed_direction(tree.particles[static_cast<std::size_t>(closest)].position, attractors[a]);
      for (std::size_t axis = 0; axis < 3; ++axis) sums[static_cast<std::size_t>(closest)][axis] += d[axis];
      ++pulls[static_cast<std::size_t>(closest)];
    }
    if (!any) break;
    const std::size_t first_new = tree.particles.size();
    for (std::size_t v = 0; v < first_new && tree.particles.size() < o.max_nodes; ++v) {
      Vec3 next;
      if (pulls[v] == 0 || !colonization_step(o, noise, tree.particles[v].position, sums[v], &next)) continue;
      if (last_child[v] >= 0 && tree.particles[static_cast<std::size_t>(last_child[v])].position == next) continue;
      last_child[v] = static_cast<std::int32_t>(tree.particles.size());
      tree.particles.push_back({next, static_cast<std::int32_t>(v), tree.particles[v].seed});
      last_child.push_back(-1);
    }
    if (tree.particles.size() == first_new) break;
    kill_near(first_new);
  }
  return tree;
}

}  // namespace dla::testing
