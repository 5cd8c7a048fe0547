#pragma once
//! \file attributes.h
//! Per-particle attributes of a grown structure, computed after growth from the tree alone
//! (and a mesh, for the distance to its surface): what the radius models, the colour maps,
//! the instancing points and the files' extra columns are made of. See docs/look.md.

#include "dla/core/cluster.h"
#include "dla/core/stop.h"
#include "dla/index/nearest_points.h"
#include "dla/look/strands.h"
#include "dla/mesh/paint.h"
#include "dla/mesh/surface_distance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

namespace dla {

//! The closest triangle of a surface to each of a structure's first particles, measured before
//! the rest of its look (run.h: on a spare core while it grew), and the fingerprint of their
//! positions, by which compute_attributes knows them for the same particles.
struct MeasuredClosest {
  const SurfaceDistance* surface = nullptr;  //!< what they were measured to
  std::vector<std::uint32_t> triangles;      //!< for the first triangles.size() particles
  std::uint64_t positions_hash = kPositionsHashStart;

  static constexpr std::uint64_t kPositionsHashStart = 0xcbf29ce484222325ULL;
  //! `hash` with one more position, a word at a time: 30,000 positions in about 0.1 ms.
  static std::uint64_t hash_with(std::uint64_t hash, const Vec3& position) {
    for (int axis = 0; axis < 3; ++axis) {
      std::uint64_t word;
      std::memcpy(&word, &position[axis], sizeof word);
      hash = (hash ^ word) * 0x9e3779b97f4a7c15ULL;
      hash ^= hash >> 32;
    }
    return hash;
  }
};

//! What the distances are measured to.
struct AttributeOptions {
  const SurfaceDistance* surface = nullptr;  //!< the constraint mesh: gives boundary_distance
  const std::vector<Vec3>* points = nullptr; //!< seed_distance is to these; default: the seeds
  int threads = 1;                           //!< for the distances to the surface and between
                                             //!< tips, 1-256; the result does not depend on it
  //! Measure Attributes::tip_gaps, which only instancing points that pick every tip use
  //! (picks_every_tip in instances.h): the POV-Ray scene's tips, PREFIX_tips.ply, the leaves.
  //! Without them those measure their own, after the rest of the attributes, in more memory.
  bool tip_gaps = true;
  //! With `surface` and its mesh's vertex colours in `mesh`: mark the particles whose closest
  //! point of the surface is painted this colour (Attributes::on_paint).
  const Paint* paint = nullptr;
  const TriangleMesh* mesh = nullptr;
  //! Closest triangles of `surface` measured before, for a first part of the particles: taken
  //! where their positions are the cluster's, instead of measuring again. Null: none.
  const MeasuredClosest* measured = nullptr;
};

//! Per-particle values, indexed as Cluster::particles (the index is the attach order): 11 bytes
//! a particle (15 with a mesh, 16 with its paint) and 4 a tip, beside the cluster's 32, so that
//! 10^7 particles and their look fit in 48 bytes a particle. What is cheap to recompute is not
//! stored: the age, the distance to the seeds, and the radii (radius_model.h).
struct Attributes {
  std::vector<std::int32_t> depth;         //!< particles on the path to its seed (a seed: 0)
  std::vector<std::int32_t> descendants;   //!< particles in its subtree, itself not counted
  //! Packed: the Strahler order (bits 0-5; tips 1, one more where two branches of the same
  //! order meet, at most 32 below 2^31 particles), branch point (bit 6), and whether the
  //! particle goes on with its parent's strand (bit 7, strands.h).
  std::vector<std::uint8_t> shape;
  //! The place along its strand (strands.h), in 65535ths: 65535 at the strand's start, falling
  //! to 0 at its tip.
  std::vector<std::uint16_t> strand_place;
  std::vector<float> boundary_distance;    //!< to the mesh's surface; empty without a mesh
  //! 1 where the particle's closest point of the surface is painted AttributeOptions::paint;
  //! empty without it.
  std::vector<std::uint8_t> on_paint;
  //! For each tip, in attach order: half the distance to the nearest other tip, in spacings,
  //! rounded down (infinity for a lone tip). Unit-radius copies scaled by it never overlap:
  //! the instancing points' scale (instances.h). Empty unless AttributeOptions::tip_gaps.
  std::vector<float> tip_gaps;
  //! A discharge's main channel (breakdown.h): the particles on the path from the struck tree's
  //! seed to Cluster::strike, in attach order (a parent comes before its child); empty when
  //! nothing struck.
  std::vector<std::int32_t> channel;
  std::int32_t largest_tree = 1;           //!< the particles of the largest tree: flow's scale
  PointDistance seed_points;               //!< the seeds (or AttributeOptions::points)
  double seed_reach = 0.0;                 //!< the largest distance of a particle to them
  double boundary_reach = 0.0;             //!< the largest boundary_distance, 0 without a mesh
  std::size_t seed_count = 0;

