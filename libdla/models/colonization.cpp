// Space colonization (colonization.h): the attractors drawn or sampled, and the growth loop.

#include "dla/models/colonization.h"

#include "colonization_step.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dla {

std::vector<Vec3> scatter_attractors(const AttractorOptions& options, std::uint64_t seed, int dimensions,
                                     const MeshConstraint* mesh) {
  validate(options);
  const bool on_mesh = options.region == AttractorRegion::mesh || options.region == AttractorRegion::surface;
  if (on_mesh && !mesh) throw InvalidInput("attractors in or on a mesh need one: a vessel or a collision mesh");
  if (on_mesh && dimensions != 3) throw InvalidInput("attractors in a mesh need 3 dimensions");
  Rng rng(seed, 0x617474726163746fULL);  // a stream of its own: "attracto"
  if (options.paint) return mesh->draw_near_paint(options.count, rng, *options.paint, "attractor_paint");
  std::vector<Vec3> points;
  points.reserve(options.count);
  for (std::size_t i = 0; i < options.count; ++i) {
    switch (options.region) {
      case AttractorRegion::sphere: {
        const double r = options.radius * std::pow(rng.uniform(), (1.0 + options.falloff) / dimensions);
        points.push_back(options.center + r * random_direction(rng, dimensions));
        break;
      }
      case AttractorRegion::box: {
        Vec3 p;
        for (int axis = 0; axis < 3; ++axis)
          p[axis] = options.box_min[axis] + rng.uniform() * (options.box_max[axis] - options.box_min[axis]);
        if (dimensions == 2) p.z() = 0.0;
        points.push_back(p);
        break;
      }
      case AttractorRegion::mesh: points.push_back(mesh->draw_inside(rng)); break;
      case AttractorRegion::surface: points.push_back(mesh->draw_near_surface(rng)); break;
    }
  }
  return points;
}

std::vector<Vec3> sample_attractors(const std::vector<Vec3>& points, std::size_t count, std::uint64_t seed) {
  if (count > points.size())
    throw InvalidInput("a sample of " + std::to_string(count) + " attractors from " + std::to_string(points.size()) +
                       " points");
  // Selection sampling (Knuth's algorithm S): each point is kept with the chance that fills
  // the sample exactly, in one pass.
  Rng rng(seed, 0x617474726163746fULL);
  std::vector<Vec3> chosen;
  chosen.reserve(count);
  for (std::size_t i = 0; i < points.size() && chosen.size() < count; ++i)
    if (static_cast<double>(points.size() - i) * rng.uniform() < static_cast<double>(count - chosen.size()))
      chosen.push_back(points[i]);
  return chosen;
}

