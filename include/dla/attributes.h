#pragma once
//! \file attributes.h
//! Per-particle attributes of a grown structure, computed after growth from the tree alone
//! (and a mesh, for the distance to its surface): what the radius models, the colour maps,
//! the instancing points and the files' extra columns are made of. See docs/look.md.

#include "dla/cluster.h"
#include "dla/nearest_points.h"
#include "dla/strands.h"
#include "dla/surface_distance.h"

#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

namespace dla {

//! What the distances are measured to.
struct AttributeOptions {
  const SurfaceDistance* surface = nullptr;  //!< the constraint mesh: gives boundary_distance
  const std::vector<Vec3>* points = nullptr; //!< seed_distance is to these; default: the seeds
  int threads = 1;                           //!< for the distances to the surface, 1-256; the
                                             //!< result does not depend on it
};

//! One value per particle, indexed as Cluster::particles (the index is the attach order).
//! About 22 bytes a particle (26 with a mesh), beside the cluster's 32.
struct Attributes {
  std::vector<std::int32_t> depth;         //!< particles on the path to its seed (a seed: 0)
  std::vector<std::int32_t> descendants;   //!< particles in its subtree, itself not counted
  std::vector<std::uint8_t> children;      //!< particles attached to it, up to 255
  std::vector<std::uint8_t> strahler;      //!< Strahler order: tips 1, and one more where two
                                           //!< branches of the same order meet
  std::vector<float> taper;                //!< place along its strand (strands.h): 1 at the
                                           //!< strand's start, falling to 0 at its tip
  std::vector<float> seed_distance;        //!< to the nearest seed (or AttributeOptions::points)
  std::vector<float> boundary_distance;    //!< to the mesh's surface; empty without a mesh
  std::size_t seed_count = 0;

  std::size_t size() const { return depth.size(); }
  //! Normalised attach order: seeds 0, the first attached particle 0, the last 1.
  float age(std::size_t i) const {
    const std::size_t attached = size() - seed_count;
    if (i < seed_count || attached < 2) return 0.0f;
    return static_cast<float>(static_cast<double>(i - seed_count) / static_cast<double>(attached - 1));
  }
  bool tip(std::size_t i) const { return children[i] == 0; }
  bool branch_point(std::size_t i) const { return children[i] >= 2; }
};

//! Every attribute of every particle. Linear in the particles, but the distance to a mesh,
//! which takes an AABB-tree query each (about a microsecond).
inline Attributes compute_attributes(const Cluster& cluster, const AttributeOptions& options = {}) {
  if (options.threads < 1 || options.threads > 256)
    throw InvalidInput("threads " + std::to_string(options.threads) + " is not in 1-256");
  const auto& ps = cluster.particles;
  const std::size_t n = ps.size();
  Attributes a;
  a.seed_count = cluster.seed_count;
  a.depth.assign(n, 0);
  a.descendants.assign(n, 0);
  a.children.assign(n, 0);
  a.strahler.assign(n, 1);
  a.taper.assign(n, 1.0f);
  a.seed_distance.resize(n);

  for (std::size_t i = 0; i < n; ++i) {
    if (ps[i].parent < 0) continue;
    const auto parent = static_cast<std::size_t>(ps[i].parent);
    a.depth[i] = a.depth[parent] + 1;
    if (a.children[parent] < 255) ++a.children[parent];
  }
  // Parents come before their children: one pass backwards finishes each subtree first.
  // Children's highest order and how many have it (orders stay far below 255: 2^254 tips).
  std::vector<std::uint8_t> highest(n, 0), times(n, 0);
  for (std::size_t i = n; i-- > 0;) {
    if (a.children[i] > 0) a.strahler[i] = static_cast<std::uint8_t>(times[i] >= 2 ? highest[i] + 1 : highest[i]);
    if (ps[i].parent < 0) continue;
    const auto parent = static_cast<std::size_t>(ps[i].parent);
    a.descendants[parent] += a.descendants[i] + 1;
    if (a.strahler[i] > highest[parent]) {
      highest[parent] = a.strahler[i];
      times[parent] = 1;
    } else if (a.strahler[i] == highest[parent]) {
      if (times[parent] < 2) ++times[parent];
    }
  }
  for_each_strand(cluster, &a.descendants, [&](const Strand& strand) {
    const double end = static_cast<double>(strand.size() - 1);
    // A strand's start belongs to the strand it continues, unless it is a seed.
    for (std::size_t k = ps[static_cast<std::size_t>(strand[0])].parent < 0 ? 0 : 1; k < strand.size(); ++k)
      a.taper[static_cast<std::size_t>(strand[k])] = end > 0 ? static_cast<float>(1.0 - static_cast<double>(k) / end) : 1.0f;
  });

  std::vector<Vec3> seeds;
  if (!options.points)
    for (std::size_t s = 0; s < cluster.seed_count; ++s) seeds.push_back(ps[s].position);
  const NearestPoints<> nearest(options.points ? *options.points : seeds);
  for (std::size_t i = 0; i < n; ++i) a.seed_distance[i] = static_cast<float>(nearest.distance(ps[i].position));

  if (options.surface) {
    a.boundary_distance.resize(n);
    const auto measure = [&](std::size_t from, std::size_t to) {
      for (std::size_t i = from; i < to; ++i)
        a.boundary_distance[i] = static_cast<float>(options.surface->distance(ps[i].position));
    };
    const auto threads = static_cast<std::size_t>(std::min<std::size_t>(static_cast<std::size_t>(options.threads), n / 4096 + 1));
    std::vector<std::thread> helpers;
    for (std::size_t t = 1; t < threads; ++t) helpers.emplace_back(measure, n * t / threads, n * (t + 1) / threads);
    measure(0, n / threads);
    for (std::thread& helper : helpers) helper.join();
  }
  return a;
}

}  // namespace dla
