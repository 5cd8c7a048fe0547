#pragma once
//! \file closed_venation.h
//! The sources of closed venation (Runions et al. 2005, section 4): each source pulls every node
//! in its relative neighbourhood, and is removed only once all of them have reached it. Veins
//! that reach one source from different sides join there. colonization.h grows with it.
//!
//! Node v is in the relative neighbourhood of source s when no other node u is nearer both:
//! |u - s| < |v - s| and |u - v| < |v - s|. Only nodes within the influence radius count. A node
//! within the kill distance of s has arrived and is no longer pulled; once every node of the
//! neighbourhood has arrived, s is removed and the nodes that reached it are linked to the one
//! nearest it (not two twigs of one vein: links.h's rule).
//!
//! A source's neighbourhood depends only on the nodes within its influence, so each new node
//! recomputes only the sources within its influence: the result is the full recomputation's at
//! every step, node for node.

#include "dla/core/cluster.h"
#include "dla/models/links.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace dla::detail {

//! Points by cells of a given width, for the points within that width of a place.
class CellLists {
 public:
  explicit CellLists(double width) : width_(width) {}

  void add(const Vec3& p, std::int32_t id) { cells_[key(cell_of(p))].push_back(id); }

  //! visit(id) for every id in the cells around p: a superset of those within the width.
  template <class Visit>
  void for_each_near(const Vec3& p, Visit&& visit) const {
    const std::array<std::int64_t, 3> c = cell_of(p);
    for (std::int64_t z = -1; z <= 1; ++z)
      for (std::int64_t y = -1; y <= 1; ++y)
        for (std::int64_t x = -1; x <= 1; ++x) {
          const auto found = cells_.find(key({c[0] + x, c[1] + y, c[2] + z}));
          if (found != cells_.end())
            for (const std::int32_t id : found->second) visit(id);
        }
  }

 private:
  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / width_)), static_cast<std::int64_t>(std::floor(p.y() / width_)),
            static_cast<std::int64_t>(std::floor(p.z() / width_))};
  }
  // Cells far apart may share a key; the callers measure every distance.
  static std::uint64_t key(const std::array<std::int64_t, 3>& c) {
    return (static_cast<std::uint64_t>(c[0]) & 0x1fffff) | (static_cast<std::uint64_t>(c[1]) & 0x1fffff) << 21 |
           (static_cast<std::uint64_t>(c[2]) & 0x1fffff) << 42;
  }

  double width_;
  std::unordered_map<std::uint64_t, std::vector<std::int32_t>> cells_;
};

//! The nodes of a source's relative neighbourhood, nearest first (ties: the lower id), from
//! `near`: (squared distance, id) of every node within its influence, which it sorts.
inline void relative_neighbourhood(const std::vector<Particle>& nodes, std::vector<std::pair<double, std::int32_t>>& near,
                                   std::vector<std::pair<double, std::int32_t>>& neighbourhood) {
  std::sort(near.begin(), near.end());
  neighbourhood.clear();
  for (std::size_t k = 0; k < near.size(); ++k) {
    const double d2 = near[k].first;
    const Vec3& v = nodes[static_cast<std::size_t>(near[k].second)].position;
    bool blocked = false;
    // A blocker lies nearer s, and most often next to v: the nearest of those first.
    for (std::size_t u = k; u-- > 0 && !blocked;)
      blocked = near[u].first < d2 && (nodes[static_cast<std::size_t>(near[u].second)].position - v).squaredNorm() < d2;
    if (!blocked) neighbourhood.push_back(near[k]);
  }
}

//! The links made where the nodes `arrived` (nearest the source first) reached one source: each
//! to the first, unless they are linked already or fewer than kLoopSteps tree steps apart (two
//! twigs of one vein: a loop as links.h makes them, of different veins).
inline void join_at_source(const std::vector<Particle>& nodes, const std::vector<std::pair<double, std::int32_t>>& arrived,
                           std::unordered_set<std::uint64_t>& linked, std::vector<Link>& links) {
  const std::int32_t hub = arrived.front().second;
  for (std::size_t k = 1; k < arrived.size(); ++k) {
    const std::int32_t v = arrived[k].second;
    const Link link{std::min(hub, v), std::max(hub, v)};
    if (tree_near(nodes, link.later, link.earlier, kLoopSteps)) continue;
    const std::uint64_t key = static_cast<std::uint64_t>(link.earlier) << 32 | static_cast<std::uint32_t>(link.later);
    if (linked.insert(key).second) links.push_back(link);
  }
}

