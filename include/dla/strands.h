#pragma once
//! \file strands.h
//! The structure as strands: chains of particles from a branch point or a seed to a tip, the
//! unit the POV-Ray exporter turns into one sphere_sweep each.

#include "dla/cluster.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace dla {

//! Particle ids from the strand's start to its tip. A strand that leaves a branch point starts
//! with that branch point, so strands join; a seed with no children is a strand of one.
using Strand = std::vector<std::int32_t>;

//! Calls visit(const Strand&) for each strand, in the order decompose_strands() returns them,
//! with one buffer. `descendants` (attributes.h), if given, saves recounting the subtrees: the
//! walk then takes 4 bytes a particle beside the cluster, else 8 while it starts, so writers
//! stream a structure of 10^7 particles without holding its strands.
template <class Visit>
void for_each_strand(const Cluster& cluster, const std::vector<std::int32_t>* descendants, Visit&& visit) {
  const auto& ps = cluster.particles;
  const std::size_t n = ps.size();
  std::vector<std::int32_t> subtree;  // fits: a cluster holds fewer than 2^31 particles
  if (!descendants) {
    subtree.assign(n, 0);
    for (std::size_t i = n; i-- > 0;)
      if (ps[i].parent >= 0) subtree[static_cast<std::size_t>(ps[i].parent)] += subtree[i] + 1;
  }
  const std::vector<std::int32_t>& size = descendants ? *descendants : subtree;
  std::vector<std::int32_t> heavy(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (ps[i].parent < 0) continue;
    std::int32_t& h = heavy[static_cast<std::size_t>(ps[i].parent)];
    if (h < 0 || size[i] > size[static_cast<std::size_t>(h)]) h = static_cast<std::int32_t>(i);
  }
  subtree = {};
  Strand strand;
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t parent = ps[i].parent;
    if (parent >= 0 && heavy[static_cast<std::size_t>(parent)] == static_cast<std::int32_t>(i)) continue;
    strand.clear();
    if (parent >= 0) strand.push_back(parent);
    for (auto j = static_cast<std::int32_t>(i); j >= 0; j = heavy[static_cast<std::size_t>(j)]) strand.push_back(j);
    visit(static_cast<const Strand&>(strand));
  }
}

template <class Visit>
void for_each_strand(const Cluster& cluster, Visit&& visit) {
  for_each_strand(cluster, nullptr, std::forward<Visit>(visit));
}

//! Splits the tree into strands. At a branch point the strand goes on into the child with the
//! largest subtree (ties: the earliest), so the long trunks stay whole; every other child
//! starts a new strand. Strands come in the order of their first new particle.
inline std::vector<Strand> decompose_strands(const Cluster& cluster) {
  std::vector<Strand> strands;
  for_each_strand(cluster, [&](const Strand& strand) { strands.push_back(strand); });
  return strands;
}

//! How many strands decompose_strands makes, without making them: every particle with a child
//! continues exactly one strand into a child, so each other particle starts one.
inline std::size_t count_strands(const Cluster& cluster) {
  std::vector<bool> has_child(cluster.particles.size(), false);
  for (const Particle& p : cluster.particles)
    if (p.parent >= 0) has_child[static_cast<std::size_t>(p.parent)] = true;
  std::size_t strands = 0;
  for (bool parent : has_child) strands += !parent;
  return strands;
}

}  // namespace dla
