#pragma once
// Space colonization as the Hyphae write-up states it: every iteration, every live attractor
// scans every node for its closest. The oracle the kept closest nodes of colonize() are tested
// against, node for node (tests/colonization_test.cpp), and the baseline they are measured
// against (bench/colonization_bench.cpp). And closed venation as Runions et al. state it: every
// iteration, every live source finds its relative neighbourhood among all nodes.

#include "dla/models/colonization.h"
#include "models/colonization_step.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <set>
#include <utility>
#include <vector>

namespace dla::testing {

//! Tree steps between particles a and b, by their ancestor chains; the largest int when they
//! are in different seeds' trees.
inline int tree_steps(const Cluster& c, std::int32_t a, std::int32_t b) {
  std::vector<std::int32_t> up;
  for (std::int32_t v = a; v >= 0; v = c.particles[static_cast<std::size_t>(v)].parent) up.push_back(v);
  int m = 0;
  for (std::int32_t v = b; v >= 0; v = c.particles[static_cast<std::size_t>(v)].parent, ++m) {
    const auto at = std::find(up.begin(), up.end(), v);
    if (at != up.end()) return static_cast<int>(at - up.begin()) + m;
  }
  return std::numeric_limits<int>::max();
}

//! What pulls each node in one iteration: the fixed-point sum of unit directions, and how many.
struct Pulls {
  explicit Pulls(std::size_t nodes) : sums(nodes, {0, 0, 0}), count(nodes, 0) {}
  void add(const Cluster& tree, std::int32_t v, const Vec3& attractor) {
    const auto d = detail::fixed_direction(tree.particles[static_cast<std::size_t>(v)].position, attractor);
    for (std::size_t axis = 0; axis < 3; ++axis) sums[static_cast<std::size_t>(v)][axis] += d[axis];
    ++count[static_cast<std::size_t>(v)];
  }
  std::vector<std::array<std::int64_t, 3>> sums;
  std::vector<int> count;
};

//! One step of growth: each pulled node grows a child, in node order, unless it would grow the
//! child it grew last; returns whether any grew.
inline bool grow_pulled(const ColonizationOptions& o, const detail::LatticeNoise& noise, const Pulls& pulls,
                        Cluster& tree, std::vector<std::int32_t>& last_child) {
  const std::size_t first_new = tree.particles.size();
  for (std::size_t v = 0; v < first_new && tree.particles.size() < o.max_nodes; ++v) {
    Vec3 next;
    if (pulls.count[v] == 0 || !colonization_step(o, noise, tree.particles[v].position, pulls.sums[v], &next)) continue;
    if (last_child[v] >= 0 && tree.particles[static_cast<std::size_t>(last_child[v])].position == next) continue;
    last_child[v] = static_cast<std::int32_t>(tree.particles.size());
    tree.particles.push_back({next, static_cast<std::int32_t>(v), tree.particles[v].seed});
    last_child.push_back(-1);
  }
  return tree.particles.size() > first_new;
}

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
    Pulls pulls(tree.particles.size());
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
      if (closest >= 0) pulls.add(tree, closest, attractors[a]);
    }
    if (!any) break;
    const std::size_t first_new = tree.particles.size();
    if (!grow_pulled(o, noise, pulls, tree, last_child)) break;
    kill_near(first_new);
  }
  return tree;
}

//! Closed venation by brute force: after every growth step, each live source scans every node
//! for its relative neighbourhood (within the influence: no node nearer both), is removed when
//! all of it lies within the kill distance, and links the nodes that reached it to the nearest.
inline Cluster colonize_closed_by_rescan(const ColonizationOptions& o, const std::vector<Vec3>& sources,
                                         const std::vector<Vec3>& roots) {
  validate(o);
  Cluster tree = detail::seeded(roots, o.spacing, o.dimensions);
  const double kill2 = detail::kill_distance2(o), reach2 = detail::reach2(o);
  std::vector<bool> alive(sources.size(), true);
  std::vector<std::vector<std::pair<double, std::int32_t>>> pulled(sources.size());
  std::set<std::pair<std::int32_t, std::int32_t>> linked;
  const auto update = [&] {
    for (std::size_t s = 0; s < sources.size(); ++s) {
      if (!alive[s]) continue;
      std::vector<std::pair<double, std::int32_t>> neighbourhood;
      for (std::size_t v = 0; v < tree.particles.size(); ++v) {
        const double d2 = (tree.particles[v].position - sources[s]).squaredNorm();
        if (d2 > reach2) continue;
        bool blocked = false;
        for (std::size_t u = 0; u < tree.particles.size() && !blocked; ++u)
          blocked = (tree.particles[u].position - sources[s]).squaredNorm() < d2 &&
                    (tree.particles[u].position - tree.particles[v].position).squaredNorm() < d2;
        if (!blocked) neighbourhood.emplace_back(d2, static_cast<std::int32_t>(v));
      }
      std::sort(neighbourhood.begin(), neighbourhood.end());
      pulled[s].clear();
      for (const auto& member : neighbourhood)
        if (member.first > kill2) pulled[s].push_back(member);
      if (neighbourhood.empty() || !pulled[s].empty()) continue;
      alive[s] = false;
      const std::int32_t hub = neighbourhood.front().second;
      for (std::size_t k = 1; k < neighbourhood.size(); ++k) {
        const std::int32_t v = neighbourhood[k].second;
        if (tree_steps(tree, hub, v) >= kLoopSteps) linked.insert({std::min(hub, v), std::max(hub, v)});
      }
    }
  };
  update();
  const detail::LatticeNoise noise(o.rng_seed);
  std::vector<std::int32_t> last_child(roots.size(), -1);
  for (std::size_t iteration = 0; iteration < o.max_iterations && tree.particles.size() < o.max_nodes; ++iteration) {
    if (std::find(alive.begin(), alive.end(), true) == alive.end()) break;
    Pulls pulls(tree.particles.size());
    for (std::size_t s = 0; s < sources.size(); ++s)
      if (alive[s])
        for (const auto& member : pulled[s]) pulls.add(tree, member.second, sources[s]);
    if (!grow_pulled(o, noise, pulls, tree, last_child)) break;
    update();
  }
  for (const auto& [a, b] : linked) tree.links.push_back({a, b});
  std::sort(tree.links.begin(), tree.links.end(),
            [](const Link& x, const Link& y) { return std::make_pair(x.later, x.earlier) < std::make_pair(y.later, y.earlier); });
  return tree;
}

}  // namespace dla::testing
