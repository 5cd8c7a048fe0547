#pragma once
//! \file grid_index.h
//! The default nearest-particle look-up: a grid of cells four spacings wide, stored in blocks
//! allocated where they are needed, with an occupancy bit per cell, a gap map (per cell, a
//! lower bound on the distance from the cell to the nearest particle, kept within four cells
//! of the structure), a node map (every fourth cell corner, its distance to the nearest
//! occupied cell, kept within 16 cells, 31 in the plane), a far map (per block of 8 cells a
//! side, the whole blocks to the nearest block holding a particle, kept within eight blocks)
//! and a pyramid of coarser occupancy bits.
//!
//! Next to the structure a probe returns the exact nearest particle, walking the lists of the
//! occupied cells of the 3x3x3 block about the point (the occupancy bits of a row of cells are
//! read in one load). From half a cell out it reads the point's gap, beyond the gap map's
//! reach the eight nodes about the point, and beyond theirs the far map and one bit per pyramid
//! level, and returns a lower bound on the distance: the walk only needs a ball free of particles.
//! nearest() finds the exact nearest particle however far the point (random drops), bound()
//! the probe's bound without reading a particle (straight lines). See docs/spatial-index.md for the
//! layout and the measurements that chose it.

#include "dla/core/errors.h"
#include "dla/core/huge_pages.h"
#include "dla/index/spatial_index.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <vector>


namespace dla {

class GridIndex {
 public:
  //! Without `distance_maps` the gap and node maps, which bound a probe far from the structure,
  //! are not kept: an insert costs several times less, and probe() answers with nearest(),
  //! exact. For models that ask only nearest() and bound() (drop.h, ballistic.h).
  GridIndex(const std::vector<Particle>& particles, double spacing, int dimensions, bool distance_maps = true)
      : particles_(particles), cell_(4.0 * spacing), planar_(dimensions == 2), distance_maps_(distance_maps),
        max_cells_(planar_ ? 32768 : 2048),
        node_reach_(planar_ ? kMostNodeReach : 16),
        node_cap_(static_cast<std::uint8_t>(node_reach_ * kNodeUnits)) {
    static_assert(kMostNodeReach * kNodeUnits < 256, "a node's value fits in its byte");
  }

  void reserve(std::size_t particles) { next_.reserve(particles); }

  //! True when the particle is the first in its cell: only such a particle changes the
  //! occupancy bits, the pyramid and the node map.
  bool insert(std::int32_t id) {
    const Vec3& p = particles_[static_cast<std::size_t>(id)].position;
    if (cells_ == 0) start(p, 0.0);
    while (!inside(p, 0.0)) grow();
    next_.push_back(-1);
    return place(id);
  }

  void cover(const Vec3& center, double radius) {
    if (cells_ == 0) start(center, radius);
    while (!inside(center, radius)) grow();
  }

  //! Whether inserting a particle within `radius` of `center`, or covering that ball, leaves the
  //! domain as it is. Only a change of domain moves what probes on other threads read: dla.h
  //! stops them first.
  bool holds(const Vec3& center, double radius) const { return cells_ > 0 && inside(center, radius); }

  Probe probe(const Vec3& x, Reach reach = Reach::set) const {
    if (cells_ == 0) return {};  // reach: any particle changes it
    if (!distance_maps_) return nearest(x).reaching(x, std::numeric_limits<double>::infinity());
    std::array<double, 3> f{0.0, 0.0, 0.0};  // position in cells from the domain's corner
    std::array<int, 3> c{0, 0, 0};
    for (int a = 0; a < axes(); ++a) {
      f[a] = (x[a] - origin_[a]) / cell_;
      if (!(f[a] >= 0.0 && f[a] < dims_[a])) return outside_domain(x);
      c[a] = static_cast<int>(f[a]);
    }
    const int gap = gap_of(c);
    // Every particle is at least `gap` from x's cell, and a particle outside the cell is
    // farther from x by x's distance to the cell's faces. From half a cell out that bound
    // saves the block search (measured: from a whole cell, which no block search beats, the
    // searches cost more than the steps they save).
    if (gap >= kGapUnits / 2) {
      Probe answer{-1, (gap * (1.0 / kGapUnits) + face_margin(f, c, 0)) * cell_};
      // Only a particle nearer to the cell than its gap (and a unit of rounding) lowers it.
      if (reach == Reach::set) block_box(c, 0, 0, (gap + 1) * (cell_ / kGapUnits), answer.reach_min, answer.reach_max);
      if (gap < kFarGap) return answer;
      // The nodes and pyramid bits change only when a particle opens a cell: an opening box.
      const Probe coarse = far_bound(f, c, reach);
      answer.distance = std::max(answer.distance, coarse.distance);
      answer.opening_min = coarse.opening_min;
      answer.opening_max = coarse.opening_max;
      return answer;
    }
    return nearest_in_block(x, f, c, reach);
  }

