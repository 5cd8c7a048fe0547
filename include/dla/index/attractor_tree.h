#pragma once
//! \file attractor_tree.h
//! Space colonization's attractors, each with its closest node, indexed so that a new node
//! finds the attractors it comes closer to without looking at the others (colonization.h).
//!
//! The attractors are sorted along a Morton curve and cut in halves, down to leaves of at most
//! kLeaf. Every range keeps its bounding box and the largest squared distance of its live
//! attractors to their nodes. A new node that is no closer to the box than that cannot change
//! any of them: the range is skipped whole. Positions are kept one coordinate to an array, so
//! that a leaf is measured in one loop the compiler vectorizes.

#include "dla/core/cluster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace dla {

class AttractorTree {
 public:
  static constexpr std::int32_t kNone = -1;  //!< an attractor's node when none is within reach
  static constexpr std::int32_t kDied = -2;  //!< what a moving attractor goes to when it dies

  //! `points` (fewer than 2^32) pull nodes within sqrt(reach2) (infinity: unbounded) and die
  //! within sqrt(kill2) of one, reach2 >= kill2. The order of `points` is not kept.
  AttractorTree(std::vector<Vec3> points, double reach2, double kill2) : kill2_(kill2), live_(points.size()) {
    const std::size_t count = points.size();
    int index_bits = 1;
    while (index_bits < 32 && (count - 1) >> index_bits) ++index_bits;
    const std::vector<std::uint64_t> keys = morton_keys(points, index_bits);
    const std::uint64_t index_mask = (std::uint64_t{1} << index_bits) - 1;
    for (auto& axis : coordinates_) axis.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Vec3& point = points[keys[i] & index_mask];
      for (std::size_t axis = 0; axis < 3; ++axis) coordinates_[axis][i] = point[static_cast<int>(axis)];
    }
    std::vector<Vec3>().swap(points);  // "points = {}" would keep the capacity
    // An attractor no node reaches yet counts as farther than the kill distance even when the
    // reach equals it, so that "closer than its distance" is the one test for taking and killing.
    distance2_.assign(count, std::max(reach2, std::nextafter(kill2, std::numeric_limits<double>::infinity())));
    closest_.assign(count, kNone);
    if (count == 0) return;
    ranges_.reserve(count_ranges(keys, 0, count));
    build(keys, 0, count);
  }

  std::size_t size() const { return closest_.size(); }
  std::size_t live() const { return live_; }
  Vec3 position(std::size_t a) const { return {coordinates_[0][a], coordinates_[1][a], coordinates_[2][a]}; }
  //! The attractor's node (kNone: none within reach); meaningless once it died.
  std::int32_t closest(std::size_t a) const { return closest_[a]; }
  bool alive(std::size_t a) const { return distance2_[a] >= 0.0; }

  //! Nodes first, first + 1, ... at `positions` are new, and come in that order: every live
  //! attractor closer to one than to its node, within reach, now pulls it, and every one within
  //! the kill distance of one dies. Each change calls moved(a, from, to), `from` being the
  //! attractor's former node or kNone, `to` the new node or kDied. An attractor sees the nodes
  //! in order, so the result is that of adding them one at a time; the nodes go down the tree
  //! together, and a range is read once for all of them.
  template <class Moved>
  void add_nodes(std::int32_t first, const std::vector<Vec3>& positions, Moved&& moved) {
    if (size() == 0 || positions.empty()) return;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      nodes_[axis].resize(positions.size());
      for (std::size_t n = 0; n < positions.size(); ++n) nodes_[axis][n] = positions[n][static_cast<int>(axis)];
    }
    candidates_.resize(4 * positions.size());
    for (std::size_t n = 0; n < positions.size(); ++n) candidates_[n] = static_cast<std::uint32_t>(n);
    visit(0, 0, positions.size(), first, moved);
  }

 private:
  static constexpr std::size_t kLeaf = 32;

  struct Range {
    Vec3 min = Vec3::Zero(), max = Vec3::Zero();  //!< the box of all its attractors, live or dead
    double largest = -1;      //!< the largest squared distance of its live ones; -1: all dead
    std::uint32_t from = 0, to = 0;  //!< its attractors
    std::uint32_t upper = 0;  //!< its upper half (its lower half follows it); 0: a leaf
    //! A node that every attractor here has met, so none is farther from its node than from
    //! it; NaN until one has
    Vec3 witness = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  };

  //! Per point, in Morton order over the points' bounding box: its code above its index. A
  //! stable radix sort of the codes, so ties stay in index order.
  static std::vector<std::uint64_t> morton_keys(const std::vector<Vec3>& points, int index_bits) {
    const std::size_t count = points.size();
    // Sixteen cells across the mean spacing of the points is fine enough to split on; fewer
    // bits, fewer passes of the sort.
    const int axis_bits = std::min((64 - index_bits) / 3, (index_bits + 2) / 3 + 4);
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (const Vec3& p : points) low = low.cwiseMin(p), high = high.cwiseMax(p);
    const double cells = std::ldexp(1.0, axis_bits) - 1.0;
    Vec3 scale;
    for (int axis = 0; axis < 3; ++axis)
      scale[axis] = high[axis] > low[axis] ? cells / (high[axis] - low[axis]) : 0.0;
    // Spreads the low 21 bits of v to every third bit.
    const auto spread = [](std::uint64_t v) {
      v &= 0x1fffff;
      v = (v | v << 32) & 0x1f00000000ffffULL;
      v = (v | v << 16) & 0x1f0000ff0000ffULL;
      v = (v | v << 8) & 0x100f00f00f00f00fULL;
      v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
      v = (v | v << 2) & 0x1249249249249249ULL;
      return v;
    };
    std::vector<std::uint64_t> keys(count), sorted(count);
    for (std::size_t i = 0; i < count; ++i) {
      std::uint64_t code = 0;
      for (int axis = 0; axis < 3; ++axis) {
        // In [0, cells] whatever the rounding: the clamp keeps a point at the high edge in.
        const double cell = std::min(cells, (points[i][axis] - low[axis]) * scale[axis]);
        code |= spread(static_cast<std::uint64_t>(cell)) << axis;
      }
      keys[i] = code << index_bits | i;
    }
    constexpr int kDigitBits = 11;
    constexpr std::uint64_t kDigitMask = (1u << kDigitBits) - 1;
    for (int shift = index_bits; shift < index_bits + 3 * axis_bits; shift += kDigitBits) {
      std::array<std::size_t, kDigitMask + 2> start{};
      for (const std::uint64_t key : keys) ++start[((key >> shift) & kDigitMask) + 1];
      for (std::size_t digit = 1; digit < start.size(); ++digit) start[digit] += start[digit - 1];
      for (const std::uint64_t key : keys) sorted[start[(key >> shift) & kDigitMask]++] = key;
      keys.swap(sorted);
    }
    return keys;
  }

  //! Where range [from, to), of more than kLeaf, is cut: where its keys' highest differing bit
  //! turns on, at a plane across the axis that bit codes, so that its halves' boxes do not
  //! overlap. Keys are distinct (they hold the index) and sorted: that bit is set in the last
  //! and not in the first.
  static std::size_t split(const std::vector<std::uint64_t>& keys, std::size_t from, std::size_t to) {
    std::uint64_t below = keys[from] ^ keys[to - 1];  // then every bit up to its highest set
    for (int shift = 1; shift < 64; shift *= 2) below |= below >> shift;
    const std::uint64_t bit = below ^ (below >> 1);
    const auto begin = keys.begin();
    return static_cast<std::size_t>(std::partition_point(begin + static_cast<std::ptrdiff_t>(from),
                                                         begin + static_cast<std::ptrdiff_t>(to),
                                                         [bit](std::uint64_t key) { return (key & bit) == 0; }) -
                                    begin);
  }

  static std::size_t count_ranges(const std::vector<std::uint64_t>& keys, std::size_t from, std::size_t to) {
    if (to - from <= kLeaf) return 1;
    const std::size_t middle = split(keys, from, to);
    return 1 + count_ranges(keys, from, middle) + count_ranges(keys, middle, to);
  }

  //! Adds the range of attractors [from, to) and those below it; returns its index.
  std::uint32_t build(const std::vector<std::uint64_t>& keys, std::size_t from, std::size_t to) {
    const auto range = static_cast<std::uint32_t>(ranges_.size());
    ranges_.push_back({});
    ranges_[range].from = static_cast<std::uint32_t>(from);
    ranges_[range].to = static_cast<std::uint32_t>(to);
    ranges_[range].largest = distance2_[from];  // the same for all, before any node
    if (to - from <= kLeaf) {
      Vec3 min = position(from), max = min;
      for (std::size_t a = from + 1; a < to; ++a) min = min.cwiseMin(position(a)), max = max.cwiseMax(position(a));
      ranges_[range].min = min, ranges_[range].max = max;
      return range;
    }
    const std::size_t middle = split(keys, from, to);
    build(keys, from, middle);
    const std::uint32_t upper = build(keys, middle, to);
    Range& r = ranges_[range];
    r.upper = upper;
    r.min = ranges_[range + 1].min.cwiseMin(ranges_[upper].min);
    r.max = ranges_[range + 1].max.cwiseMax(ranges_[upper].max);
    return range;
  }

  //! Sends the nodes candidates_[begin, end) into range `range`, keeping those that may change
  //! it. Returns the last of them that changed it (its index in the batch), or -1.
  template <class Moved>
  std::int64_t visit(std::uint32_t range, std::size_t begin, std::size_t end, std::int32_t first, Moved& moved) {
    Range& r = ranges_[range];
    const std::size_t kept = end;
    if (candidates_.size() < kept + (end - begin)) candidates_.resize(2 * (kept + (end - begin)));
    const double min_x = r.min.x(), min_y = r.min.y(), min_z = r.min.z(), max_x = r.max.x(), max_y = r.max.y(),
                 max_z = r.max.z(), largest = r.largest;
    const double *x = nodes_[0].data(), *y = nodes_[1].data(), *z = nodes_[2].data();
    std::uint32_t* list = candidates_.data();
    std::size_t kept_end = kept;
    // The distance to [min, max] along an axis, exactly, without a branch: v + |v| is 2 v or 0.
    const auto gap = [](double v, double min, double max) {
      const double below = min - v, above = v - max;
      return 0.5 * ((below + std::abs(below)) + (above + std::abs(above)));
    };
    for (std::size_t c = begin; c < end; ++c) {
      const std::uint32_t n = list[c];
      // Its distance to the box, term by term as an attractor's is measured: never above any of
      // theirs. No live attractor is farther from its node (all dead: -1): nothing to change.
      const double gx = gap(x[n], min_x, max_x), gy = gap(y[n], min_y, max_y), gz = gap(z[n], min_z, max_z);
      list[kept_end] = n;  // kept only if the count moves on: no branch to mispredict
      kept_end += gx * gx + gy * gy + gz * gz < largest;
    }
    // An attractor a is never farther from its node than from the witness w, a node, so n takes
    // it only if |a - n| < |a - w|, that is 2 (a - w).(n - w) > |n - w|^2: only if the box
    // reaches across the plane halfway between them. All relative to w, where the box's
    // centre c and half sides h are exact enough: (a - w).(n - w) <= (c - w).(n - w) +
    // sum(h |n - w|). The margin covers the rounding, here and in the squared distances; no
    // witness (NaN) keeps every node. Asked second, of fewer nodes, and only where attractors
    // may be farther from their nodes than the box is wide: nearer the tree it seldom cuts,
    // and costs more than the leaves it saves.
    const Vec3 low = r.min - r.witness, high = r.max - r.witness;
    if (largest > (high - low).squaredNorm()) {
      const Vec3 center = 0.5 * (low + high), half = 0.5 * (high - low);
      const Vec3 farthest = low.cwiseAbs().cwiseMax(high.cwiseAbs());
      const double farthest2 = farthest.squaredNorm();
      std::size_t across_end = kept;
      for (std::size_t c = kept; c < kept_end; ++c) {
        const std::uint32_t n = list[c];
        const double nx = x[n] - r.witness.x(), ny = y[n] - r.witness.y(), nz = z[n] - r.witness.z();
        const double n2 = nx * nx + ny * ny + nz * nz;
        const double ahead = center.x() * nx + center.y() * ny + center.z() * nz +
                             (half.x() * std::abs(nx) + half.y() * std::abs(ny) + half.z() * std::abs(nz));
        const double scale = farthest.x() * std::abs(nx) + farthest.y() * std::abs(ny) + farthest.z() * std::abs(nz);
        list[across_end] = n;
        across_end += !(n2 - 2.0 * ahead >= 1e-12 * (n2 + 2.0 * scale + farthest2));
      }
      kept_end = across_end;
    }
    if (kept == kept_end) return -1;
    std::int64_t changer = -1;
    if (r.upper != 0) {
      const std::int64_t lower = visit(range + 1, kept, kept_end, first, moved);
      changer = std::max(lower, visit(r.upper, kept, kept_end, first, moved));
      if (changer >= 0) r.largest = std::max(ranges_[range + 1].largest, ranges_[r.upper].largest);
    } else {
      for (std::size_t c = kept; c < kept_end; ++c)
        if (scan(r, candidates_[c], static_cast<std::int32_t>(first + candidates_[c]), moved)) changer = candidates_[c];
      if (changer >= 0) r.largest = *std::max_element(distance2_.begin() + r.from, distance2_.begin() + r.to);
    }
    // Every attractor here has now met the changer, so none is farther from its node than from it.
    if (changer >= 0) r.witness = Vec3(x[changer], y[changer], z[changer]);
    return changer;
  }

  //! Node `node`, the batch's n-th, against leaf r's attractors; returns whether any changed.
  template <class Moved>
  bool scan(const Range& r, std::uint32_t n, std::int32_t node, Moved& moved) {
    // Measure the leaf in one vectorized loop; most leaves change nowhere.
    std::array<double, kLeaf> d2;
    const std::size_t from = r.from, length = r.to - r.from;
    const double *x = coordinates_[0].data() + from, *y = coordinates_[1].data() + from,
                 *z = coordinates_[2].data() + from, *known = distance2_.data() + from;
    const double px = nodes_[0][n], py = nodes_[1][n], pz = nodes_[2][n];
    double hits = 0.0;  // a double: GCC 12 vectorizes no integer sum of double comparisons
    for (std::size_t i = 0; i < length; ++i) {
      const double dx = x[i] - px, dy = y[i] - py, dz = z[i] - pz;
      d2[i] = dx * dx + dy * dy + dz * dz;
      hits += d2[i] < known[i] ? 1.0 : 0.0;
    }
    if (hits == 0.0) return false;
    for (std::size_t i = 0; i < length; ++i) {
      if (!(d2[i] < known[i])) continue;
      const std::size_t a = from + i;
      if (d2[i] <= kill2_) {
        moved(a, closest_[a], kDied);
        distance2_[a] = -1.0;
        --live_;
      } else {
        moved(a, closest_[a], node);
        closest_[a] = node;
        distance2_[a] = d2[i];
      }
    }
    return true;
  }

  double kill2_;
  std::size_t live_;
  std::array<std::vector<double>, 3> coordinates_;  //!< in Morton order
  std::vector<double> distance2_;                   //!< to the closest node; -1: dead
  std::vector<std::int32_t> closest_;
  std::vector<Range> ranges_;                       //!< ranges_[0] holds all
  std::array<std::vector<double>, 3> nodes_;        //!< the nodes being added
  //! Per range on the way down, the nodes that may change it (indices into nodes_), each
  //! range's after its parent's.
  std::vector<std::uint32_t> candidates_;
};

}  // namespace dla
