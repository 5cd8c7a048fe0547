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
//! Nodes are only ever added, so a source's neighbourhood changes only where a new node leaves
//! out the members whose lune it lies in, or joins: each new node updates the sources within
//! its influence so, and the result is the full recomputation's at every step, node for node.

#include "dla/core/cluster.h"
#include "dla/core/stop.h"
#include "dla/models/links.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_set>
#include <utility>
#include <vector>

namespace dla::detail {

//! A box cut into cells about `width` wide, at most 8 a point of `count` (the cells widen for
//! more): the cell of any point, clamped to the box, so a point beyond it falls in an edge cell.
class CellFrame {
 public:
  CellFrame(const Vec3& lo, const Vec3& hi, double width, std::size_t count) : origin_(lo) {
    const Vec3 extent = (hi - lo).cwiseMax(Vec3::Constant(width));
    width_ = std::max(width, std::cbrt(extent.prod() / (8.0 * static_cast<double>(std::max<std::size_t>(count, 1)))));
    for (std::size_t a = 0; a < 3; ++a)
      dims_[a] = static_cast<std::int64_t>(std::floor((hi[static_cast<int>(a)] - lo[static_cast<int>(a)]) / width_)) + 1;
  }

  std::size_t cells() const { return static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]); }

  std::array<std::int64_t, 3> cell_of(const Vec3& p) const {
    std::array<std::int64_t, 3> c{};
    for (std::size_t a = 0; a < 3; ++a) {
      const double at = std::floor((p[static_cast<int>(a)] - origin_[static_cast<int>(a)]) / width_);
      c[a] = static_cast<std::int64_t>(std::clamp(at, 0.0, static_cast<double>(dims_[a] - 1)));
    }
    return c;
  }
  std::size_t index(const std::array<std::int64_t, 3>& c) const {
    return static_cast<std::size_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
  }

 private:
  Vec3 origin_;
  double width_ = 1.0;
  std::array<std::int64_t, 3> dims_{1, 1, 1};
};

//! Fixed points by cells, each cell's ids together: the points near a place at the cost of the
//! cells it meets.
class PointGrid {
 public:
  //! The points `keep(i)` keeps.
  template <class Keep>
  PointGrid(const std::vector<Vec3>& points, const CellFrame& frame, Keep&& keep)
      : frame_(frame), start_(frame.cells() + 1, 0) {
    for (std::size_t i = 0; i < points.size(); ++i)
      if (keep(i)) ++start_[frame_.index(frame_.cell_of(points[i])) + 1];
    for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
    ids_.resize(start_.back());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (keep(i)) ids_[fill[frame_.index(frame_.cell_of(points[i]))]++] = static_cast<std::int32_t>(i);
  }

  std::size_t size() const { return ids_.size(); }

  //! visit(id) for the points in the cells that meet the cube of half-side r about p.
  template <class Visit>
  void for_each_near(const Vec3& p, double r, Visit&& visit) const {
    const std::array<std::int64_t, 3> a = frame_.cell_of(p - Vec3::Constant(r)), b = frame_.cell_of(p + Vec3::Constant(r));
    for (std::int64_t z = a[2]; z <= b[2]; ++z)
      for (std::int64_t y = a[1]; y <= b[1]; ++y) {
        const std::size_t row = frame_.index({0, y, z});
        for (std::uint32_t k = start_[row + static_cast<std::size_t>(a[0])]; k < start_[row + static_cast<std::size_t>(b[0]) + 1]; ++k)
          visit(ids_[k]);
      }
  }

 private:
  CellFrame frame_;
  std::vector<std::uint32_t> start_;
  std::vector<std::int32_t> ids_;
};

//! Points added one by one, by cells.
class GrowingGrid {
 public:
  explicit GrowingGrid(const CellFrame& frame) : frame_(frame), cells_(frame.cells()) {}

  void add(const Vec3& p, std::int32_t id) { cells_[frame_.index(frame_.cell_of(p))].push_back(id); }

  //! Whether find(id) is true for an id in the cells that meet the box [lo, hi] (a superset of
  //! those in it), the cell of `first` searched first; stops at the first.
  template <class Find>
  bool any_in_box(const Vec3& lo, const Vec3& hi, const Vec3& first, Find&& find) const {
    const auto in = [&](std::size_t cell) {
      for (const std::int32_t id : cells_[cell])
        if (find(id)) return true;
      return false;
    };
    const std::size_t f = frame_.index(frame_.cell_of(first));
    if (in(f)) return true;
    const std::array<std::int64_t, 3> a = frame_.cell_of(lo), b = frame_.cell_of(hi);
    for (std::int64_t z = a[2]; z <= b[2]; ++z)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t x = a[0]; x <= b[0]; ++x) {
          const std::size_t cell = frame_.index({x, y, z});
          if (cell != f && in(cell)) return true;
        }
    return false;
  }

 private:
  CellFrame frame_;
  std::vector<std::vector<std::int32_t>> cells_;
};