Cluster colonize(const ColonizationOptions& o, std::vector<Vec3> attractors, const std::vector<Vec3>& roots,
                 const ProgressFn& progress, const StopFlag* stop) {
  validate(o);
  if (roots.empty()) throw InvalidInput("there is no root");
  if (roots.size() > o.max_nodes)
    throw InvalidInput(std::to_string(roots.size()) + " roots are more than the " + std::to_string(o.max_nodes) +
                       " nodes allowed");
  for (std::size_t i = 0; i < roots.size(); ++i) {
    detail::require_representable("root " + std::to_string(i + 1), roots[i], o.spacing);
    if (o.vessel && !o.vessel->on_growth_side(roots[i]))
      throw InvalidInput("root " + std::to_string(i + 1) + " is outside the vessel");
  }
  if (attractors.size() > kMaxAttractors)
    throw InvalidInput(std::to_string(attractors.size()) + " attractors are more than " +
                       std::to_string(kMaxAttractors));
  for (const Vec3& a : attractors) detail::require_representable("an attractor", a, o.spacing);

  Cluster tree = detail::seeded(roots, o.spacing, o.dimensions);
  const double kill2 = detail::kill_distance2(o), reach2 = detail::reach2(o);

  const bool closed = o.venation == Venation::closed;
  // The attractors: open venation's index of closest nodes, or closed venation's sources.
  std::optional<AttractorTree> index;
  std::optional<detail::ClosedVenation> sources;
  if (closed) sources.emplace(std::move(attractors), reach2, kill2);
  else index.emplace(std::move(attractors), reach2, kill2);
  const auto live = [&] { return closed ? sources->live() : index->live(); };

  // Per node: the fixed-point sum of unit directions to its attractors, how many, and its
  // last child (a node whose attractors have not changed would grow the same child again).
  std::vector<std::array<std::int64_t, 3>> sums(roots.size(), {0, 0, 0});
  std::vector<std::int32_t> pulls(roots.size(), 0), last_child(roots.size(), -1);
  // Whether a node's attractors changed since it last tried to grow: if not, it would find
  // what it found then (no step, or the same child), and the collision's queries are skipped.
  std::vector<std::uint8_t> changed(roots.size(), 0);

  const auto pull = [&](const Vec3& attractor, std::int32_t v, std::int64_t sign) {
    const auto node = static_cast<std::size_t>(v);
    const auto d = detail::fixed_direction(tree.particles[node].position, attractor);
    for (std::size_t axis = 0; axis < 3; ++axis) sums[node][axis] += sign * d[axis];
    pulls[node] += static_cast<std::int32_t>(sign);
    changed[node] = 1;
  };
  const auto moved = [&](std::size_t a, std::int32_t from, std::int32_t to) {
    const Vec3 attractor = index->position(a);
    if (from != AttractorTree::kNone) pull(attractor, from, -1);
    if (to != AttractorTree::kDied) pull(attractor, to, 1);
  };
  std::vector<Vec3> new_positions;
  const auto add_nodes = [&](std::size_t first) {
    if (closed) {
      sources->add_nodes(
          tree.particles, first,
          [&](std::size_t s, std::int32_t v, std::int64_t sign) { pull(sources->position(s), v, sign); }, tree.links,
          stop);
      return;
    }
    new_positions.clear();
    for (std::size_t v = first; v < tree.particles.size(); ++v) new_positions.push_back(tree.particles[v].position);
    index->add_nodes(static_cast<std::int32_t>(first), new_positions, moved);
  };
  add_nodes(0);

  const detail::LatticeNoise noise(o.rng_seed);
  std::vector<std::pair<std::int32_t, Vec3>> grown;  // this iteration's new nodes: parent, position
  detail::ModelShell shell(progress, stop);
  try {
    for (std::size_t iteration = 0; iteration < o.max_iterations && live() > 0 && tree.particles.size() < o.max_nodes;
         ++iteration) {
      if (!shell.go_on(tree)) {
        tree.complete = false;
        break;
      }
      grown.clear();
      for (std::size_t v = 0; v < tree.particles.size(); ++v) {
        if (pulls[v] == 0 || !changed[v]) continue;
        changed[v] = 0;
        Vec3 next;
        if (!colonization_step(o, noise, tree.particles[v].position, sums[v], &next)) continue;
        // Its attractors changed but still pull it to where it last grew: the same child again.
        if (last_child[v] >= 0 && tree.particles[static_cast<std::size_t>(last_child[v])].position == next) continue;
        grown.emplace_back(static_cast<std::int32_t>(v), next);
      }
      if (grown.empty()) break;  // stalled: no node grows
      const std::size_t first_new = tree.particles.size();
      for (const auto& [parent, position] : grown) {
        if (tree.particles.size() >= o.max_nodes) break;
        const auto v = static_cast<std::int32_t>(tree.particles.size());
        tree.particles.push_back({position, parent, tree.particles[static_cast<std::size_t>(parent)].seed});
        sums.push_back({0, 0, 0});
        pulls.push_back(0);
        last_child.push_back(-1);
        changed.push_back(0);
        last_child[static_cast<std::size_t>(parent)] = v;
      }
      add_nodes(first_new);
      if (stopped(stop)) {  // closed venation may have taken in only some of the new nodes
        tree.complete = false;
        break;
      }
    }
  } catch (...) {
    detail::ModelShell::keep_what_grew(tree);
  }
  // In order of the later node, as every structure keeps its links.
  std::sort(tree.links.begin(), tree.links.end(),
            [](const Link& a, const Link& b) { return std::make_pair(a.later, a.earlier) < std::make_pair(b.later, b.earlier); });
  shell.finish(tree);
  return tree;
}

}  // namespace dla