  //! A lower bound on the distance from x to the nearest particle from the gap and node maps
  //! (without them, the occupancy bits) and the pyramid, without reading a cell's particles:
  //! cheap, and coarse next to the structure. For tracing a straight line (ballistic.h),
  //! which tests the last stretch exactly.
  double bound(const Vec3& x) const {
    if (cells_ == 0) return std::numeric_limits<double>::infinity();
    std::array<double, 3> f{0.0, 0.0, 0.0};
    std::array<int, 3> c{0, 0, 0};
    for (int a = 0; a < axes(); ++a) {
      f[a] = (x[a] - origin_[a]) / cell_;
      if (!(f[a] >= 0.0 && f[a] < dims_[a])) return distance_to_domain(x);
      c[a] = static_cast<int>(f[a]);
    }
    if (!distance_maps_) {
      // The nearest occupied cell of the 3x3x3 block about x's, from the occupancy bits.
      const auto gaps = axis_gaps(x, c);
      const int dz = planar_ ? 0 : 1;
      const int x0 = std::max(c[0] - 1, 0), x1 = std::min(c[0] + 1, dims_[0] - 1);
      double best2 = std::numeric_limits<double>::infinity();
      for (int z = std::max(c[2] - dz, 0); z <= std::min(c[2] + dz, dims_[2] - 1); ++z)
        for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims_[1] - 1); ++y)
          for (std::uint64_t row = occupied_.row({x0, y, z}, x1 - x0 + 1); row; row &= row - 1) {
            const int cx = x0 + __builtin_ctzll(row);
            best2 = std::min(best2, gaps[0][cx - c[0] + 1] + gaps[1][y - c[1] + 1] + gaps[2][z - c[2] + 1]);
          }
      if (best2 < std::numeric_limits<double>::infinity()) return std::sqrt(best2);
      return std::max((1.0 + face_margin(f, c, 0)) * cell_, pyramid_bound(f, c, Reach::skip).distance);
    }
    const int gap = gap_of(c);
    if (gap == 0) return 0.0;  // a particle may lie in x's cell
    const double distance = (gap * (1.0 / kGapUnits) + face_margin(f, c, 0)) * cell_;
    return gap < kFarGap ? distance : std::max(distance, far_bound(f, c, Reach::skip).distance);
  }

  //! The exact nearest particle to x, however far; among equally near particles, the lowest
  //! id. Near the structure it searches the cells about x's shell by shell, while a particle
  //! may lie nearer than the next shell; farther out, best-first down the pyramid (coarse cells
  //! nearest x first, a cell's finer cells only while they may beat the best particle found).
  //! The cost grows with the cells near the sphere through the answer, never with the
  //! particles. Not for use while another thread inserts.
  Probe nearest(const Vec3& x) const;

  template <class Visit>
  void for_each_within(const Vec3& x, double radius, Visit&& visit) const {
    if (cells_ == 0) return;
    std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int a = 0; a < axes(); ++a) {
      const double from = std::floor((x[a] - radius - origin_[a]) / cell_);
      const double to = std::floor((x[a] + radius - origin_[a]) / cell_);
      if (to < 0.0 || from >= dims_[a]) return;
      lo[a] = static_cast<int>(std::max(from, 0.0));
      hi[a] = static_cast<int>(std::min(to, dims_[a] - 1.0));
    }
    const double r2 = radius * radius;
    // The cells' lists are walked side by side, a few at a time: their loads do not wait on
    // one another.
    constexpr std::size_t kLanes = 16;
    std::array<std::int32_t, kLanes> at;
    std::size_t lanes = 0;
    const auto walk = [&] {
      while (lanes > 0)
        for (std::size_t i = 0; i < lanes;) {
          const std::int32_t id = at[i];
          const double d2 = distance2(position(id), x);
          if (d2 <= r2) visit(id, d2);
          at[i] = next(id);
          if (at[i] < 0) at[i] = at[--lanes]; else ++i;
        }
    };
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int xx = lo[0]; xx <= hi[0]; ++xx) {
          const std::int32_t first = head({xx, y, z});
          if (first < 0) continue;
          at[lanes++] = first;
          if (lanes == kLanes) walk();
        }
    walk();
  }

 private:
  static constexpr int kBlockShift = 3;                   // blocks of 8 cells a side
  static constexpr int kNearShells = 5;                   // nearest(): empty shells before the pyramid
  static constexpr int kMostShells = 8;                   // nearest(): shells to confirm a particle
  static constexpr std::size_t kMaxLevelWords = 1 << 22;  // 32 MiB; finer levels are skipped
  static constexpr int kGapUnits = 32;                    // gap map units per cell width
  static constexpr int kGapReach = 4;                     // cells a particle lowers gaps around
  static constexpr int kFarGap = kGapReach * kGapUnits;   // gap of cells beyond every reach
  static constexpr int kNodeShift = 2;                    // a node every 4 cells along each axis
  static constexpr int kNodeUnits = 8;                    // node map units per cell width
  static constexpr int kMostNodeReach = 31;               // a node's byte holds 31 cells' units
  static constexpr int kFarReach = 8;                     // blocks a block's first particle lowers the far map within
  static constexpr int kFarCap = kFarReach * kFarReach;   // far map value beyond every reach

  using Cell = std::array<int, 3>;

  // What probes read may be written meanwhile by the one thread that inserts (see
  // dla.h): word-sized atomic loads and stores, which cost nothing more than plain ones.
  template <class T>
  static T load(const T& v) { return __atomic_load_n(&v, __ATOMIC_RELAXED); }
  template <class T>
  static T load_acquire(const T& v) { return __atomic_load_n(&v, __ATOMIC_ACQUIRE); }
  template <class T>
  static void store(T& v, T value) { __atomic_store_n(&v, value, __ATOMIC_RELAXED); }
  template <class T>
  static void store_release(T& v, T value) { __atomic_store_n(&v, value, __ATOMIC_RELEASE); }

  //! One bit per cell of a box of cells, x fastest.
  struct BitGrid {
    Cell dims{0, 0, 0};
    HugePageVector<std::uint64_t> words;

    void reset(const Cell& size) {
      dims = size;
      words.assign((static_cast<std::size_t>(dims[0]) * dims[1] * dims[2] + 63) / 64 + 1, 0);
    }
    std::size_t bit(const Cell& c) const {
      return (static_cast<std::size_t>(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
    }
    bool test(const Cell& c) const {
      const std::size_t b = bit(c);
      return (load(words[b >> 6]) >> (b & 63)) & 1u;
    }
    //! One writer: no read-modify-write instruction needed. A bit already set is not written
    //! again, which would take the cache line from the cores reading it.
    void set(const Cell& c) {
      const std::size_t b = bit(c);
      const std::uint64_t word = load(words[b >> 6]), with = word | std::uint64_t{1} << (b & 63);
      if (with != word) store(words[b >> 6], with);
    }
    //! The bits of `length` (<= 56) cells from `first` along x, lowest bit first, from the
    //! two words they may straddle (the words are padded so it never reads past the end).
    std::uint64_t row(const Cell& first, int length) const {
      const std::size_t b = bit(first);
      const int shift = static_cast<int>(b & 63);
      std::uint64_t bits = load(words[b >> 6]) >> shift;
      if (shift + length > 64) bits |= load(words[(b >> 6) + 1]) << (64 - shift);
      return bits & ((std::uint64_t{1} << length) - 1);
    }
  };

  //! One pyramid level: cells of 2^shift cells a side. `near` has a bit set when a particle
  //! lies in the cell or one of its 26 neighbours, so one bit answers "is the 3x3x3 block
  //! empty"; `held` when one lies in the cell, for nearest()'s descent.
  struct Level {
    int shift;
    BitGrid near;
    BitGrid held;

    Cell up(const Cell& cell, bool planar) const {
      return {cell[0] >> shift, cell[1] >> shift, planar ? 0 : cell[2] >> shift};
    }
    void mark(const Cell& cell, bool planar) {
      const Cell c = up(cell, planar);
      const int dz = planar ? 0 : 1;
      for (int z = std::max(c[2] - dz, 0); z <= std::min(c[2] + dz, near.dims[2] - 1); ++z)
        for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, near.dims[1] - 1); ++y)
          for (int x = std::max(c[0] - 1, 0); x <= std::min(c[0] + 1, near.dims[0] - 1); ++x)
            near.set({x, y, z});
      held.set(c);
    }
  };

  //! Blocks carved from slabs filled ahead with a block's empty value. The slabs double from
  //! 16 blocks to 2 MiB, which HugePageAllocator puts in one huge page: a run's blocks lie in
  //! a few pages rather than scattered over the heap. A block never moves once carved.
  template <class T>
  struct Slabs {
    explicit Slabs(T empty_value) : empty(empty_value) {}

    T empty;
    std::vector<HugePageVector<T>> slabs;
    std::size_t used = 0;  // of the last slab

    T* carve(std::size_t block) {
      if (slabs.empty() || used + block > slabs.back().size()) {
        const std::size_t size = slabs.empty() ? 16 * block : 2 * slabs.back().size();
        slabs.emplace_back(std::min(size, kHugePageBytes / sizeof(T)), empty);
        used = 0;
      }
      used += block;
      return slabs.back().data() + used - block;
    }
  };

  //! An occupied cell near the query and the distance from the query to its box.
  struct Candidate {
    double gap2;
    Cell cell;
  };

  int axes() const { return planar_ ? 2 : 3; }
  //! |p - x|^2; in the plane, where z is 0, without it (the same value).
  double distance2(const Vec3& p, const Vec3& x) const {
    return planar_ ? (p.head<2>() - x.head<2>()).squaredNorm() : (p - x).squaredNorm();
  }
  const Vec3& position(std::int32_t id) const { return particles_[static_cast<std::size_t>(id)].position; }

  //! Squared gap along each axis from x to the cells at offsets -1..1 from `home`;
  //! index [axis][offset + 1]. A cell's squared distance to x is the sum over axes.
  std::array<std::array<double, 3>, 3> axis_gaps(const Vec3& x, const Cell& home) const {
    std::array<std::array<double, 3>, 3> gaps{};
    for (int a = 0; a < axes(); ++a)
      for (int o = -1; o <= 1; ++o) {
        const double lo = origin_[a] + (home[a] + o) * cell_;
        const double gap = std::max({lo - x[a], x[a] - lo - cell_, 0.0});
        gaps[a][o + 1] = gap * gap;
      }
    return gaps;
  }

  //! The nearest particle if it lies within the 3x3x3 block of cells about x and nearer than
  //! the block's boundary, else the distance to that boundary as a bound. Occupied cells are
  //! read a row at a time from the occupancy bits and searched nearest ring first.
  Probe nearest_in_block(const Vec3& x, const std::array<double, 3>& f, const Cell& c, Reach reach) const {
    const auto gaps = axis_gaps(x, c);
    const int dz = planar_ ? 0 : 1;
    std::array<std::array<Candidate, 27>, 2> rings;  // occupied cells: x's own, the 26 around
    std::array<std::size_t, 2> counts{0, 0};
    const int x0 = std::max(c[0] - 1, 0), x1 = std::min(c[0] + 1, dims_[0] - 1);
    for (int z = std::max(c[2] - dz, 0); z <= std::min(c[2] + dz, dims_[2] - 1); ++z)
      for (int y = std::max(c[1] - 1, 0); y <= std::min(c[1] + 1, dims_[1] - 1); ++y) {
        const double gap2_yz = gaps[1][y - c[1] + 1] + gaps[2][z - c[2] + 1];
        const bool off_axis = y != c[1] || z != c[2];
        for (std::uint64_t row = occupied_.row({x0, y, z}, x1 - x0 + 1); row; row &= row - 1) {
          const int cx = x0 + __builtin_ctzll(row);
          const int ring = off_axis || cx != c[0];
          rings[ring][counts[ring]++] = {gap2_yz + gaps[0][cx - c[0] + 1], {cx, y, z}};
        }
      }
    const double margin = face_margin(f, c, 0);
    std::int32_t best = -1;
    double best2 = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring < 2; ++ring) {
      const double reach = ring == 0 ? 0.0 : margin * cell_;  // nearest the 26 around get
      if (reach * reach >= best2) break;
      // The cells' lists are walked side by side: their loads do not wait on one another.
      std::array<std::int32_t, 27> at;
      std::size_t lanes = 0;
      for (std::size_t i = 0; i < counts[ring]; ++i) {
        if (rings[ring][i].gap2 >= best2) continue;
        const std::int32_t first = head(rings[ring][i].cell);
        if (first >= 0) at[lanes++] = first;
      }
      while (lanes > 0) {
        for (std::size_t i = 0; i < lanes;) {
          const std::int32_t id = at[i];
          const double d2 = distance2(position(id), x);
          if (d2 < best2) {
            best2 = d2;
            best = id;
          }
          at[i] = next(id);
          if (at[i] < 0) at[i] = at[--lanes]; else ++i;
        }
      }
    }
    const double boundary = (1.0 + margin) * cell_;
    Probe answer{-1, boundary};
    if (best >= 0 && best2 <= boundary * boundary) answer = {best, std::sqrt(best2)};
    if (reach == Reach::set) answer.reaching(x, answer.distance);
    return answer;
  }

  //! Distance from fractional cell position f to the faces of its cell at level `shift`, in cells.
  double face_margin(const std::array<double, 3>& f, const Cell& c, int shift) const {
    double margin = std::numeric_limits<double>::infinity();
    for (int a = 0; a < axes(); ++a) {
      const double lo = static_cast<double>((c[a] >> shift) << shift);
      margin = std::min({margin, f[a] - lo, lo + (1 << shift) - f[a]});
    }
    return std::max(margin, 0.0);
  }

  double distance_to_domain(const Vec3& x) const {
    double d2 = 0.0;
    for (int a = 0; a < axes(); ++a) {
      const double lo = origin_[a], hi = origin_[a] + dims_[a] * cell_;
      const double out = std::max({lo - x[a], x[a] - hi, 0.0});
      d2 += out * out;
    }
    return std::sqrt(d2);
  }

  //! Whether the ball lies in the domain with kGapReach cells to spare, so that every cell a
  //! particle lowers the gap of exists.
  bool inside(const Vec3& center, double radius) const {
    const double reach = radius + kGapReach * cell_;
    for (int a = 0; a < axes(); ++a)
      if (!(center[a] - reach >= origin_[a] && center[a] + reach < origin_[a] + dims_[a] * cell_)) return false;
    return true;
  }

  void start(const Vec3& center, double radius);

  //! Doubles the domain about its centre. The domain's corner moves by a whole number of
  //! blocks, so the blocks (cell lists and gaps) stay as they are: only the block tables, the
  //! occupancy bits and the node map are made again.
  void grow();

  //! Sizes the domain, the block tables and the occupancy bits for cells_ cells a side, empty.
  void lay_out();

  //! Sets the occupancy bits of the cells of a block (whose first cell is `first`) that hold
  //! particles, and lowers the nodes about them.
  void mark_occupied(const Cell& first, const std::int32_t* heads);

  Cell cell_of(const Vec3& p) const {
    Cell c{0, 0, 0};
    for (int a = 0; a < axes(); ++a)
      c[a] = std::min(static_cast<int>((p[a] - origin_[a]) / cell_), dims_[a] - 1);
    return c;
  }

  int block_cells() const { return planar_ ? 64 : 512; }

  std::size_t block_of(const Cell& c) const {
    return (static_cast<std::size_t>(c[2] >> kBlockShift) * block_dims_[1] + (c[1] >> kBlockShift)) *
               block_dims_[0] +
           (c[0] >> kBlockShift);
  }

  //! A cell's place within its block.
  static std::size_t cell_in_block(const Cell& c) {
    const int m = (1 << kBlockShift) - 1;
    return static_cast<std::size_t>(((c[2] & m) << kBlockShift | (c[1] & m)) << kBlockShift | (c[0] & m));
  }

  //! Cell c's gap, in gap units (kFarGap beyond the gap map's reach). Where no particle lies in
  //! c's block or a block next to it, the far map says so: every particle is more than a block
  //! (8 cells) away, beyond the gap map's reach (4). Its byte a block stays in the caches where
  //! the block table's pointer, 8 bytes a block, misses at 10^7.
  int gap_of(const Cell& c) const {
    static_assert(kGapReach < (1 << kBlockShift), "a gap reaches no farther than the next block");
    const std::size_t block = block_of(c);
    if (load(far_[block]) > 0) return kFarGap;
    const std::uint8_t* gaps = load_acquire(gaps_of_[block]);
    return gaps ? load(gaps[cell_in_block(c)]) : kFarGap;
  }

  //! The first particle of cell c's list, or -1.
  std::int32_t head(const Cell& c) const {
    const std::int32_t* heads = load_acquire(heads_of_[block_of(c)]);
    return heads ? load_acquire(heads[cell_in_block(c)]) : -1;
  }

  std::int32_t next(std::int32_t id) const { return load(next_[static_cast<std::size_t>(id)]); }

  template <class Visit>
  void for_each_in_cell(const Cell& c, Visit&& visit) const {
    for (std::int32_t id = head(c); id >= 0; id = next(id)) visit(id);
  }

  //! The block of cell lists holding cell c, allocated (no particles) if it was not.
  std::int32_t* heads_at(const Cell& c) {
    std::int32_t*& heads = heads_of_[block_of(c)];
    if (!heads) {
      store_release(heads, head_blocks_.carve(static_cast<std::size_t>(block_cells())));
    }
    return heads;
  }

  //! The block of gaps holding cell c, allocated (gaps beyond reach) if it was not.
  std::uint8_t* gaps_at(const Cell& c) {
    std::uint8_t*& gaps = gaps_of_[block_of(c)];
    if (!gaps) {
      store_release(gaps, gap_blocks_.carve(static_cast<std::size_t>(block_cells())));
    }
    return gaps;
  }

  //! Files a particle; true if its cell held none. Probes may run on other threads meanwhile:
  //! each store publishes a consistent state (the particle is in the store before its id is
  //! in a list).
  bool place(std::int32_t id);

  //! Lowers the gap of every cell within kGapReach cells of p's cell `home` to the distance
  //! from the cell's box to p, where that is smaller.
  void lower_gaps(const Vec3& p, const Cell& home);

  std::size_t node_index(const Cell& n) const {
    return (static_cast<std::size_t>(n[2]) * node_dims_[1] + n[1]) * node_dims_[0] + n[0];
  }

  //! Beyond the gap map's reach: from each corner k of the node cell (4 cells a side) holding
  //! base cell c, every particle is at least the node's value V_k away, so at least V_k less
  //! the corner's distance from f. The largest of the eight, or where every node is beyond
  //! the node map's reach, the larger of that and the far map's bound, and the pyramid's where
  //! the far map says nothing (0) or is at its cap. Only a particle that opens a cell changes
  //! a node, the far map or the pyramid.
  Probe far_bound(const std::array<double, 3>& f, const Cell& c, Reach reach) const {
    const Cell n0{c[0] >> kNodeShift, c[1] >> kNodeShift, planar_ ? 0 : c[2] >> kNodeShift};
    const std::size_t first = node_index(n0);
    const std::size_t step_y = static_cast<std::size_t>(node_dims_[0]);
    const std::size_t step_z = planar_ ? 0 : step_y * static_cast<std::size_t>(node_dims_[1]);
    // Squared offsets along each axis from f to the node cell's low and high faces, in cells.
    std::array<std::array<double, 2>, 3> offset2{};
    for (int a = 0; a < axes(); ++a) {
      const double low = f[a] - static_cast<double>(n0[a] << kNodeShift), high = low - (1 << kNodeShift);
      offset2[a] = {low * low, high * high};
    }
    // The eight terms are independent (no chain of maxima through square roots). In the
    // plane the node cell has four corners.
    const int corners = planar_ ? 4 : 8;
    std::array<double, 8> term;
    term.fill(-std::numeric_limits<double>::infinity());
    int capped = 0;
    for (int k = 0; k < corners; ++k) {
      const int value = load(nodes_[first + (k & 1) + (k >> 1 & 1) * step_y + (k >> 2 & 1) * step_z]);
      capped += value == node_cap_;
      term[k] = value * (1.0 / kNodeUnits) -
                std::sqrt(offset2[0][k & 1] + offset2[1][k >> 1 & 1] + offset2[2][k >> 2 & 1]);
    }
    const double best = std::max({term[0], term[1], term[2], term[3], term[4], term[5], term[6], term[7], 0.0});
    if (capped == corners) {
      // A node lowered later would take the far map and the pyramid out of the answer: any
      // of them counts. Below its cap the far map's bound is within two block diagonals and
      // the pyramid seldom beats it, and at 10^7 the pyramid's bit is a miss in the caches.
      // The pyramid beats the capped far map only at a level 8 blocks wide or coarser, whose
      // box holds every block that could bring the far map below its cap.
      const int held2 = load(far_[block_of(c)]);
      Probe coarse = far_map_bound(f, c, held2, reach);
      if (held2 == 0 || held2 == kFarCap) {
        const Probe pyramid = pyramid_bound(f, c, reach);
        if (pyramid.distance > coarse.distance) coarse = pyramid;
      }
      if (reach == Reach::set) node_box(n0, 1, node_cap_, coarse);
      coarse.distance = std::max(coarse.distance, best * cell_);
      return coarse;
    }
    Probe answer = unchangeable(best * cell_);
    if (reach == Reach::set) {  // only a lower winning node lowers the answer
      const int win = static_cast<int>(std::max_element(term.begin(), term.end()) - term.begin());
      const Cell n{n0[0] + (win & 1), n0[1] + (win >> 1 & 1), n0[2] + (win >> 2 & 1)};
      node_box(n, 0, load(nodes_[node_index(n)]), answer);
    }
    return answer;
  }

  //! From the far map: every particle lies in a block at least sqrt(B) whole blocks from x's
  //! block (B, the block's value), so at least that far from x plus x's distance to its own
  //! block's faces (each axis the blocks are apart on adds at least that margin). Only a
  //! particle that opens a block, in the blocks within ceil(sqrt(B)) of x's, lowers B.
  Probe far_map_bound(const std::array<double, 3>& f, const Cell& c, int held2, Reach reach) const {
    if (held2 == 0) return unchangeable(0.0);  // a particle may lie in x's own block
    const double blocks = std::sqrt(static_cast<double>(held2));
    Probe answer = unchangeable((blocks * (1 << kBlockShift) + face_margin(f, c, kBlockShift)) * cell_);
    if (reach == Reach::set)
      block_box(c, kBlockShift, static_cast<int>(std::ceil(blocks)), 0.0, answer.opening_min, answer.opening_max);
    return answer;
  }

  //! Lowers the far map over the blocks within kFarReach of cell c's block, which has just
  //! got its first particle: each to its squared number of whole blocks between the two.
  void lower_far(const Cell& c);

  //! Widens a probe's opening box over every cell that lowers a node from n to n + span (in
  //! nodes, per axis) below `value`: a cell whose box is nearer than that, rounding included.
  void node_box(const Cell& n, int span, int value, Probe& probe) const {
    const double widen = (value + 1) * (cell_ / kNodeUnits) + cell_;
    for (int a = 0; a < 3; ++a) {
      if (a == 2 && planar_) {
        probe.opening_min[a] = -std::numeric_limits<double>::infinity();
        probe.opening_max[a] = std::numeric_limits<double>::infinity();
        continue;
      }
      const double low = origin_[a] + static_cast<double>(n[a] << kNodeShift) * cell_;
      probe.opening_min[a] = std::min(probe.opening_min[a], low - widen);
      probe.opening_max[a] = std::max(probe.opening_max[a], low + static_cast<double>(span << kNodeShift) * cell_ + widen);
    }
  }

  //! Lowers every node within node_reach_ cells of cell c, newly occupied, to its distance from
  //! the cell's box, in kNodeUnits per cell, rounded down.
  void lower_nodes(const Cell& c);

  //! A bound from the pyramid: the coarsest level whose 3x3x3 block about cell c is empty
  //! bounds the distance by its cell size plus f's distance to its own cell's faces; 0 when
  //! even the finest level's block holds a particle. Only a particle in that block sets a bit
  //! the answer read.
  Probe pyramid_bound(const std::array<double, 3>& f, const Cell& c, Reach reach) const {
    int clear = -1;
    for (int l = 0; l < static_cast<int>(levels_.size()); ++l) {
      if (levels_[l].near.test(levels_[l].up(c, planar_))) break;
      clear = l;
    }
    if (clear < 0) return unchangeable(0.0);
    const int shift = levels_[clear].shift;
    Probe answer = unchangeable(((1 << shift) + face_margin(f, c, shift)) * cell_);
    // Only a particle that opens a cell sets a bit.
    if (reach == Reach::set) block_box(c, shift, 1, 0.0, answer.opening_min, answer.opening_max);
    return answer;
  }

  //! Sets a box (a probe's reach or opening box) to the cells at level `shift` (2^shift cells
  //! wide) within `ring` of the one holding base cell c, widened by `margin`. In the plane it
  //! spans all z.
  void block_box(const Cell& c, int shift, int ring, double margin, Vec3& min, Vec3& max) const {
    for (int a = 0; a < 3; ++a) {
      if (a == 2 && planar_) {
        min[a] = -std::numeric_limits<double>::infinity();
        max[a] = std::numeric_limits<double>::infinity();
        continue;
      }
      const int up = c[a] >> shift, width = 1 << shift;  // up - ring may be -1: multiplied, not shifted
      min[a] = origin_[a] + static_cast<double>((up - ring) * width) * cell_ - margin;
      max[a] = origin_[a] + static_cast<double>((up + ring + 1) * width) * cell_ + margin;
    }
  }

  //! Outside the domain the bound is the distance to it, which no particle changes.
  Probe outside_domain(const Vec3& x) const { return unchangeable(distance_to_domain(x)); }

  //! A bound no particle inserted later changes: its reach is empty.
  static Probe unchangeable(double distance) {
    Probe probe{-1, distance};
    probe.reach_min = Vec3::Constant(std::numeric_limits<double>::infinity());
    probe.reach_max = -probe.reach_min;
    return probe;
  }

  const std::vector<Particle>& particles_;
  double cell_;  // cell edge: four spacings (with the gap map, faster than five; docs/spatial-index.md)
  bool planar_;
  bool distance_maps_;  // whether the gap and node maps are kept
  // Cells a side at most: 3D DLA reaches ~1,900 spacings (480 cells) at 10^8 particles, 2D
  // ~40,000 (10,000 cells) at 10^8 and 65,536 spacings at ~2x10^8. The dense tables then take
  // ~1.5 GB in 3D and ~0.55 GB in 2D, beside the particles' 4.8 GB at 10^8.
  int max_cells_;
  // Cells an occupied cell lowers nodes within. In the plane, a walk between far branches
  // takes 6-9% fewer steps with 31 than with 16, and lowering the nodes costs little
  // (docs/dev/performance-notes.md); in space it would cost seven times as much.
  int node_reach_;
  std::uint8_t node_cap_;  // value of nodes beyond every reach
  Vec3 center_ = Vec3::Zero();
  Vec3 origin_ = Vec3::Zero();
  int cells_ = 0;  // cells a side (z is one cell when planar); 0 until the first use
  Cell dims_{0, 0, 0};
  Cell block_dims_{0, 0, 0};
  // Blocks never move once allocated, so probes on other threads may follow a table's pointer
  // while the writer allocates more (the tables themselves change only with the domain).
  HugePageVector<std::int32_t*> heads_of_;  // block table: per cell of the block, its first
                                            // particle or -1; null while the block is empty
  HugePageVector<std::uint8_t*> gaps_of_;   // block table: per cell of the block, its distance
                                            // to the nearest particle, rounded down, in cell
                                            // widths / kGapUnits; null while beyond reach
  Slabs<std::int32_t> head_blocks_{-1};
  Slabs<std::uint8_t> gap_blocks_{static_cast<std::uint8_t>(kFarGap)};
  HugePageVector<std::int32_t> next_;       // per particle: next particle in its cell, or -1
  BitGrid occupied_;                        // per cell: holds a particle
  Cell node_dims_{0, 0, 0};
  HugePageVector<std::uint8_t> nodes_;      // per node (every 4th cell corner, x fastest):
                                            // distance to the nearest occupied cell's box,
                                            // rounded down, in cell widths / kNodeUnits;
                                            // node_cap_ beyond reach
  HugePageVector<std::uint8_t> far_;        // per block (x fastest): squared number of whole
                                            // blocks between it and the nearest block holding
                                            // a particle; kFarCap beyond reach
  std::vector<Level> levels_;               // finest first
};

}  // namespace dla