//! The links made where the nodes `arrived` (nearest the source first) reached one source: each
//! to the first, unless they are linked already or fewer than kLoopSteps tree steps apart (two
//! twigs of one vein: a loop as links.h makes them, of different veins).
inline void join_at_source(const std::vector<Particle>& nodes, const std::vector<std::int32_t>& arrived,
                           std::unordered_set<std::uint64_t>& linked, std::vector<Link>& links) {
  const std::int32_t hub = arrived.front();
  for (std::size_t k = 1; k < arrived.size(); ++k) {
    const std::int32_t v = arrived[k];
    const Link link{std::min(hub, v), std::max(hub, v)};
    if (tree_near(nodes, link.later, link.earlier, kLoopSteps)) continue;
    const std::uint64_t key = static_cast<std::uint64_t>(link.earlier) << 32 | static_cast<std::uint32_t>(link.later);
    if (linked.insert(key).second) links.push_back(link);
  }
}

class ClosedVenation {
 public:
  //! `sources` pull nodes within sqrt(reach2) (finite), and count them arrived within sqrt(kill2).
  ClosedVenation(const std::vector<Vec3>& sources, double reach2, double kill2)
      : sources_(in_cells(sources, std::sqrt(reach2) / 4)), reach2_(reach2), kill2_(kill2), reach_(std::sqrt(reach2)),
        source_grid_(sources_, frame(sources_, reach_ / 4), [](std::size_t) { return true; }),
        node_cells_(frame(sources_, reach_ / 2)), alive_(sources_.size(), 1), neighbourhood_(sources_.size()),
        touched_(sources_.size(), 0), live_(sources_.size()) {}

  std::size_t live() const { return live_; }
  const Vec3& position(std::size_t s) const { return sources_[s]; }

  //! Takes in nodes [first, end) of `nodes`, just added. A new node changes a source's
  //! neighbourhood only by leaving out the members whose lune it lies in, and by joining it when
  //! no node lies in its own: the neighbourhoods stay exact with no rescan. pull(source, node,
  //! +1 or -1) hears each change of whom a source pulls: a member not arrived, which it stays
  //! (nodes do not move). The links made where sources are removed are appended to `links`.
  //! Once `stop` is set, no more nodes are taken in (a node among 10^5 sources within the
  //! influence takes milliseconds), and growth is to end.
  template <class Pull>
  void add_nodes(const std::vector<Particle>& nodes, std::size_t first, Pull&& pull, std::vector<Link>& links,
                 const StopFlag* stop) {
    changed_.clear();
    nodes_ = &nodes;
    // One node at a time, each against the nodes before it: a neighbourhood is then the exact
    // one of the nodes so far after each.
    for (std::size_t v = first; v < nodes.size() && !stopped(stop); ++v) {
      const Vec3& p = nodes[v].position;
      node_cells_.add(p, static_cast<std::int32_t>(v));
      recent_.clear();
      const std::int32_t parent = nodes[v].parent;
      if (parent >= 0) recent_.push_back(nodes[static_cast<std::size_t>(parent)].position);
      source_grid_.for_each_near(p, reach_, [&](std::int32_t id) {
        const auto s = static_cast<std::size_t>(id);
        if (!alive_[s]) return;
        const double d2 = (sources_[s] - p).squaredNorm();
        if (d2 > reach2_) return;
        // The members whose lune v lies in leave; a member nearer the source and v than they
        // are to each other blocks v; nearer than every member, v is the nearest node, which
        // is always in the neighbourhood.
        std::vector<Member>& members = neighbourhood_[s];
        bool changed = false, blocked = false, nearest = true;
        for (std::size_t k = 0; k < members.size();) {
          const Member& m = members[k];
          const double apart2 = (m.at - p).squaredNorm();
          if (d2 < m.d2 && apart2 < m.d2) {
            if (m.d2 > kill2_) pull(s, m.node, -1);
            members[k] = members.back();
            members.pop_back();
            changed = true;
            continue;
          }
          blocked = blocked || (m.d2 < d2 && apart2 < d2);
          nearest = nearest && d2 < m.d2;
          ++k;
        }
        if (!blocked && (nearest || !blocked_by_others(s, static_cast<std::int32_t>(v), p, d2))) {
          members.push_back({d2, static_cast<std::int32_t>(v), p});
          if (d2 > kill2_) pull(s, static_cast<std::int32_t>(v), 1);
          changed = true;
        }
        if (changed && !touched_[s]) {
          touched_[s] = 1;
          changed_.push_back(id);
        }
      });
    }
    std::sort(changed_.begin(), changed_.end());
    for (const std::int32_t s : changed_) {
      touched_[static_cast<std::size_t>(s)] = 0;
      remove_if_arrived(nodes, static_cast<std::size_t>(s), links);
    }
    // Removed sources are passed over; once they are half the grid's, it is made again without.
    if (2 * live_ < source_grid_.size())
      source_grid_ = PointGrid(sources_, frame(sources_, reach_ / 4), [&](std::size_t s) { return alive_[s] != 0; });
  }

