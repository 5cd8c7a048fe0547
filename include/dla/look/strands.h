#pragma once
//! \file strands.h
//! The structure as strands: chains of particles from a branch point or a seed to a tip, the
//! unit the POV-Ray exporter turns into one sphere_sweep each and the tube mesh into one tube.

#include "dla/core/cluster.h"

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

namespace dla {

//! Particle ids from the strand's start to its tip. A strand that leaves a branch point starts
//! with that branch point, so strands join; a seed with no children is a strand of one.
using Strand = std::vector<std::int32_t>;

//! Which particles are tips (no child), from the tree alone: 1 bit a particle.
inline std::vector<bool> tip_flags(const Cluster& cluster) {
  std::vector<bool> tip(cluster.particles.size(), true);
  for (const Particle& p : cluster.particles)
    if (p.parent >= 0) tip[static_cast<std::size_t>(p.parent)] = false;
  return tip;
}

//! for_each_strand (below) for the strands whose tips are among particles [begin, end), with
//! `is_tip(i)` saying which are tips. Consecutive ranges visit the strands in for_each_strand's
//! order, so a writer can format ranges on several threads and join the results in order.
template <class IsTip, class Continues, class Visit>
void for_each_strand_in(const Cluster& cluster, std::size_t begin, std::size_t end, IsTip&& is_tip,
                        Continues&& continues, Visit&& visit) {
  const auto& ps = cluster.particles;
  Strand strand;
  for (std::size_t tip = begin; tip < end; ++tip) {
    if (!is_tip(tip)) continue;
    // Up from the tip to the strand's first own particle, then its branch point if any.
    strand.clear();
    auto j = static_cast<std::int32_t>(tip);
    strand.push_back(j);
    while (ps[static_cast<std::size_t>(j)].parent >= 0 && continues(static_cast<std::size_t>(j))) {
      j = ps[static_cast<std::size_t>(j)].parent;
      strand.push_back(j);
    }
    if (ps[static_cast<std::size_t>(j)].parent >= 0) strand.push_back(ps[static_cast<std::size_t>(j)].parent);
    std::reverse(strand.begin(), strand.end());
    visit(static_cast<const Strand&>(strand));
  }
}

//! Calls visit(const Strand&) for each strand, one per tip in the tips' attach order, with one
//! buffer and nothing else: writers stream a structure of 10^7 particles without holding its
//! strands. `continues(i)` says whether particle i (not a seed) goes on with its parent's
//! strand; each parent has exactly one such child (Attributes::continues_strand gives it).
template <class Continues, class Visit>
void for_each_strand(const Cluster& cluster, Continues&& continues, Visit&& visit) {
  const std::vector<bool> tips = tip_flags(cluster);
  for_each_strand_in(
      cluster, 0, cluster.particles.size(), [&](std::size_t i) { return static_cast<bool>(tips[i]); },
      std::forward<Continues>(continues), std::forward<Visit>(visit));
}

//! Whether a strand begins at a seed of its own rather than leaving a branch point: true for
//! the one strand that goes on from each seed (and a lone seed), false for every strand that
//! starts inside its parent's branch.
template <class Continues>
bool starts_at_own_seed(const Strand& strand, Continues&& continues) {
  return strand.size() == 1 || continues(static_cast<std::size_t>(strand[1]));
}

//! For each particle, whether it goes on with its parent's strand: at a branch point the strand
//! goes on into the child with the largest subtree (ties: the earliest), so the long trunks
//! stay whole; every other child starts a new strand. 1 bit a particle, from 4 for `subtree`
//! (particles in each subtree, itself not counted).
inline std::vector<bool> continuing_children(const Cluster& cluster, const std::vector<std::int32_t>& subtree) {
  const auto& ps = cluster.particles;
  const std::size_t n = ps.size();
  std::vector<std::int32_t> heaviest(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (ps[i].parent < 0) continue;
    std::int32_t& h = heaviest[static_cast<std::size_t>(ps[i].parent)];
    if (h < 0 || subtree[i] > subtree[static_cast<std::size_t>(h)]) h = static_cast<std::int32_t>(i);
  }
  std::vector<bool> continues(n, false);
  for (std::size_t i = 0; i < n; ++i)
    continues[i] = ps[i].parent >= 0 && heaviest[static_cast<std::size_t>(ps[i].parent)] == static_cast<std::int32_t>(i);
  return continues;
}

//! Particles in each subtree, itself not counted: parents come before their children, so one
//! pass backwards finishes each subtree first.
inline std::vector<std::int32_t> subtree_sizes(const Cluster& cluster) {
  const auto& ps = cluster.particles;
  std::vector<std::int32_t> size(ps.size(), 0);
  for (std::size_t i = ps.size(); i-- > 0;)
    if (ps[i].parent >= 0) size[static_cast<std::size_t>(ps[i].parent)] += size[i] + 1;
  return size;
}

//! Every strand, for a cluster without Attributes (tests and small structures).
template <class Visit>
void for_each_strand(const Cluster& cluster, Visit&& visit) {
  const std::vector<bool> continues = continuing_children(cluster, subtree_sizes(cluster));
  for_each_strand(cluster, [&](std::size_t i) { return static_cast<bool>(continues[i]); }, std::forward<Visit>(visit));
}

//! Splits the tree into strands, one per tip, in the tips' attach order (for_each_strand).
inline std::vector<Strand> decompose_strands(const Cluster& cluster) {
  std::vector<Strand> strands;
  for_each_strand(cluster, [&](const Strand& strand) { strands.push_back(strand); });
  return strands;
}

//! How many strands decompose_strands makes, without making them: one per tip.
inline std::size_t count_strands(const Cluster& cluster) {
  const std::vector<bool> tips = tip_flags(cluster);
  return static_cast<std::size_t>(std::count(tips.begin(), tips.end(), true));
}

}  // namespace dla
