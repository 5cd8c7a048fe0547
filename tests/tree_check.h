#pragma once
// What makes a grown structure a tree, for every model, checked once here and used by every
// test that grows one: the unit tests, the property test (on the CSV it reads back) and the
// command line's fuzzer.

#include "dla/core/cluster.h"
#include "dla/index/kdtree_index.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace dla::testing {

//! What a model allows beyond the rules every tree keeps.
struct TreeRules {
  double shortest = 1.0;  //!< a branch's least length, in spacings: 0 where branches are clipped
  double longest = 1.0;   //!< its greatest, in spacings: more with noise, or an Eden mask's reach
  bool apart = true;      //!< no two particles closer than a spacing
};

//! Empty when `c` is a tree: the seeds first, each its own tree with no parent; every other
//! particle after its parent, in its parent's tree, a branch length from it within the rules;
//! every position finite, and in z = 0 for 2D growth; with `rules.apart`, no two particles
//! closer than the spacing (found with a k-d tree). Otherwise what is wrong, in one line.
inline std::string tree_fault(const Cluster& c, const TreeRules& rules = {}) {
  const auto& ps = c.particles;
  const double s = c.spacing;
  if (c.seed_count > ps.size()) return "more seeds than particles";
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const Particle& p = ps[i];
    const std::string at = "particle " + std::to_string(i) + ": ";
    if (!p.position.allFinite()) return at + "a position that is not finite";
    if (c.dimensions == 2 && p.position.z() != 0.0) return at + "out of the plane z = 0 of 2D growth";
    if (i < c.seed_count) {
      if (p.parent != -1) return at + "a seed with a parent";
      if (p.seed != static_cast<std::int32_t>(i)) return at + "a seed that is not its own tree";
      continue;
    }
    if (p.parent < 0 || static_cast<std::size_t>(p.parent) >= i) return at + "its parent does not come before it";
    const Particle& parent = ps[static_cast<std::size_t>(p.parent)];
    if (p.seed != parent.seed) return at + "in another tree than its parent";
    // A branch's length is off by the rounding of its ends: relative to their size, not the
    // spacing's (a tree of spacing 1e-6 rooted 50 away).
    const double rounding = 1e-9 * s + 8 * std::numeric_limits<double>::epsilon() *
                                           std::max(p.position.cwiseAbs().maxCoeff(), parent.position.cwiseAbs().maxCoeff());
    const double length = (p.position - parent.position).norm();
    if (!(length > 0.0) || length < rules.shortest * s - rounding || length > rules.longest * s + rounding)
      return at + "a branch of length " + std::to_string(length) + " for spacing " + std::to_string(s);
  }
  if (rules.apart && ps.size() > 1) {
    KdTreeIndex all(ps, s, c.dimensions);
    for (std::size_t i = 0; i < ps.size(); ++i) all.insert(static_cast<std::int32_t>(i));
    for (std::size_t i = 0; i < ps.size(); ++i) {
      std::int32_t closest = -1;
      all.for_each_within(ps[i].position, s * (1 - 1e-9), [&](std::int32_t j, double) {
        if (static_cast<std::size_t>(j) != i) closest = j;
      });
      if (closest >= 0)
        return "particles " + std::to_string(i) + " and " + std::to_string(closest) + " are closer than a spacing";
    }
  }
  return "";
}

}  // namespace dla::testing