 private:
  //! Cells half the influence wide over the sources' box: the nodes that matter to a source
  //! lie within its influence, and those beyond the box fall in its edge cells.
  static CellFrame frame(const std::vector<Vec3>& sources, double width) {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& p : sources) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    if (sources.empty()) lo = hi = Vec3::Zero();
    return CellFrame(lo, hi, width, sources.size());
  }

  //! The points in the order of their cells: a source's neighbours in space are then its
  //! neighbours in memory. (The order of the sources changes nothing grown.)
  static std::vector<Vec3> in_cells(const std::vector<Vec3>& points, double width) {
    const CellFrame cells = frame(points, width);
    std::vector<std::pair<std::size_t, std::size_t>> order(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) order[i] = {cells.index(cells.cell_of(points[i])), i};
    std::sort(order.begin(), order.end());
    std::vector<Vec3> sorted(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) sorted[i] = points[order[i].second];
    return sorted;
  }

  //! A node of a source's neighbourhood: its squared distance to the source, and where it is.
  struct Member {
    double d2;
    std::int32_t node;
    Vec3 at;
    bool operator<(const Member& other) const { return d2 < other.d2 || (d2 == other.d2 && node < other.node); }
  };

  //! Whether a node other than v (at p) lies nearer both source s and v than they are to each
  //! other (d2 apart), when no member of the source's neighbourhood does: v's parent and what
  //! blocked v from the sources before (near these, it most often blocks it again), then every
  //! node in the lune's box.
  bool blocked_by_others(std::size_t s, std::int32_t v, const Vec3& p, double d2) {
    const Vec3& at = sources_[s];
    const auto blocks = [&](const Vec3& q) { return (q - at).squaredNorm() < d2 && (q - p).squaredNorm() < d2; };
    for (const Vec3& q : recent_)
      if (blocks(q)) return true;
    // The lune lies in the ball about the midpoint of radius sqrt(3)/2 of the distance, and in
    // the ball about v of the distance.
    const Vec3 middle = 0.5 * (at + p);
    const double d = std::sqrt(d2), r = 0.8661 * d;
    const Vec3 lo = (middle - Vec3::Constant(r)).cwiseMax(p - Vec3::Constant(d));
    const Vec3 hi = (middle + Vec3::Constant(r)).cwiseMin(p + Vec3::Constant(d));
    const Vec3* blocker = nullptr;
    const bool found = node_cells_.any_in_box(lo, hi, p, [&](std::int32_t u) {
      blocker = &(*nodes_)[static_cast<std::size_t>(u)].position;
      return u != v && blocks(*blocker);
    });
    if (found) {
      if (recent_.size() < kRecent) recent_.push_back(*blocker);
      else recent_[1 + next_recent_++ % (kRecent - 1)] = *blocker;
    }
    return found;
  }

  //! After its neighbourhood changed: source s, with every member arrived, is removed and
  //! joins them.
  void remove_if_arrived(const std::vector<Particle>& nodes, std::size_t s, std::vector<Link>& links) {
    std::vector<Member>& members = neighbourhood_[s];
    if (members.empty()) return;
    for (const Member& m : members)
      if (m.d2 > kill2_) return;
    alive_[s] = 0;
    --live_;
    std::sort(members.begin(), members.end());
    arrived_.clear();
    for (const Member& m : members) arrived_.push_back(m.node);
    join_at_source(nodes, arrived_, linked_, links);
    std::vector<Member>().swap(members);
  }

  std::vector<Vec3> sources_;
  double reach2_, kill2_, reach_;
  PointGrid source_grid_;
  GrowingGrid node_cells_;
  std::vector<std::uint8_t> alive_;
  std::vector<std::vector<Member>> neighbourhood_;  // each source's relative neighbourhood
  std::vector<std::uint8_t> touched_;               // whether a source is in changed_
  std::size_t live_;
  std::unordered_set<std::uint64_t> linked_;
  std::vector<std::int32_t> changed_, arrived_;
  // The last few nodes that blocked the node being taken in from a source.
  static constexpr std::size_t kRecent = 5;  // the parent and four
  std::vector<Vec3> recent_;
  const std::vector<Particle>* nodes_ = nullptr;
  std::size_t next_recent_ = 0;
};

}  // namespace dla::detail