  static constexpr std::uint8_t kOrderBits = 0x3f, kBranchPointBit = 0x40, kContinuesBit = 0x80;
  static constexpr double kPlaceSteps = 65535.0;

  std::size_t size() const { return depth.size(); }
  //! Normalised attach order: seeds 0, the first attached particle 0, the last 1.
  float age(std::size_t i) const {
    const std::size_t attached = size() - seed_count;
    if (i < seed_count || attached < 2) return 0.0f;
    return static_cast<float>(static_cast<double>(i - seed_count) / static_cast<double>(attached - 1));
  }
  int strahler(std::size_t i) const { return shape[i] & kOrderBits; }
  bool tip(std::size_t i) const { return descendants[i] == 0; }
  bool branch_point(std::size_t i) const { return (shape[i] & kBranchPointBit) != 0; }
  bool continues_strand(std::size_t i) const { return (shape[i] & kContinuesBit) != 0; }
  //! 1 at its strand's start, falling to 0 at its tip.
  double taper(std::size_t i) const { return strand_place[i] / kPlaceSteps; }
  //! Whether particle i is on a discharge's main channel.
  bool on_channel(std::size_t i) const {
    return std::binary_search(channel.begin(), channel.end(), static_cast<std::int32_t>(i));
  }
  //! The particles whose charge flows through particle i, itself among them: its subtree, which
  //! drains towards its seed as the pipe model's sap does. On a main channel the struck tree's
  //! charge flows to the strike instead, so there it is every particle of the tree but those
  //! past i along the channel: the current grows towards the strike, which carries it all.
  std::int32_t flow(std::size_t i) const {
    if (!channel.empty()) {
      const auto at = std::lower_bound(channel.begin(), channel.end(), static_cast<std::int32_t>(i));
      if (at != channel.end() && *at == static_cast<std::int32_t>(i)) {
        const std::int32_t tree = descendants[static_cast<std::size_t>(channel.front())] + 1;
        return at + 1 == channel.end() ? tree : tree - descendants[static_cast<std::size_t>(at[1])] - 1;
      }
    }
    return descendants[i] + 1;
  }
  //! flow(i) as a fraction of the largest tree: 1 at the strike (or the largest seed).
  float current(std::size_t i) const { return static_cast<float>(flow(i)) / static_cast<float>(largest_tree); }
  //! When the leader reaches particle i, in attach order: 0 at the seeds and the first particle,
  //! 1 at the strike (the return stroke), past 1 for what grew after it; age(i) without a strike.
  float light(std::size_t i) const {
    if (channel.empty()) return age(i);
    const auto strike = static_cast<std::size_t>(channel.back());
    if (i < seed_count) return 0.0f;
    const double span = strike > seed_count ? static_cast<double>(strike - seed_count) : 1.0;
    return static_cast<float>(static_cast<double>(i - seed_count) / span);
  }
  //! The distance from a particle at `position` to the nearest seed (or given point).
  double seed_distance(const Vec3& position) const { return seed_points(position); }
};

//! For each particle with selected[i], in attach order: half the distance to the nearest other
//! selected particle, in spacings, rounded down (infinity for a lone one). The look-ups are
//! shared among `threads`; the result does not depend on them.
inline std::vector<float> half_gaps(const Cluster& cluster, const std::vector<bool>& selected, int threads = 1) {
  const auto& ps = cluster.particles;
  const std::size_t n = ps.size();
  const auto count = static_cast<std::size_t>(std::count(selected.begin(), selected.end(), true));
  std::vector<float> gaps;
  if (count == 0) return gaps;
  NearestOther nearest(ps[0].position, cluster.spacing, count);
  for (std::size_t i = 0; i < n; ++i)
    if (selected[i]) nearest.add(ps[i].position);
  nearest.build();
  gaps.resize(count);
  const auto measure = [&](std::size_t from, std::size_t to) {
    nearest.distances_to_others(from, to, [&](std::size_t k, double distance) {
      const double half = 0.5 * distance / cluster.spacing;
      float gap = static_cast<float>(half);
      if (static_cast<double>(gap) > half) gap = std::nextafter(gap, 0.0f);
      gaps[k] = gap;
    });
  };
  const auto parts = std::min<std::size_t>(static_cast<std::size_t>(std::max(threads, 1)), count / 4096 + 1);
  std::vector<std::thread> helpers;
  for (std::size_t t = 1; t < parts; ++t) helpers.emplace_back(measure, count * t / parts, count * (t + 1) / parts);
  measure(0, count / parts);
  for (std::thread& helper : helpers) helper.join();
  return gaps;
}

//! Every attribute of every particle, with no more memory on the side than it keeps. Linear
//! in the particles, but the distance to a mesh, which takes an AABB-tree query each (about a
//! microsecond).
inline Attributes compute_attributes(const Cluster& cluster, const AttributeOptions& options = {}) {
  if (options.threads < 1 || options.threads > 256)
    throw InvalidInput("threads " + std::to_string(options.threads) + " is not in 1-256");
  const auto& ps = cluster.particles;
  const std::size_t n = ps.size();
  const auto parent_of = [&](std::size_t i) { return static_cast<std::size_t>(ps[i].parent); };
  Attributes a;
  a.seed_count = cluster.seed_count;
  // First, while nothing else is held: the tree of the tips takes 16 bytes a tip.
  if (options.tip_gaps) a.tip_gaps = half_gaps(cluster, tip_flags(cluster), options.threads);
  a.descendants = subtree_sizes(cluster);
  a.shape.assign(n, 1);
  a.strand_place.assign(n, 0);
  {
    // The strands' own rule (strands.h), before `depth` exists: its 4 bytes a particle of
    // scratch come and go in depth's place, as the places' below do.
    const std::vector<bool> continues = continuing_children(cluster, a.descendants);
    for (std::size_t i = 0; i < n; ++i) {
      if (continues[i]) a.shape[i] |= Attributes::kContinuesBit;
      else if (ps[i].parent >= 0) a.shape[parent_of(i)] |= Attributes::kBranchPointBit;  // beside the one going on
    }
  }
  // Strahler order, backwards. `strand_place` holds each parent's children's highest order
  // (low byte) and how many have it, up to 2 (high byte), until it is filled.
  for (std::size_t i = n; i-- > 0;) {
    if (a.descendants[i] > 0) {
      const unsigned highest = a.strand_place[i] & 0xffu, times = a.strand_place[i] >> 8;
      a.shape[i] = static_cast<std::uint8_t>((a.shape[i] & ~Attributes::kOrderBits) | (times >= 2 ? highest + 1 : highest));
    }
    if (ps[i].parent < 0) continue;
    std::uint16_t& parent = a.strand_place[parent_of(i)];
    const unsigned order = a.shape[i] & Attributes::kOrderBits, highest = parent & 0xffu, times = parent >> 8;
    if (order > highest) parent = static_cast<std::uint16_t>(order | 1u << 8);
    else if (order == highest && times < 2) parent = static_cast<std::uint16_t>(order | (times + 1) << 8);
  }
  {
    // Each particle's place along its strand, in two passes over the parents rather than a walk
    // down every strand (which jumps about memory at 10^7). `step` holds first the particles
    // after each one to its strand's tip (backwards: each parent's one continuing child comes
    // after it), then its own place k (forwards: a strand's first own particle is 1, after its
    // branch point; a seed is 0), so the strand's last place is k plus what was there.
    std::vector<std::int32_t> step(n, 0);
    for (std::size_t i = n; i-- > 0;)
      if (a.continues_strand(i)) step[parent_of(i)] = step[i] + 1;
    for (std::size_t i = 0; i < n; ++i) {
      const std::int32_t k = ps[i].parent < 0 ? 0 : a.continues_strand(i) ? step[parent_of(i)] + 1 : 1;
      const double end = static_cast<double>(k + step[i]);
      step[i] = k;
      // A strand leaving a branch point starts there (its k = 0), but the branch point keeps
      // its place on the strand it continues.
      a.strand_place[i] = static_cast<std::uint16_t>(
          std::lround(end > 0 ? Attributes::kPlaceSteps * (1.0 - static_cast<double>(k) / end) : Attributes::kPlaceSteps));
    }
  }
  a.depth.resize(n);
  for (std::size_t i = 0; i < n; ++i) a.depth[i] = ps[i].parent < 0 ? 0 : a.depth[parent_of(i)] + 1;
  for (std::size_t i = 0; i < n; ++i)
    if (ps[i].parent < 0) a.largest_tree = std::max(a.largest_tree, a.descendants[i] + 1);
  if (cluster.strike >= 0 && static_cast<std::size_t>(cluster.strike) < n) {
    for (std::int32_t i = cluster.strike; i >= 0; i = ps[static_cast<std::size_t>(i)].parent) a.channel.push_back(i);
    std::reverse(a.channel.begin(), a.channel.end());
  }

  std::vector<Vec3> seeds;
  if (options.points) seeds = *options.points;
  else
    for (std::size_t s = 0; s < cluster.seed_count; ++s) seeds.push_back(ps[s].position);
  a.seed_points = PointDistance(std::move(seeds));
  for (std::size_t i = 0; i < n; ++i) {
    const double d = a.seed_distance(ps[i].position);
    if (d > a.seed_reach && std::isfinite(d)) a.seed_reach = d;
  }

  const bool painted = options.surface && options.paint;
  if (painted) {
    if (!options.mesh || options.mesh->colors.empty())
      throw InvalidInput("the mesh has no vertex colours to read the paint from: paint it, and save it as PLY, OFF "
                         "or OBJ with its colours");
    a.on_paint.resize(n);
  }
  if (options.surface) {
    a.boundary_distance.resize(n);
    // Each particle's closest triangle, plus one (0: not yet measured). A measured parent's
    // starts the search; it only speeds it, so which thread measured what does not matter.
    std::vector<std::atomic<std::uint32_t>> nearest(n);
    const auto keep = [&](std::size_t i, const SurfaceDistance::Closest& closest) {
      nearest[i].store(closest.triangle + 1, std::memory_order_relaxed);
      a.boundary_distance[i] = static_cast<float>((closest.point - ps[i].position).norm());
      if (painted) a.on_paint[i] = options.paint->matches(paint_at(*options.mesh, closest.triangle, closest.point));
    };
    // The triangles measured before, if they are this cluster's: the closest point of each is
    // the one its query gave, bit for bit (the same function of the same triangle).
    std::size_t measured = 0;
    if (const MeasuredClosest* before = options.measured;
        before && before->surface == options.surface && before->triangles.size() <= n) {
      std::uint64_t hash = MeasuredClosest::kPositionsHashStart;
      for (std::size_t i = 0; i < before->triangles.size(); ++i) hash = MeasuredClosest::hash_with(hash, ps[i].position);
      if (hash == before->positions_hash) measured = before->triangles.size();
    }
    const auto measure = [&](std::size_t from, std::size_t to) {
      for (std::size_t i = from; i < to; ++i) {
        if (i < measured) {
          keep(i, options.surface->on_triangle(ps[i].position, options.measured->triangles[i]));
          continue;
        }
        const std::uint32_t parent = ps[i].parent < 0 ? 0 : nearest[parent_of(i)].load(std::memory_order_relaxed);
        keep(i, options.surface->closest(ps[i].position, parent > 0 ? parent - 1 : SurfaceDistance::kNoHint));
      }
    };
    // Runs of particles handed out in turn: those deep in the mesh, which take longer, are
    // many among the first, so halves would leave one thread working alone.
    constexpr std::size_t kRun = 1024;
    std::atomic<std::size_t> next_run{0};
    const StopFlag* const stop = detail::scoped_stop();  // the helpers watch the caller's flag
    const auto measure_runs = [&] {
      for (std::size_t from; !stopped(stop) && (from = next_run.fetch_add(kRun, std::memory_order_relaxed)) < n;)
        measure(from, std::min(n, from + kRun));
    };
    const auto threads = std::min<std::size_t>(static_cast<std::size_t>(options.threads), n / 4096 + 1);
    std::vector<std::thread> helpers;
    for (std::size_t t = 1; t < threads; ++t) helpers.emplace_back(measure_runs);
    measure_runs();
    for (std::thread& helper : helpers) helper.join();
    detail::throw_if_stopped("measuring the distances to the mesh");
    if (n > 0) a.boundary_reach = *std::max_element(a.boundary_distance.begin(), a.boundary_distance.end());
  }
  return a;
}

}  // namespace dla