class ClosedVenation {
 public:
  //! `sources` pull nodes within sqrt(reach2) (finite), and arrive within sqrt(kill2).
  ClosedVenation(std::vector<Vec3> sources, double reach2, double kill2)
      : sources_(std::move(sources)), reach2_(reach2), kill2_(kill2), source_cells_(std::sqrt(reach2)),
        node_cells_(std::sqrt(reach2)), alive_(sources_.size(), 1), pulled_(sources_.size()), live_(sources_.size()) {
    for (std::size_t s = 0; s < sources_.size(); ++s) source_cells_.add(sources_[s], static_cast<std::int32_t>(s));
  }

  std::size_t live() const { return live_; }
  const Vec3& position(std::size_t s) const { return sources_[s]; }

  //! Takes in nodes [first, end) of `nodes`, just added: the sources within their influence
  //! find their neighbourhoods again. pull(source, node, +1 or -1) hears each change of whom a
  //! source pulls; the links made where sources are removed are appended to `links`.
  template <class Pull>
  void add_nodes(const std::vector<Particle>& nodes, std::size_t first, Pull&& pull, std::vector<Link>& links) {
    dirty_.clear();
    for (std::size_t v = first; v < nodes.size(); ++v) {
      const Vec3& p = nodes[v].position;
      node_cells_.add(p, static_cast<std::int32_t>(v));
      source_cells_.for_each_near(p, [&](std::int32_t s) {
        if (alive_[static_cast<std::size_t>(s)] && (sources_[static_cast<std::size_t>(s)] - p).squaredNorm() <= reach2_)
          dirty_.push_back(s);
      });
    }
    std::sort(dirty_.begin(), dirty_.end());
    dirty_.erase(std::unique(dirty_.begin(), dirty_.end()), dirty_.end());
    for (const std::int32_t s : dirty_) update(nodes, static_cast<std::size_t>(s), pull, links);
  }

 private:
  template <class Pull>
  void update(const std::vector<Particle>& nodes, std::size_t s, Pull&& pull, std::vector<Link>& links) {
    const Vec3& at = sources_[s];
    near_.clear();
    node_cells_.for_each_near(at, [&](std::int32_t v) {
      const double d2 = (nodes[static_cast<std::size_t>(v)].position - at).squaredNorm();
      if (d2 <= reach2_) near_.emplace_back(d2, v);
    });
    relative_neighbourhood(nodes, near_, neighbourhood_);
    std::vector<std::int32_t>& pulled = pulled_[s];
    wanted_.clear();
    for (const auto& [d2, v] : neighbourhood_)
      if (d2 > kill2_) wanted_.push_back(v);
    if (!neighbourhood_.empty() && wanted_.empty()) {  // every vein growing to it has arrived
      alive_[s] = 0;
      --live_;
      join_at_source(nodes, neighbourhood_, linked_, links);
    }
    std::sort(wanted_.begin(), wanted_.end());
    // What changed: the pulls that end and those that begin.
    std::size_t a = 0, b = 0;
    while (a < pulled.size() || b < wanted_.size()) {
      if (b == wanted_.size() || (a < pulled.size() && pulled[a] < wanted_[b])) pull(s, pulled[a++], -1);
      else if (a == pulled.size() || wanted_[b] < pulled[a]) pull(s, wanted_[b++], 1);
      else ++a, ++b;
    }
    pulled.swap(wanted_);
  }

  std::vector<Vec3> sources_;
  double reach2_, kill2_;
  CellLists source_cells_, node_cells_;
  std::vector<std::uint8_t> alive_;
  std::vector<std::vector<std::int32_t>> pulled_;  // each source's pulled nodes, by id
  std::size_t live_;
  std::unordered_set<std::uint64_t> linked_;
  std::vector<std::int32_t> dirty_, wanted_;
  std::vector<std::pair<double, std::int32_t>> near_, neighbourhood_;
};

}  // namespace dla::detail
